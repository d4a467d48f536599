"""Reduction modulo the radicals (`PolynomialRing.reduce`: s^2 = m for each radical s)
against sympy's polynomial remainder by s^2 - m in s, which shares none of its
arithmetic: on random polynomials of degree up to six in two radicals, the result is
the same, of degree at most one in each radical."""

from __future__ import annotations

import random

import pytest
import sympy

from davies_sym.algebra.polynomials import PolynomialRing
from davies_sym.algebra.square_root_symbol import Radical

A, B, C = sympy.symbols("a b c", positive=True)
S, T = sympy.symbols("s t", positive=True)
RADICALS = (Radical(S, A**2 + 3 * B), Radical(T, 2 * C - A * B + 5))


def _random_polynomial(rng: random.Random) -> sympy.Expr:
    terms = []
    for _ in range(rng.randint(1, 12)):
        coefficient = rng.choice([-7, -2, -1, 1, 3, 11])
        monomial = sympy.Mul(*(x ** rng.randint(0, 2) for x in (A, B, C)))
        terms.append(coefficient * monomial * S ** rng.randint(0, 6) * T ** rng.randint(0, 5))
    return sympy.Add(*terms)


@pytest.mark.parametrize("seed", range(60))
def test_reduction_equals_the_remainder_by_each_radicals_relation(seed: int) -> None:
    rng = random.Random(seed)
    ring = PolynomialRing([A, B, C], RADICALS)
    expr = _random_polynomial(rng)
    expected = expr
    for r in RADICALS:
        expected = sympy.rem(sympy.expand(expected), r.symbol**2 - r.radicand, r.symbol)
    got = ring.reduce(ring.polynomial(expr))
    assert got == ring.polynomial(sympy.expand(expected))
    for r in RADICALS:
        assert got.degrees()[ring.symbols.index(r.symbol)] <= 1


@pytest.mark.parametrize("seed", range(20))
def test_a_root_both_sides_share_cancels_before_any_conjugate(seed: int) -> None:
    """A quotient whose value does not depend on the roots (as an efficiency does not
    depend on where a free planet axis is drawn): ``(p h) / (q h)`` with ``h`` carrying
    both roots comes out as ``p / q`` itself, the root-free p and q built here, not
    ``p h h' / (q h h')`` with the conjugates multiplied in."""
    rng = random.Random(seed)
    ring = PolynomialRing([A, B, C], RADICALS)
    p, q = (sympy.Add(*(rng.choice([-3, 1, 2]) * x ** rng.randint(0, 2) for x in (A, B, C))) for _ in "pq")
    h = 1 + A * S + B * T + rng.randint(1, 4) * C * S * T
    num, den = ring.rationalised(ring.polynomial(sympy.expand(p * h)), ring.polynomial(sympy.expand(q * h)))
    # The same value, p / q, in the same terms up to the sign of both sides.
    assert num * ring.polynomial(q) == den * ring.polynomial(p)
    assert {len(num), len(den)} <= {len(ring.polynomial(p)), len(ring.polynomial(q))} | {0}
    assert all(num.degrees()[ring.symbols.index(r.symbol)] == 0 for r in RADICALS)
