"""Tooth numbers searched with the shift scheme (``derive shifts --teeth NAME=LO:HI``):
the sets' tooth numbers are symbols of the file, and every whole assignment within the
bounds that the rules of ``derive search`` admit (whole teeth, the fewest teeth,
planets assembled equally spaced and clear of each other) is a design whose schemes
the level-1 search finds.

Never the blind product of designs and schemes:

1. The member speeds are written once in the tooth numbers (`member_forms`); their
   exact values at every design (`ExactRational`) sort the designs into kinematic
   classes: designs whose every speed coefficient is equal have the same schemes.
2. A vectorised screen (`shift_screen`, floating point) evaluates the
   ratio of every combination of engaged elements in every class at once and keeps the
   classes where each target has some combination within the tolerance.
3. The level-1 search (`shift_schedules.shift_schemes`, exact rationals) runs on each
   kept class, through the fan-out.
4. Each distinct scheme's gears are derived once in the tooth numbers (Laus Tables 5
   and 6, the formula module of `derive search`) and their efficiencies evaluated at
   every design of the classes that have the scheme, in one vectorised call per gear.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from itertools import combinations
from math import comb

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.emit.formula_code import compiled_module
from davies_sym.errors import InputError, Problem
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.progress import Progress, silent
from davies_sym.synthesis import rules
from davies_sym.synthesis.exact_values import ExactRational
from davies_sym.synthesis.formulas import DerivedState, StateFormulas, derived_in_state
from davies_sym.synthesis.planet_sets import planet_sets
from davies_sym.synthesis.problem import MIN_TEETH, SearchProblem, Target, search_problem
from davies_sym.synthesis.shift_connections import ConnectedScheme
from davies_sym.synthesis.shift_kinematics import MemberForms, MemberSpeeds, member_forms
from davies_sym.synthesis.shift_schedules import RULES, ShiftQuestion, ShiftScheme, shift_schemes
from davies_sym.synthesis.shift_screen import combination_ratios, in_reach
from davies_sym.synthesis.shift_search import (
    Ranking,
    ShiftCandidate,
    ShiftResult,
    gear_state,
    open_speeds,
    port_member,
    ports_joined,
)
from davies_sym.synthesis.tooth_search import planet_filtered, planet_rules, ratio_feasible
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.loader import load
from davies_sym.topology.model import State, Train

#: Classes times combinations of engaged elements the screen evaluates at most.
MAX_SCREENED = 50_000_000
#: Tooth designs (the product of the ranges) a search takes at most.
MAX_DESIGNS = 2_000_000
#: Designs listed at most (the best by score); the count of all feasible ones is kept.
MAX_LISTED = 1000


@dataclass(frozen=True)
class ToothRanges:
    """``--teeth`` (bounds of the free tooth numbers by name), ``--planets`` and ``--min-teeth``."""

    bounds: Mapping[str, tuple[int, int]]
    planets: int | None = None
    min_teeth: int = MIN_TEETH


@dataclass(frozen=True)
class ToothDesigns:
    """Every admissible design: ``teeth`` every tooth number by name (free and dependent),
    one entry per design, and the checked ``problem`` they come from."""

    problem: SearchProblem
    teeth: Mapping[str, NDArray[np.int64]]
    #: The tooth rules, as `derive search` lists them (a planet rule says why it was not applied).
    rules: tuple[rules.Rule, ...]

    def __len__(self) -> int:
        return len(next(iter(self.teeth.values()))) if self.teeth else 0


def tooth_designs(train: Train, ranges: ToothRanges) -> ToothDesigns:
    """The whole tooth numbers within ``ranges`` that the rules of ``derive search``
    admit: dependent tooth numbers whole, no gear below the fewest teeth, and with
    ``--planets`` the planets assembled equally spaced and clear of each other's tips."""
    # One placeholder target checks the options; the designs need no ratio yet.
    problem = search_problem(train, [(None, Fraction(1))], Fraction(0), ranges.bounds, ranges.planets, ranges.min_teeth)
    problem = replace(problem, targets=())
    if problem.size > MAX_DESIGNS:
        why = f"the ranges hold {problem.size:,} tooth designs, beyond {MAX_DESIGNS:,}: narrow them"
        raise InputError([Problem("--teeth", why)], train.path)
    rows, teeth, _ = ratio_feasible(problem, [])
    whole = resolved_train(train)
    sets = planet_sets(whole, train_layout(whole))
    rows, teeth = planet_filtered(problem, sets, rows, teeth)
    # The tooth numbers in the order their gears are written.
    written = [str(g.teeth) for g in train.gears if isinstance(g.teeth, sympy.Symbol)]
    teeth = {n: teeth[n] for n in sorted(teeth, key=lambda n: written.index(n) if n in written else len(written))}
    applied = (
        rules.Rule(rules.WHOLE, rules.MEANINGS[rules.WHOLE]),
        rules.Rule(rules.MIN_TEETH, rules.MEANINGS[rules.MIN_TEETH]),
        *planet_rules(problem, sets),
    )
    return ToothDesigns(problem, teeth, applied)


