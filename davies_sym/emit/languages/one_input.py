"""The program of a train driven at one port: one routine per turning condition, one per
variant, and the choice, as the Python module (`davies_sym.emit.formula_runtime`)
makes it.

A variant is the formula of one power flow: the input port and the sign of every turning
condition say which gear drives in each mesh (Laus 2011, Tables 5 and 6), and at light
load the signs of its loaded forces (the losses can reverse a tooth force).  The choice
``efficiency_from_<port>`` tries the variants of that input port in their order and takes
the first whose conditions hold: a condition counts as negative where its value is
``< 0`` (anything else, zero included, as positive, as the Python module's region code
does) and every loaded force must be ``>= 0`` times its sign.  Outside the admissible
parameters (ranges and relations), where no variant holds, and where the efficiency is
outside (0, 1] (the train self-locks) there is no efficiency.  ``efficiency(...,
input_port)`` picks the port's choice.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import sympy

from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.parameters import (
    admissible_relations,
    eliminated_symbols,
    given_form,
    given_parameters,
    parameter_table,
)
from davies_sym.efficiency.variant_result import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.program import NOT_COVERED, UPPER, Argument, Kind, Program, Routine, Step
from davies_sym.emit.languages.routines import (
    Check,
    call,
    checks_routine,
    formula_routine,
    fresh,
    relation,
)
from davies_sym.emit.languages.text import identifier_part, origin_text, parameter_lines
from davies_sym.emit.variant_report import condition_text, mesh_text, variant_forces


def bound(value: float) -> sympy.Expr:
    """A range bound as an exact number (``oo`` for an infinite one)."""
    if math.isinf(value):
        return sympy.oo if value > 0 else -sympy.oo
    return sympy.Integer(int(value)) if value.is_integer() else sympy.Float(value)


def range_checks(parameters: tuple[Parameter, ...], names: tuple[str, ...]) -> list[Check]:
    """``low < p`` (or ``<=``) and ``p <= high`` for each parameter in ``names``: what
    the Python module's ``_admissible`` compares, infinite bounds included (a NaN fails
    them)."""
    out: list[Check] = []
    for p in parameters:
        if p.name in names:
            symbol = sympy.Symbol(p.name)
            out += [(symbol, ">=" if p.closed_low else ">", bound(p.low)), (symbol, "<=", bound(p.high))]
    return out


def _where(variants: VariantSet, variant: Variant) -> str:
    conditions = condition_text(variants, variant)
    return f"input {variant.input}, output {variant.output}" + (
        f", where {' and '.join(conditions)}" if conditions else ""
    )


def one_input_program(variants: VariantSet, module: str, not_covered: str, state: str | None = None) -> Program:
    """The program of ``variants``; ``module``: the namespace's identifier; ``not_covered``:
    what the target language returns where there is no efficiency (``NaN``); ``state``:
    the operating state the variants are of, for the comments."""
    train = variants.train
    radicals = variants.analysis.network.layout.radicals

    def public(expr: sympy.Expr) -> sympy.Expr:
        """A formula in the parameters the user gives (radicals and defined symbols replaced)."""
        return given_form(expr, train, radicals)

    names = tuple(given_parameters(variants))
    table = parameter_table(variants)
    routines: list[Routine] = []
    for c in variants.conditions:
        routines.append(
            formula_routine(
                f"condition_{c.name}",
                f"turning condition {c.name} = {sympy.sstr(c.simplified)}; its sign picks the variants",
                public(c.expression),
                names,
            )
        )
    forces: dict[str, Routine] = {}
    for v in variants.variants:
        routines.append(
            formula_routine(
                v.name, f"efficiency of variant ({v.number}): {_where(variants, v)}", public(v.efficiency), names
            )
        )
        if v.loaded_forces:
            checks: list[Check] = [
                (public(f.to_expr() * sign), ">=", sympy.Integer(0)) for f, sign in v.loaded_forces.values()
            ]
            forces[v.name] = checks_routine(
                f"{v.name}_forces_agree",
                f"whether the loaded forces of {', '.join(v.loaded_forces)} have the signs variant ({v.number}) needs",
                checks,
                names,
            )
    routines += forces.values()
    relations = [r for r in admissible_relations(variants) if {str(s) for s in r.free_symbols} <= set(names)]
    checks = [*range_checks(table, names), *((r, ">", sympy.Integer(0)) for r in relations)]
    admissible = checks_routine(
        "admissible", "whether every parameter is in its range and every relation holds", checks, names
    )
    routines.append(admissible)
    ports = (train.ports.input, train.ports.output)
    ratio = public(variants.analysis.speed_ratio().to_expr())
    turning = None
    if {str(x) for x in ratio.free_symbols} <= set(names):
        summary = f"the speed ratio, {ports[0]} over {ports[1]}; 0 or infinite: a port does not turn"
        # A helper (the Python module's speed_ratio screens its values; this one is raw).
        turning = replace(formula_routine("raw_speed_ratio", summary, ratio, names), exported=False)
        routines.append(turning)
    steps = [_choice_steps(variants, port, names, routines, forces, admissible, turning) for port in ports]
    choices = [_port_choice(variants, port, names, st, not_covered) for port, st in zip(ports, steps, strict=True)]
    reasons = [_port_reason(variants, port, names, st) for port, st in zip(ports, steps, strict=True)]
    routines += [*choices, *reasons]
    port_argument = fresh("input_port", names)
    entry = _by_port("efficiency", "the efficiency", choices, names, port_argument, ports, not_covered)
    routines += [
        entry,
        _by_port("reason", "why there is an efficiency or not", reasons, names, port_argument, ports, not_covered),
    ]
    routines += _sensitivities(variants, names, public, steps, port_argument, ports, not_covered)
    _check_unique(routines, names)
    header = _header(variants, names, table, relations, routines, not_covered, state)
    return Program(module, header, tuple(routines), entry.name, names, ports)


@dataclass(frozen=True)
class _Choice:
    """The steps that pick the variant of one input port: ``ok`` (the design is
    admissible), ``turns`` (both ports turn: the speed ratio is finite and not 0),
    ``chosen`` (the first variant whose conditions hold and whose loaded forces agree, NaN
    where none does); ``held``: the conditions under which one does, in order;
    ``regions``: each variant with the conditions of its region alone (loaded forces
    aside)."""

    steps: tuple[Step, ...]
    ok: sympy.Symbol
    turns: sympy.Symbol
    chosen: sympy.Symbol
    held: tuple[sympy.Basic, ...]
    regions: tuple[tuple[sympy.Expr, sympy.Basic], ...]
    local: Callable[[str], str]
    #: The variant of each branch of ``held``, in order.
    order: tuple[str, ...] = ()


def _choice_steps(
    variants: VariantSet,
    port: str,
    names: tuple[str, ...],
    routines: list[Routine],
    forces: dict[str, Routine],
    admissible: Routine,
    turning: Routine | None,
) -> _Choice:
    taken = set(names)

    def local(base: str) -> str:
        name = fresh(base, taken)
        taken.add(name)
        return name

    steps: list[Step] = []
    ok = local("ok")
    steps.append(Step(ok, Kind.BOOL, call(admissible)))
    turns = local("turns")
    if turning is None:
        steps.append(Step(turns, Kind.BOOL, sympy.true))
    else:
        ratio = local("ratio")
        steps.append(Step(ratio, Kind.REAL, call(turning)))
        finite = relation(sympy.Abs(sympy.Symbol(ratio)), "<", LARGEST)
        steps.append(Step(turns, Kind.BOOL, sympy.And(finite, relation(sympy.Symbol(ratio), "!=", sympy.Integer(0)))))
    negative: dict[str, sympy.Symbol] = {}
    by_name = {r.name: r for r in routines}
    for c in variants.conditions:
        name = local(f"negative_{c.name}")
        negative[c.name] = sympy.Symbol(name)
        steps.append(Step(name, Kind.BOOL, relation(call(by_name[f"condition_{c.name}"]), "<", sympy.Integer(0))))
    mine = [v for v in variants.variants if v.input == port]
    agrees: dict[str, sympy.Symbol] = {}
    for v in mine:
        if v.name in forces:
            name = local(f"agrees_{v.number}")
            agrees[v.name] = sympy.Symbol(name)
            steps.append(Step(name, Kind.BOOL, call(forces[v.name])))
    branches, regions = [], []
    for v in mine:
        signs = [negative[c] if s < 0 else sympy.Not(negative[c]) for c, s in v.signs.items()]
        holds = sympy.And(sympy.Symbol(ok), *signs, *([agrees[v.name]] if v.name in agrees else []))
        branches.append((call(by_name[v.name]), holds))
        regions.append((call(by_name[v.name]), sympy.And(sympy.Symbol(ok), *signs)))
    # Where the losses move a turning point past its lossless boundary, the variant of
    # another region whose loaded forces all agree holds.
    branches += [(call(by_name[v.name]), sympy.And(sympy.Symbol(ok), agrees[v.name])) for v in mine if v.name in agrees]
    order = [v.name for v in mine] + [v.name for v in mine if v.name in agrees]
    chosen = local("chosen")
    steps.append(Step(chosen, Kind.REAL, sympy.Piecewise(*branches, (NOT_COVERED, True), evaluate=False)))
    return _Choice(
        tuple(steps),
        sympy.Symbol(ok),
        sympy.Symbol(turns),
        sympy.Symbol(chosen),
        tuple(condition for _, condition in branches),
        tuple(regions),
        local,
        tuple(order),
    )


def _sensitivities(
    variants: VariantSet,
    names: tuple[str, ...],
    public: Callable[[sympy.Expr], sympy.Expr],
    choices: list[_Choice],
    port_argument: str,
    ports: tuple[str, str],
    not_covered: str,
) -> list[Routine]:
    """For each parameter: each variant's exact partial derivative of its efficiency, and
    ``sensitivity_<name>(..., input_port)``, the derivative of the variant the choice takes
    (where the efficiency is, else ``not_covered``), as the Python module's ``sensitivity``."""
    symbols = given_parameters(variants)
    out: list[Routine] = []
    for name in names:
        part = identifier_part(name)
        slopes = {
            v.name: formula_routine(
                f"{v.name}_d_{part}",
                f"partial derivative in {name} of the efficiency of variant ({v.number})",
                sympy.diff(public(v.efficiency), symbols[name]),
                names,
            )
            for v in variants.variants
        }
        out += slopes.values()
        by_port = []
        for port, choice in zip(ports, choices, strict=True):
            slope, value = choice.local(f"d_{part}"), choice.local(f"value_d_{part}")
            branches = [(call(slopes[v]), held) for v, held in zip(choice.order, choice.held, strict=True)]
            taken = sympy.Piecewise(*branches, (NOT_COVERED, True), evaluate=False)
            screened = sympy.Piecewise(
                (sympy.Symbol(slope), sympy.And(choice.ok, choice.turns, working(choice.chosen))),
                (NOT_COVERED, True),
                evaluate=False,
            )
            by_port.append(
                Routine(
                    f"sensitivity_{part}_from_{identifier_part(port)}",
                    f"partial derivative in {name} of efficiency_from_{identifier_part(port)}",
                    tuple(Argument(n, Kind.REAL) for n in names),
                    Kind.REAL,
                    (*choice.steps, Step(slope, Kind.REAL, taken), Step(value, Kind.REAL, screened)),
                    sympy.Symbol(value),
                )
            )
        out += by_port
        out.append(
            _by_port(
                f"sensitivity_{part}",
                f"the partial derivative of the efficiency in {name}",
                by_port,
                names,
                port_argument,
                ports,
                not_covered,
            )
        )
    return out


