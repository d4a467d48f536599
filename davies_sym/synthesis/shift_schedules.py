"""Shift schemes of a transmission whose sets and permanent connections are given
(level 1 of ``derive shifts``): which shift elements, engaged in which gears, give a
ratio table.

Never the blind product: the ratio of a gear depends only on which elements it engages,
so the ratio of every combination of ``engaged`` candidate elements is screened once in
floating point (`shift_screen`), the exact ratio (`shift_elements.ratio_of`) computed
where a target is in reach, and each target keeps the combinations within its
tolerance; the schedules are then matched gear by gear, forward gears in order of
falling ratio, with the rules pruning as they go:

- a gear's engaged elements are independent and leave exactly one degree of freedom
  (`shift_kinematics.one_motion`);
- consecutive forward gears differ by one element engaged and one released (single
  transitions, unless lifted);
- the scheme uses exactly its ``elements`` elements, each in some gear;
- no two gears engage the same elements.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations
from math import comb

import numpy as np

from davies_sym.synthesis.shift_elements import ShiftElement, candidate_elements, ratio_of
from davies_sym.synthesis.shift_kinematics import MemberSpeeds
from davies_sym.synthesis.shift_screen import combination_ratios, in_reach

#: The rules a scheme is checked by, as the output lists them.
RULES = (
    "a gear's engaged elements are independent and leave exactly one degree of freedom",
    "consecutive forward gears (by falling ratio) differ by one element engaged and one released",
    "every element is engaged in some gear",
    "no two gears engage the same elements",
    "elements that lock the same degree of freedom (a clutch between any two members of one set) count once",
)


@dataclass(frozen=True)
class GearTarget:
    """A gear of the ratio table: its name and input-over-output speed ratio (negative:
    a reverse gear)."""

    name: str
    ratio: Fraction


@dataclass(frozen=True)
class ShiftQuestion:
    """What is asked: the ratio table within a relative ``tolerance``; ``elements`` in
    the scheme (None: the fewest that work), ``engaged`` per gear (None: the degrees of
    freedom less one, after the connections), single-transition shifts between forward
    gears unless lifted."""

    targets: tuple[GearTarget, ...]
    tolerance: Fraction
    elements: int | None = None
    engaged: int | None = None
    single_transitions: bool = True
    #: Permanent joins searched with the elements (`shift_connections`); 0: as written.
    connections: int = 0


@dataclass(frozen=True)
class ShiftScheme:
    """A feasible scheme: its elements (brakes first, then clutches, each named by a
    letter in this order), the elements each gear engages, and each gear's exact
    speed ratio."""

    elements: tuple[ShiftElement, ...]
    schedule: Mapping[str, tuple[int, ...]]
    ratios: Mapping[str, Fraction]

    def engaged(self, gear: str) -> tuple[ShiftElement, ...]:
        return tuple(self.elements[k] for k in self.schedule[gear])


def element_letter(k: int) -> str:
    """A, B, ..., Z, AA, AB, ...: the name of the ``k``-th element of a scheme."""
    return chr(ord("A") + k) if k < 26 else element_letter(k // 26 - 1) + chr(ord("A") + k % 26)


def gear_order(targets: Sequence[GearTarget]) -> tuple[GearTarget, ...]:
    """Forward gears by falling ratio, then the reverse gears (by falling magnitude)."""
    forward = sorted((t for t in targets if t.ratio > 0), key=lambda t: -t.ratio)
    reverse = sorted((t for t in targets if t.ratio < 0), key=lambda t: t.ratio)
    return (*forward, *reverse)


def gear_options(
    speeds: MemberSpeeds, ports: tuple[str, str], candidates: Sequence[ShiftElement], question: ShiftQuestion
) -> dict[str, list[tuple[frozenset[int], Fraction]]]:
    """For every target, the combinations of engaged candidates (by index) whose exact
    ratio is within the tolerance, with that ratio; each combination evaluated once."""
    engaged = question.engaged if question.engaged is not None else speeds.degrees_of_freedom - 1
    options: dict[str, list[tuple[frozenset[int], Fraction]]] = {t.name: [] for t in question.targets}
    combos = np.array(list(combinations(range(len(candidates)), engaged)), dtype=np.int64).reshape(-1, engaged)
    forms = np.array([[[float(x) for x in e.form(speeds)] for e in candidates]]).reshape(1, len(candidates), -1)
    into, out = (np.array([[float(x) for x in speeds.forms[p]]]) for p in ports)
    screened = combination_ratios(forms, into, out, combos)[0]
    near = [in_reach(screened, t.ratio, question.tolerance) for t in question.targets]
    if not all(n.any() for n in near):
        return options  # a target out of every combination's reach: no scheme
    reach = np.logical_or.reduce(near)
    # The exact ratio only where the screen finds a target in reach.
    for combo in combos[reach].tolist():
        ratio = ratio_of(tuple(candidates[k] for k in combo), speeds, ports)
        if ratio is None:
            continue
        for t in question.targets:
            if abs(ratio - t.ratio) <= question.tolerance * abs(t.ratio):
                options[t.name].append((frozenset(combo), ratio))
    return options


def _matched(
    order: Sequence[GearTarget],
    options: Mapping[str, list[tuple[frozenset[int], Fraction]]],
    size: int,
    single: bool,
) -> Iterator[list[tuple[frozenset[int], Fraction]]]:
    """Every choice of one option per gear (in ``order``) using exactly ``size``
    elements in all, distinct per gear, with single transitions between consecutive
    forward gears when ``single``."""
    chosen: list[tuple[frozenset[int], Fraction]] = []

    def extend(i: int, used: frozenset[int]) -> Iterator[list[tuple[frozenset[int], Fraction]]]:
        if i == len(order):
            if len(used) == size:
                yield list(chosen)
            return
        previous = chosen[-1][0] if chosen and order[i].ratio > 0 else None
        for combo, ratio in options[order[i].name]:
            if any(combo == c for c, _ in chosen) or len(used | combo) > size:
                continue
            if single and previous is not None and len(combo & previous) != len(combo) - 1:
                continue
            chosen.append((combo, ratio))
            yield from extend(i + 1, used | combo)
            chosen.pop()

    yield from extend(0, frozenset())


def shift_schemes(speeds: MemberSpeeds, ports: tuple[str, str], question: ShiftQuestion) -> tuple[ShiftScheme, ...]:
    """Every feasible scheme of ``question.elements`` elements (or of the fewest that
    give one), each once; ``ports``: the input and output members."""
    return scheme_search(speeds, ports, question)[0]


def scheme_search(
    speeds: MemberSpeeds, ports: tuple[str, str], question: ShiftQuestion
) -> tuple[tuple[ShiftScheme, ...], int]:
    """`shift_schemes`, and how many combinations of engaged elements were screened."""
    candidates = candidate_elements(speeds, ports)
    engaged = question.engaged if question.engaged is not None else speeds.degrees_of_freedom - 1
    searched = comb(len(candidates), engaged)
    options = gear_options(speeds, ports, candidates, question)
    if any(not found for found in options.values()):
        return (), searched
    order = gear_order(question.targets)
    sizes = [question.elements] if question.elements is not None else range(engaged, len(candidates) + 1)
    for size in sizes:
        found = [
            _scheme(order, choice, candidates) for choice in _matched(order, options, size, question.single_transitions)
        ]
        if found:
            return tuple(found), searched
    return (), searched


def _scheme(
    order: Sequence[GearTarget], choice: Sequence[tuple[frozenset[int], Fraction]], candidates: Sequence[ShiftElement]
) -> ShiftScheme:
    """The scheme of one matched choice, its elements renumbered brakes first, then
    clutches, each in the order of the candidates."""
    used = sorted({k for combo, _ in choice for k in combo}, key=lambda k: (candidates[k].kind != "brake", k))
    number = {k: n for n, k in enumerate(used)}
    schedule = {t.name: tuple(sorted(number[k] for k in combo)) for t, (combo, _) in zip(order, choice, strict=True)}
    ratios = {t.name: ratio for t, (_, ratio) in zip(order, choice, strict=True)}
    return ShiftScheme(tuple(candidates[k] for k in used), schedule, ratios)
