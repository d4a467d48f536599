"""C99: one ``.c`` file, no header, ``#include <math.h>`` and ``<stdbool.h>``; every
variant, turning condition and choice a ``double`` function, the helpers ``static``.
The input port is an ``int`` (0: the declared input port, 1: the other), as the file's
opening comment says."""

from __future__ import annotations

from davies_sym.emit.languages.names import check_names, comment_lines
from davies_sym.emit.languages.printers import c_printer, printed_names
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.emit.languages.target import Target, indented, kind_names

_KINDS = {Kind.REAL: "double", Kind.BOOL: "bool", Kind.PORT: "int"}

#: C99's keywords, <stdbool.h>'s macros, <math.h>'s constants and the printer's functions.
RESERVED = frozenset(
    {
        "auto",
        "break",
        "case",
        "char",
        "const",
        "continue",
        "default",
        "do",
        "double",
        "else",
        "enum",
        "extern",
        "float",
        "for",
        "goto",
        "if",
        "inline",
        "int",
        "long",
        "register",
        "restrict",
        "return",
        "short",
        "signed",
        "sizeof",
        "static",
        "struct",
        "switch",
        "typedef",
        "union",
        "unsigned",
        "void",
        "volatile",
        "while",
        "_Bool",
        "_Complex",
        "_Imaginary",
        "bool",
        "true",
        "false",
        "NAN",
        "INFINITY",
        "HUGE_VAL",
        "M_PI",
        "M_E",
        "main",
        "math",
        "errno",
    }
) | printed_names(c_printer())


def _comment(lines: tuple[str, ...]) -> list[str]:
    """A block comment (``*/`` and ``/*`` in the text broken up); one line alone stays on one line."""
    body = [line.replace("*/", "* /").replace("/*", "/ *") for line in comment_lines(lines)]
    if len(body) == 1:
        return [f"/* {body[0]} */"]
    return ["/*", *(f" * {line}".rstrip() for line in body), " */"]


def _routine(routine: Routine) -> list[str]:
    printer = c_printer()
    arguments = ", ".join(f"{t} {n}" for t, n in kind_names(_KINDS, routine)) or "void"
    storage = "" if routine.exported else "static "
    lines = [*_comment((routine.summary,)), f"{storage}{_KINDS[routine.returns]} {routine.name}({arguments})", "{"]
    for step in routine.steps:
        if step.is_choice:
            lines.append(f"    {_KINDS[step.kind]} {step.target};")
            lines += indented(printer.doprint(step.value, assign_to=step.target), "    ")
        else:
            lines.append(f"    const {_KINDS[step.kind]} {step.target} = {printer.doprint(step.value)};")
    lines += [f"    return {printer.doprint(routine.result)};", "}"]
    return lines


def write_c(program: Program) -> str:
    """The C99 source of ``program``."""
    check_names(program, "C", RESERVED)
    port = (
        "The input port is an int: "
        + ", ".join(f"{k} for {p} as the input" for k, p in enumerate(program.ports))
        + "; efficiency returns NaN for any other value."
        if program.ports
        else ""
    )
    notes = (
        "",
        "C99, one file without a header: cc -std=c99 -O2 -c FILE.c (link with -lm); declare the functions "
        "you call (double name(double ...);). " + port,
    )
    lines = _comment((*program.header, *notes))
    lines += ["", "#include <math.h>", "#include <stdbool.h>"]
    # Strict C99 leaves M_PI out of math.h (an angle given in degrees is a multiple of pi).
    lines += ["", "#ifndef M_PI", "#define M_PI 3.14159265358979323846", "#endif"]
    for routine in program.routines:
        lines += ["", *_routine(routine)]
    return "\n".join(lines) + "\n"


C = Target("c", "NaN", write_c)
