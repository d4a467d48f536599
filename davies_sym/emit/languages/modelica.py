"""Modelica: a ``package`` with one ``function`` per variant, turning condition and
choice (``input Real`` arguments, one output, an ``algorithm`` section), so a Modelica
model can call ``Package.efficiency(...)``.  The input port is an ``Integer`` (0: the
declared input port, 1: the other).  Modelica has no NaN: the choice functions return 0
where the other languages return NaN (a valid efficiency is in (0, 1]), and a range's
infinite bound is not checked (a Modelica Real is finite)."""

from __future__ import annotations

import sympy

from davies_sym.emit.languages.modelica_printer import ModelicaPrinter
from davies_sym.emit.languages.names import check_names, comment_lines, comment_text
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.emit.languages.routines import fresh
from davies_sym.emit.languages.target import Target

_KINDS = {Kind.REAL: "Real", Kind.BOOL: "Boolean", Kind.PORT: "Integer"}
_NOT_COVERED = "0"

#: Modelica's keywords, its predefined types and the functions the printed code uses.
RESERVED = frozenset(
    {
        "algorithm",
        "and",
        "annotation",
        "block",
        "break",
        "class",
        "connect",
        "connector",
        "constant",
        "constrainedby",
        "der",
        "discrete",
        "each",
        "else",
        "elseif",
        "elsewhen",
        "encapsulated",
        "end",
        "enumeration",
        "equation",
        "expandable",
        "extends",
        "external",
        "false",
        "final",
        "flow",
        "for",
        "function",
        "if",
        "import",
        "impure",
        "in",
        "initial",
        "inner",
        "input",
        "loop",
        "model",
        "not",
        "operator",
        "or",
        "outer",
        "output",
        "package",
        "parameter",
        "partial",
        "protected",
        "public",
        "pure",
        "record",
        "redeclare",
        "replaceable",
        "return",
        "stream",
        "then",
        "true",
        "type",
        "when",
        "while",
        "within",
        "Real",
        "Integer",
        "Boolean",
        "String",
        "time",
        "Modelica",
        "sqrt",
        "abs",
        "exp",
        "log",
        "sin",
        "cos",
        "tan",
        "asin",
        "acos",
        "atan",
        "sinh",
        "cosh",
        "tanh",
        "assert",
        "terminal",
        "sample",
        "pre",
        "edge",
        "change",
        "reinit",
        "noEvent",
        "smooth",
        "size",
        "ndims",
        "zeros",
        "ones",
        "fill",
        "min",
        "max",
        "sum",
        "product",
        "integer",
        "floor",
        "ceil",
        "div",
        "mod",
        "rem",
        "sign",
        "homotopy",
        "semiLinear",
        "delay",
        "cardinality",
        "inStream",
        "actualStream",
        "getInstanceName",
    }
)


def _string(text: str) -> str:
    """A Modelica string literal (a description)."""
    return '"' + comment_text(text).replace("\\", "\\\\").replace('"', '\\"') + '"'


def _finite(value: sympy.Basic) -> sympy.Basic:
    """``value`` without the checks against an infinite bound (Modelica has no infinity;
    its Reals are finite, so those checks hold)."""

    def finite(rel: sympy.Basic) -> bool:
        return not (isinstance(rel, sympy.core.relational.Relational) and rel.rhs.is_infinite)

    if isinstance(value, sympy.And):
        return sympy.And(*(a for a in value.args if finite(a)))
    return value if finite(value) else sympy.true


def _routine(routine: Routine) -> list[str]:
    printer = ModelicaPrinter({"not_covered": "0.0"})
    output = fresh("result", {*routine.argument_names, *(s.target for s in routine.steps)})
    lines = [f"  function {routine.name} {_string(routine.summary)}"]
    lines += [f"    input {_KINDS[a.kind]} {a.name};" for a in routine.arguments]
    lines.append(f"    output {_KINDS[routine.returns]} {output};")
    if routine.steps:
        lines.append("  protected")
        lines += [f"    {_KINDS[s.kind]} {s.target};" for s in routine.steps]
    lines.append("  algorithm")
    lines += [f"    {s.target} := {printer.doprint(s.value)};" for s in routine.steps]
    lines += [f"    {output} := {printer.doprint(_finite(routine.result))};", f"  end {routine.name};"]
    return lines


