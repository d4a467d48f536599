"""The floating-point screen of the shift search: the speed ratio of many combinations of
engaged elements at once, for one train or for many kinematic classes of tooth designs,
so that the exact (rational) evaluation runs only where a target is in reach.

A gear's motion is the null vector of its engaged elements' equations (``engaged`` rows
of ``freedom`` columns, one fewer rows than columns): by Cramer's rule its components
are the signed maximal minors, ``(-1)**j det(rows without column j)``, evaluated for a
whole stack of combinations by ``numpy.linalg.det``.  A singular combination (a
redundant element) gives the zero vector and no ratio.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from numpy.typing import NDArray

Floats = NDArray[np.float64]

#: Relative slack of the screen: a ratio is in reach when within the tolerance widened
#: by this much (far beyond the rounding of the minors of small whole numbers; the exact
#: evaluation decides).
SLACK = 1e-6
#: Floats one batch of the screen holds at most (classes x combinations x rows x columns).
BATCH_FLOATS = 2_000_000


def combination_ratios(elements: Floats, into: Floats, out: Floats, combos: NDArray[np.int64]) -> Floats:
    """Input over output speed of every combination (rows of ``combos``, indices into the
    elements) in every class: ``elements`` is classes x elements x freedom (each
    element's equation), ``into`` and ``out`` classes x freedom (the ports' speeds).
    NaN or infinite where the combination leaves no single motion or a port stands."""
    classes, _, freedom = elements.shape
    engaged = combos.shape[1]
    out_ratios = np.full((classes, len(combos)), np.nan)
    if engaged != freedom - 1:
        return out_ratios  # too few or too many equations: never exactly one motion
    batch = max(1, BATCH_FLOATS // max(1, classes * engaged * freedom))
    for start in range(0, len(combos), batch):
        rows = elements[:, combos[start : start + batch]]  # classes x combos x engaged x freedom
        motion = np.stack([(-1) ** j * np.linalg.det(np.delete(rows, j, axis=3)) for j in range(freedom)], axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.einsum("cd,cbd->cb", into, motion) / np.einsum("cd,cbd->cb", out, motion)
        zero = np.abs(motion).max(axis=-1) == 0
        out_ratios[:, start : start + batch] = np.where(zero, np.nan, ratio)
    return out_ratios


def in_reach(ratios: Floats, target: Fraction, tolerance: Fraction) -> NDArray[np.bool_]:
    """Where a screened ratio may lie within ``tolerance`` (relative) of ``target``."""
    wanted = float(target)
    reach = float(tolerance) * abs(wanted) * (1 + SLACK) + SLACK * 1e-6
    with np.errstate(invalid="ignore"):
        return np.asarray(np.abs(ratios - wanted) <= reach, dtype=bool)