def working(value: sympy.Symbol) -> sympy.Basic:
    """``0 < value <= 1`` (to rounding): the train runs; else it self-locks."""
    return sympy.And(relation(value, ">", sympy.Integer(0)), relation(value, "<=", UPPER))


def _port_choice(variants: VariantSet, port: str, names: tuple[str, ...], choice: _Choice, not_covered: str) -> Routine:
    """``efficiency_from_<port>(...)``: the first variant of ``port`` whose turning
    conditions hold and whose loaded forces agree, screened for self-locking."""
    eta = choice.local("eta")
    chosen = choice.chosen
    picked = sympy.Piecewise(
        (chosen, sympy.And(choice.ok, choice.turns, working(chosen))), (NOT_COVERED, True), evaluate=False
    )
    other = variants.train.ports.output if port == variants.train.ports.input else variants.train.ports.input
    return Routine(
        f"efficiency_from_{identifier_part(port)}",
        f"the efficiency with {port} as the input port ({other} the output): the first of its variants "
        f"whose turning conditions hold (and loaded forces agree); {not_covered} outside the admissible "
        "parameters, where none holds, or where the efficiency is outside (0, 1] (self-locking)",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(eta, Kind.REAL, picked)),
        sympy.Symbol(eta),
    )


#: Why ``efficiency_from_<port>`` has no efficiency, as ``reason_from_<port>`` numbers it:
#: the reasons of the Python module (`davies_sym.emit.formula_runtime`) and the API.
REASONS = (
    (0, "an efficiency (the train runs)"),
    (1, "outside the admissible parameters (PARAMETERS, RELATIONS)"),
    (2, "no variant's power flow agrees with its own forces (the losses reverse forces as no variant covers)"),
    (3, "the train self-locks (efficiency outside (0, 1])"),
    (4, "a port does not turn (speed ratio 0 or infinite)"),
)

