"""Shift schemes of given gearsets and connections (level 1 of the shift search): the
published schemes of the Simpson three-speed and the ZF 8HP70 found again from their
ratio tables, every ratio recomputed by Willis per set (written here, sharing no code
with the search), and the matching checked against a brute force over every element
set and schedule."""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations, pairwise, product
from pathlib import Path

import pytest
import sympy

from davies_sym.errors import InputError
from davies_sym.synthesis.shift_elements import ShiftElement, candidate_elements, ratio_of
from davies_sym.synthesis.shift_kinematics import member_speeds
from davies_sym.synthesis.shift_schedules import GearTarget, ShiftQuestion, gear_order, shift_schemes
from davies_sym.topology.loader import load, loads

DATA = Path(__file__).resolve().parent / "data"
SIMPSON = DATA / "shifts_simpson_sets.yaml"
EIGHT = DATA / "shifts_eight_speed.yaml"

#: Simpson: (sun, ring, carrier) of each set and their teeth; input shaft `in`, output `o`.
SIMPSON_SETS = [(("s", "r1", "o"), (30, 70)), (("s", "o", "c2"), (30, 70))]
SIMPSON_TABLE = {"1": "2.4286", "2": "1.4286", "3": "1", "R": "-2.3333"}
#: ZF 8HP70: the sets' (sun, ring, carrier) and teeth, from benchmarks/search_eight_speed.yaml.
EIGHT_SETS = [
    (("s12", "r1", "c1r4"), (48, 96)),
    (("s12", "r2s3", "in"), (48, 96)),
    (("r2s3", "r3s4", "c3"), (69, 111)),
    (("r3s4", "c1r4", "out"), (23, 85)),
]
#: Its ratio table, rounded as published, and the exact ratios of the published teeth
#: (the file's comments: 108/23, 72/23, ...).
EIGHT_TABLE = {
    "R": "-3.2968", "1": "4.6957", "2": "3.1304", "3": "2.1039", "4": "1.6667",
    "5": "1.2845", "6": "1", "7": "0.8392", "8": "0.6667",
}  # fmt: skip
EIGHT_EXACT = {
    "R": Fraction(-1744, 529), "1": Fraction(108, 23), "2": Fraction(72, 23), "3": Fraction(162, 77),
    "4": Fraction(5, 3), "5": Fraction(8826, 6871), "6": Fraction(1), "7": Fraction(120, 143), "8": Fraction(2, 3),
}  # fmt: skip
#: The published elements (A, B brakes; C, D, E clutches) and the gears that engage each.
EIGHT_ELEMENTS = {"A": ("s12",), "B": ("r1",), "C": ("in", "r3s4"), "D": ("c3", "out"), "E": ("r2s3", "r3s4")}
EIGHT_SCHEDULE = {
    "1": "ABC", "2": "ABE", "3": "BCE", "4": "BDE", "5": "BCD", "6": "CDE", "7": "ACD", "8": "ADE", "R": "ABD",
}  # fmt: skip


def willis_ratio(sets: list, members: list[str], engaged: list[tuple[str, ...]], ports: tuple[str, str]) -> Fraction:
    """Input over output speed from Willis's equation of each simple set,
    (w_sun - w_carrier) z_sun = -(w_ring - w_carrier) z_ring, with the engaged brakes
    (w = 0) and clutches (equal speeds), the input at unit speed."""
    w = {m: sympy.Symbol(f"w_{m}") for m in members}
    equations = [(w[s] - w[c]) * zs + (w[r] - w[c]) * zr for (s, r, c), (zs, zr) in sets]  # the sets' Willis equations
    equations += [w[e[0]] if len(e) == 1 else w[e[0]] - w[e[1]] for e in engaged]
    equations.append(w[ports[0]] - 1)
    (solution,) = sympy.linsolve(equations, list(w.values()))
    value = sympy.Rational(1) / dict(zip(w.values(), solution, strict=True))[w[ports[1]]]
    return Fraction(int(value.p), int(value.q))


def _question(table: dict[str, str], elements: int | None = None, single: bool = True) -> ShiftQuestion:
    targets = tuple(GearTarget(g, Fraction(r)) for g, r in table.items())
    return ShiftQuestion(targets, Fraction(5, 1000), elements, None, single)


