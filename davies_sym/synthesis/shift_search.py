"""The whole shift search of given gearsets and connections: the schemes that give the
ratio table (`shift_schedules`), each gear of each scheme derived as an operating state
(brakes and clutches of `davies_sym.topology.states`, Laus Tables 5 and 6) and its
exact efficiency taken at the file's numbers, the schemes ranked by the weighted mean
efficiency over the gears.  The states are derived through the one fan-out, each gear
of each scheme one task."""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

import sympy

from davies_sym.efficiency.variants import derive_variants
from davies_sym.errors import InputError, MissingValuesError, NotCoveredError, Problem
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.progress import Progress, silent
from davies_sym.synthesis.shift_connections import ConnectedScheme, designs, join_groups, joined_speeds, joins_of
from davies_sym.synthesis.shift_elements import candidate_elements, gear_motion
from davies_sym.synthesis.shift_kinematics import MemberSpeeds, member_speeds, speed
from davies_sym.synthesis.shift_schedules import (
    RULES,
    ShiftQuestion,
    ShiftScheme,
    element_letter,
    gear_options,
)
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.loader import load
from davies_sym.topology.model import State, Train
from davies_sym.topology.states import train_in_state


@dataclass(frozen=True)
class GearTask:
    """One gear of one scheme to derive: the train (or its file's path, for a worker in
    another process) and the gear as an operating state."""

    train: Train | str
    state: State


def gear_efficiency(task: GearTask) -> str | None:
    """The exact efficiency of the task's gear at the file's numbers (as text, cheap to
    send), or None where no variant covers it (the gear self-locks)."""
    train = load(task.train) if isinstance(task.train, str) else task.train
    if ports_joined(train, task.state):
        # Input and output are one member: the power passes through no mesh. Only the
        # bearings could lose, and a lossy one would need the load split between them.
        lossless = all(c.friction.lossless for c in bearings(train.couplings))
        return "1" if lossless else None
    whole = replace(train, states=(task.state,))
    variants = derive_variants(train_in_state(whole, task.state))
    try:
        return str(variants.design_point({}).efficiency)
    except MissingValuesError as exc:
        needed = exc.problems[0].message.removeprefix("missing values for ")
        why = f"the efficiencies need values for {needed}: write every loss as a number in the file"
        raise InputError([Problem("", why)], train.path) from None
    except NotCoveredError:
        return None


def ports_joined(train: Train, state: State) -> bool:
    """Whether the state's clutches make the input and output members one."""
    into, out = port_member(train, state.input), port_member(train, state.output)
    return any(into in group and out in group for group in join_groups(state.clutch))


@dataclass(frozen=True)
class Ranking:
    """How schemes are scored: each gear's ``weight`` (default 1, e.g. its share of a drive
    cycle's time) and the ``drag`` coefficient of the open elements: each slips at its
    relative speed v with a drag torque ``drag`` v, losing ``drag`` v**2 in units of the
    input power at unit input speed."""

    weights: Mapping[str, float] = field(default_factory=dict)
    drag: float = 0.0

    def score(
        self, efficiency: Mapping[str, Fraction | None], open_speed: Mapping[str, Mapping[str, Fraction]]
    ) -> float:
        """The weighted mean over the gears of the efficiency less the open elements'
        drag loss; a gear not covered counts as zero."""
        total = sum(self.weights.get(g, 1.0) for g in efficiency)
        value = 0.0
        for gear, eta in efficiency.items():
            loss = self.drag * sum(float(v) ** 2 for v in open_speed[gear].values())
            value += self.weights.get(gear, 1.0) * (float(eta) - loss if eta is not None else 0.0)
        return value / total


@dataclass(frozen=True)
class ShiftCandidate:
    """A ranked scheme: its efficiency per gear (None: not covered), the relative speed
    of every open element per gear (input speed 1) and the score."""

    scheme: ShiftScheme
    efficiency: Mapping[str, Fraction | None]
    open_speed: Mapping[str, Mapping[str, Fraction]]
    score: float
    #: The groups of members joined for good (empty: the connections as written).
    connections: frozenset[frozenset[str]] = frozenset()
    #: The tooth numbers by name, where they were searched with the scheme (`shift_teeth`).
    teeth: Mapping[str, int] = field(default_factory=dict)

    def document(self) -> dict[str, Any]:
        """The candidate as ``derive shifts --json`` writes it."""
        s = self.scheme
        names = [element_letter(k) for k in range(len(s.elements))]
        return {
            "elements": {n: e.document() for n, e in zip(names, s.elements, strict=True)},
            "schedule": {g: [names[k] for k in ks] for g, ks in s.schedule.items()},
            "connections": [list(j) for j in joins_of(self.connections)],
            "teeth": dict(self.teeth),
            "speed_ratio": {g: float(r) for g, r in s.ratios.items()},
            "efficiency": {g: None if v is None else float(v) for g, v in self.efficiency.items()},
            "open_speed": {g: {n: float(v) for n, v in o.items()} for g, o in self.open_speed.items()},
            "score": self.score,
        }


