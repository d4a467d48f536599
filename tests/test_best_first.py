"""The best-first search over boxes of tooth numbers: the ranges it prunes by contain
every value (checked in exact rationals at every whole point of random boxes), and its
answer is the brute-force answer wherever it says it finished; where its budget stops
it, no design it did not keep scores above the bound it gives."""

from __future__ import annotations

import functools
import itertools
import math
import random
from fractions import Fraction

import numpy as np
import pytest
import sympy

from davies_sym.synthesis import best_first as bf
from davies_sym.synthesis.box_bounds import WIDENING, PolynomialRange, RationalRange

X = sympy.symbols("x0:3", positive=True)


def _random_polynomial(rng: random.Random, degree: int = 3, terms: int = 6) -> sympy.Expr:
    out = sympy.Integer(0)
    for _ in range(terms):
        exponents = [rng.randint(0, degree) for _ in X]
        out += rng.randint(-9, 9) * sympy.Mul(*(x**e for x, e in zip(X, exponents, strict=True)))
    return out


@functools.cache
def _integer_parts(expression: sympy.Expr):  # type: ignore[no-untyped-def]
    """The numerator and denominator as functions of whole numbers in Python integers."""
    numerator, denominator = sympy.fraction(sympy.together(expression))
    return sympy.lambdify(X, numerator, modules=[]), sympy.lambdify(X, denominator, modules=[])


def _exact(expression: sympy.Expr, point: tuple[int, ...]) -> Fraction | None:
    """The value in exact rationals (None at a pole), independent of the ranges' floats."""
    numerator, denominator = _integer_parts(expression)
    below = denominator(*point)
    return None if below == 0 else Fraction(numerator(*point), below)


def _random_boxes(rng: random.Random, expression: sympy.Expr, bounds, corner: int, width: int):  # type: ignore[no-untyped-def]
    """Five random boxes: each one's low corner, the range claimed over it, and the exact
    value at each of its whole points."""
    for _ in range(5):
        low = [rng.randint(1, corner) for _ in X]
        high = [a + rng.randint(0, width) for a in low]
        least, greatest = bounds.range(np.array([low], dtype=float), np.array([high], dtype=float))
        points = itertools.product(*(range(a, b + 1) for a, b in zip(low, high, strict=True)))
        yield low, least[0], greatest[0], [_exact(expression, point) for point in points]


@pytest.mark.parametrize("seed", range(8))
def test_a_polynomials_range_holds_every_whole_point_of_the_box(seed: int) -> None:
    """P+(lo) - P-(hi) <= P <= P+(hi) - P-(lo) on positive boxes, the values in exact
    rationals; exact (up to the widening) at a single point."""
    rng = random.Random(seed)
    p = _random_polynomial(rng)
    bounds = PolynomialRange.of(p, X)
    for low, least, greatest, values in _random_boxes(rng, p, bounds, 12, 3):
        assert all(least <= value <= greatest for value in values)
        at = np.array([low], dtype=float)
        single = bounds.range(at, at)
        magnitude = sum(abs(float(t.subs(dict(zip(X, low, strict=True))))) for t in sympy.Add.make_args(p)) + 1
        exact = float(_exact(p, tuple(low)))
        assert single[0][0] <= exact <= single[1][0]
        assert single[1][0] - single[0][0] <= 2.01 * WIDENING * magnitude  # only the widening


@pytest.mark.parametrize("seed", range(8))
def test_a_quotients_range_holds_wherever_its_denominator_keeps_a_sign(seed: int) -> None:
    rng = random.Random(100 + seed)
    f = _random_polynomial(rng) / (_random_polynomial(rng, 2, 3) + 40)
    bounds = RationalRange.of(f, X)
    for _, least, greatest, values in _random_boxes(rng, f, bounds, 8, 2):
        for value in values:
            if value is None:  # a pole at a whole point: the range must claim nothing
                assert (least, greatest) == (-math.inf, math.inf)
            else:
                assert least <= value <= greatest


@pytest.fixture(autouse=True)
def _small_leaves(monkeypatch: pytest.MonkeyPatch) -> None:
    """Boxes of 1728 designs split many times before they are scored."""
    monkeypatch.setattr(bf, "LEAF", 8)


def _problem(seed: int):  # type: ignore[no-untyped-def]
    """A score (a rational function of three numbers in 1..12, -inf outside a window of
    another) with its exact values at every point: the brute-force oracle."""
    rng = random.Random(seed)
    score = (_random_polynomial(rng, 2, 4) + 200) / (_random_polynomial(rng, 1, 3) + 60)
    window = X[0] * X[1] - 2 * X[2]
    low, high = rng.randint(0, 20), rng.randint(40, 80)
    values = {}
    for point in itertools.product(range(1, 13), repeat=3):
        w = _exact(window, point)
        value = _exact(score, point)
        if low <= w <= high and value is not None:
            values[point] = float(value)
    score_range, window_range = RationalRange.of(score, X), RationalRange.of(window, X)

    def possible(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        least, greatest = window_range.range(a, b)
        return (greatest >= low) & (least <= high)

    def upper(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return score_range.range(a, b)[1]

    def scored(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        kept = [r for r in rows if tuple(int(v) for v in r) in values]
        found = np.array(kept, dtype=np.int64).reshape(len(kept), 3)
        return found, np.array([values[tuple(int(v) for v in r)] for r in found], dtype=float)

    return values, possible, upper, scored


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("keep", [1, 3])
def test_a_finished_search_keeps_what_scoring_every_design_keeps(seed: int, keep: int) -> None:
    values, possible, upper, scored = _problem(seed)
    result = bf.best_first([1, 1, 1], [12, 12, 12], possible, upper, scored, keep)
    assert result.complete
    ranked = sorted(values.values(), reverse=True)
    threshold = ranked[keep - 1]
    expected = sorted(p for p, v in values.items() if v >= threshold)
    assert sorted(tuple(int(v) for v in r) for r in result.rows) == expected


@pytest.mark.parametrize("seed", range(6))
def test_a_search_stopped_by_its_budget_bounds_what_it_did_not_score(seed: int) -> None:
    """Any design scoring above the best kept lies within the bound it reports."""
    values, possible, upper, scored = _problem(seed)
    result = bf.best_first([1, 1, 1], [12, 12, 12], possible, upper, scored, 1, budget=200)
    best = max(result.scores, default=-math.inf)
    better = [v for v in values.values() if v > best + 1e-12]
    if result.complete:
        assert not better
    else:
        assert all(v <= result.unexplored for v in better)
    assert result.examined <= 200 + bf.BATCH * 2 * bf.LEAF


@pytest.mark.parametrize("seed", range(4))
def test_the_probe_stops_at_a_design_and_proves_an_empty_window_empty(seed: int) -> None:
    values, possible, _, scored = _problem(seed)

    def flat(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.ones(len(a))

    def feasible(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        found, _ = scored(rows)
        return found, np.ones(len(found))

    found = bf.best_first([1, 1, 1], [12, 12, 12], possible, flat, feasible, 1, enough=1.0)
    assert bool(len(found.rows)) == bool(values)
    if len(found.rows):
        assert all(tuple(int(v) for v in r) in values for r in found.rows)
    # Nothing in a window no point meets: the whole box is pruned or scored empty.
    empty = bf.best_first([1, 1, 1], [12, 12, 12], lambda a, b: possible(a, b) & False, flat, feasible, 1)
    assert empty.complete and not len(empty.rows)
