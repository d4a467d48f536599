"""Best-first search over boxes of tooth numbers (branch and bound): the designs of the
highest score, found without scoring every feasible one.

A box of tooth numbers whose windows it cannot meet (their ranges over the box, from
`davies_sym.synthesis.box_bounds`, miss the window) is dropped.  The others are taken
in the order of the highest score they could reach (among equal bounds, the highest
estimate, then the smallest box: a dive to whole designs), and split along their widest
tooth number until a box holds at most `LEAF` designs, which are scored exactly.  The
search ends when no box left can reach the ``keep``-th best score found: then its
answer is the one scoring every design would give.  Its work is bounded: past
``budget`` designs scored and boxes bounded it stops and says so, with the highest
score a design not scored could still reach.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import count

import numpy as np
from numpy.typing import NDArray

#: The most designs in a box scored one by one (a box is split until it holds no more).
LEAF = 4096
#: Boxes taken from the queue together (their designs scored in one vectorised call).
BATCH = 64
#: Designs scored plus boxes bounded before the search stops unfinished.
BUDGET = 2_000_000

Rows = NDArray[np.int64]
Floats = NDArray[np.float64]
#: Which boxes (``low``, ``high``: one row each) the windows may admit.
Possible = Callable[[Floats, Floats], NDArray[np.bool_]]
#: The highest score of any design in each box.
Upper = Callable[[Floats, Floats], Floats]
#: The designs among ``rows`` that count and their exact scores.
Score = Callable[[Rows], tuple[Rows, Floats]]


@dataclass(frozen=True)
class BestFirst:
    """The designs scoring at least the ``keep``-th best score (ties kept), their scores,
    the work done, and the highest score a design not scored could reach: ``-inf`` when
    the search finished (nothing left could reach the kept scores)."""

    rows: Rows
    scores: Floats
    examined: int
    unexplored: float

    @property
    def complete(self) -> bool:
        return self.unexplored == -math.inf


def grid(low: Rows, high: Rows) -> Rows:
    """Every whole point of the box ``low <= x <= high``, one row each."""
    axes = [np.arange(a, b + 1, dtype=np.int64) for a, b in zip(low, high, strict=True)]
    return np.stack([m.reshape(-1) for m in np.meshgrid(*axes, indexing="ij")], axis=1)


def _margin(threshold: float) -> float:
    """How far below the kept scores a bound must fall before its box is dropped."""
    return 1e-9 * max(1.0, abs(threshold)) if math.isfinite(threshold) else 0.0


@dataclass
class Kept:
    """The best designs so far: those scoring at least the ``keep``-th best."""

    keep: int
    rows: Rows
    scores: Floats

    @property
    def threshold(self) -> float:
        return float(np.sort(self.scores)[-self.keep]) if len(self.scores) >= self.keep else -math.inf

    def add(self, rows: Rows, scores: Floats) -> None:
        rows, scores = np.concatenate([self.rows, rows]), np.concatenate([self.scores, scores])
        finite = np.isfinite(scores)
        self.rows, self.scores = rows[finite], scores[finite]
        best = self.threshold
        if math.isfinite(best):
            self.rows, self.scores = self.rows[self.scores >= best], self.scores[self.scores >= best]


def best_first(
    low: Sequence[int],
    high: Sequence[int],
    possible: Possible,
    upper: Upper,
    score: Score,
    keep: int = 1,
    budget: int = BUDGET,
    enough: float = math.inf,
    estimate: Upper | None = None,
) -> BestFirst:
    """The designs within ``low <= x <= high`` (inclusive, whole numbers) of the highest
    ``score``, ties kept (see the module's docstring); the search also ends once the
    ``keep``-th best score reaches ``enough`` (a feasibility probe asks for one design).
    ``estimate`` orders boxes of equal bound (it bounds nothing)."""
    root_low, root_high = np.asarray(low, dtype=np.int64), np.asarray(high, dtype=np.int64)
    kept = Kept(keep, np.zeros((0, len(root_low)), dtype=np.int64), np.zeros(0))
    order = count()
    queue: list[tuple[float, float, int, int, Rows, Rows]] = []

    def enqueue(lows: Rows, highs: Rows) -> int:
        admitted = possible(lows.astype(float), highs.astype(float))
        lows, highs = lows[admitted], highs[admitted]
        if len(lows):
            bounds = upper(lows.astype(float), highs.astype(float))
            guesses = estimate(lows.astype(float), highs.astype(float)) if estimate else np.zeros(len(lows))
            sizes = np.prod(highs - lows + 1, axis=1)
            for a, b, u, g, n in zip(lows, highs, bounds, guesses, sizes, strict=True):
                heapq.heappush(queue, (-float(u), -float(g), int(n), next(order), a, b))
        return len(admitted)

    work = enqueue(root_low[None, :], root_high[None, :])
    while queue and work < budget and kept.threshold < enough:
        threshold = kept.threshold
        if -queue[0][0] < threshold - _margin(threshold):
            queue.clear()  # no box left can reach the kept scores
            break
        batch: list[tuple[float, float, int, int, Rows, Rows]] = []
        while queue and len(batch) < BATCH and -queue[0][0] >= threshold - _margin(threshold):
            batch.append(heapq.heappop(queue))
        sizes = [int(np.prod(b - a + 1)) for *_, a, b in batch]
        leaves = [(a, b) for (*_, a, b), n in zip(batch, sizes, strict=True) if n <= LEAF]
        if leaves:
            rows = np.concatenate([grid(a, b) for a, b in leaves])
            kept.add(*score(rows))
            work += len(rows)
        split = [(a, b) for (*_, a, b), n in zip(batch, sizes, strict=True) if n > LEAF]
        if split:
            lows, highs = [], []
            for a, b in split:
                axis = int(np.argmax(b - a))
                middle = (a[axis] + b[axis]) // 2
                lows += [a, np.where(np.arange(len(a)) == axis, middle + 1, a)]
                highs += [np.where(np.arange(len(b)) == axis, middle, b), b]
            work += enqueue(np.array(lows), np.array(highs))
    threshold = kept.threshold
    unexplored = max((-entry[0] for entry in queue if -entry[0] >= threshold - _margin(threshold)), default=-math.inf)
    return BestFirst(kept.rows, kept.scores, work, unexplored)
