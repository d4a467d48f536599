"""``derive`` on a machine file (Laus ch. 4): the closed forms per friction mode, an
evaluation at a position or over a cycle (``--eval``), or a task (``--task``)."""

from __future__ import annotations

import argparse
import json
from typing import Any

import sympy

from davies_sym.cli.arguments import figure_suffix
from davies_sym.emit.machine_latex import machine_latex_document
from davies_sym.emit.machine_report import closed_form_json, closed_form_text, task_json, task_text
from davies_sym.errors import InputError, MissingValuesError, NotCoveredError, Problem
from davies_sym.machines.closed_form import ClosedForms, derive_closed_forms
from davies_sym.machines.cycle import CycleEfficiency, check_assembles, cycle_efficiency
from davies_sym.machines.machine_model import Machine
from davies_sym.machines.numeric import NumericMachine, solve_position
from davies_sym.machines.task import run_task
from davies_sym.progress import Progress
from davies_sym.topology.expressions import assignments

Outputs = list[tuple[str | None, str | bytes]]
#: Options of gear trains that a machine does not take, and what to write instead.
_TRAIN_ONLY = {
    "python": "--python",
    "emit": "--emit",
    "state": "--state",
    "vs": "--vs",
    "at": "--at",
    "output": "--output",
}


def _refuse_train_options(machine: Machine, args: argparse.Namespace) -> None:
    for attribute, option in _TRAIN_ONLY.items():
        if getattr(args, attribute, None):
            raise InputError(
                [
                    Problem(
                        option,
                        f"{option} is for gear trains; for a machine write --eval, --task NAME, --json or --plot "
                        "with --task",
                    )
                ],
                machine.path,
            )


def _values(machine: Machine, pairs: list[str]) -> dict[sympy.Symbol, sympy.Expr]:
    named = machine.symbols()
    given = assignments(pairs, "--eval", machine.path)
    unknown = [n for n in given if n not in named]
    if unknown:
        raise InputError(
            [Problem("--eval", f"{unknown[0]!r} is not a name of the machine (its names: {', '.join(sorted(named))})")],
            machine.path,
        )
    return {**machine.values, **{named[n]: v for n, v in given.items()}}


def _input_port(machine: Machine, args: argparse.Namespace) -> str:
    port = args.input or machine.input
    if port not in [p.name for p in machine.ports]:
        raise InputError(
            [Problem("--input", f"{port!r} is not a port (ports: {', '.join(p.name for p in machine.ports)})")],
            machine.path,
        )
    return port


def _closed(machine: Machine) -> tuple[ClosedForms | None, str | None]:
    try:
        return derive_closed_forms(machine), None
    except NotCoveredError as exc:
        return None, str(exc)


def _missing(
    expr: sympy.Expr,
    values: dict[sympy.Symbol, sympy.Expr],
    path: str | None,
    free: frozenset[sympy.Symbol] = frozenset(),
) -> None:
    """Refuse an evaluation that leaves names of ``expr`` without values (``free``: those
    that vary, as the cycle's variable)."""
    left = sorted(s.name for s in expr.free_symbols - set(values) - free)
    if left:
        raise InputError([Problem("--eval", f"give {', '.join(f'{n}=...' for n in left)}")], path)


def _evaluate(machine: Machine, args: argparse.Namespace, forms: ClosedForms | None) -> tuple[str, dict[str, Any]]:
    values = _values(machine, args.eval)
    port = _input_port(machine, args)
    at_position = all(s in values for s in machine.position)
    if forms is not None and at_position:
        _assembles(machine, values)
        direction = forms.direction(port)
        for variant in direction.variants:
            for c in variant.conditions:
                _missing(c, values, machine.path)
            if all(sympy.N(c.subs(values)) > 0 for c in variant.conditions):
                _missing(variant.efficiency, values, machine.path)
                eta = float(sympy.N(variant.efficiency.subs(values), 20))
                signs = ", ".join(f"{s} = {v:+d}" for s, v in variant.signs)
                return _checked(eta, f"input {port}, output {direction.output}; friction mode {signs}", port)
        raise NotCoveredError("no friction mode is consistent here: the machine locks (self-locking)")
    if forms is not None and machine.cycle is not None:
        for variant in forms.direction(port).variants:
            _missing(variant.efficiency, values, machine.path, frozenset({machine.cycle.variable}))
        check_assembles(machine, machine.cycle, values)
        cycle = cycle_efficiency(forms.direction(port), machine.cycle, values)
        eta = cycle.evaluate(values)
        return _checked(eta, f"input {port}; efficiency over one cycle ({cycle.equation})", port)
    if not at_position:
        raise InputError(
            [Problem("--eval", f"give the position: {', '.join(f'{s.name}=...' for s in machine.position)}")],
            machine.path,
        )
    return _numeric(machine, values, port)


def _assembles(machine: Machine, values: dict[sympy.Symbol, sympy.Expr]) -> None:
    """Refuse a position where the linkage cannot be assembled (or leaves its limits)."""
    numeric = NumericMachine(machine)
    missing = numeric.missing(values)
    if not missing:
        numeric.couplings({s: float(sympy.N(v)) for s, v in values.items()})


