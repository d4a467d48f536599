"""Square roots of the geometry, kept exact as symbols with a defining relation.

A tilted bevel-planet axis makes the pitch points irrational in the radii: in the
Humpage train, sin of the shaft angle is sqrt(4 r2^2 - (r5 - r1)^2) / (2 r2) (Laus
eqs. (80)-(84)).  Each distinct square root becomes a symbol ``s`` with ``s^2 = m``,
``m`` a square-free integer polynomial that is positive on every admissible design.
The polynomial ring reduces every polynomial modulo ``s^2 - m`` and rationalises
denominators, so zero tests stay exact and results that are rational in the radii
(powers, efficiencies, turning conditions) come out free of ``s``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from itertools import combinations

import sympy

from davies_sym.algebra.flint_conversion import factor
from davies_sym.algebra.polynomials import PolynomialRing
from davies_sym.algebra.screws import Vector, vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.algebra.square_root_symbol import Radical
from davies_sym.algebra.symbol_order import sorted_symbols

__all__ = ["Radical", "RadicalError", "RadicalTable", "has_square_root", "radicals_form_a_field", "restore"]


class RadicalError(ValueError):
    """A square root the table cannot write as ``q * s`` (nested roots, or a factor
    whose sign the known facts do not decide)."""


@dataclass
class RadicalTable:
    """Collects the square roots a layout needs, one symbol per square-free radicand."""

    radicals: list[Radical] = field(default_factory=list)
    #: Expressions known to be positive (an annulus larger than its pinion), for the signs
    #: of the factors a root takes out.
    facts: list[sympy.Expr] = field(default_factory=list)
    #: Symbols the drawing is free to choose (an axis distance left free): a factor in
    #: them whose sign nothing decides is taken positive, the other side being the mirror
    #: drawing, and recorded in ``chosen``.
    free: frozenset[sympy.Symbol] = frozenset()
    #: The factors taken positive by the choice of drawing.
    chosen: list[sympy.Expr] = field(default_factory=list)

    def sqrt(self, value: sympy.Expr) -> sympy.Expr:
        """``sqrt(value)`` of a rational expression positive on the design, as
        ``q * s`` with ``q`` rational and ``s`` a radical symbol (or just ``q``);
        `RadicalError` when it cannot be written so."""
        num, den = sympy.fraction(self.reduce(value))
        if (num * den).free_symbols & {r.symbol for r in self.radicals}:
            raise RadicalError(f"nested square roots: sqrt({self.restore(value)})")
        # sqrt(n / d) = sqrt(n d) / |d|: only the product's square-free part stays inside.
        content, factors = _factor_list(sympy.expand(num * den))
        oracle = SignOracle(self.facts)
        outside, inside = sympy.sqrt(sympy.Abs(content)).as_coeff_Mul()
        inside = inside**2 * (1 if content > 0 else -1)
        for base, exponent in factors:
            if exponent >= 2:
                sign = oracle.factor_sign(base)
                if sign not in (1, -1) and base.free_symbols & self.free:
                    # The drawing's side is recorded in sympy's sign convention for the
                    # factor (leading coefficient positive in lex order).
                    base = base if sympy.Poly(base).LC() > 0 else -base
                    sign = self._choose(base)
                if sign not in (1, -1):
                    raise RadicalError(f"cannot tell the sign of {base} under a square root")
                outside *= (sign * base) ** (exponent // 2)
            inside *= base ** (exponent % 2)
        inside = sympy.expand(inside)
        den_sign = oracle.sign(den)
        if den_sign not in (1, -1):
            raise RadicalError(f"cannot tell the sign of {den} under a square root")
        outside = outside / (den_sign * den)
        if inside == 1:
            return sympy.expand(outside) if outside.is_polynomial() else outside
        return outside * self.symbol_for(inside)

    def _choose(self, base: sympy.Expr) -> int:
        """Draw where ``base`` (in a free symbol of the drawing) is positive: its sign from
        now on, a fact of every design so drawn."""
        self.chosen.append(base)
        self.facts.append(base)
        return 1

    def absorb(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` with every square root written in it (``sqrt(4*r2**2 - ...)``, also
        ``1/sqrt(...)``) replaced by its radical symbol, denominators rationalised."""
        roots = [p for p in sympy.preorder_traversal(expr) if _is_half_power(p)]
        if not roots:
            return expr
        return self.reduce(expr.xreplace({r: self.sqrt(r.base) ** r.exp.p for r in roots}))

    def symbol_for(self, radicand: sympy.Expr) -> sympy.Symbol:
        for radical in self.radicals:
            if sympy.expand(radical.radicand - radicand) == 0:
                return radical.symbol
        symbol = sympy.Symbol(f"sqrt{len(self.radicals) + 1}_", positive=True)
        self.radicals.append(Radical(symbol, radicand))
        return symbol

    def reduce(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` with every power ``s^k`` (k >= 2) replaced by ``m^(k // 2) s^(k % 2)``
        and denominators rationalised: zero exactly when ``expr`` vanishes."""
        symbols = {*expr.free_symbols, *(x for r in self.radicals for x in r.radicand.free_symbols)}
        symbols -= {r.symbol for r in self.radicals}
        # The ring of these radicals reduces and rationalises inside flint; the quotient
        # comes back in lowest terms, numerator and denominator expanded.
        ring = PolynomialRing(symbols, self.radicals)
        value = ring.rational(expr)
        return ring.to_expr(value.num) / ring.to_expr(value.den)

    def reduced(self, components: Iterable[sympy.Expr | int]) -> Vector:
        """The vector of ``components`` (expressions or numbers), each one `reduce`d."""
        return vector([self.reduce(sympy.sympify(x)) for x in components])

    def restore(self, expr: sympy.Expr) -> sympy.Expr:
        """Radical symbols replaced by their square roots (for output)."""
        return restore(expr, self.radicals)


def restore(expr: sympy.Expr, radicals: Iterable[Radical]) -> sympy.Expr:
    """``expr`` with the symbols of ``radicals`` written as the square roots they are."""
    return expr.xreplace({r.symbol: r.expression for r in radicals})


def _factor_list(polynomial: sympy.Expr) -> tuple[sympy.Rational, list[tuple[sympy.Expr, int]]]:
    """The content and irreducible factors of a ``polynomial`` with rational
    coefficients, factored by flint (sympy's ``factor_list`` gives the same up to the
    factors' signs, many times slower in several symbols); the content carries the sign
    of the whole."""
    symbols = sorted_symbols(polynomial.free_symbols)
    if not symbols:
        return sympy.Rational(polynomial), []
    ring = PolynomialRing(symbols)
    integral, denominator = ring.integral(polynomial)
    content, factors = factor(integral)
    return sympy.Rational(content, denominator), [(ring.to_expr(f), e) for f, e in factors]


def _is_half_power(expr: object) -> bool:
    return isinstance(expr, sympy.Pow) and expr.exp.is_Rational and expr.exp.q == 2


def has_square_root(expr: object) -> bool:
    """Whether a sympy expression contains a square root (any power k/2)."""
    return isinstance(expr, sympy.Basic) and any(_is_half_power(p) for p in sympy.preorder_traversal(expr))


def radicals_form_a_field(radicals: Sequence[Radical], most: int = 6) -> bool:
    """Whether adjoining the square roots to the rational functions gives a field of
    degree 2^k: no product of some of the radicands is a square (each a square-free
    polynomial, so a product is a square only where every irreducible factor appears an
    even number of times). False beyond ``most`` radicals, where it is not checked."""
    if len(radicals) > most:
        return False
    odd: list[frozenset[sympy.Expr]] = []
    for r in radicals:
        content, factors = sympy.factor_list(sympy.expand(r.radicand))
        parts = {sympy.Integer(p) for p, e in sympy.factorint(abs(content)).items() if e % 2}
        parts |= {sympy.expand(f) for f, e in factors if e % 2}
        if content < 0:
            parts.add(sympy.Integer(-1))
        odd.append(frozenset(parts))
    for size in range(1, len(odd) + 1):
        for subset in combinations(odd, size):
            parity: set[sympy.Expr] = set()
            for chosen in subset:
                parity.symmetric_difference_update(chosen)
            if not parity:
                return False
    return True