#: Beyond this a speed ratio counts as infinite (a division by zero in floating point; a
#: bound every language prints as a finite double).
LARGEST = sympy.Float(1e300)


def _port_reason(variants: VariantSet, port: str, names: tuple[str, ...], choice: _Choice) -> Routine:
    """``reason_from_<port>(...)``: why the choice of ``port`` has an efficiency or not
    (`REASONS`), decided as the Python module decides: where no variant agrees with its
    loaded forces, the train self-locks if its region's own variant is not positive."""
    # Piecewise steps, which every language prints as statements: a disjunction of
    # conjunctions would need parentheses that C compilers ask for.  ``held`` numbers the
    # branch that held (distinct values: sympy would merge equal ones into one condition).
    held, own, code = choice.local("held"), choice.local("own"), choice.local("code")
    found = sympy.Piecewise(
        *((sympy.Integer(k), condition) for k, condition in enumerate(choice.held, 1)),
        (sympy.Integer(0), True),
        evaluate=False,
    )
    region = sympy.Piecewise(*choice.regions, (NOT_COVERED, True), evaluate=False)
    number = sympy.Piecewise(
        (sympy.Integer(1), sympy.Not(choice.ok)),
        (sympy.Integer(4), sympy.Not(choice.turns)),
        (sympy.Integer(0), working(choice.chosen)),
        (sympy.Integer(3), relation(sympy.Symbol(held), ">", sympy.Integer(0))),
        (sympy.Integer(3), relation(sympy.Symbol(own), "<=", sympy.Integer(0))),
        (sympy.Integer(2), True),
        evaluate=False,
    )
    codes = "; ".join(f"{k}: {text}" for k, text in REASONS)
    return Routine(
        f"reason_from_{identifier_part(port)}",
        f"why efficiency_from_{identifier_part(port)} has an efficiency or not: {codes}",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(held, Kind.REAL, found), Step(own, Kind.REAL, region), Step(code, Kind.REAL, number)),
        sympy.Symbol(code),
    )