def _numeric(machine: Machine, values: dict[sympy.Symbol, sympy.Expr], port: str) -> tuple[str, dict[str, Any]]:
    if len(machine.ports) != 2:
        raise NotCoveredError("--eval evaluates a machine with two ports; run one of its tasks with --task")
    numeric = NumericMachine(machine)
    floats = {s: float(sympy.N(v)) for s, v in values.items()}
    network = numeric.network(floats)
    into = network.ports[port]
    other = next(n for n in network.ports if n != port)
    solution = solve_position(numeric, floats, {into.power_terms[0][1]: 1.0}, {into.action: 1.0})
    p_in, p_out = solution.port_power[port], solution.port_power[other]
    return _checked(-p_out / p_in, f"input {port}, output {other}; friction solved numerically", port)


def _checked(eta: float, what: str, port: str) -> tuple[str, dict[str, Any]]:
    if not eta > 0:
        raise NotCoveredError(f"the efficiency with input {port} is {eta:.6g} here: the machine locks (self-locking)")
    return f"{what}\n{eta!r}\n", {"status": "ok", "input": port, "description": what, "efficiency": eta}


def _task(machine: Machine, args: argparse.Namespace, progress: Progress) -> Outputs:
    if args.task not in machine.tasks:
        names = ", ".join(machine.tasks) or "none"
        raise InputError(
            [Problem("--task", f"{args.task!r} is not a task of the machine (tasks: {names})")], machine.path
        )
    if args.plot:
        raise InputError(
            [Problem("--plot", "with --task, --plot takes no value (it draws the task's powers)")], machine.path
        )
    marks = set()

    def report(done: int, total: int) -> None:
        quarter = 4 * done // total
        if quarter not in marks:
            marks.add(quarter)
            progress(f"task {args.task}: {done}/{total} time steps")

    result = run_task(machine, args.task, report)
    if args.plot is not None:
        from davies_sym.emit.machine_plots import task_figure

        if not args.out:
            raise InputError([Problem("--plot", "write the figure to a file: -o FIG.png (.svg, .pdf)")], machine.path)
        return [(args.out, task_figure(machine, result, figure_suffix(args.out, machine.path)))]
    text = json.dumps(task_json(machine, result), indent=1) + "\n" if args.json else task_text(machine, result)
    return [(args.out, text)]


def machine_outputs(machine: Machine, args: argparse.Namespace, progress: Progress) -> Outputs:
    """What ``derive`` writes for a machine file."""
    _refuse_train_options(machine, args)
    if args.input is not None:
        _input_port(machine, args)  # a port, with --eval or without
    if args.task:
        return _task(machine, args, progress)
    if args.plot is not None:
        raise InputError([Problem("--plot", "for a machine, draw a task: --task NAME --plot -o FIG.png")], machine.path)
    if args.eval is not None:
        progress("closed forms per friction mode")
        forms, _ = _closed(machine)
        text, document = _evaluate(machine, args, forms)
        return [(None, json.dumps(document, indent=2) + "\n" if args.json else text)]
    chosen = "json" if args.json else "latex" if args.latex else "text"
    return [(args.out, machine_document(machine, chosen, progress))]


def _derived(machine: Machine, progress: Progress) -> tuple[ClosedForms | None, str | None, dict[str, CycleEfficiency]]:
    """The closed forms (or why there are none) and the cycle efficiencies."""
    progress("closed forms per friction mode")
    forms, reason = _closed(machine)
    cycles: dict[str, CycleEfficiency] = {}
    if forms is not None and machine.cycle is not None:
        sample = machine.sample()
        try:
            for direction in forms.directions:
                cycles[direction.input] = cycle_efficiency(direction, machine.cycle, sample)
        except MissingValuesError as exc:
            progress(f"no cycle efficiency: {exc.problems[0].message}")
            cycles = {}
    return forms, reason, cycles


def _render(
    machine: Machine, derived: tuple[ClosedForms | None, str | None, dict[str, CycleEfficiency]], kind: str
) -> str:
    """One format (``text``, ``json``, ``latex``) of a machine's derivation: its closed
    forms per friction mode and cycle efficiencies, or its summary and why it has none
    (then its tasks; LaTeX is then refused)."""
    forms, reason, cycles = derived
    if forms is not None:
        if kind == "json":
            return json.dumps(closed_form_json(forms, cycles), indent=2) + "\n"
        return machine_latex_document(forms, cycles) if kind == "latex" else closed_form_text(forms, cycles)
    if kind == "latex":
        raise InputError(
            [Problem("--latex", f"the machine has no closed form to typeset ({reason}); use --eval or --task")],
            machine.path,
        )
    if kind == "json":
        body = {"status": "ok", "machine": machine.name, "closed_form": None, "reason": reason}
        return json.dumps({**body, "tasks": list(machine.tasks)}, indent=2) + "\n"
    lines = [f"machine: {machine.name}" + (f" ({machine.source})" if machine.source else "")]
    lines.append(f"efficiency: no closed form ({reason})")
    if machine.tasks:
        lines.append(f"tasks: {', '.join(machine.tasks)} (derive FILE --task NAME)")
    else:
        lines.append("evaluate it at a position: derive FILE --eval NAME=VALUE ...")
    return "\n".join(lines) + "\n"


def machine_document(machine: Machine, kind: str, progress: Progress) -> str:
    """The derivation of a machine file as ``text``, ``json`` or ``latex``."""
    return _render(machine, _derived(machine, progress), kind)


def machine_derivations(machine: Machine, stem: str, progress: Progress) -> list[tuple[str, str]]:
    """What ``derive --out DIR`` writes of a machine: ``STEM.txt``, and ``STEM.tex``
    where it has closed forms."""
    derived = _derived(machine, progress)
    written = [(f"{stem}.txt", _render(machine, derived, "text"))]
    if derived[0] is not None:
        written.append((f"{stem}.tex", _render(machine, derived, "latex")))
    return written
