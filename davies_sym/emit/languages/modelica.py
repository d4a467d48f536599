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
    lines += [f"end {program.module};"]
    return "\n".join(lines) + "\n"


MODELICA = Target("modelica", _NOT_COVERED, write_modelica)
