"""The program of a train driven at several ports: one routine per speed condition, one
per power-flow region, and the choice, as the Python module
(`davies_sym.emit.several_inputs_runtime`) makes it.

The speed conditions are linear forms in the input speeds; a region is one choice of
their signs (and, at light load, of the signs of its loaded forces), the several-input
counterpart of a variant's turning conditions (Laus 2011, Tables 5 and 6; Mantriota and
Pennestri 2003).  The choice takes the region whose conditions hold (a condition counts
as negative where its value is ``< 0``) and whose loaded forces are all ``>= 0`` times the
sign it assumes, when exactly one does; there is no efficiency on a condition line (a
value exactly 0), where no region or several hold, outside the parameters' ranges, and
where the efficiency is outside (0, 1].
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.parameters import given_forms
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, Region, SeveralInputs
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.one_input_program import range_checks
from davies_sym.emit.languages.program import NOT_COVERED, Argument, Kind, Program, Routine, Step
from davies_sym.emit.languages.routines import (
    call,
    checks_routine,
    forces_agree_routine,
    formula_routine,
    fresh,
    relation,
)
from davies_sym.emit.languages.text import origin_text, parameter_lines
from davies_sym.emit.languages.variant_choice_program import working
from davies_sym.emit.several_inputs_report import condition_text, mesh_text, region_force_text
from davies_sym.losses.definitions import parameters_of


def several_inputs_program(si: SeveralInputs, module: str, not_covered: str) -> Program:
    """The program of ``si``; ``module`` and ``not_covered`` as for a one-input train."""
    public = given_forms(si)
    names = _parameter_names(si, public)
    table = si.parameter_table([known_symbols(si)[n] for n in names])
    conditions = {
        c.name: formula_routine(
            f"condition_{c.name}",
            f"speed condition {c.name} = {sympy.sstr(c.form)} ({'; '.join(c.decides)})",
            public(c.form),
            names,
        )
        for c in si.conditions
    }
    regions, forces = _region_routines(si, public, names)
    speeds, torques = _port_routines(si, public, names)
    in_ranges = checks_routine(
        "in_ranges", "whether every parameter is in its range", range_checks(table, names), names
    )
    routines = [*conditions.values(), *speeds, *regions.values(), *torques, *forces.values(), in_ranges]
    choice = _choice_steps(si, names, conditions, regions, forces, in_ranges)
    routines += [_choice(choice, names, not_covered), _reason(choice, names)]
    _check_routine_names(routines, names)
    lines = _header_lines(si, table, names, routines, not_covered)
    return Program(module, tuple(lines), tuple(routines), "efficiency", names, ())


def _parameter_names(si: SeveralInputs, public: Callable[[sympy.Expr], sympy.Expr]) -> tuple[str, ...]:
    """The parameters the Python module's efficiency takes (and checks the ranges of),
    in its order."""
    used: set[sympy.Basic] = set()
    for c in si.conditions:
        used |= public(c.form).free_symbols
    for v in si.port_speeds.values():
        used |= public(v.to_expr()).free_symbols
    for r in si.regions:
        used |= public(r.efficiency).free_symbols
        for p in si.train.ports.every:
            used |= public(r.torques[p].to_expr()).free_symbols
        for f, assumed in r.loaded_forces.values():
            used |= public(f.to_expr() * assumed).free_symbols
    return tuple(str(s) for s in sorted_symbols({sympy.Symbol(str(s)) for s in used}))


def known_symbols(si: SeveralInputs) -> dict[str, sympy.Symbol]:
    """Every symbol a parameter name may stand for: speeds, the load torque, the train's
    symbols and the parameters of its loss definitions."""
    train = si.train
    every = (
        *si.speeds,
        LOAD_TORQUE,
        *train.symbols.values(),
        *parameters_of(set(train.symbols.values()), train.definitions),
    )
    return {str(s): s for s in every}


def _region_routines(
    si: SeveralInputs, public: Callable[[sympy.Expr], sympy.Expr], names: tuple[str, ...]
) -> tuple[dict[int, Routine], dict[int, Routine]]:
    """The efficiency of each region (Mantriota and Pennestri 2003, eq. (6)) and, where
    it assumes loaded forces, the check that they agree."""
    regions: dict[int, Routine] = {}
    forces: dict[int, Routine] = {}
    for r in si.regions:
        regions[r.number] = formula_routine(
            f"region_{r.number}",
            f"efficiency in region ({r.number}), where "
            f"{' and '.join(condition_text(si, r))}: power in at "
            f"{', '.join(r.inputs)}, out at {', '.join(r.outputs)}",
            public(r.efficiency),
            names,
        )
        if r.loaded_forces:
            needs = f"region ({r.number}) assumes"
            forces[r.number] = forces_agree_routine(f"region_{r.number}", needs, r.loaded_forces, public, names)
    return regions, forces


def _port_routines(
    si: SeveralInputs, public: Callable[[sympy.Expr], sympy.Expr], names: tuple[str, ...]
) -> tuple[list[Routine], list[Routine]]:
    """The speed of each port the inputs do not set, in the input speeds, and the torque
    the outside applies at each port in each region (in the load torque; Mantriota and
    Pennestri 2003, eqs. (3)-(5)): what a simulation needs besides the efficiency."""
    ports = si.train.ports
    speeds = [
        (f"speed_{p}", f"speed of port {p} (signed, rad/s) in the input speeds", si.port_speeds[p])
        for p in ports.every
        if p not in ports.inputs
    ]
    torque = "torque the outside applies at port {} in region ({}) (power into the train: torque times speed)"
    torques = [
        (f"region_{r.number}_torque_{p}", torque.format(p, r.number), r.torques[p])
        for r in si.regions
        for p in ports.every
    ]
    speed_routines, torque_routines = (
        [formula_routine(name, summary, public(form.to_expr()), names) for name, summary, form in group]
        for group in (speeds, torques)
    )
    return speed_routines, torque_routines


def _check_routine_names(routines: Sequence[Routine], names: tuple[str, ...]) -> None:
    """Refuse a generated function named like a parameter or like another function."""
    seen: set[str] = set()
    for routine in routines:
        if routine.name in names:
            raise RefusedName("symbol", routine.name, "it is also the name of a generated function", "code")
        if routine.name in seen:
            why = "it is also the name of another function"
            raise RefusedName("generated function name", routine.name, why, "code")
        seen.add(routine.name)


def _header_lines(
    si: SeveralInputs, table: Sequence[Parameter], names: tuple[str, ...], routines: Sequence[Routine], not_covered: str
) -> list[str]:
    """The comment at the head of the program: source, inputs, parameters, speed
    conditions, regions, functions and the reasons of ``not_covered``."""
    train = si.train
    ports = train.ports
    lines = [
        f"Efficiency of {train.name}, driven at {', '.join(ports.inputs)}: every power-flow region "
        "(Mantriota and Pennestri 2003, eq. (6); Davies' method).",
        f"Source: {train.source or 'not given'}.",
        f"Generated by davies_sym from {origin_text(train.path, None)}; do not edit.",
        "",
        f"Input speeds {', '.join(str(s) for s in si.speeds)} (signed, rad/s), load torque {LOAD_TORQUE} at "
        f"{ports.output} (magnitude, resisting its motion).",
        "",
        "Parameters (every function takes those it uses, in this order):",
        *parameter_lines(table, names),
        "",
        "Speed conditions (lines through the origin of the input speeds):",
        *(f"  {c.name} = {sympy.sstr(c.form)}: {'; '.join(c.decides)}" for c in si.conditions),
        "",
        "Regions (the choice takes the one whose conditions hold and whose loaded forces agree, when exactly "
        "one does):",
    ]
    for r in si.regions:
        lines.append(
            f"  ({r.number}) region_{r.number}: {' and '.join(condition_text(si, r))}; {'; '.join(mesh_text(si, r))}"
        )
        lines += [f"      loaded force {text}" for text in region_force_text(r)]
    lines += [
        "",
        "Functions:",
        *(f"  {r.name}({', '.join(r.argument_names)}): {r.summary}" for r in routines),
        "",
        f"{not_covered} means: on a speed-condition line, in no region or several, outside the parameters' "
        "ranges, or an efficiency outside (0, 1]; reason(...) says which, as the Python module's DesignError does:",
        *(f"  {k}: {text}" for k, text in REASONS),
    ]
    return lines


@dataclass(frozen=True)
class _Choice:
    """The steps that pick the region: ``ok`` (every parameter in its range),
    ``off_lines`` (off every speed-condition line), ``chosen`` (the formula of the one
    region that holds, NaN where none or several do) and ``held``: the conditions under
    which one alone holds."""

    steps: tuple[Step, ...]
    ok: sympy.Symbol
    off_lines: sympy.Symbol
    chosen: sympy.Symbol
    held: tuple[sympy.Basic, ...]
    local: Callable[[str], str]


def _choice_steps(
    si: SeveralInputs,
    names: tuple[str, ...],
    conditions: dict[str, Routine],
    regions: dict[int, Routine],
    forces: dict[int, Routine],
    in_ranges: Routine,
) -> _Choice:
    taken = set(names)

    def local(base: str) -> str:
        name = fresh(base, taken)
        taken.add(name)
        return name

    steps: list[Step] = []
    ok = sympy.Symbol(local("ok"))
    steps.append(Step(ok.name, Kind.BOOL, call(in_ranges)))
    negative: dict[str, sympy.Symbol] = {}
    on_line: list[sympy.Basic] = []
    for name, routine in conditions.items():
        value = sympy.Symbol(local(f"value_{name}"))
        steps.append(Step(value.name, Kind.REAL, call(routine)))
        negative[name] = sympy.Symbol(local(f"negative_{name}"))
        steps.append(Step(negative[name].name, Kind.BOOL, relation(value, "<", sympy.Integer(0))))
        on_line.append(relation(value, "==", sympy.Integer(0)))
    off_lines = sympy.Symbol(local("off_lines"))
    steps.append(Step(off_lines.name, Kind.BOOL, sympy.Not(sympy.Or(*on_line)) if on_line else sympy.true))
    holds: dict[int, sympy.Symbol] = {}
    for r in si.regions:
        agree: list[sympy.Symbol] = []
        if r.number in forces:
            agree.append(sympy.Symbol(local(f"agrees_{r.number}")))
            steps.append(Step(agree[0].name, Kind.BOOL, call(forces[r.number])))
        holds[r.number] = sympy.Symbol(local(f"holds_{r.number}"))
        steps.append(Step(holds[r.number].name, Kind.BOOL, _holds(r, negative, off_lines, agree)))
    branches = [
        (call(regions[n]), sympy.And(ok, h, *(sympy.Not(o) for m, o in holds.items() if m != n)))
        for n, h in holds.items()
    ]
    chosen = sympy.Symbol(local("chosen"))
    steps.append(Step(chosen.name, Kind.REAL, sympy.Piecewise(*branches, (NOT_COVERED, True), evaluate=False)))
    return _Choice(tuple(steps), ok, off_lines, chosen, tuple(c for _, c in branches), local)


def _choice(choice: _Choice, names: tuple[str, ...], not_covered: str) -> Routine:
    """``efficiency(...)``: the region that holds, alone, screened as the Python module's
    ``_not_covered`` does."""
    eta = choice.local("eta")
    picked = sympy.Piecewise((choice.chosen, working(choice.chosen)), (NOT_COVERED, True), evaluate=False)
    return Routine(
        "efficiency",
        "Mantriota and Pennestri's efficiency (eq. (6)): the output's power over the sum of "
        "the input shafts' powers in the region that holds; " + not_covered + " where the formulas do "
        "not hold",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(eta, Kind.REAL, picked)),
        sympy.Symbol(eta),
    )


#: Why ``efficiency`` has no value, as ``reason`` numbers it: the reasons of the Python
#: module's DesignError (`davies_sym.emit.several_inputs_runtime`).
REASONS = (
    (0, "an efficiency"),
    (1, "outside the parameters' ranges (PARAMETERS)"),
    (2, "no region's loaded forces agree with their assumed signs, or several do"),
    (3, "an efficiency outside (0, 1]"),
    (4, "on a speed-condition line"),
)


def _reason(choice: _Choice, names: tuple[str, ...]) -> Routine:
    """``reason(...)``: why ``efficiency`` has a value or not (`REASONS`), in the order the
    Python module counts them."""
    held, code = choice.local("held"), choice.local("code")
    # Distinct numbers per branch: sympy would merge equal values into one condition.
    found = sympy.Piecewise(
        *((sympy.Integer(k), c) for k, c in enumerate(choice.held, 1)), (sympy.Integer(0), True), evaluate=False
    )
    number = sympy.Piecewise(
        (sympy.Integer(1), sympy.Not(choice.ok)),
        (sympy.Integer(4), sympy.Not(choice.off_lines)),
        (sympy.Integer(0), working(choice.chosen)),
        (sympy.Integer(3), relation(sympy.Symbol(held), ">", sympy.Integer(0))),
        (sympy.Integer(2), True),
        evaluate=False,
    )
    return Routine(
        "reason",
        "why efficiency has a value or not: " + "; ".join(f"{k}: {text}" for k, text in REASONS),
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(held, Kind.REAL, found), Step(code, Kind.REAL, number)),
        sympy.Symbol(code),
    )


def _holds(
    region: Region, negative: dict[str, sympy.Symbol], off_lines: sympy.Symbol, agree: list[sympy.Symbol]
) -> sympy.Basic:
    """Whether ``region`` holds: off every condition line, each condition's sign its own,
    its loaded forces agreeing (``agree``: the step saying so, if it has any)."""
    signs = [negative[c] if s < 0 else sympy.Not(negative[c]) for c, s in region.signs.items()]
    return sympy.And(off_lines, *signs, *agree)
