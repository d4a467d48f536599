"""Exact forms kept small without changing a value: a wrench moment that is a quotient
is one numerator over one denominator (`network.screw_system.expanded`), and a
polynomial factored once is looked up after (`algebra.flint_conversion.factor`)."""

from __future__ import annotations

import random

import sympy
from flint import fmpz_mpoly_ctx

from davies_sym.algebra.flint_conversion import factor
from davies_sym.network.screw_system import expanded

r1, r2, r3, s1 = sympy.symbols("r1 r2 r3 sqrt1_", positive=True)


def _at_random_points(a: sympy.Expr, b: sympy.Expr, symbols: tuple[sympy.Symbol, ...]) -> None:
    rng = random.Random(7)
    for _ in range(20):
        point = {s: sympy.Rational(rng.randint(1, 97), rng.randint(1, 13)) for s in symbols}
        assert sympy.nsimplify(a.subs(point) - b.subs(point)) == 0, point


def test_a_quotient_stays_one_fraction_of_the_same_value() -> None:
    """A moment about a point placed by a triangle: products of sums over a squared sum.
    ``sympy.expand`` spreads the denominator over every term; the compact form is the
    reduced numerator over the denominator, equal at every rational point."""
    moment = (r1**2 * s1 + 2 * r1 * r2 * s1 - r3**2) * (r2 * s1 - r3 * r1 + 3) / (r1 * r3 + r2**2 + r3) ** 2 - (
        r1 + r2 * s1
    ) * (r2 - r3) / (r1 * r3 + r2**2 + r3)
    compact = expanded(moment)
    num, den = sympy.fraction(compact)
    assert den != 1 and not any(p.exp.is_negative for p in num.atoms(sympy.Pow))
    assert sympy.count_ops(compact) < sympy.count_ops(sympy.expand(moment))
    _at_random_points(compact, moment, (r1, r2, r3, s1))


def test_a_polynomial_stays_expanded_as_before() -> None:
    poly = (r1 + 2 * r2) * (r3 - s1) ** 2
    assert expanded(poly) == sympy.expand(poly)


def test_a_factorisation_looked_up_is_the_one_found_and_cannot_be_spoilt() -> None:
    ctx = fmpz_mpoly_ctx.get(("x", "y"))
    x, y = ctx.gens()
    p = 6 * (x + y) ** 2 * (x - 2 * y)
    first = factor(p)
    assert first[0] == 6 and sorted((str(f), e) for f, e in first[1]) == [("x + y", 2), ("x - 2*y", 1)]
    first[1].clear()  # a caller's list is its own: the memo keeps its factors
    again = factor(6 * (x + y) ** 2 * (x - 2 * y))
    assert again[0] == 6 and len(again[1]) == 2
    product = again[0] * (again[1][0][0] ** again[1][0][1]) * (again[1][1][0] ** again[1][1][1])
    assert product == p