def test_the_simpson_scheme_is_the_one_found() -> None:
    """Two simple sets with a common sun (front carrier = rear ring = output) and the
    Simpson ratios 17/7, 10/7, 1, -7/3: the forward clutch to the front ring, the
    direct clutch to the sun, brakes on the sun and the rear carrier, two per gear."""
    speeds = member_speeds(load(SIMPSON))
    (scheme,) = shift_schemes(speeds, ("in", "o"), _question(SIMPSON_TABLE))
    engaged = {g: {e.members for e in scheme.engaged(g)} for g in SIMPSON_TABLE}
    assert engaged == {
        "1": {("in", "r1"), ("c2",)},
        "2": {("in", "r1"), ("s",)},
        "3": {("in", "r1"), ("in", "s")},
        "R": {("in", "s"), ("c2",)},
    }
    members = list(speeds.forms)
    for gear in SIMPSON_TABLE:
        elements = [e.members for e in scheme.engaged(gear)]
        assert scheme.ratios[gear] == willis_ratio(SIMPSON_SETS, members, elements, ("in", "o"))
    assert scheme.ratios == {"1": Fraction(17, 7), "2": Fraction(10, 7), "3": 1, "R": Fraction(-7, 3)}


def test_the_published_eight_speed_scheme_is_found_from_its_ratio_table() -> None:
    """ZF 8HP70 (benchmarks/search_eight_speed.yaml: teeth, connections and the
    published scheme): with five elements the search finds the published brakes,
    clutches and schedule, up to which two members of set 3 the locking clutch joins,
    and nothing else; every ratio is the exact ratio of the published teeth."""
    speeds = member_speeds(load(EIGHT))
    (scheme,) = shift_schemes(speeds, ("in", "out"), _question(EIGHT_TABLE, elements=5))
    published = {name: {EIGHT_ELEMENTS[k] for k in letters} for name, letters in EIGHT_SCHEDULE.items()}
    lock = ("r2s3", "r3s4")  # the set-3 lock, whichever two members it is written between
    for gear, wanted in published.items():
        found = {lock if lock in (e.members, *e.alike) else e.members for e in scheme.engaged(gear)}
        assert found == wanted, gear
    assert scheme.ratios == EIGHT_EXACT
    members = list(speeds.forms)
    for gear in EIGHT_TABLE:
        elements = [e.members for e in scheme.engaged(gear)]
        assert willis_ratio(EIGHT_SETS, members, elements, ("in", "out")) == EIGHT_EXACT[gear]


def test_fewest_elements_by_default() -> None:
    """Nine gears of three engaged elements need five elements (four give four
    combinations); without --elements the search answers with five."""
    speeds = member_speeds(load(EIGHT))
    schemes = shift_schemes(speeds, ("in", "out"), _question(EIGHT_TABLE))
    assert schemes and all(len(s.elements) == 5 for s in schemes)


def _brute_force(speeds, ports, table, size: int, single: bool) -> set:
    """Every set of ``size`` candidate elements and every schedule over it, the rules
    tested on the finished scheme (no pruning): what the matching must equal."""
    candidates = candidate_elements(speeds, ports)
    order = [t.name for t in gear_order([GearTarget(g, Fraction(r)) for g, r in table.items()])]
    engaged = speeds.degrees_of_freedom - 1
    ratio = {
        c: ratio_of(tuple(candidates[k] for k in c), speeds, ports)
        for c in combinations(range(len(candidates)), engaged)
    }
    found = set()
    for chosen in combinations(range(len(candidates)), size):
        combos = list(combinations(chosen, engaged))
        for schedule in product(combos, repeat=len(order)):
            if len(set(schedule)) < len(schedule) or {k for c in schedule for k in c} != set(chosen):
                continue
            ratios = [ratio[c] for c in schedule]
            targets = [Fraction(table[g]) for g in order]
            if any(r is None or abs(r - t) > Fraction(5, 1000) * abs(t) for r, t in zip(ratios, targets, strict=True)):
                continue
            forward = [set(c) for c, t in zip(schedule, targets, strict=True) if t > 0]
            if single and any(len(a & b) != len(a) - 1 for a, b in pairwise(forward)):
                continue
            found.add(tuple(frozenset(candidates[k].members for k in c) for c in schedule))
    return found


