"""The best designs of a search found best-first (`davies_sym.synthesis.best_first`),
for trains whose free tooth numbers are too many to enumerate every feasible design.

The windows prune boxes of tooth numbers by their rigorous ranges over the box
(`davies_sym.synthesis.box_bounds`); the score of a box is bounded by the variants:
where a design runs its efficiency is one of its state's variants (Laus Tables 5 and 6)
and at most 1, so the largest of the variants' upper bounds, capped at 1, bounds it.  A
design is scored by the same exact rules and formula modules as the whole enumeration
(`davies_sym.synthesis.tooth_search`), so a search that finishes keeps exactly the
designs that enumeration keeps.

Over wide boxes those ranges are loose (the terms of an efficiency's numerator and
denominator cancel), so with many free tooth numbers the bound prunes little: the
search is led by estimates (the score at a box's centre), and where its budget stops it,
a climb scores the neighbourhoods of its best design whole while that improves.  Its
answer is then the best design it scored, said so with the bound it could not close.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.synthesis.best_first import BUDGET, BestFirst, Kept, Score, Upper, best_first, grid
from davies_sym.synthesis.box_bounds import RationalRange
from davies_sym.synthesis.design_enumeration import SLACK, Table, WindowFilter
from davies_sym.synthesis.feasible_designs import ExactRules
from davies_sym.synthesis.formulas import StateFormulas
from davies_sym.synthesis.planet_sets import planet_sets
from davies_sym.synthesis.problem import SearchProblem
from davies_sym.synthesis.tooth_search import design_scores, planet_filtered, windows

Rows = NDArray[np.int64]
Floats = NDArray[np.float64]


@dataclass(frozen=True)
class BoundedDesigns:
    """What `ratio_feasible` gives (rows of free tooth numbers, every tooth number by
    name, the work done), for the best designs only, and the highest score a design
    the search did not score could reach (``-inf``: the search finished)."""

    rows: Rows
    teeth: dict[str, Rows]
    examined: int
    unexplored: float

    @property
    def feasible(self) -> tuple[Rows, dict[str, Rows], int]:
        return self.rows, self.teeth, self.examined


class _Windows:
    """The windows as a test of boxes (their ranges) and of rows (floats, then exact)."""

    def __init__(
        self, problem: SearchProblem, ratios: Sequence[sympy.Expr], singular: Sequence[sympy.Expr] = ()
    ) -> None:
        self.free = problem.free
        found = windows(problem, ratios)
        self.ranges = [(RationalRange.of(w.expression, self.free), w.low, w.high) for w in found]
        self.rows_test = WindowFilter(found)
        self.exact = ExactRules.of(problem, ratios, singular)
        self.dependent = [(str(d), sympy.lambdify(self.free, e, "numpy")) for d, e in problem.dependent]

    def centres(self, low: Floats, high: Floats) -> dict[str, Floats]:
        """Every tooth number by name at each box's centre (not whole: an estimate's point)."""
        middle = (low + high) / 2
        teeth = {str(s): middle[:, k] for k, s in enumerate(self.free)}
        for name, function in self.dependent:
            teeth[name] = np.broadcast_to(np.asarray(function(*middle.T), dtype=float), (len(low),))
        return teeth

    def miss(self, low: Floats, high: Floats) -> Floats:
        """How far each box's centre lies outside the windows (0: inside), relative to each
        window's bound: what leads a dive towards feasible designs."""
        middle = {s: (low[:, k] + high[:, k]) / 2 for k, s in enumerate(self.free)}
        total = np.zeros(len(low))
        for _, symbols, function, lowest, highest in self.rows_test.tests:
            with np.errstate(all="ignore"):
                value = np.broadcast_to(np.asarray(function(*(middle[x] for x in symbols)), dtype=float), (len(low),))
            outside = np.maximum(lowest - value, 0) / max(abs(lowest), 1) if math.isfinite(lowest) else 0
            outside = outside + (np.maximum(value - highest, 0) / max(abs(highest), 1) if math.isfinite(highest) else 0)
            total += np.where(np.isfinite(value), outside, 1.0)
        return total

    def possible(self, low: Floats, high: Floats) -> NDArray[np.bool_]:
        ok = np.ones(len(low), dtype=bool)
        for expression, lowest, highest in self.ranges:
            least, greatest = expression.range(low, high)
            ok &= (greatest >= lowest - SLACK * abs(lowest)) & (least <= highest + SLACK * abs(highest))
        return ok

    def feasible(self, rows: Rows) -> tuple[Rows, dict[str, Rows]]:
        return self.exact.feasible(self.rows_test(Table(self.free, rows)).rows)


