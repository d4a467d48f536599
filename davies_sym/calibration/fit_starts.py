"""A fit from several start points (``derive calibrate --starts N``): a least-squares fit
of loss parameters can stop in a local minimum, so the fit is repeated from start points
spread over the parameters' ranges and the least sum of squares kept; how many starts
reached it says whether the answer depends on where the fit began.

The first start is the file's own (``calibrate: start``, else the defaults); the others
are a scrambled Sobol sequence (``scipy.stats.qmc``, seeded: the same points on every
run) over an ordinary efficiency's range [0.5, 1) and a coefficient's [0, 10 x its
start].  The starts go out in groups, one group a task, through the project's fan-out:
a worker derives the train once per group."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.stats import qmc

from davies_sym.calibration.least_squares import Fit
from davies_sym.errors import CalibrationError, FitFailure

#: Two fits reached the same minimum when their sums of squares agree to this (relative).
SAME_MINIMUM = 1e-6
#: The range of an ordinary efficiency's start values, and a coefficient's as a multiple of its start.
EFFICIENCY_STARTS, COEFFICIENT_SPAN = (0.5, 1.0), 10.0


@dataclass(frozen=True)
class FitBounds:
    """The parameters fitted, their start values and bounds, and which are ordinary
    efficiencies (the rest are coefficients >= 0)."""

    fitted: tuple[str, ...]
    start: Mapping[str, float]
    lower: Mapping[str, float]
    upper: Mapping[str, float]
    efficiencies: frozenset[str]


@dataclass(frozen=True)
class StartFailure:
    """Why the fit from one start gave no answer (a `CalibrationError`'s message and cause)."""

    message: str
    cause: FitFailure | None


@dataclass(frozen=True)
class MultiStart:
    """The fit with the least sum of squares over ``tried`` starts: ``converged`` of them
    gave a fit, ``at_best`` of those reached its sum of squares, and ``other_rms`` lists
    the rms of the other minima found (a local minimum each), least first."""

    best: Fit
    tried: int
    converged: int
    at_best: int
    other_rms: tuple[float, ...]

    def as_dict(self) -> dict[str, object]:
        """JSON-ready counts."""
        return {
            "tried": self.tried,
            "converged": self.converged,
            "at_best": self.at_best,
            "other_minima_rms": list(self.other_rms),
        }

    def text(self) -> str:
        """One line for the text answer."""
        line = f"starts: {self.tried} tried, {self.converged} converged, {self.at_best} reached the least rms"
        if self.other_rms:
            shown = ", ".join(f"{r:.3g}" for r in self.other_rms[:5])
            line += f"; other minima at rms {shown}"
        return line + "\n"


def start_points(bounds: FitBounds, count: int) -> tuple[dict[str, float], ...]:
    """``count`` start points: the file's start, then Sobol points over the ranges."""
    first = {n: float(bounds.start[n]) for n in bounds.fitted}
    if count <= 1:
        return (first,)
    sampler = qmc.Sobol(d=len(bounds.fitted), scramble=True, seed=0)
    # Sobol points come in powers of two; the first count - 1 of the next one are used.
    unit = sampler.random(2 ** math.ceil(math.log2(count - 1)) if count > 2 else 1)[: count - 1]
    points = [first]
    for row in unit:
        point = {}
        for name, u in zip(bounds.fitted, row, strict=True):
            low, high = EFFICIENCY_STARTS if name in bounds.efficiencies else (0.0, COEFFICIENT_SPAN * first[name])
            point[name] = float(min(max(low + (high - low) * u, bounds.lower[name]), bounds.upper[name]))
        points.append(point)
    return tuple(points)


def start_groups(points: Sequence[dict[str, float]], groups: int) -> tuple[tuple[dict[str, float], ...], ...]:
    """The points in ``groups`` runs of consecutive points (fewer when there are fewer points)."""
    groups = max(1, min(groups, len(points)))
    size = math.ceil(len(points) / groups)
    return tuple(tuple(points[k : k + size]) for k in range(0, len(points), size))


def best_of(results: Sequence[Fit | StartFailure]) -> MultiStart:
    """The least-squares fit among ``results`` (a `Fit` per start, or why it failed),
    refused (`CalibrationError`, the first start's reason) when none converged."""
    fits = [r for r in results if isinstance(r, Fit)]
    if not fits:
        first = results[0]
        assert isinstance(first, StartFailure)
        raise CalibrationError(first.message, first.cause)
    squares = [float(np.sum(f.residuals * f.residuals)) for f in fits]
    best = int(np.argmin(squares))
    least = squares[best]
    same = [abs(s - least) <= SAME_MINIMUM * max(least, 1e-300) for s in squares]
    others: list[float] = []
    for fit, alike in sorted(zip(fits, same, strict=True), key=lambda pair: pair[0].rms):
        if not alike and all(abs(fit.rms - r) > SAME_MINIMUM * r for r in others):
            others.append(fit.rms)
    return MultiStart(fits[best], len(results), len(fits), sum(same), tuple(others))
