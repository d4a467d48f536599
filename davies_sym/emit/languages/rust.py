"""Rust: one file of ``pub fn`` on ``f64`` (use it as a module, ``mod tuplin;``), one per
variant, turning condition and choice, the helpers private; the input port an ``i32``
(0: the declared input port, 1: the other)."""

from __future__ import annotations

from davies_sym.emit.languages.names import check_names, comment_lines
from davies_sym.emit.languages.printers import printed_names, rust_printer
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.emit.languages.target import Target, kind_names

_KINDS = {Kind.REAL: "f64", Kind.BOOL: "bool", Kind.PORT: "i32"}

#: Rust's keywords (strict, reserved and weak ones that matter), the types used and the
#: prelude's enum variants.
RESERVED = frozenset(
    {
        "as",
        "break",
        "const",
        "continue",
        "crate",
        "else",
        "enum",
        "extern",
        "false",
        "fn",
        "for",
        "if",
        "impl",
        "in",
        "let",
        "loop",
        "match",
        "mod",
        "move",
        "mut",
        "pub",
        "ref",
        "return",
        "self",
        "Self",
        "static",
        "struct",
        "super",
        "trait",
        "true",
        "type",
        "unsafe",
        "use",
        "where",
        "while",
        "async",
        "await",
        "dyn",
        "abstract",
        "become",
        "box",
        "do",
        "final",
        "macro",
        "override",
        "priv",
        "typeof",
        "unsized",
        "virtual",
        "yield",
        "try",
        "gen",
        "union",
        "f64",
        "f32",
        "i32",
        "bool",
        "std",
        "core",
        # The prelude's enum variants: a parameter of that name is a pattern that cannot bind.
        "Some",
        "None",
        "Ok",
        "Err",
    }
) | printed_names(rust_printer())


def _routine(routine: Routine) -> list[str]:
    printer = rust_printer()
    arguments = ", ".join(f"{n}: {t}" for t, n in kind_names(_KINDS, routine))
    visibility = "pub " if routine.exported else ""
    lines = [
        *(f"/// {line}".rstrip() for line in comment_lines([routine.summary])),
        f"{visibility}fn {routine.name}({arguments}) -> {_KINDS[routine.returns]} {{",
    ]
    for step in routine.steps:
        lines.append(f"    let {step.target}: {_KINDS[step.kind]} = {printer.doprint(step.value)};")
    lines += [f"    {printer.doprint(routine.result)}", "}"]
    return lines


def write_rust(program: Program) -> str:
    """The Rust source of ``program``."""
    check_names(program, "Rust", RESERVED)
    port = (
        "The input port is an i32: "
        + ", ".join(f"{k} for {p} as the input" for k, p in enumerate(program.ports))
        + "; efficiency returns f64::NAN for any other value."
        if program.ports
        else ""
    )
    notes = ("", "Rust: a module file (mod NAME; in your crate) or a crate of its own. " + port)
    lines = [f"// {line}".rstrip() for line in comment_lines((*program.header, *notes))]
    lines += ["", "#![allow(non_snake_case, unused_parens, clippy::all)]"]
    for routine in program.routines:
        lines += ["", *_routine(routine)]
    return "\n".join(lines) + "\n"


RUST = Target("rust", "NaN", write_rust)
