"""A machine executing a task (Laus sec. 4.3.4): actions and powers at every time step,
the energy per coupling and the task efficiency.

The task prescribes the position variables as functions of time; the ``drive``
coupling's motion follows from their derivatives (a free coupling: the velocity of its
point, Laus's u_M, v_M, w_M; another: its freedoms in the order of the variables).
Each step starts its friction iteration from the previous step's actions.  Energies
are integrated by the trapezoid rule over the time samples.  The task efficiency is
the energy delivered to the loaded ports over the energy the driving ports supply.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import sympy

from davies_sym.errors import NotCoveredError, Problem, TopologyError
from davies_sym.machines import passages
from davies_sym.machines.machine_model import MAX_STEPS, TIME, Machine, Task
from davies_sym.machines.numeric import NumericMachine, PositionSolution, solve_position


@dataclass(frozen=True)
class TaskStep:
    time: float
    port_power: dict[str, float]
    friction_power: dict[str, float]
    port_action: dict[str, float]
    port_speed: dict[str, float]


@dataclass(frozen=True)
class TaskResult:
    task: str
    steps: tuple[TaskStep, ...]
    drivers: tuple[str, ...]
    loads: tuple[str, ...]
    supplied: float
    delivered: float
    lost: dict[str, float]
    efficiency: float


def _time_samples(task: Task, values: Mapping[sympy.Symbol, float]) -> np.ndarray:
    start, stop, step = (float(sympy.N(e.subs(values))) for e in (task.start, task.stop, task.step))
    if not (step > 0 and stop > start):
        raise TopologyError(
            [Problem(f"tasks.{task.name}", "write time: [start, stop] with stop > start, and a step > 0")], None
        )
    count = round((stop - start) / step)
    if count > MAX_STEPS:
        raise TopologyError(
            [
                Problem(
                    f"tasks.{task.name}.step", f"{count} steps is too many (at most {MAX_STEPS}); take a longer step"
                )
            ],
            None,
        )
    return np.linspace(start, stop, count + 1)


def _known_motions(
    machine: Machine, task: Task, values: Mapping[sympy.Symbol, float], drive_freedoms: list[str]
) -> Callable[[float], tuple[dict[sympy.Symbol, float], dict[str, float]]]:
    """Position values and the drive coupling's known motions at a time."""
    path = {s: e.subs(values) for s, e in task.path.items()}
    missing = [s.name for s in machine.position if s not in path]
    if missing:
        raise TopologyError([Problem(f"tasks.{task.name}.path", f"give {', '.join(missing)} as functions of t")], None)
    rates = {s: sympy.diff(e, TIME) for s, e in path.items()}
    drive = next(c for c in machine.couplings if c.name == task.drive)
    if drive.kind == "free":
        # The velocity of the drive's point: its coordinates' derivatives along the path.
        velocity = [
            sum((sympy.diff(c.subs(values), s) * rates[s] for s in machine.position), sympy.Integer(0))
            for c in drive.at
        ]
        names, speeds = [f"{letter}_{drive.name}" for letter in "uvw"], velocity
    else:
        # The drive's freedoms turn or slide at the rates of the position variables.
        if len(drive_freedoms) != len(machine.position):
            raise TopologyError(
                [
                    Problem(
                        f"tasks.{task.name}.drive",
                        f"{drive.name} has {len(drive_freedoms)} freedoms for {len(machine.position)} position "
                        "variables; drive a free coupling or one with a freedom per variable",
                    )
                ],
                machine.path,
            )
        names, speeds = drive_freedoms, [rates[s] for s in machine.position]
    positions = sympy.lambdify(TIME, [path[s] for s in machine.position], "math")
    speed_fn = sympy.lambdify([TIME, *machine.position], speeds, "math")

    def at(t: float) -> tuple[dict[sympy.Symbol, float], dict[str, float]]:
        where = dict(zip(machine.position, (float(v) for v in positions(t)), strict=True))
        return where, dict(zip(names, (float(v) for v in speed_fn(t, *where.values())), strict=True))

    return at


def run_task(machine: Machine, task_name: str, progress: Callable[[int, int], None] | None = None) -> TaskResult:
    """Laus Algorithm 2 at every time sample of the task."""
    task = machine.tasks[task_name]
    numeric = NumericMachine(machine)
    values = {s: float(sympy.N(v)) for s, v in machine.values.items()}
    times = _time_samples(task, values)
    if task.drive not in {c.name for c in machine.couplings}:
        raise TopologyError([Problem(f"tasks.{task.name}.drive", "name the coupling the path moves")], machine.path)
    first = {**values, **{s: float(sympy.N(e.subs(values).subs(TIME, times[0]))) for s, e in task.path.items()}}
    try:
        network = numeric.network(first)
    except NotCoveredError as exc:
        raise NotCoveredError(f"task {task_name}, step 0 (t = {times[0]:.6g} s): {exc}") from None
    joint = next(j for j in network.joints if j.coupling == task.drive)
    state = _known_motions(machine, task, values, [m for m, _ in joint.freedoms])
    loads = {port: sympy.lambdify(TIME, e.subs(values), "math") for port, e in task.loads.items()}
    steps: list[TaskStep] = []
    previous: PositionSolution | None = None
    for k, t in enumerate(times):
        where, motions = state(float(t))
        known_actions = {network.ports[port].action: float(load(float(t))) for port, load in loads.items()}
        try:
            solution = solve_position(
                numeric, {**values, **where}, motions, known_actions, previous.actions if previous else None
            )
        except NotCoveredError as exc:
            raise NotCoveredError(f"task {task_name}, step {k} (t = {t:.6g} s): {exc}") from None
        changed = passages.passed(previous.orientation, solution.orientation) if previous else []
        if changed:
            raise NotCoveredError(
                f"task {task_name}, between step {k - 1} (t = {times[k - 1]:.6g} s) and step {k} (t = {t:.6g} s): "
                f"the path passes through a singular position: {'; '.join(changed)}"
            )
        ports = solution.network.ports
        steps.append(
            TaskStep(
                float(t),
                solution.port_power,
                solution.friction_power,
                {name: solution.actions[p.action] for name, p in ports.items()},
                {name: sum(float(c) * solution.motions[m] for c, m in p.power_terms) for name, p in ports.items()},
            )
        )
        previous = solution
        if progress is not None:
            progress(k + 1, len(times))
    return _energies(task_name, steps, tuple(loads), times)


def _energies(task: str, steps: list[TaskStep], loads: tuple[str, ...], times: np.ndarray) -> TaskResult:
    def integral(series: list[float]) -> float:
        values = np.asarray(series)
        return float(np.sum((values[1:] + values[:-1]) * np.diff(times)) / 2)  # the trapezoid rule

    ports = tuple(steps[0].port_power)
    drivers = tuple(p for p in ports if p not in loads)
    supplied = sum(integral([s.port_power[p] for s in steps]) for p in drivers)
    delivered = -sum(integral([s.port_power[p] for s in steps]) for p in loads)
    if abs(delivered) <= 1e-9 * abs(supplied):
        delivered = 0.0  # a closed path: the loads end where they started
    lost = {c: -integral([s.friction_power[c] for s in steps]) for c in steps[0].friction_power}
    if not supplied > 0:
        raise NotCoveredError(
            f"task {task}: the drive supplies no energy over the task (the loads do no work against it): no efficiency"
        )
    efficiency = delivered / supplied
    return TaskResult(task, tuple(steps), drivers, loads, supplied, delivered, lost, efficiency)
