"""Factored elimination (`davies_sym.algebra.factored`) against the expanded one
(`davies_sym.algebra.linalg.gauss_jordan`), which shares none of its arithmetic: on random
sparse systems of products of small polynomials, both give the same solution, the known
factorisation of every solution entry is exactly what flint's ``factor`` gives for the
expanded numerator and denominator (same content, factors and order, so the printed
formulas do not change), and products of rational functions formed factor by factor
equal the expanded products."""

from __future__ import annotations

import random

import pytest
import sympy

from davies_sym.algebra.factored import factored_gauss_jordan
from davies_sym.algebra.flint_conversion import factor
from davies_sym.algebra.linalg import gauss_jordan
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction

SYMBOLS = sympy.symbols("a b c d e", positive=True)


def _random_entry(ring: PolynomialRing, rng: random.Random):
    """A product of one to three small random polynomials (stages multiply), or a number."""
    if rng.random() < 0.4:
        return ring.one * rng.choice([-2, -1, 1, 1, 3])
    out = ring.one * rng.choice([-1, 1, 2])
    for _ in range(rng.randint(1, 3)):
        terms = {}
        for _ in range(rng.randint(1, 3)):
            monom = tuple(rng.randint(0, 1) for _ in SYMBOLS)
            terms[monom] = rng.choice([-3, -1, 1, 2])
        factor_poly = ring.ctx.from_dict(terms)
        if not factor_poly.is_zero():
            out = out * factor_poly
    return out


def _system(seed: int):
    rng = random.Random(seed)
    ring = PolynomialRing(SYMBOLS)
    n = rng.randint(3, 6)
    rows = []
    for _ in range(n - 1):
        row = {}
        for c in rng.sample(range(n), rng.randint(2, min(4, n))):
            row[c] = _random_entry(ring, rng)
        rows.append(row)
    return ring, rows, n


@pytest.mark.parametrize("seed", range(40))
def test_factored_and_expanded_elimination_agree(seed: int) -> None:
    ring, rows, n = _system(seed)
    plain = gauss_jordan([dict(r) for r in rows], n, prefer_free=[0])
    factored = factored_gauss_jordan([dict(r) for r in rows], n, ring.one, prefer_free=[0])
    assert factored.free == plain.free
    expected, got = plain.solution(ring), factored.solution(ring)
    for col in range(n):
        assert got[col].keys() == expected[col].keys(), col
        for j, value in got[col].items():
            assert value == expected[col][j]
            # Lowest terms, positive leading coefficient of the denominator: the same
            # numerator and denominator, and the factorisation flint gives for them.
            assert value.num == expected[col][j].num and value.den == expected[col][j].den
            (cn, fn), (cd, fd) = value.factorisation
            assert (cn, fn) == factor(value.num)
            assert (cd, fd) == factor(value.den)


@pytest.mark.parametrize("seed", range(40))
def test_products_by_factors_equal_expanded_products(seed: int) -> None:
    ring, rows, n = _system(seed)
    solution = factored_gauss_jordan(rows, n, ring.one, prefer_free=[0]).solution(ring)
    # Kept small: the check multiplies out and factors the products the plain way.
    values = [v for col in range(n) for v in solution[col].values() if not v.is_zero() and len(v.num) + len(v.den) < 60]
    if not values:
        pytest.skip("no small entry in this system")
    rng = random.Random(seed)
    small = RationalFunction.make(ring, ring.gen(SYMBOLS[0]) + 2, ring.gen(SYMBOLS[1]) * 3)
    for _ in range(5):
        a = rng.choice(values)
        b = rng.choice([*values, small])
        product = a * b
        plain = RationalFunction.make(ring, a.num * b.num, a.den * b.den)
        assert product.num == plain.num and product.den == plain.den
        assert product.factorisation == (factor(plain.num), factor(plain.den))
        assert product.to_expr() == plain.to_expr()
        assert (a / b) * b == a
        assert (-a).factorisation == (factor(-a.num), factor(a.den))
