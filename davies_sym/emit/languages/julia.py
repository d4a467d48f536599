"""Julia: a ``module`` with one function per variant, turning condition and choice, the
choice ``efficiency`` exported; the arguments untyped (any real number), the input port
an integer (0: the declared input port, 1: the other)."""

from __future__ import annotations

from davies_sym.emit.languages.names import called_names, check_names, comment_lines
from davies_sym.emit.languages.printers import julia_printer, printed_names
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.emit.languages.target import Target, indented

#: Julia's keywords and the constants and types the printed code uses; the functions the
#: printer may write (`FUNCTIONS`) are reserved where the file calls them.
RESERVED = frozenset(
    {
        "baremodule",
        "begin",
        "break",
        "catch",
        "const",
        "continue",
        "do",
        "else",
        "elseif",
        "end",
        "export",
        "false",
        "finally",
        "for",
        "function",
        "global",
        "if",
        "import",
        "let",
        "local",
        "macro",
        "module",
        "quote",
        "return",
        "struct",
        "true",
        "try",
        "using",
        "while",
        "abstract",
        "type",
        "mutable",
        "primitive",
        "where",
        "in",
        "isa",
        "outer",
        "public",
        "NaN",
        "Inf",
        "pi",
        "im",
        "Base",
        "Core",
        "Main",
        "nothing",
        "missing",
        "Integer",
        "Real",
        "Float64",
        "Bool",
    }
)
FUNCTIONS = printed_names(julia_printer())


def _routine(routine: Routine) -> list[str]:
    printer = julia_printer()
    arguments = ", ".join(f"{a.name}::Integer" if a.kind is Kind.PORT else a.name for a in routine.arguments)
    lines = [
        *(f"# {line}".rstrip() for line in comment_lines([routine.summary])),
        f"function {routine.name}({arguments})",
    ]
    for step in routine.steps:
        lines += indented(printer.doprint(step.value, assign_to=step.target), "    ")
    lines += [f"    return {printer.doprint(routine.result)}", "end"]
    return lines


def write_julia(program: Program) -> str:
    """The Julia source of ``program``."""
    blocks = [_routine(routine) for routine in program.routines]
    called = called_names((line for block in blocks for line in block), FUNCTIONS, "#")
    check_names(program, "Julia", RESERVED | called, extra={program.module})
    port = (
        "The input port is an integer: "
        + ", ".join(f"{k} for {p} as the input" for k, p in enumerate(program.ports))
        + "; efficiency returns NaN for any other value."
        if program.ports
        else ""
    )
    notes = ("", f'Julia: include("FILE.jl"); using .{program.module}; efficiency(...). ' + port)
    lines = [f"# {line}".rstrip() for line in comment_lines((*program.header, *notes))]
    lines += ["", f"module {program.module}", "", f"export {program.entry}"]
    for block in blocks:
        lines += ["", *block]
    lines += ["", f"end  # module {program.module}"]
    return "\n".join(lines) + "\n"


JULIA = Target("julia", "NaN", write_julia)