def _by_port(
    name: str,
    what: str,
    choices: list[Routine],
    names: tuple[str, ...],
    port_argument: str,
    ports: tuple[str, str],
    not_covered: str,
) -> Routine:
    """``name(..., input_port)``: ``choices[input_port]`` (the routine of that input port)."""
    port = sympy.Symbol(port_argument, integer=True)
    picked = sympy.Piecewise(
        *((call(choice), sympy.Eq(port, k)) for k, choice in enumerate(choices)), (NOT_COVERED, True), evaluate=False
    )
    result = fresh("value", names)
    return Routine(
        name,
        f"{what} with {port_argument} = 0: {ports[0]} the input, {ports[1]} the "
        f"output, = 1: {ports[1]} the input, {ports[0]} the output; "
        f"{not_covered} for any other value",
        (*(Argument(n, Kind.REAL) for n in names), Argument(port_argument, Kind.PORT)),
        Kind.REAL,
        (Step(result, Kind.REAL, picked),),
        sympy.Symbol(result),
    )


def _check_unique(routines: list[Routine], names: tuple[str, ...]) -> None:
    """Every routine's name is its own and no parameter's (the choice takes every parameter
    and calls every routine)."""
    seen: set[str] = set()
    for r in routines:
        if r.name in names:
            raise RefusedName("symbol", r.name, "it is also the name of a generated function", "code")
        if r.name in seen:
            raise RefusedName("generated function name", r.name, "it is also the name of another function", "code")
        seen.add(r.name)


