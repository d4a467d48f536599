"""The joins of `davies_sym.synthesis.design_enumeration` against the blind product of
the tooth-number ranges, which shares none of their code: the same designs, also where
a window no assignment meets leaves an empty table to join (a train of the 7-link atlas,
atlas7_r92_d24, asks for a ratio one of its states cannot reach within the bounds)."""

from __future__ import annotations

import itertools
import random

import pytest
import sympy

from davies_sym.synthesis.design_enumeration import Window, enumerate_designs

A, B, C, D = sympy.symbols("za zb zc zd", positive=True)


def _blind(free, bounds, windows) -> set[tuple[int, ...]]:
    """Every assignment of the ranges that every window admits, one by one."""
    out = set()
    for values in itertools.product(*(range(bounds[s][0], bounds[s][1] + 1) for s in free)):
        point = dict(zip(free, values, strict=True))
        if all(w.low <= float(w.expression.subs(point)) <= w.high for w in windows):
            out.add(values)
    return out


def _found(free, bounds, windows) -> set[tuple[int, ...]]:
    enumeration = enumerate_designs(free, bounds, windows)
    return {tuple(int(v) for v in row) for row in enumeration.candidates}


def test_a_window_no_assignment_meets_joins_to_no_design() -> None:
    """za / zb reaches at most 40 / 5 = 8 within the bounds: its table, made after the
    smaller one of zb + zc, is empty, and joining the two on zb must give no design."""
    free = (A, B, C)
    bounds = {A: (5, 40), B: (5, 12), C: (5, 12)}
    windows = [Window(A / B, 9.0, 10.0), Window(B + C, 10.0, 14.0)]
    assert _blind(free, bounds, windows) == set()
    assert _found(free, bounds, windows) == set()


@pytest.mark.parametrize("seed", range(12))
def test_random_windows_give_the_blind_products_designs(seed: int) -> None:
    rng = random.Random(seed)
    free = (A, B, C, D)
    bounds = {s: (rng.randint(3, 6), rng.randint(8, 11)) for s in free}
    shapes = [A / B, B * C / (A * D), C + D - A, (A + B) / D, C / D]
    windows = []
    for expression in rng.sample(shapes, 3):
        centre = rng.uniform(0.2, 3.0) if expression.is_Mul or expression.is_Pow else rng.uniform(-4, 12)
        windows.append(Window(expression, centre * 0.8 if centre > 0 else centre - 2, centre * 1.2 + 1))
    assert _found(free, bounds, windows) == _blind(free, bounds, windows)
