"""Checks of a machine file's entries beyond their types: every key known, the names a
task, a cycle or a check refers to defined, times and loads numbers where the numeric
route needs numbers.  Each returns ``(entry, message)`` pairs that the loader records
with their lines, so a mistake is said where it is written, not later in the numerics.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping
from typing import Any

import sympy

from davies_sym.algebra.screws import UNIT
from davies_sym.machines.joints import JOINT_KINDS
from davies_sym.machines.machine_model import MAX_STEPS, TIME, Cycle, Expected, Task

Said = list[tuple[str, str]]

#: The keys each kind of entry takes.
PORT_KEYS = ("coupling", "force", "torque")
TASK_KEYS = ("time", "step", "path", "loads", "drive")
CYCLE_KEYS = ("variable", "from", "to", "steady")
EXPECTED_KEYS = ("quantity", "value", "tolerance", "source", "values", "input", "task")
#: What a machine's published check may state.
QUANTITIES = ("cycle_efficiency", "task_efficiency", "efficiency")


def unknown_keys(spec: Mapping[str, Any], known: Iterable[str], entry: str) -> Said:
    """Keys of ``spec`` that ``known`` does not hold."""
    allowed = tuple(known)
    return [
        (f"{entry}.{key}", f"unknown entry {key!r} (write {', '.join(allowed)})") for key in spec if key not in allowed
    ]


def repeated(names: Iterable[str], entry: str) -> Said:
    """Names written twice in a list."""
    seen: set[str] = set()
    out: Said = []
    for name in names:
        if name in seen:
            out.append((entry, f"{name!r} is written twice: write each once"))
        seen.add(name)
    return out


def _number(value: sympy.Expr) -> float | None:
    """``value`` as a finite float if it is a number, else None."""
    if not value.is_number:
        return None
    number = float(value)
    return number if math.isfinite(number) else None


def task_problems(
    task: Task,
    position: Collection[sympy.Symbol],
    values: Mapping[sympy.Symbol, sympy.Expr],
    couplings: Mapping[str, str],
) -> Said:
    """The time interval and step (numbers, stop after start, a bounded count), the drive (a
    coupling), the path (a function of t for every position variable, no other) and the
    loads (at least one, functions of t and the file's values)."""
    entry = f"tasks.{task.name}"
    out: Said = []
    start, stop, step = (_number(v.subs(values)) for v in (task.start, task.stop, task.step))
    if start is None or stop is None or not stop > start:
        out.append((f"{entry}.time", "write time: [start, stop] as numbers of seconds with stop > start"))
    elif step is None or not step > 0:
        out.append((f"{entry}.step", "write step: a number of seconds > 0"))
    elif (stop - start) / step > MAX_STEPS:
        out.append((f"{entry}.step", f"{(stop - start) / step:.0f} steps is too many (at most {MAX_STEPS})"))
    if task.drive not in couplings:
        out.append((f"{entry}.drive", f"name the coupling the path moves, one of {', '.join(sorted(couplings))}"))
    elif not JOINT_KINDS[couplings[task.drive]].virtual:
        # The drive's freedoms turn or slide at the rates of the position variables, one each.
        axes = (UNIT["z"], UNIT["x"], UNIT["y"])
        freedoms = len(JOINT_KINDS[couplings[task.drive]].screws(*axes)[0])
        if freedoms != len(position):
            out.append(
                (
                    f"{entry}.drive",
                    f"{task.drive} has {freedoms} freedoms for {len(position)} position variables; drive a free "
                    "coupling or one with a freedom per variable",
                )
            )
    names = {s.name for s in position}
    known = {TIME.name, *(s.name for s in values)}
    for symbol, expr in task.path.items():
        if symbol.name not in names:
            out.append(
                (f"{entry}.path.{symbol.name}", f"{symbol.name} is not a position variable ({', '.join(names)})")
            )
        elif not {s.name for s in expr.free_symbols} <= known:
            out.append((f"{entry}.path.{symbol.name}", "write a function of the time t and the file's values"))
    missing = sorted(names - {s.name for s in task.path})
    if missing:
        out.append((f"{entry}.path", f"give {', '.join(missing)} as functions of t"))
    if not task.loads:
        out.append((f"{entry}.loads", "give the load of at least one port (port: force or torque, a function of t)"))
    for port, expr in task.loads.items():
        unknown = sorted(s.name for s in expr.free_symbols if s.name not in known)
        if unknown:
            out.append((f"{entry}.loads.{port}", f"{', '.join(unknown)} is not t or a value of the file"))
    return out


def cycle_problems(cycle: Cycle, position: Collection[sympy.Symbol], values: Mapping[sympy.Symbol, sympy.Expr]) -> Said:
    """The cycle's variable is a position variable and its interval runs forwards."""
    out: Said = []
    if cycle.variable not in position:
        names = ", ".join(s.name for s in position)
        out.append(("cycle.variable", f"{cycle.variable.name} is not a position variable ({names})"))
    start, stop = _number(cycle.start.subs(values)), _number(cycle.stop.subs(values))
    if start is None or stop is None or not stop > start:
        out.append(("cycle.to", "write from: and to: as numbers (radians, pi allowed) with to > from"))
    return out


def expected_problems(check: Expected, index: int, tasks: Collection[str]) -> Said:
    """A published check states a known quantity, a finite value and a task that exists."""
    entry = f"expected[{index}]"
    out: Said = []
    if check.quantity not in QUANTITIES:
        out.append((f"{entry}.quantity", f"unknown quantity {check.quantity!r} (write one of {', '.join(QUANTITIES)})"))
    if not math.isfinite(check.value) or not math.isfinite(check.tolerance) or not check.tolerance > 0:
        out.append((f"{entry}.value", "write a finite value and a tolerance > 0"))
    if check.task is not None and check.task not in tasks:
        out.append(
            (f"{entry}.task", f"{check.task!r} is not a task of the file ({', '.join(sorted(tasks)) or 'none'})")
        )
    return out


def value_problems(values: Mapping[sympy.Symbol, sympy.Expr], coefficients: Collection[sympy.Symbol]) -> Said:
    """Each value a number or an expression of other values; a friction coefficient not
    negative."""
    out: Said = []
    for symbol, value in values.items():
        if not value.free_symbols <= set(values):
            stray = ", ".join(sorted(s.name for s in value.free_symbols - set(values)))
            out.append((f"values.{symbol.name}", f"{stray} has no value: write a number or an expression of values"))
        elif symbol in coefficients and value.is_number and value < 0:
            out.append((f"values.{symbol.name}", f"{symbol.name} is a friction coefficient: write a number >= 0"))
    return out
