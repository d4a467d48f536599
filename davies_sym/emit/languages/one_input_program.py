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
from dataclasses import replace

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.parameters import (
    admissible_relations,
    eliminated_symbols,
    given_forms,
    given_parameters,
    parameter_table,
)
from davies_sym.efficiency.variant_result import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.program import NOT_COVERED, Kind, Program, Routine, Step
from davies_sym.emit.languages.routines import (
    Check,
    call,
    checks_routine,
    forces_agree_routine,
    formula_routine,
    fresh,
    relation,
)
from davies_sym.emit.languages.sensitivities import sensitivity_routines
from davies_sym.emit.languages.text import origin_text, parameter_lines
from davies_sym.emit.languages.variant_choice_program import (
    LARGEST,
    REASONS,
    ChoiceRoutines,
    PortSignature,
    by_port,
    choice_steps,
    port_choice,
    port_reason,
    port_variant,
)
from davies_sym.emit.variant_report import condition_text, mesh_text, variant_forces
from davies_sym.network.motion_singularities import vanishing_denominators


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


#: The routine of the speed ratio in all its symbols (the Python module's ``speed_ratio``).
RATIO = "speed_ratio"


def one_input_program(variants: VariantSet, module: str, not_covered: str, state: str | None = None) -> Program:
    """The program of ``variants``; ``module``: the namespace's identifier; ``not_covered``:
    what the target language returns where there is no efficiency (``NaN``); ``state``:
    the operating state the variants are of, for the comments."""
    train = variants.train
    public = given_forms(variants)

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
            needs = f"variant ({v.number}) needs"
            forces[v.name] = forces_agree_routine(v.name, needs, v.loaded_forces, public, names)
    routines += forces.values()
    relations = [r for r in admissible_relations(variants) if {str(s) for s in r.free_symbols} <= set(names)]
    checks = [*range_checks(table, names), *((r, ">", sympy.Integer(0)) for r in relations)]
    admissible = checks_routine(
        "admissible", "whether every parameter is in its range and every relation holds", checks, names
    )
    routines.append(admissible)
    ports = (train.ports.input, train.ports.output)
    ratio_routines, turning = _ratio_routines(variants, public, names, (table, relations), ports)
    routines += ratio_routines
    moving = _moving_routine(variants, public, names)
    routines += [moving] if moving is not None else []
    called = ChoiceRoutines({r.name: r for r in routines}, forces, admissible, turning, moving)
    steps = [choice_steps(variants, port, names, called) for port in ports]
    choices = [port_choice(variants, port, names, st, not_covered) for port, st in zip(ports, steps, strict=True)]
    reasons = [port_reason(variants, port, names, st) for port, st in zip(ports, steps, strict=True)]
    numbers = [port_variant(variants, port, names, st) for port, st in zip(ports, steps, strict=True)]
    routines += [*choices, *reasons, *numbers]
    signature = PortSignature(names, fresh("input_port", names), ports, not_covered)
    entry = by_port("efficiency", "the efficiency", choices, signature)
    routines += [entry, by_port("reason", "why there is an efficiency or not", reasons, signature)]
    routines.append(by_port("variant", "the number of the variant that holds (0: none)", numbers, signature))
    routines += sensitivity_routines(variants, public, steps, signature)
    _check_unique(routines, names)
    header = _header(variants, signature, table, relations, routines, state)
    return Program(module, header, tuple(routines), entry.name, names, ports)


def _ratio_routines(
    variants: VariantSet,
    public: Callable[[sympy.Expr], sympy.Expr],
    names: tuple[str, ...],
    screen: tuple[tuple[Parameter, ...], list[sympy.Expr]],
    ports: tuple[str, str],
) -> tuple[list[Routine], Routine | None]:
    """``speed_ratio`` in every symbol the ratio takes, screened as the Python module's is
    (NaN outside its symbols' ranges and relations ``screen``, or where it is not finite),
    its helpers, and the choice's raw ratio in the formulas' parameters (None where the
    ratio takes others)."""
    ratio = public(variants.analysis.speed_ratio().to_expr())
    extra = tuple(str(s) for s in sorted_symbols(ratio.free_symbols) if str(s) not in names)
    order = (*names, *extra)
    raw_summary = f"the speed ratio, {ports[0]} over {ports[1]}, unscreened; 0 or infinite: a port does not turn"
    raw = replace(formula_routine("raw_speed_ratio", raw_summary, ratio, order), exported=False)
    own = set(raw.argument_names)
    table, relations = screen
    checks = [
        *range_checks(table, tuple(own)),
        *((r, ">", sympy.Integer(0)) for r in relations if {str(s) for s in r.free_symbols} <= own),
    ]
    in_ranges = checks_routine("ratio_admissible", "whether the speed ratio's symbols are admissible", checks, order)
    value, ok, out = (fresh(n, order) for n in ("ratio", "ok", "screened"))
    finite = sympy.And(sympy.Symbol(ok), relation(sympy.Abs(sympy.Symbol(value)), "<", LARGEST))
    steps = (
        Step(value, Kind.REAL, call(raw)),
        Step(ok, Kind.BOOL, call(in_ranges)),
        Step(out, Kind.REAL, sympy.Piecewise((sympy.Symbol(value), finite), (NOT_COVERED, True), evaluate=False)),
    )
    summary = (
        f"the speed ratio, {ports[0]} over {ports[1]}, in every symbol it takes; NaN outside their ranges and "
        "relations or where a port does not turn (0: the output stands still)"
    )
    speed = Routine(RATIO, summary, raw.arguments, Kind.REAL, steps, sympy.Symbol(out))
    return [raw, in_ranges, speed], (raw if not extra else None)


def _moving_routine(
    variants: VariantSet, public: Callable[[sympy.Expr], sympy.Expr], names: tuple[str, ...]
) -> Routine | None:
    """``train_moves``: whether no denominator of the motions vanishes (`vanishing_denominators`,
    those in the formulas' parameters); None where none can."""
    factors = [public(d) for d in vanishing_denominators(variants.analysis)]
    checks = [(d, "!=", sympy.Integer(0)) for d in factors if {str(s) for s in d.free_symbols} <= set(names)]
    if not checks:
        return None
    summary = "whether no denominator of the motions vanishes (where one does the train locks)"
    return checks_routine("train_moves", summary, checks, names)


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
    signature: PortSignature,
    table: tuple[Parameter, ...],
    relations: list[sympy.Expr],
    routines: list[Routine],
    state: str | None,
) -> tuple[str, ...]:
    """The opening comment: train, source, parameters, conditions, variants, functions."""
    train, names, not_covered = variants.train, signature.names, signature.not_covered
    lines = [
        f"Efficiency of {train.name}: every turning-condition variant (Davies' method; Laus 2011, Tables 5 and 6).",
        f"Source: {train.source or 'not given'}.",
        f"Generated by davies_sym from {origin_text(train.path, state)}; do not edit.",
    ]
    eliminated = eliminated_symbols(variants)
    if eliminated:
        given = ", ".join(f"{k} = {sympy.sstr(v)}" for k, v in sorted(eliminated.items(), key=lambda kv: str(kv[0])))
        lines.append(f"The geometric constraints give {given}; the formulas use the other parameters.")
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