def write_modelica(program: Program) -> str:
    """The Modelica source of ``program``."""
    check_names(program, "Modelica", RESERVED, extra={program.module}, leading_underscore=False)
    port = (
        "The input port is an Integer: "
        + ", ".join(f"{k} for {p} as the input" for k, p in enumerate(program.ports))
        + "; efficiency returns 0 for any other value. "
        if program.ports
        else ""
    )
    notes = (
        "",
        f"Modelica: {program.module}.{program.entry}(...) from a model. " + port + "Modelica has no NaN: "
        "the choice functions return 0 where there is no efficiency (a valid one is in (0, 1]), and infinite "
        "range bounds are not checked.",
    )
    lines = [f"// {line}".rstrip() for line in comment_lines((*program.header, *notes))]
    lines += [f"package {program.module} {_string(program.header[0])}"]
    for routine in program.routines:
        lines += ["", *_routine(routine)]
    if program.ports:
        lines += ["", *_flange_model(program)]
    lines += [f"end {program.module};"]
    return "\n".join(lines) + "\n"


def _flange_model(program: Program) -> list[str]:
    """``model Gear``: the train between two rotational flanges (``flange_a`` the input
    port, ``flange_b`` the output port), its efficiency chosen as the FMU chooses it
    (`davies_sym.emit.fmu_sources`): from the power the output flange takes in, the
    input's variants where the load takes power, the output's where it gives power
    (at standstill the input's); an assertion stops the model where no formula holds."""
    by_name = {r.name: r for r in program.routines}
    ratio = by_name["speed_ratio"]
    names = [*program.parameters, *(n for n in ratio.argument_names if n not in program.parameters)]
    local = {*names}
    ratio_name, power, forward, backward = (fresh(n, local) for n in ("ratio", "power_b", "eta_ab", "eta_ba"))
    arguments = "".join(f"{n}, " for n in program.parameters)
    flange = "Modelica.Mechanics.Rotational.Interfaces"
    model = fresh("Gear", set(by_name))
    lines = [f"  model {model} {_string('the train between two rotational flanges, four quadrants')}"]
    lines += [f"    parameter Real {n};" for n in names]
    lines += [
        f'    {flange}.Flange_a flange_a "{program.ports[0]}, the input port";',
        f'    {flange}.Flange_b flange_b "{program.ports[1]}, the output port";',
        f'    Real {ratio_name} "speed ratio, {program.ports[0]} over {program.ports[1]}";',
        f'    Real {power} "power into the train at flange_b";',
        f'    Real {forward} "efficiency with flange_a driving";',
        f'    Real {backward} "efficiency with flange_b driving";',
        "  equation",
        f"    {ratio_name} = speed_ratio({', '.join(ratio.argument_names)});",
        f"    {forward} = efficiency({arguments}0);",
        f"    {backward} = efficiency({arguments}1);",
        f"    flange_a.phi = {ratio_name} * flange_b.phi;",
        f"    {power} = flange_b.tau * der(flange_b.phi);",
        f"    flange_a.tau = if {power} > 0 then -{backward} * flange_b.tau / {ratio_name}",
        f"      else -flange_b.tau / ({ratio_name} * {forward});",
        f'    assert({power} > 0 or {forward} > 0, "no efficiency with flange_a driving: reason " +',
        f"      String(reason({arguments}0)));",
        f'    assert({power} <= 0 or {backward} > 0, "no efficiency with flange_b driving: reason " +',
        f"      String(reason({arguments}1)));",
        f"  end {model};",
    ]
    return lines


MODELICA = Target("modelica", _NOT_COVERED, write_modelica)