@dataclass(frozen=True)
class ShiftResult:
    """Every feasible scheme, best first, with what was searched."""

    candidates: tuple[ShiftCandidate, ...]
    searched: int
    seconds: float
    rules: tuple[str, ...] = RULES
    #: Feasible designs, where more were found than listed (the tooth search lists the best).
    found: int | None = None
    #: Tooth designs the rules admit, where the teeth were searched.
    tooth_designs: int | None = None

    @property
    def feasible(self) -> int:
        return len(self.candidates) if self.found is None else self.found

    def document(self, top: int) -> dict[str, Any]:
        out = {
            "candidates": [c.document() for c in self.candidates[:top]],
            "searched": self.searched,
            "feasible": self.feasible,
            "rules": list(self.rules),
            "seconds": round(self.seconds, 3),
        }
        if self.tooth_designs is not None:
            out["tooth_designs"] = self.tooth_designs
        return out


def gear_state(train: Train, design: ConnectedScheme, gear: str) -> State:
    """The gear ``gear`` of ``design`` as an operating state of ``train``: its engaged
    brakes and clutches, and the permanent connections as clutches engaged in every
    gear."""
    scheme = design.scheme
    engaged = scheme.engaged(gear)
    letters = " ".join(element_letter(k) for k in scheme.schedule[gear])
    joined = " and the connections" if design.connections else ""
    return State(
        gear,
        train.ports.input,
        train.ports.output,
        brake=tuple(e.members[0] for e in engaged if e.kind == "brake"),
        clutch=(
            *joins_of(design.connections),
            *((e.members[0], e.members[1]) for e in engaged if e.kind == "clutch"),
        ),
        description=f"gear {gear} ({letters}{joined})",
    )


def open_speeds(scheme: ShiftScheme, speeds: MemberSpeeds, ports: tuple[str, str]) -> dict[str, dict[str, Fraction]]:
    """The speed each open element slips at in each gear (its equation's value), the
    input at unit speed: what its drag loss grows with."""
    out: dict[str, dict[str, Fraction]] = {}
    for gear, engaged in scheme.schedule.items():
        motion = gear_motion(scheme.engaged(gear), speeds, ports)
        assert motion is not None  # a matched gear leaves one motion
        out[gear] = {
            element_letter(k): speed(e.form(speeds), motion) for k, e in enumerate(scheme.elements) if k not in engaged
        }
    return out


def unreached(speeds: MemberSpeeds, ports: tuple[str, str], question: ShiftQuestion) -> list[str]:
    """For each target no combination reaches, a line naming the closest ratios there are."""
    candidates = candidate_elements(speeds, ports)
    options = gear_options(speeds, ports, candidates, replace(question, tolerance=Fraction(10**9)))
    lines = []
    for target in question.targets:
        if any(abs(r - target.ratio) <= question.tolerance * abs(target.ratio) for _, r in options[target.name]):
            continue
        near = sorted(options[target.name], key=lambda o: abs(o[1] - target.ratio))[:3]
        shown = ", ".join(f"{float(r):.4f} ({' + '.join(candidates[k].text() for k in sorted(c))})" for c, r in near)
        lines.append(f"gear {target.name}: no elements give {float(target.ratio):g}; the closest: {shown or 'none'}")
    return lines


def shift_search(
    train: Train,
    question: ShiftQuestion,
    ranking: Ranking | None = None,
    workers: Workers = IN_THIS_PROCESS,
    progress: Progress = silent,
) -> ShiftResult:
    """Every scheme of ``question`` for ``train`` (its sets, connections and ports as
    written, no states), its gears derived and ranked by ``ranking`` (weighted mean
    efficiency less drag), then the ratio error, then fewer elements."""
    start = time.perf_counter()
    speeds = member_speeds(train)
    ports = (port_member(train, train.ports.input), port_member(train, train.ports.output))
    found, searched = designs(train, speeds, ports, question, workers, progress)
    progress(f"{len(found)} scheme(s) give the ratio table; deriving their gears")
    gears = [gear_state(train, d, g) for d in found for g in d.scheme.schedule]
    if not train.path or workers.here(len(gears)):
        workers, tasks = IN_THIS_PROCESS, [GearTask(train, state) for state in gears]
    else:  # a worker reads the file itself
        tasks = [GearTask(train.path, state) for state in gears]
    values = iter(fan_out(gear_efficiency, tasks, workers, Counted(progress, "gear")))
    ranking = ranking or Ranking()
    ranked = []
    for d in found:
        efficiency = {
            g: None if (v := next(values)) is None else Fraction(str(sympy.Rational(v))) for g in d.scheme.schedule
        }
        joined = joined_speeds(speeds, d.connections) if d.connections else speeds
        assert joined is not None  # a found design's joins leave the train movable
        slips = open_speeds(d.scheme, joined, ports)
        ranked.append(ShiftCandidate(d.scheme, efficiency, slips, ranking.score(efficiency, slips), d.connections))
    error = {id(c): sum(abs(float(c.scheme.ratios[t.name] / t.ratio) - 1) for t in question.targets) for c in ranked}
    ranked.sort(key=lambda c: (-c.score, error[id(c)], len(c.scheme.elements)))
    return ShiftResult(tuple(ranked), searched, time.perf_counter() - start)


def port_member(train: Train, port: str) -> str:
    """The main-axis member a port's bearing carries (the link other than the reference)."""
    coupling = train.coupling(port)
    return coupling.links[1] if coupling.links[0] == train.reference else coupling.links[0]
