"""Sign reasoning on polynomials and factored rational functions.

Used to decide which way a force or a relative motion points from the symbols'
assumptions (radii positive) and known geometric facts (an annulus is larger than the
pinion it meshes).  An undecided sign is reported as such, never guessed.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from functools import lru_cache

import sympy

from davies_sym.algebra.flint_conversion import factor_expression
from davies_sym.algebra.symbol_order import sorted_symbols


@lru_cache(maxsize=4096)
def _poly_sign(expr: sympy.Expr) -> int | None:
    """+1 or -1 if every coefficient has that sign and every symbol is positive (a pure
    function's memo: the states of a train ask of the same factors)."""
    expr = _expanded(expr)
    if expr == 0:
        return 0
    if expr.is_number:
        return 1 if expr > 0 else -1
    if not all(s.is_positive for s in expr.free_symbols):
        return None
    if not expr.is_polynomial(*expr.free_symbols):
        return None
    coeffs = list(expr.as_coefficients_dict().values())
    if all(c > 0 for c in coeffs):
        return 1
    if all(c < 0 for c in coeffs):
        return -1
    return None


def _constant_ratio(a: sympy.Expr, b: sympy.Expr) -> sympy.Rational | None:
    """``a / b`` when the expanded polynomials ``a`` and ``b`` are proportional by a
    non-zero number, else None: compared term by term, no division."""
    terms_a, terms_b = a.as_coefficients_dict(), b.as_coefficients_dict()
    if terms_a.keys() != terms_b.keys() or not terms_a:
        return None
    if not all(c.is_Rational for c in (*terms_a.values(), *terms_b.values())):
        return None
    ratios = {sympy.Rational(terms_a[m]) / sympy.Rational(terms_b[m]) for m in terms_a}
    return ratios.pop() if len(ratios) == 1 else None


@lru_cache(maxsize=4096)
def _expanded(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` expanded (a pure function's memo: the turning conditions of a region are
    compared with every factor of every force of its variants)."""
    return sympy.expand(expr)


def _known_sign(base: sympy.Expr, known: Mapping[sympy.Expr, int]) -> int | None:
    """The sign ``known`` gives ``base`` (an expression equal to it or to its negative):
    expanded sums are canonical, so equal ones are equal terms."""
    expanded = _expanded(base)
    for expr, sign in known.items():
        other = _expanded(expr)
        if expanded == other:
            return sign
        if expanded == -other:
            return -sign
    return None


def without_positive_factors(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` without its provably positive factors, sign kept: m (z1 - z3)/2 > 0 says
    z1 - z3 > 0, and m (z1 - z3 - z2 + z4) = 0 says z1 - z3 - z2 + z4 = 0."""
    if sympy.expand(expr) == 0:
        return sympy.Integer(0)
    sign, parts = factor_expression(expr)
    kept = []
    for base, power in parts:
        s = _poly_sign(base)
        if s in (1, -1):
            sign *= s**power
        else:
            kept.append(base**power)
    return sympy.expand(sign * sympy.Mul(*kept))


def _numerator_times_denominator(expr: sympy.Expr) -> sympy.Expr:
    """A polynomial with the sign of the rational expression ``expr`` (a radius r1**2/r2)."""
    num, den = sympy.fraction(sympy.together(expr))
    return sympy.expand(num * den)


def _slack_substitution(fact: sympy.Expr) -> dict[sympy.Symbol, sympy.Expr] | None:
    """``fact`` > 0 solved for its first symbol with a constant coefficient, the fact's
    value a new positive symbol (None when no symbol has a constant coefficient)."""
    for symbol in sorted_symbols(fact.free_symbols):
        if sympy.degree(fact, symbol) != 1:
            continue
        coefficient = fact.coeff(symbol)
        if coefficient.is_number and coefficient != 0:
            slack = sympy.Dummy("slack", positive=True)
            return {symbol: sympy.expand((slack - (fact - coefficient * symbol)) / coefficient)}
    return None


# The states of one train share their layout's facts: each is prepared once (pure
# functions of immutable expressions, memoised with a bound).
@lru_cache(maxsize=4096)
def _prepared_fact(fact: sympy.Expr) -> sympy.Expr:
    """``fact`` > 0 as a polynomial of its sign without its plainly positive factors."""
    return without_positive_factors(_numerator_times_denominator(fact))


@lru_cache(maxsize=4096)
def _slack_of(fact: sympy.Expr) -> tuple[tuple[sympy.Symbol, sympy.Expr], ...] | None:
    """`_slack_substitution` of ``fact`` as items (its slack symbol shared by every
    oracle that knows the fact)."""
    found = _slack_substitution(fact)
    return None if found is None else tuple(found.items())


class SignOracle:
    """Decides signs of polynomial factors under positivity and known positive facts."""

    def __init__(
        self, facts: Iterable[sympy.Expr] = (), substitutions: Iterable[Mapping[sympy.Symbol, sympy.Expr]] = ()
    ):
        self.facts = tuple(_prepared_fact(f) for f in facts)
        #: Ways to eliminate a symbol with a geometric constraint (r4 -> r2 - r1 + r3).
        self.substitutions = tuple(dict(s) for s in substitutions)
        #: Each fact f > 0 linear in a symbol, solved for it with a positive slack f = e:
        #: a radius 3 r2 - r1 gives r1 -> 3 r2 - e, so 4 r2 - r1 = r2 + e is positive.
        self.slacks = tuple(dict(s) for s in map(_slack_of, self.facts) if s is not None)
        self._decided: dict[sympy.Expr, int | None] = {}  # memo: the same factors recur

    def factor_sign(self, factor: sympy.Expr) -> int | None:
        """Sign of one (irreducible) polynomial factor, or None if undecided."""
        if factor not in self._decided:
            self._decided[factor] = self._factor_sign(factor)
        return self._decided[factor]

    def _factor_sign(self, factor: sympy.Expr) -> int | None:
        sign = _poly_sign(factor)
        if sign is not None:
            return sign
        expanded = _expanded(factor)
        for fact in self.facts:
            # The factor may be a positive multiple of a fact, or of its negative.
            ratio = _constant_ratio(expanded, fact)
            if ratio is not None:
                return 1 if ratio > 0 else -1
        for substitution in self.substitutions + self.slacks:
            # On the constraint the factor may have a plain sign (rr - rp - rs = rp).
            sign = _poly_sign(expanded.subs(substitution))
            if sign in (1, -1):
                return sign
        return None

    def classify(
        self,
        content_sign: int,
        factors: Iterable[tuple[sympy.Expr, int]],
        known: Mapping[sympy.Expr, int] | None = None,
    ) -> tuple[int | None, sympy.Expr]:
        """Sign of ``content_sign * prod(f**e)`` and the product of the undecided odd-power
        factors times the sign of the rest (so that both have the same sign).  ``known``
        gives the signs of some expressions in a region (a variant's turning conditions);
        a factor equal to one of them, or to its negative, takes that sign."""
        total, kept = content_sign, []
        for base, power in factors:
            s = self.factor_sign(base)
            if s is None and known:
                s = _known_sign(base, known)
            if s is None:
                if power % 2:
                    kept.append(base)
            elif s == 0:
                return 0, sympy.Integer(0)
            else:
                total *= s**power
        return (total if not kept else None), total * sympy.Mul(*kept)

    def _factors(self, expr: sympy.Expr) -> tuple[int, list[tuple[sympy.Expr, int]]]:
        num, den = sympy.fraction(sympy.together(expr))
        sign, factors = 1, []
        for part in (num, den):
            content_sign, parts = factor_expression(part)
            sign *= content_sign
            factors += parts
        return sign, factors

    def sign(self, expr: sympy.Expr) -> int | None:
        """Sign of a product/quotient of factors; None if any factor is undecided."""
        return self.classify(*self._factors(expr))[0]
