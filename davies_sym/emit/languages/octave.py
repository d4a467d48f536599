"""Octave (and MATLAB syntax): a script file (it opens with ``1;``) defining one function
per variant, turning condition and choice; ``source`` it, then call them.  The input
port is a number (0: the declared input port, 1: the other)."""

from __future__ import annotations

from davies_sym.emit.languages.names import called_names, check_names, comment_lines
from davies_sym.emit.languages.printers import octave_printer, printed_names
from davies_sym.emit.languages.program import Program, Routine
from davies_sym.emit.languages.routines import fresh
from davies_sym.emit.languages.target import Target, indented

#: Octave's keywords and the constants and variables the printed code uses; the functions
#: the printer may write (`FUNCTIONS`) are reserved where the file calls them.
RESERVED = frozenset(
    {
        "__FILE__",
        "__LINE__",
        "break",
        "case",
        "catch",
        "classdef",
        "continue",
        "do",
        "else",
        "elseif",
        "end",
        "end_try_catch",
        "end_unwind_protect",
        "endclassdef",
        "endenumeration",
        "endevents",
        "endfor",
        "endfunction",
        "endif",
        "endmethods",
        "endparfor",
        "endproperties",
        "endswitch",
        "endwhile",
        "enumeration",
        "events",
        "for",
        "function",
        "global",
        "if",
        "methods",
        "otherwise",
        "parfor",
        "persistent",
        "properties",
        "return",
        "switch",
        "try",
        "until",
        "unwind_protect",
        "unwind_protect_cleanup",
        "while",
        "NaN",
        "nan",
        "Inf",
        "inf",
        "pi",
        "e",
        "i",
        "j",
        "true",
        "false",
        "ans",
        "nargin",
        "nargout",
        "varargin",
        "varargout",
    }
)
FUNCTIONS = printed_names(octave_printer())


def _routine(routine: Routine) -> list[str]:
    printer = octave_printer()
    output = fresh("result", {*routine.argument_names, *(s.target for s in routine.steps)})
    lines = [
        *(f"% {line}".rstrip() for line in comment_lines([routine.summary])),
        f"function {output} = {routine.name}({', '.join(routine.argument_names)})",
    ]
    for step in routine.steps:
        lines += indented(printer.doprint(step.value, assign_to=step.target), "  ")
    lines += indented(printer.doprint(routine.result, assign_to=output), "  ")
    lines.append("end")
    return lines


def write_octave(program: Program) -> str:
    """The Octave source of ``program``."""
    blocks = [_routine(routine) for routine in program.routines]
    called = called_names((line for block in blocks for line in block), FUNCTIONS, "%")
    check_names(program, "Octave", RESERVED | called, leading_underscore=False)
    port = (
        "The input port is a number: "
        + ", ".join(f"{k} for {p} as the input" for k, p in enumerate(program.ports))
        + "; efficiency returns NaN for any other value."
        if program.ports
        else ""
    )
    notes = ("", "Octave: source('FILE.m') defines the functions (scalar arguments). " + port)
    lines = [f"% {line}".rstrip() for line in comment_lines((*program.header, *notes))]
    lines += ["", "1;  % a script file: the functions below are defined when it is run"]
    for block in blocks:
        lines += ["", *block]
    return "\n".join(lines) + "\n"


OCTAVE = Target("octave", "NaN", write_octave)
