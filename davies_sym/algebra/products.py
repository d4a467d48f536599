"""Polynomials as products of factors: ``content * prod f_i^e_i``.

Products and exact divisions of such products are bookkeeping on the factor lists; only
a sum is expanded, and only past the factors its terms share (`common`).  The factored
elimination of D_A and the sums of rational functions whose factorisations are known
both work on them, so that nothing grows with the expanded size of a stage product.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import reduce
from math import gcd

from flint import fmpz_mpoly

from davies_sym.algebra.flint_conversion import factor

#: Sums up to this many terms are factored at once; larger ones stay a single factor
#: until the solution needs them irreducible.
SMALL_SUM = 400

Factors = tuple[tuple[fmpz_mpoly, int], ...]


@dataclass(frozen=True, eq=False)
class Product:
    """``content * prod(f**e)``; each ``f`` primitive with a positive leading coefficient."""

    content: int
    factors: Factors

    def expand_in(self, one: fmpz_mpoly) -> fmpz_mpoly:
        """The expanded polynomial (``one``: the ring's 1, for a constant product)."""
        out = one * self.content
        for f, e in self.factors:
            out = out * f**e
        return out

    @property
    def size(self) -> int:
        return sum(len(f) * e for f, e in self.factors)

    def is_constant(self) -> bool:
        return not self.factors


def product_of(p: fmpz_mpoly) -> Product:
    """``p`` as a product: factored by flint when small, else its content and primitive part."""
    if len(p) <= SMALL_SUM:
        content, factors = factor(p)
        return Product(content, tuple(factors))
    content = reduce(gcd, map(int, p.coeffs()))
    if p.leading_coefficient() < 0:
        content = -content
    return Product(content, ((p / content, 1),))


def _merge(a: Factors, b: Factors, sign: int = 1) -> Factors:
    """The factors of a * b (``sign`` = 1) or a / b (-1, b dividing a)."""
    out = list(a)
    for f, e in b:
        for k, (g, d) in enumerate(out):
            if g == f:
                out[k] = (g, d + sign * e)
                break
        else:
            if sign < 0:
                raise ArithmeticError("inexact division of factored polynomials")
            out.append((f, e))
    return tuple((f, e) for f, e in out if e)


def multiply(a: Product, b: Product) -> Product:
    return Product(a.content * b.content, _merge(a.factors, b.factors))


def divide(a: Product, b: Product) -> Product:
    """``a / b`` for ``b`` a common divisor found by `common`."""
    return Product(a.content // b.content, _merge(a.factors, b.factors, -1))


def common(a: Product, b: Product) -> Product:
    """The factors ``a`` and ``b`` share (a divisor of their gcd, the whole gcd when every
    factor is irreducible), with the gcd of the contents."""
    shared = []
    for f, e in a.factors:
        for g, d in b.factors:
            if f == g:
                shared.append((f, min(e, d)))
                break
    return Product(gcd(a.content, b.content) or 1, tuple(shared))


FactorList = list[tuple[fmpz_mpoly, int]]
#: A fraction as (content, factors) of its numerator and of its denominator.
Fraction = tuple[tuple[int, FactorList], tuple[int, FactorList]]


def _lcm_factors(a: FactorList, b: FactorList) -> FactorList:
    out = list(a)
    for f, e in b:
        for k, (g, d) in enumerate(out):
            if g == f:
                out[k] = (g, max(d, e))
                break
        else:
            out.append((f, e))
    return out


def fraction_sum(one: fmpz_mpoly, a: Fraction, b: Fraction) -> Fraction | None:
    """``a + b`` over the least common denominator of their factors (None when zero).
    The numerators' shared factors stay out of the one expansion; the rest is factored
    while small, and a larger rest is one factor, divided by the denominator's factors
    it holds (so the result stays in lowest terms)."""
    (an, afn), (ad, afd) = a
    (bn, bfn), (bd, bfd) = b
    den_content = ad * bd // gcd(ad, bd)
    den_factors = _lcm_factors(afd, bfd)

    def over_common(content: int, factors: FactorList, own: FactorList, d: int) -> Product:
        """A numerator over the common denominator: times the denominator factors it lacks."""
        lacking = _merge(tuple(den_factors), tuple(own), -1)
        return multiply(Product(content, tuple(factors)), Product(den_content // d, lacking))

    ta, tb = over_common(an, afn, afd, ad), over_common(bn, bfn, bfd, bd)
    shared = common(ta, tb)
    rest = divide(ta, shared).expand_in(one) + divide(tb, shared).expand_in(one)
    if rest.is_zero():
        return None
    numerator = product_of(rest)
    if len(rest) > SMALL_SUM:
        ((big, _),) = numerator.factors
        for k, (g, e) in enumerate(den_factors):
            while e and (quotient := divmod(big, g))[1].is_zero():
                big, e = quotient[0], e - 1
            den_factors[k] = (g, e)
        numerator = Product(numerator.content, ((big, 1),))
    numerator = multiply(shared, numerator)
    return (numerator.content, list(numerator.factors)), (den_content, [(f, e) for f, e in den_factors if e])


def factor_sort_key(item: tuple[fmpz_mpoly, int]) -> tuple[int, list[tuple[tuple[int, ...], int]]]:
    """The order python-flint lists the factors of ``factor()`` in (multiplicity, then the
    terms in the ring's order), so that a factorisation put together from parts prints as
    the factoring of the whole would."""
    f, e = item
    return e, [(tuple(m), int(c)) for m, c in zip(f.monoms(), f.coeffs(), strict=True)]


def lowest_terms(
    num_content: int,
    den_content: int,
    num_factors: Iterable[tuple[fmpz_mpoly, int]],
    den_factors: Iterable[tuple[fmpz_mpoly, int]],
) -> Fraction:
    """``num_content prod(num_factors) / (den_content prod(den_factors))`` of irreducible
    (flint-normalised) factors, repeats allowed: identical factors merge and cancel, the
    contents divide by their gcd, the denominator's sign goes to the numerator, and each
    side lists its factors in python-flint's own order (`factor_sort_key`)."""
    merged = _merge((), (*num_factors, *((f, -e) for f, e in den_factors)))
    shared = gcd(num_content, den_content)
    cn, cd = num_content // shared, den_content // shared
    if cd < 0:
        cn, cd = -cn, -cd
    fn = [(f, e) for f, e in merged if e > 0]
    fd = [(f, -e) for f, e in merged if e < 0]
    for side in (fn, fd):
        if len(side) > 1:  # the key lists every term: not formed for a single factor
            side.sort(key=factor_sort_key)
    return (cn, fn), (cd, fd)


def homogenised(p: fmpz_mpoly, name: str, n: fmpz_mpoly, d: fmpz_mpoly, degree: int) -> fmpz_mpoly:
    """``p(x = n/d) d^degree`` for ``degree`` at least p's degree in ``x`` (named
    ``name``): p = sum_k c_k x^k with c_k = (d^k p / dx^k)(0) / k!."""
    total, derivative, factorial = p * 0, p, 1
    for k in range(degree + 1):
        if k:
            derivative = derivative.derivative(name)
            factorial *= k
            if derivative.is_zero():
                break
        coefficient = derivative.subs({name: 0})
        if not coefficient.is_zero():
            total += (coefficient / factorial) * n**k * d ** (degree - k)
    return total


@dataclass(frozen=True)
class Replacement:
    """The variable ``name`` (generator ``index``) replaced by ``n / d``; ``den`` is the
    content and irreducible factors of ``d``."""

    name: str
    index: int
    n: fmpz_mpoly
    d: fmpz_mpoly
    den: tuple[int, FactorList]


def fraction_substituted(fraction: Fraction, replacements: Sequence[Replacement]) -> Fraction:
    """``fraction`` with every replacement made at once, factor by factor: each factor f
    becomes f(n1/d1, n2/d2, ...) d1^k1 d2^k2 ... (k the degree it has in each variable
    when its turn comes), factored once, and the powers of each d (its known factors)
    are put back on the side they fall on.  ZeroDivisionError when the denominator
    vanishes."""
    sides: dict[int, tuple[int, FactorList]] = {1: (fraction[0][0], []), -1: (fraction[1][0], [])}
    exponents = [0] * len(replacements)  # of each d in the result
    for side, factors in ((1, fraction[0][1]), (-1, fraction[1][1])):
        for f, e in factors:
            content, found = sides[side]
            p, changed = f, False
            for k, r in enumerate(replacements):
                degree = int(p.degrees()[r.index])
                if degree > 0:
                    p, changed = homogenised(p, r.name, r.n, r.d, degree), True
                    exponents[k] -= side * degree * e
            if not changed:
                found.append((f, e))
                continue
            c, parts = factor(p)
            sides[side] = (content * c**e, found + [(g, m * e) for g, m in parts])
    if sides[-1][0] == 0:
        raise ZeroDivisionError("the substitution makes the denominator zero")
    for r, exponent in zip(replacements, exponents, strict=True):
        if exponent:
            side = 1 if exponent > 0 else -1
            content, found = sides[side]
            dc, df = r.den
            sides[side] = (content * dc ** abs(exponent), found + [(g, m * abs(exponent)) for g, m in df])
    (cn, fn), (cd, fd) = sides[1], sides[-1]
    if cn == 0:
        return (0, []), (1, [])
    return lowest_terms(cn, cd, fn, fd)