@pytest.mark.parametrize("single", [True, False], ids=["single transitions", "any shifts"])
def test_the_matching_equals_a_brute_force(single: bool) -> None:
    speeds = member_speeds(load(SIMPSON))
    question = _question(SIMPSON_TABLE, elements=4, single=single)
    order = [t.name for t in gear_order(question.targets)]
    matched = {
        tuple(frozenset(e.members for e in s.engaged(g)) for g in order)
        for s in shift_schemes(speeds, ("in", "o"), question)
    }
    assert matched == _brute_force(speeds, ("in", "o"), SIMPSON_TABLE, 4, single)
    assert matched


def test_a_clutch_within_one_set_counts_once() -> None:
    """Any two members of a simple set locked together lock the set: the three clutches
    within set 3 of the eight-speed are one candidate with two alike."""
    candidates = candidate_elements(member_speeds(load(EIGHT)), ("in", "out"))
    within = [c for c in candidates if {c.members, *c.alike} & {("r2s3", "r3s4"), ("r2s3", "c3"), ("r3s4", "c3")}]
    assert len(within) == 1
    assert {within[0].members, *within[0].alike} == {("r2s3", "r3s4"), ("r2s3", "c3"), ("r3s4", "c3")}
    assert ShiftElement(("c3", "out")).document() == {"clutch": ["c3", "out"]}


def test_a_symbolic_tooth_number_is_refused_at_its_bearing() -> None:
    """A sun and planets of free size (the rings fix only their sum): the member speeds
    are not numbers, and the shift search says so at the first bearing concerned."""
    text = SIMPSON.read_text(encoding="utf-8").replace("radius: 30", "radius: rs")
    text = text.replace("P1: {link: p1, radius: 20}", "P1: {link: p1, radius: rp1}")
    text = text.replace("P2: {link: p2, radius: 20}", "P2: {link: p2, radius: rp2}")
    with pytest.raises(InputError, match=r"couplings\.[A-Z]: the speed of this bearing's member is"):
        member_speeds(loads(text))


TWO_SETS = DATA / "shifts_two_sets.yaml"


def test_connections_rediscover_the_simpson_three_speed() -> None:
    """Two identical simple sets, nothing connected, three joins and four elements for
    the Simpson ratios: among the designs is the Simpson set (common sun, front carrier
    = rear ring = output) with its elements (clutches from the input to the front ring
    and to the sun, brakes on the sun and on the rear carrier), found once for both
    labellings of the two sets."""
    from davies_sym.synthesis.shift_connections import designs, planetary_sets, relabellings

    train = load(TWO_SETS)
    speeds = member_speeds(train)
    targets = tuple(GearTarget(g, Fraction(r)) for g, r in SIMPSON_TABLE.items())
    found, searched = designs(train, speeds, ("in", "out"), ShiftQuestion(targets, Fraction(5, 1000), 4, None, True, 3))
    assert searched > 0
    matches = []
    for mapping in relabellings(planetary_sets(train, speeds.members())):
        groups = {frozenset(mapping[m] for m in b) for b in ({"s1", "s2"}, {"c1", "r2", "out"})}
        sun = {(mapping["s1"],), (mapping["s2"],)}
        front_ring = {("in", mapping["r1"])}
        to_sun = {("in", mapping["s1"]), ("in", mapping["s2"])}
        rear_carrier = {(mapping["c2"],)}
        wanted = {
            "1": [front_ring, rear_carrier],
            "2": [front_ring, sun],
            "3": [front_ring, to_sun],
            "R": [to_sun, rear_carrier],
        }
        for d in (d for d in found if d.connections == groups):
            writings = {g: [{e.members, *e.alike} for e in d.scheme.engaged(g)] for g in SIMPSON_TABLE}
            if all(any(w & options for w in writings[g]) for g, opts in wanted.items() for options in opts):
                matches.append(d)
    assert len(matches) == 1, "the Simpson design appears once, in one labelling of the sets"
    assert matches[0].scheme.ratios == {"1": Fraction(17, 7), "2": Fraction(10, 7), "3": 1, "R": Fraction(-7, 3)}
