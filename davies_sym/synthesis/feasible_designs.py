"""The exact rules every design of a search meets before it is scored: dependent tooth
numbers whole and large enough, every tooth number at least the minimum, every speed
ratio within its window, and the train moving as one degree of freedom from its input
(no denominator of the motions vanishing), decided in integers
(`davies_sym.synthesis.rules`), the rational functions prepared once and applied to any
rows of free tooth numbers."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.synthesis import rules
from davies_sym.synthesis.exact_values import ExactRational
from davies_sym.synthesis.problem import SearchProblem

Rows = NDArray[np.int64]


@dataclass(frozen=True)
class ExactRules:
    """The exact rules of ``problem`` for the speed ratios ``ratios`` (one per target, in
    the free tooth numbers)."""

    problem: SearchProblem
    ratios: tuple[ExactRational, ...]
    dependent: tuple[tuple[str, ExactRational], ...]
    #: Polynomials that vanish where the motions do not hold (`state_motion`).
    singular: tuple[ExactRational, ...] = ()

    @classmethod
    def of(
        cls, problem: SearchProblem, ratios: Sequence[sympy.Expr], singular: Sequence[sympy.Expr] = ()
    ) -> ExactRules:
        free = problem.free
        dependent = tuple((str(s), ExactRational.of(e, free)) for s, e in problem.dependent)
        exact = tuple(ExactRational.of(r, free) for r in ratios)
        return cls(problem, exact, dependent, tuple(ExactRational.of(e, free) for e in singular))

    def feasible(self, rows: Rows) -> tuple[Rows, dict[str, Rows]]:
        """The rows (free tooth numbers in ``problem.free``'s order) that meet every rule,
        and every tooth number by name at those rows."""
        teeth = {str(s): rows[:, k] for k, s in enumerate(self.problem.free)}
        columns = list(rows.T)
        keep = np.ones(len(rows), dtype=bool)
        for name, exact in self.dependent:
            whole, value = rules.dependent_whole(exact, columns)
            keep &= whole
            teeth[name] = value
        keep &= rules.enough_teeth(teeth, self.problem.min_teeth)
        for target, exact in zip(self.problem.targets, self.ratios, strict=True):
            keep &= rules.ratio_within(exact, columns, self.problem.window(target))
        for exact in self.singular:
            keep &= rules.moves(exact, columns)
        return rows[keep], {n: t[keep] for n, t in teeth.items()}
