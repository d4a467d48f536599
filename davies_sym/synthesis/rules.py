"""The feasibility rules of a design, one function each, and the record of which were
applied.  A design is feasible when every applied rule holds; `RULES` names them in the
order the search applies them (the cheap exact ones first)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from davies_sym.synthesis.planet_sets import PlanetSet, assembles


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


def whole(dependent: Mapping[str, Fraction | None]) -> bool:
    """Every dependent tooth number is a whole number (the free ones are by construction)."""
    return all(v is not None and v.denominator == 1 for v in dependent.values())


def enough_teeth(teeth: Mapping[str, int], minimum: int) -> bool:
    """Every tooth number is at least ``minimum``."""
    return all(z >= minimum for z in teeth.values())


def within(ratio: Fraction | None, window: tuple[Fraction, Fraction]) -> bool:
    """The exact ratio lies in the closed window (target +- tolerance * |target|)."""
    return ratio is not None and window[0] <= ratio <= window[1]


def equally_spaced(sets: Sequence[PlanetSet], teeth: Mapping[str, int], planets: int) -> bool:
    """Every planet set assembles with ``planets`` copies equally spaced (a set whose
    condition could not be decided within the bound counts as not assembling)."""
    return all(assembles(s, teeth, planets) is True for s in sets)


def tips_clear(orbits: Sequence[float], tip_diameters: Sequence[float], planets: int) -> bool:
    """Copies of a planet at orbit radius a, 2 a sin(pi/N) apart, clear a tip diameter d
    (one per planet gear, paired with its planet's orbit) with room to spare."""
    if planets < 2:
        return True
    gap = 2 * math.sin(math.pi / planets)
    return all(gap * a > d * (1 + 1e-12) for a, d in zip(orbits, tip_diameters, strict=True))


def runs(efficiencies: Mapping[str | None, float]) -> bool:
    """Every state's efficiency is a number in (0, 1]."""
    return all(0 < e <= 1 + 1e-12 for e in efficiencies.values())