def _bounds(problem: SearchProblem) -> tuple[list[int], list[int]]:
    return [problem.bounds[s][0] for s in problem.free], [problem.bounds[s][1] for s in problem.free]


def ratio_reachable(
    problem: SearchProblem, ratios: Sequence[sympy.Expr], singular: Sequence[sympy.Expr] = (), budget: int = BUDGET
) -> bool | None:
    """Whether some design meets every exact rule of the ratios (best-first, stopping at
    the first): None where the budget ran out before it was decided."""
    test = _Windows(problem, ratios, singular)

    def score(rows: Rows) -> tuple[Rows, Floats]:
        found, _ = test.feasible(rows)
        return found, np.ones(len(found))

    def unbounded(low: Floats, high: Floats) -> Floats:
        return np.ones(len(low))

    def closeness(low: Floats, high: Floats) -> Floats:
        return -test.miss(low, high)

    result = best_first(*_bounds(problem), test.possible, unbounded, score, 1, budget, 1.0, closeness)
    return True if len(result.rows) else (False if result.complete else None)


def _upper(formulas: Sequence[StateFormulas], free: tuple[sympy.Symbol, ...]) -> Upper:
    """The bound of the score over boxes: per state the largest variant bound, capped at
    1 (a running design's efficiency is at most 1), weighted as the score is."""
    weights = np.array([f.target.weight for f in formulas], dtype=float)
    variants = [[RationalRange.of(v, free) for v in f.variants] for f in formulas]

    def upper(low: Floats, high: Floats) -> Floats:
        per_state = []
        for ranges in variants:
            bound = np.full(len(low), -np.inf) if ranges else np.ones(len(low))
            for r in ranges:
                bound = np.maximum(bound, r.range(low, high)[1])
            per_state.append(np.minimum(bound, 1.0))
        return np.asarray(weights @ np.stack(per_state) / weights.sum(), dtype=float)

    return upper


def best_designs(
    problem: SearchProblem, formulas: Sequence[StateFormulas], keep: int, budget: int = BUDGET
) -> BoundedDesigns:
    """The designs whose score reaches the ``keep``-th best (ties kept), found best-first."""
    test = _Windows(problem, [f.ratio for f in formulas], [x for f in formulas for x in f.singular])
    whole_train = resolved_train(problem.train)
    sets = planet_sets(whole_train, train_layout(whole_train))

    def score(rows: Rows) -> tuple[Rows, Floats]:
        found, teeth = planet_filtered(problem, sets, *test.feasible(rows))
        return found, design_scores(formulas, teeth) if len(found) else np.zeros(0)

    def promise(low: Floats, high: Floats) -> Floats:
        """The score at the box's centre where it meets the windows, else how far it misses."""
        missed = test.miss(low, high)
        guess = design_scores(formulas, test.centres(low, high))
        return np.where(missed == 0, np.where(np.isfinite(guess), guess, -0.5), -1 - missed)

    low, high = _bounds(problem)
    result: BestFirst = best_first(
        low, high, test.possible, _upper(formulas, problem.free), score, keep, budget, math.inf, promise
    )
    if not result.complete:
        result = _climbed(result, np.array(low), np.array(high), score, keep, budget)
    rows, teeth = test.exact.feasible(result.rows)
    return BoundedDesigns(rows, teeth, result.examined, result.unexplored)


#: The most designs of one neighbourhood a climb scores at once.
NEIGHBOURHOOD = 250_000


def _climbed(found: BestFirst, low: Rows, high: Rows, score: Score, keep: int, budget: int) -> BestFirst:
    """``found`` improved by climbing: the designs within a few teeth of the best one
    scored whole, moving to the best of them while that scores higher, within ``budget``
    (a search stopped at its budget has dived where the estimates led, and the best
    design of a smooth efficiency lies near the best it scored)."""
    if not len(found.rows):
        return found
    reach = max(1, int((NEIGHBOURHOOD ** (1 / len(low)) - 1) // 2))
    kept, work = Kept(keep, found.rows, found.scores), found.examined
    while work < 2 * budget:
        centre = kept.rows[int(np.argmax(kept.scores))]
        near = grid(np.maximum(centre - reach, low), np.minimum(centre + reach, high))
        more, values = score(near)
        work += len(near)
        if not len(values) or values.max() <= kept.scores.max():
            break
        kept.add(more, values)
    return BestFirst(kept.rows, kept.scores, work, found.unexplored)