def _header(
    variants: VariantSet,
    names: tuple[str, ...],
    table: tuple[Parameter, ...],
    relations: list[sympy.Expr],
    routines: list[Routine],
    not_covered: str,
    state: str | None,
) -> tuple[str, ...]:
    """The opening comment: train, source, parameters, conditions, variants, functions."""
    train = variants.train
    lines = [
        f"Efficiency of {train.name}: every turning-condition variant (Davies' method; Laus 2011, Tables 5 and 6).",
        f"Source: {train.source or 'not given'}.",
        f"Generated by davies_sym from {origin_text(train.path, state)}; do not edit.",
    ]
    eliminated = eliminated_symbols(variants)
    if eliminated:
        given = ", ".join(f"{k} = {sympy.sstr(v)}" for k, v in sorted(eliminated.items(), key=lambda kv: str(kv[0])))
        lines.append(f"The geometric constraints give {given}; the formulas use the other radii.")
    lines += ["", "Parameters (every function takes those it uses, in this order):"]
    lines += parameter_lines(table, names)
    if relations:
        lines.append(f"Admissible designs also need {', '.join(f'{sympy.sstr(r)} > 0' for r in relations)}.")
    lines += ["", "Turning conditions (their signs say which gear drives in each mesh):"]
    lines += [f"  {c.name} = {sympy.sstr(c.simplified)}" for c in variants.conditions] or ["  none"]
    lines += ["", "Variants, in the order the choice tries them (a condition counts as negative where it is < 0):"]
    for v in variants.variants:
        lines.append(f"  ({v.number}) {v.name}: {_where(variants, v)}")
        lines.append(f"      meshes: {'; '.join(mesh_text(variants, v))}")
        lines += [f"      loaded force {text} (needed for this variant)" for text in _force_lines(variants, v)]
    lines += ["", "Functions:"]
    lines += [f"  {r.name}({', '.join(r.argument_names)}): {r.summary}" for r in routines]
    lines += [
        "",
        f"{not_covered} means: outside the admissible parameters, in no variant, or self-locking "
        "(efficiency outside (0, 1]); reason(...) says which, as the Python module's DesignError does:",
        *(f"  {k}: {text}" for k, text in REASONS),
    ]
    return tuple(lines)


def _force_lines(variants: VariantSet, variant: Variant) -> list[str]:
    return [
        f"{what}: {sympy.sstr(force)} {'>' if sign > 0 else '<'} 0"
        for what, force, sign in variant_forces(variants, variant)
    ]
