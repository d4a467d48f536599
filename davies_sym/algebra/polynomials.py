"""Exact polynomials and rational functions on python-flint (``fmpz_mpoly``).

One polynomial ring per derivation holds every symbol of the train.  Sympy
expressions enter through `PolynomialRing.rational` and leave through
`RationalFunction.to_expr`, which builds the product of flint's irreducible
factors directly, so no sympy simplification runs in the pipeline.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from functools import cached_property
from math import factorial, gcd

import sympy
from flint import fmpq, fmpq_mpoly, fmpz_mpoly, fmpz_mpoly_ctx

from davies_sym.algebra.flint_conversion import ExpressionConverter, expanded_expr, factor, polynomial_key
from davies_sym.algebra.point_values import PointValues
from davies_sym.algebra.products import (
    Product,
    Replacement,
    fraction_substituted,
    fraction_sum,
    homogenised,
    lowest_terms,
)
from davies_sym.algebra.square_root_symbol import Radical
from davies_sym.algebra.symbol_order import describe_assumptions, symbol_key
from davies_sym.errors import DerivationError


class PolynomialRing:
    """Z[x1, ..., xn] over the given sympy symbols (ordered by name)."""

    def __init__(self, symbols: Iterable[sympy.Symbol], radicals: Iterable[Radical] = ()):
        radicals = tuple(radicals)
        unique: dict[str, sympy.Symbol] = {}
        for s in (*symbols, *(r.symbol for r in radicals), *(x for r in radicals for x in r.radicand.free_symbols)):
            known = unique.setdefault(s.name, s)
            if known != s:
                # One name, two symbols: the ring would keep whichever the iterable yields
                # first (hash order for a set).  The cause is upstream: a symbol made
                # outside the train's symbol table.
                first, second = sorted((known, s), key=symbol_key)
                raise DerivationError(
                    f"symbol {s.name} exists with two sets of assumptions: "
                    f"({describe_assumptions(first)}) and ({describe_assumptions(second)})"
                )
        self.symbols: tuple[sympy.Symbol, ...] = tuple(unique[n] for n in sorted(unique))
        names = tuple(s.name for s in self.symbols) or ("_one",)
        self.ctx = fmpz_mpoly_ctx.get(names, "degrevlex")
        self._gens: dict[sympy.Symbol, fmpz_mpoly] = dict(zip(self.symbols, self.ctx.gens(), strict=False))
        self._converter = ExpressionConverter(self.ctx, self._gens)
        self.radicals = radicals
        # Radical symbols stay symbols (positive) in expressions: sign reasoning needs
        # polynomials; documents write them as square roots (RadicalTable.restore).
        self._exprs = tuple(self.symbols)
        #: (generator index, radicand) of every radical symbol: s^2 = m.
        self._relations = tuple((self.symbols.index(r.symbol), self.polynomial(r.radicand)) for r in radicals)
        #: Exact values at rational points; a radical's from its radicand, exactly.
        self.points = PointValues(
            self.ctx,
            self.symbols,
            lambda: tuple((self.symbols.index(r.symbol), self.rational(r.radicand)) for r in radicals),
        )

    def reduce(self, p: fmpz_mpoly) -> fmpz_mpoly:
        """``p`` modulo ``s^2 - m`` for every radical: degree at most one in each ``s``
        (a canonical form, so ``is_zero`` is exact).  The top power s^k at a time: its
        coefficient c (the k-th derivative over k!, free of s) turns c s^k into c m s^(k-2);
        linear in the size of ``p``, unlike a composition."""
        gens, names = self.ctx.gens(), self.ctx.names()
        for index, radicand in self._relations:
            k = p.degrees()[index]
            while k >= 2:
                top = p
                for _ in range(k):
                    top = top.derivative(names[index])
                s = gens[index]
                p = p + (top / factorial(k)) * (radicand * s ** (k - 2) - s**k)
                k = p.degrees()[index]
        return p

    def rationalised(self, num: fmpz_mpoly, den: fmpz_mpoly) -> tuple[fmpz_mpoly, fmpz_mpoly]:
        """``num / den`` reduced, with every radical moved out of the denominator by
        multiplying with its conjugate ``den(-s)`` (after their common factor is
        divided out: the quotients of reduced polynomials are reduced)."""
        num, den = self.reduce(num), self.reduce(den)
        for index, _ in self._relations:
            if den.degrees()[index] == 0:
                continue
            # A factor both share may carry the root (where the value does not depend on
            # the drawing, it carries them all): taken out first, the conjugate
            # multiplies the rest, not the whole (which can swell a thousandfold).
            shared = num.gcd(den)
            if not shared.is_one():
                num, den = num / shared, den / shared
                if den.degrees()[index] == 0:
                    continue
            conjugate = self.ctx.from_dict({m: (-c if m[index] % 2 else c) for m, c in den.to_dict().items()})
            num, den = self.reduce(num * conjugate), self.reduce(den * conjugate)
        return num, den

    @property
    def zero(self) -> fmpz_mpoly:
        return self.ctx.from_dict({})

    @property
    def one(self) -> fmpz_mpoly:
        return self.ctx.constant(1)

    def gen(self, symbol: sympy.Symbol) -> fmpz_mpoly:
        return self._gens[symbol]

    def integral(self, expr: sympy.Expr) -> tuple[fmpz_mpoly, int]:
        """``expr`` (polynomial, rational coefficients) as ``(p, d)`` with expr = p / d,
        ``d`` the least positive integer that makes ``p`` integral."""
        num, den = self._converter.fraction(sympy.sympify(expr))
        if not den.is_constant():
            raise DerivationError(f"{expr} is not a polynomial in the train's symbols (it divides by {den})")
        d = int(den.leading_coefficient())
        g = gcd(d, *map(int, num.coeffs()))
        if d < 0:
            g = -g
        return (num / g if g != 1 else num), d // g

    def rational(self, expr: sympy.Expr) -> RationalFunction:
        """A sympy rational expression as a `RationalFunction`."""
        num, den = self._converter.fraction(sympy.sympify(expr))
        if den.is_zero():
            raise DerivationError(f"{expr} divides by zero")
        return RationalFunction.make(self, num, den)

    def polynomial(self, expr: sympy.Expr) -> fmpz_mpoly:
        """A polynomial with integer coefficients (after clearing denominators)."""
        return self.integral(expr)[0]

    def to_expr(self, p: fmpz_mpoly) -> sympy.Expr:
        """Expanded sympy expression of ``p``."""
        return expanded_expr(p, self._exprs)


#: Content and irreducible factors with their exponents, as flint's ``factor`` gives them.
Factorisation = tuple[int, list[tuple[fmpz_mpoly, int]]]


#: A polynomial with at most this many terms is factored to multiply in factored form.
SMALL = 40


class RationalFunction:
    """``num / den`` in lowest terms, ``den`` with a positive leading coefficient; a value
    (nothing can be set).  Built from known factors (`from_factors`), it keeps them and
    expands ``num`` and ``den`` only when read: products, quotients, sums, substitutions,
    evaluation and conversion to sympy work on the factors."""

    ring: PolynomialRing

    def __init__(self, ring: PolynomialRing, num: fmpz_mpoly, den: fmpz_mpoly):
        self.__dict__.update(ring=ring, num=num, den=den)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"a RationalFunction is a value: {name} cannot be set")

    @classmethod
    def _from_factorisation(cls, ring: PolynomialRing, known: tuple[Factorisation, Factorisation]) -> RationalFunction:
        out = cls.__new__(cls)
        out.__dict__.update(ring=ring, factorisation=known)
        return out

    @cached_property
    def num(self) -> fmpz_mpoly:
        return self._expanded(0)

    @cached_property
    def den(self) -> fmpz_mpoly:
        return self._expanded(1)

    def _expanded(self, side: int) -> fmpz_mpoly:
        content, factors = self.factorisation[side]
        return Product(content, tuple(factors)).expand_in(self.ring.one)

    def _expanded_known(self) -> bool:
        return "num" in self.__dict__  # read or given: the expanded parts exist

    @classmethod
    def make(cls, ring: PolynomialRing, num: fmpz_mpoly, den: fmpz_mpoly) -> RationalFunction:
        if den.is_zero():
            raise ZeroDivisionError("rational function with zero denominator")
        if ring.radicals:
            num, den = ring.rationalised(num, den)
        if num.is_zero():
            return cls(ring, num, ring.one)
        g = num.gcd(den)
        if not g.is_one():
            num, den = num / g, den / g
        if den.leading_coefficient() < 0:
            num, den = -num, -den
        return cls(ring, num, den)

    @classmethod
    def polynomial(cls, ring: PolynomialRing, p: fmpz_mpoly) -> RationalFunction:
        return cls.make(ring, p, ring.one)

    @classmethod
    def from_factors(
        cls,
        ring: PolynomialRing,
        num_content: int,
        den_content: int,
        num_factors: Iterable[tuple[fmpz_mpoly, int]],
        den_factors: Iterable[tuple[fmpz_mpoly, int]],
    ) -> RationalFunction:
        """``num_content prod(num_factors) / (den_content prod(den_factors))`` from irreducible
        factors (`davies_sym.algebra.products.lowest_terms`), expanded only when read."""
        if num_content == 0:
            return cls.polynomial(ring, ring.zero)
        return cls._from_factorisation(ring, lowest_terms(num_content, den_content, num_factors, den_factors))

    @cached_property
    def factorisation(self) -> tuple[Factorisation, Factorisation]:
        """Content and irreducible factors of the numerator and of the denominator."""
        return factor(self.num), factor(self.den)

    def _factored_enough(self) -> bool:
        """Whether a product can be formed factor by factor: the factorisation is known, or
        cheap (small numerator and denominator)."""
        return "factorisation" in self.__dict__ or len(self.num) + len(self.den) <= SMALL

    def is_zero(self) -> bool:
        if self._expanded_known():
            return bool(self.num.is_zero())
        return self.factorisation[0][0] == 0

    def _is_polynomial(self) -> bool:
        if self._expanded_known():
            return bool(self.den.is_one())
        cd, fd = self.factorisation[1]
        return cd == 1 and not fd

    @property
    def free_symbols(self) -> set[sympy.Symbol]:
        """The symbols the function depends on, read off the degrees (no sympy expression)."""
        if self._expanded_known():
            parts = [self.num, self.den]
        else:
            (_, fn), (_, fd) = self.factorisation
            parts = [f for f, _ in (*fn, *fd)]
        used = [any(d) for d in zip(*(p.degrees() for p in parts), strict=True)] if parts else []
        return {s for s, u in zip(self.ring.symbols, used, strict=False) if u}

    def __add__(self, other: RationalFunction) -> RationalFunction:
        if other.is_zero():
            return self
        if self.is_zero():
            return other
        if not self.ring.radicals and _factored(self, other):
            return _sum(self, other)
        if self.den == other.den:
            return RationalFunction.make(self.ring, self.num + other.num, self.den)
        g = self.den.gcd(other.den)
        a, b = self.den / g, other.den / g
        return RationalFunction.make(self.ring, self.num * b + other.num * a, self.den * b)

    def __neg__(self) -> RationalFunction:
        if "factorisation" in self.__dict__:
            (cn, fn), den = self.factorisation
            out = RationalFunction._from_factorisation(self.ring, ((-cn, fn), den))
            if self._expanded_known():
                out.__dict__.update(num=-self.num, den=self.den)
            return out
        return RationalFunction(self.ring, -self.num, self.den)

    def __sub__(self, other: RationalFunction) -> RationalFunction:
        return self + (-other)

    def __mul__(self, other: RationalFunction) -> RationalFunction:
        if self.is_zero() or other.is_zero():
            return RationalFunction.polynomial(self.ring, self.ring.zero)
        if (
            not self.ring.radicals
            and self._factored_enough()
            and other._factored_enough()
            and ("factorisation" in self.__dict__ or "factorisation" in other.__dict__)
        ):
            return _product(self, other)
        # Cross-cancel first so the products stay small.
        g1, g2 = self.num.gcd(other.den), other.num.gcd(self.den)
        num = (self.num / g1) * (other.num / g2)
        den = (self.den / g2) * (other.den / g1)
        return RationalFunction.make(self.ring, num, den)

    def factor_list(self) -> tuple[int, list[tuple[sympy.Expr, int]]]:
        """Sign of the content and the factors of numerator and denominator together
        (denominator factors are listed too: only their parity matters for signs)."""
        (cn, fn), (cd, fd) = self.factorisation
        factors = [(self.ring.to_expr(f), int(e)) for f, e in (*fn, *fd)]
        return (1 if cn * cd > 0 else -1), factors

    def inverse(self) -> RationalFunction:
        if "factorisation" in self.__dict__ and not self.ring.radicals:
            (cn, fn), (cd, fd) = self.factorisation
            if cn < 0:  # the denominator keeps a positive leading coefficient
                return RationalFunction._from_factorisation(self.ring, ((-cd, fd), (-cn, fn)))
            return RationalFunction._from_factorisation(self.ring, ((cd, fd), (cn, fn)))
        return RationalFunction.make(self.ring, self.den, self.num)

    def __truediv__(self, other: RationalFunction) -> RationalFunction:
        return self * other.inverse()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RationalFunction):
            return NotImplemented
        return bool(self.num * other.den == other.num * self.den)

    def __hash__(self) -> int:  # pragma: no cover - not used as a key
        return hash((polynomial_key(self.num), polynomial_key(self.den)))

    def substitute(self, values: Mapping[sympy.Symbol, RationalFunction]) -> RationalFunction:
        """``self`` with every symbol of ``values`` replaced at once (the values must not
        contain the replaced symbols), without expanding the whole fraction: factor by
        factor where the factors are known (each f(n1/d1, ...) d1^k1 ..., factored once),
        else on the expanded numerator and denominator, one symbol after the other."""
        indices = {symbol: self.ring.symbols.index(symbol) for symbol in values}
        factored = not self.ring.radicals and self._factored_enough()
        if factored and all(value._factored_enough() for value in values.values()):
            factors = [f for part in self.factorisation for f, _ in part[1]]
            used = [s for s in values if any(f.degrees()[indices[s]] > 0 for f in factors)]
            if not used:
                return self
            replacements = [
                Replacement(s.name, indices[s], values[s].num, values[s].den, values[s].factorisation[1]) for s in used
            ]
            (cn, fn), (cd, fd) = fraction_substituted(self.factorisation, replacements)
            return RationalFunction.from_factors(self.ring, cn, cd, fn, fd)
        out = self
        for symbol, value in values.items():
            degree = max(out.num.degrees()[indices[symbol]], out.den.degrees()[indices[symbol]])
            if degree:
                num = homogenised(out.num, symbol.name, value.num, value.den, degree)
                den = homogenised(out.den, symbol.name, value.num, value.den, degree)
                out = RationalFunction.make(self.ring, num, den)
        return out

    def evaluate(self, point: Mapping[sympy.Symbol, object] | tuple[fmpq | None, ...]) -> fmpq:
        """Exact value at a rational point (a mapping, or the ring's ``points.args``);
        ZeroDivisionError on a pole."""
        args = point if isinstance(point, tuple) else self.ring.points.args(point)
        if not self._expanded_known():
            (cn, fn), (cd, fd) = self._rational_factors
            value = fmpq(cn)
            for f, q, used, e in fn:
                value *= self.ring.points.evaluate(f, args, q, used) ** e
            denominator = fmpq(cd)
            for f, q, used, e in fd:
                denominator *= self.ring.points.evaluate(f, args, q, used) ** e
            return value / denominator
        (num_q, num_used), (den_q, den_used) = self._rational_parts
        return self.ring.points.evaluate(self.num, args, num_q, num_used) / self.ring.points.evaluate(
            self.den, args, den_q, den_used
        )

    @cached_property
    def _rational_factors(self) -> tuple[tuple[int, list[tuple[fmpz_mpoly, fmpq_mpoly, int, int]]], ...]:
        """The factors with their ``fmpq_mpoly`` forms and used generators, for evaluation."""
        ring = self.ring
        return tuple(
            (content, [(f, ring.points.rational_form(f), ring.points.used(f), e) for f, e in factors])
            for content, factors in self.factorisation
        )

    @cached_property
    def _rational_parts(self) -> tuple[tuple[fmpq_mpoly, int], tuple[fmpq_mpoly, int]]:
        ring = self.ring
        return (ring.points.rational_form(self.num), ring.points.used(self.num)), (
            ring.points.rational_form(self.den),
            ring.points.used(self.den),
        )

    def derivative_at(self, symbol: sympy.Symbol, point: Mapping[sympy.Symbol, object]) -> fmpq:
        """Value of the partial derivative at ``point``, without forming it
        ((N' D - N D') / D^2 evaluated number by number)."""
        if symbol not in self.ring.symbols:
            return fmpq(0)
        args = self.ring.points.args(point)
        name = symbol.name
        (num_q, num_used), (den_q, den_used) = self._rational_parts
        n, d = (
            self.ring.points.evaluate(self.num, args, num_q, num_used),
            self.ring.points.evaluate(self.den, args, den_q, den_used),
        )
        dn = self.ring.points.evaluate(self.num.derivative(name), args)
        dd = self.ring.points.evaluate(self.den.derivative(name), args)
        return (dn * d - n * dd) / (d * d)

    def to_expr(self, factored: bool = True) -> sympy.Expr:
        """Sympy expression: product of factors over product of factors (default)."""
        if not factored:
            num = self.ring.to_expr(self.num)
            return num if self.den.is_one() else num / self.ring.to_expr(self.den)
        if self.is_zero():
            return sympy.Integer(0)
        (cn, fn), (cd, fd) = self.factorisation
        num = sympy.Mul(sympy.Integer(cn), *(self.ring.to_expr(f) ** e for f, e in fn))
        if cd == 1 and not fd:
            return num
        return num / sympy.Mul(sympy.Integer(cd), *(self.ring.to_expr(f) ** e for f, e in fd))


def _factored(a: RationalFunction, b: RationalFunction) -> bool:
    """Whether ``a + b`` is best formed factor by factor: one of them was never expanded,
    or the factors of both are known or cheap to find."""
    return not (a._expanded_known() and b._expanded_known()) or (a._factored_enough() and b._factored_enough())


def _sum(a: RationalFunction, b: RationalFunction) -> RationalFunction:
    """``a + b`` from the factorisations (`davies_sym.algebra.products.fraction_sum`)."""
    found = fraction_sum(a.ring.one, a.factorisation, b.factorisation)
    if found is None:
        return RationalFunction.polynomial(a.ring, a.ring.zero)
    (cn, fn), (cd, fd) = found
    return RationalFunction.from_factors(a.ring, cn, cd, fn, fd)


def _product(a: RationalFunction, b: RationalFunction) -> RationalFunction:
    """``a * b`` from the factorisations (`RationalFunction.from_factors`)."""
    (an, afn), (ad, afd) = a.factorisation
    (bn, bfn), (bd, bfd) = b.factorisation
    return RationalFunction.from_factors(a.ring, an * bn, ad * bd, (*afn, *bfn), (*afd, *bfd))
