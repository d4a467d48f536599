"""The feasibility rules of a design, one function each (vectorised: each gives the rows
of a table of designs where it holds), and the record of which were applied.  A design is
feasible when every applied rule holds; the search applies them in the order of `MEANINGS`
(the cheap exact ones first)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from numpy.typing import NDArray

from davies_sym.synthesis.exact_values import ExactRational
from davies_sym.synthesis.planet_sets import PlanetSet, assembles_rows

Column = NDArray[np.int64]
Floats = NDArray[np.float64]
Mask = NDArray[np.bool_]


@dataclass(frozen=True)
class Rule:
    """A rule as the JSON lists it: its name, what it asks, whether it was applied and why not."""

    name: str
    meaning: str
    applied: bool = True
    note: str = ""

    def document(self) -> dict[str, object]:
        out: dict[str, object] = {"name": self.name, "meaning": self.meaning, "applied": self.applied}
        if self.note:
            out["note"] = self.note
        return out


WHOLE = "whole tooth numbers"
MIN_TEETH = "minimum tooth number"
RATIO = "speed ratio within tolerance"
ASSEMBLY = "equal spacing of the planets"
TIP_CLEARANCE = "tip clearance of neighbouring planets"
RUNS = "the train runs"

MEANINGS = {
    WHOLE: "every free tooth number whole within its bounds, every dependent one (a planet's) whole",
    MIN_TEETH: "every gear has at least the minimum number of teeth",
    RATIO: "every state's speed ratio (input over output speed) within the relative tolerance of its target",
    ASSEMBLY: "N planets equally spaced can be assembled (the assembly condition of each planet set)",
    TIP_CLEARANCE: "neighbouring planets' tip circles (addendum of one module) do not touch",
    RUNS: "every state's efficiency is in (0, 1]: the train neither self-locks nor leaves every variant",
}


def dependent_whole(exact: ExactRational, columns: Sequence[Column]) -> tuple[Mask, Column]:
    """Where a dependent tooth number (a rational function of the free ones, e.g. a
    planet's (zr - zs)/2) is whole at every row, and its value there (0 elsewhere)."""
    return exact.whole_rows(columns)


def enough_teeth(teeth: Mapping[str, Column], minimum: int) -> Mask:
    """Where every tooth number is at least ``minimum``."""
    return np.asarray(np.all([t >= minimum for t in teeth.values()], axis=0), dtype=bool)


def ratio_within(exact: ExactRational, columns: Sequence[Column], window: tuple[Fraction, Fraction]) -> Mask:
    """Where the exact ratio lies in the closed window (target -+ tolerance * |target|),
    decided in integers: a ratio on the edge is in."""
    return exact.within_rows(columns, *window)


def moves(singular: ExactRational, columns: Sequence[Column]) -> Mask:
    """Where a denominator of the motions (a member's speed over the input's) does not
    vanish: elsewhere the train does not move as one degree of freedom from its input,
    however finite the reduced speed ratio stays."""
    numerator, _ = singular.rows(columns)
    return np.asarray(numerator != 0, dtype=bool)


def equally_spaced(sets: Sequence[PlanetSet], gears: Mapping[str, Column], planets: int) -> Mask:
    """Where every planet set assembles with ``planets`` copies equally spaced (a set whose
    condition is not decided within `MAX_PHASINGS` counts as not assembling)."""
    size = len(next(iter(gears.values()))) if gears else 0
    ok = np.ones(size, dtype=bool)
    for s in sets:
        ok &= assembles_rows(s, gears, planets)
    return ok


def tips_clear(orbit: Floats, tip_diameter: Floats, planets: int) -> Mask:
    """Where copies of a planet gear at orbit radius a, 2 a sin(pi/N) apart, clear its tip
    diameter d (= m (z + 2)) with room to spare; always for one planet."""
    if planets < 2:
        return np.ones(np.shape(orbit), dtype=bool)
    return np.asarray(2 * math.sin(math.pi / planets) * orbit > tip_diameter * (1 + 1e-12), dtype=bool)


def runs(efficiencies: Mapping[str | None, Floats]) -> Mask:
    """Where every state's efficiency is a number in (0, 1] (NaN: self-locking or no
    variant holds, the formula module's reasons)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(np.all([(e > 0) & (e <= 1 + 1e-12) for e in efficiencies.values()], axis=0), dtype=bool)
