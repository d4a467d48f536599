"""Shift elements: brakes (a main-axis member held to the reference) and clutches (two
main-axis members joined), each one linear equation on the member speeds
(`davies_sym.synthesis.shift_kinematics`).

Two elements whose equations are multiples of each other lock the same degree of
freedom and are one choice: a clutch between any two members of a simple (or a
Ravigneaux) set locks the set as a whole, whichever two it joins.  They are kept as one
element with the others listed as alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations

from davies_sym.synthesis.shift_kinematics import Form, MemberSpeeds, one_motion, speed


@dataclass(frozen=True)
class ShiftElement:
    """A brake (``members`` one member, held to the reference) or a clutch (two
    members joined); ``alike``: other elements that lock the same degree of freedom."""

    members: tuple[str, ...]
    alike: tuple[tuple[str, ...], ...] = ()

    @property
    def kind(self) -> str:
        return "brake" if len(self.members) == 1 else "clutch"

    def form(self, speeds: MemberSpeeds) -> Form:
        """The speed this element makes zero: the member's (a brake), or the difference
        of the two members' (a clutch)."""
        first = speeds.forms[self.members[0]]
        if len(self.members) == 1:
            return first
        second = speeds.forms[self.members[1]]
        return tuple(a - b for a, b in zip(first, second, strict=True))

    def text(self) -> str:
        return f"{self.kind} {'-'.join(self.members)}"

    def document(self) -> dict[str, str | list[str]]:
        """As ``derive shifts --json`` writes it: ``{"brake": LINK}`` or ``{"clutch": [A, B]}``."""
        return {"brake": self.members[0]} if self.kind == "brake" else {"clutch": list(self.members)}


def _direction(form: Form) -> Form | None:
    """``form`` scaled so that its first non-zero coefficient is 1 (None: all zero)."""
    lead = next((x for x in form if x != 0), None)
    return None if lead is None else tuple(x / lead for x in form)


def candidate_elements(speeds: MemberSpeeds, ports: tuple[str, str]) -> tuple[ShiftElement, ...]:
    """Every distinct shift element among the main-axis members: brakes on every member
    but the input's and the output's (holding either stops the transmission), clutches
    between any two members; elements that lock the same degree of freedom (equations
    that are multiples of each other) are one, and one that locks nothing (a clutch
    between two members that always turn together) is left out."""
    members = speeds.members()
    written = [(m,) for m in members if m not in ports] + list(combinations(members, 2))
    kept: dict[Form, list[tuple[str, ...]]] = {}
    for element in written:
        direction = _direction(ShiftElement(element).form(speeds))
        if direction is not None:
            kept.setdefault(direction, []).append(element)
    return tuple(ShiftElement(group[0], tuple(group[1:])) for group in kept.values())


def gear_motion(engaged: tuple[ShiftElement, ...], speeds: MemberSpeeds, ports: tuple[str, str]) -> Form | None:
    """The one motion the ``engaged`` elements leave, scaled to unit input speed, or
    None when they do not leave exactly one degree of freedom (too few, or one
    redundant) or the input or the output stands still."""
    motion = one_motion([e.form(speeds) for e in engaged], speeds.degrees_of_freedom)
    if motion is None:
        return None
    into, out = speed(speeds.forms[ports[0]], motion), speed(speeds.forms[ports[1]], motion)
    if into == 0 or out == 0:
        return None
    return tuple(x / into for x in motion)


def ratio_of(engaged: tuple[ShiftElement, ...], speeds: MemberSpeeds, ports: tuple[str, str]) -> Fraction | None:
    """The speed ratio (input over output member speed) of the gear ``engaged`` makes,
    or None where `gear_motion` finds none."""
    motion = gear_motion(engaged, speeds, ports)
    return None if motion is None else 1 / speed(speeds.forms[ports[1]], motion)