@dataclass(frozen=True)
class KinematicClass:
    """Designs with the same exact member speeds: those speeds, and the designs' indices."""

    speeds: MemberSpeeds
    designs: NDArray[np.int64]


def kinematic_classes(forms: MemberForms, designs: ToothDesigns) -> list[KinematicClass]:
    """The designs sorted by their exact member speeds (every coefficient a reduced
    fraction), each class once, in the order of its first design."""
    problem = designs.problem
    by_name = {str(s): s for s in (*problem.free, *(s for s, _ in problem.dependent))}
    columns = [designs.teeth[str(s)] for s in problem.free]
    keys = []
    for form in forms.forms.values():
        for coefficient in form:
            expr = coefficient.xreplace({s: by_name.get(str(s), s) for s in coefficient.free_symbols})
            num, den = ExactRational.of(expr.subs(dict(problem.dependent)), problem.free).rows(columns)
            num, den = np.broadcast_to(num, (len(designs),)), np.broadcast_to(den, (len(designs),))
            common = np.gcd(num.astype(np.int64), den.astype(np.int64))
            keys += [num // np.where(common == 0, 1, common), den // np.where(common == 0, 1, common)]
    table = np.stack(keys, axis=1) if keys else np.zeros((len(designs), 0), dtype=np.int64)
    _, first, inverse = np.unique(table, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    members, width = list(forms.forms), len(forms.free)
    classes = []
    for k in np.argsort(first):
        row = table[first[k]]
        values = [Fraction(int(row[2 * j]), int(row[2 * j + 1])) for j in range(len(row) // 2)]
        speeds = {m: tuple(values[i * width : (i + 1) * width]) for i, m in enumerate(members)}
        classes.append(
            KinematicClass(MemberSpeeds(forms.free, speeds, dict(forms.shaft)), np.flatnonzero(inverse == k))
        )
    return classes


def screened(classes: Sequence[KinematicClass], ports: tuple[str, str], question: ShiftQuestion) -> NDArray[np.bool_]:
    """Which classes have, for every target, some combination of engaged elements whose
    ratio is in reach (`shift_screen`): the exact search needs to look at no other."""
    if not classes:
        return np.zeros(0, dtype=bool)
    members = classes[0].speeds.members()
    speeds = np.array([[[float(x) for x in c.speeds.forms[m]] for m in members] for c in classes])
    index = {m: k for k, m in enumerate(members)}
    written = [(index[m],) for m in members if m not in ports] + list(combinations(range(len(members)), 2))
    elements = np.stack([speeds[:, e[0]] - (speeds[:, e[1]] if len(e) == 2 else 0.0) for e in written], axis=1)
    freedom = speeds.shape[2]
    engaged = question.engaged if question.engaged is not None else freedom - 1
    combos = np.array(list(combinations(range(len(written)), engaged)), dtype=np.int64).reshape(-1, engaged)
    if len(classes) * len(combos) > MAX_SCREENED:
        why = (
            f"{len(classes)} kinematically different designs times {len(combos)} combinations of engaged elements "
            f"is beyond {MAX_SCREENED:,}: narrow the --teeth ranges"
        )
        raise InputError([Problem("--teeth", why)])
    ratios = combination_ratios(elements, speeds[:, index[ports[0]]], speeds[:, index[ports[1]]], combos)
    hit = np.stack([in_reach(ratios, t.ratio, question.tolerance).any(axis=1) for t in question.targets], axis=1)
    return np.asarray(hit.all(axis=1), dtype=bool)


@dataclass(frozen=True)
class ClassTask:
    """The level-1 search of one kinematic class (exact speeds, the ports' members)."""

    speeds: MemberSpeeds
    ports: tuple[str, str]
    question: ShiftQuestion


def class_schemes(task: ClassTask) -> tuple[ShiftScheme, ...]:
    """Every feasible scheme of one class."""
    return shift_schemes(task.speeds, task.ports, task.question)


@dataclass(frozen=True)
class GearFormulaTask:
    """One gear of a scheme to derive in the tooth numbers: the train (or its file's path
    for a worker in another process), the gear as a state, the tooth-number names."""

    train: Train | str
    state: State
    teeth: frozenset[str]


def gear_formulas(task: GearFormulaTask) -> DerivedState | None:
    """The formulas of the task's gear, or None where the clutches join the input and
    the output (the power passes through no mesh: efficiency 1 with lossless bearings)."""
    train = load(task.train) if isinstance(task.train, str) else task.train
    if ports_joined(train, task.state):
        return None
    return derived_in_state(train, task.state, task.teeth)


def _structure(scheme: ShiftScheme) -> tuple[object, ...]:
    """What a scheme is apart from its ratios: its elements and schedule."""
    return (tuple(e.members for e in scheme.elements), tuple(sorted(scheme.schedule.items())))


def _gear_efficiencies(
    train: Train,
    derived: Sequence[DerivedState | None],
    gears: Sequence[str],
    teeth: Mapping[str, NDArray[np.int64]],
) -> dict[str, NDArray[np.float64]]:
    """Each gear's efficiency at every design of ``teeth`` (NaN: not covered)."""
    size = len(next(iter(teeth.values())))
    lossless = all(c.friction.lossless for c in bearings(train.couplings))
    out = {}
    for gear, d in zip(gears, derived, strict=True):
        if d is None:
            out[gear] = np.full(size, 1.0 if lossless else np.nan)
            continue
        if d.others:
            why = f"the efficiencies need values for {', '.join(d.others)}: write every loss as a number in the file"
            raise InputError([Problem("", why)], train.path)
        formulas = StateFormulas(Target(gear, Fraction(1)), d.port, sympy.Integer(1), compiled_module(d.source, gear))
        out[gear] = np.broadcast_to(formulas.efficiency(dict(teeth)), (size,)).astype(float)
    return out


def _derive_gears(
    train: Train, schemes: Sequence[ShiftScheme], teeth: frozenset[str], workers: Workers, progress: Progress
) -> list[list[DerivedState | None]]:
    """Every gear of every scheme derived once in the tooth numbers, by ``workers``."""
    states = [[gear_state(train, ConnectedScheme(frozenset(), s), g) for g in s.schedule] for s in schemes]
    flat = [state for group in states for state in group]
    here = not train.path or workers.here(len(flat))
    tasks = [GearFormulaTask(train if here else str(train.path), state, teeth) for state in flat]
    progress(f"deriving the {len(tasks)} gear(s) of {len(schemes)} scheme(s) in the tooth numbers")
    values = iter(fan_out(gear_formulas, tasks, IN_THIS_PROCESS if here else workers, Counted(progress, "gear")))
    return [[next(values) for _ in group] for group in states]


@dataclass(frozen=True)
class _Scored:
    """One design with one scheme: the class, the design's index, its score and ratio error."""

    klass: int
    design: int
    scheme: ShiftScheme
    score: float
    error: float
    efficiency: Mapping[str, float]


@dataclass(frozen=True)
class _Search:
    """What scoring the found schemes needs: the train, its designs and their classes,
    the question and the ranking."""

    train: Train
    designs: ToothDesigns
    classes: Sequence[KinematicClass]
    question: ShiftQuestion
    ranking: Ranking

    def scored(
        self, found: Mapping[tuple[object, ...], list[tuple[int, ShiftScheme]]], workers: Workers, progress: Progress
    ) -> list[_Scored]:
        """Every design with each of its class's schemes, scored: efficiencies per scheme
        evaluated at all its designs in one call per gear."""
        designs, classes = self.designs, self.classes
        names = frozenset(designs.teeth)
        derived = _derive_gears(self.train, [group[0][1] for group in found.values()], names, workers, progress)
        out = []
        for group, gears in zip(found.values(), derived, strict=True):
            at = np.concatenate([classes[k].designs for k, _ in group])
            order = list(group[0][1].schedule)
            etas = _gear_efficiencies(self.train, gears, order, {n: t[at] for n, t in designs.teeth.items()})
            position = 0
            for k, scheme in group:
                slips = open_speeds(scheme, classes[k].speeds, _ports(self.train))
                error = sum(abs(float(scheme.ratios[t.name] / t.ratio) - 1) for t in self.question.targets)
                for design in classes[k].designs:
                    efficiency = {g: float(etas[g][position]) for g in order}
                    covered = {g: None if np.isnan(v) else Fraction(v) for g, v in efficiency.items()}
                    out.append(_Scored(k, int(design), scheme, self.ranking.score(covered, slips), error, efficiency))
                    position += 1
        return out


def _ports(train: Train) -> tuple[str, str]:
    return port_member(train, train.ports.input), port_member(train, train.ports.output)


def shift_teeth_search(
    train: Train,
    question: ShiftQuestion,
    ranges: ToothRanges,
    ranking: Ranking | None = None,
    workers: Workers = IN_THIS_PROCESS,
    progress: Progress = silent,
) -> ShiftResult:
    """Every design of ``ranges`` with every scheme of ``question`` it admits, ranked by
    ``ranking`` (weighted mean efficiency less drag), then the ratio error, then fewer
    elements, then fewer teeth in all; the best `MAX_LISTED` listed."""
    start = time.perf_counter()
    ranking = ranking or Ranking()
    designs = tooth_designs(train, ranges)
    classes = kinematic_classes(member_forms(train), designs)
    progress(f"{len(designs)} admissible tooth designs in {len(classes)} kinematic classes")
    ports = _ports(train)
    kept = np.flatnonzero(screened(classes, ports, question))
    progress(f"{len(kept)} class(es) reach every target; the exact search of their schemes")
    tasks = [ClassTask(classes[k].speeds, ports, question) for k in kept]
    found: dict[tuple[object, ...], list[tuple[int, ShiftScheme]]] = {}
    for k, schemes in zip(kept, fan_out(class_schemes, tasks, workers, Counted(progress, "class")), strict=True):
        for scheme in schemes:
            found.setdefault(_structure(scheme), []).append((int(k), scheme))
    scored = _Search(train, designs, classes, question, ranking).scored(found, workers, progress)
    # Ties (designs of equal ratios) go to the smaller design: the fewest teeth in all.
    size = np.vstack([t.astype(np.int64) for t in designs.teeth.values()]).sum(axis=0)
    scored.sort(key=lambda s: (-s.score, s.error, len(s.scheme.elements), int(size[s.design])))
    candidates = tuple(_candidate(s, classes, designs, ports) for s in scored[:MAX_LISTED])
    width = len(classes[0].speeds.members()) if classes else 0
    written = width - 2 + comb(width, 2)
    engaged = question.engaged if question.engaged is not None else (len(classes[0].speeds.free) - 1 if classes else 0)
    searched = len(classes) * comb(written, engaged)
    applied = tuple(r.meaning if r.applied else f"{r.meaning} (not applied: {r.note})" for r in designs.rules)
    return ShiftResult(candidates, searched, time.perf_counter() - start, RULES + applied, len(scored), len(designs))


def _candidate(
    s: _Scored, classes: Sequence[KinematicClass], designs: ToothDesigns, ports: tuple[str, str]
) -> ShiftCandidate:
    teeth = {name: int(column[s.design]) for name, column in designs.teeth.items()}
    efficiency = {g: None if np.isnan(v) else Fraction(v) for g, v in s.efficiency.items()}
    slips = open_speeds(s.scheme, classes[s.klass].speeds, ports)
    return ShiftCandidate(s.scheme, efficiency, slips, s.score, frozenset(), teeth)
