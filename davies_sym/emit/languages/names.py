"""Names and comments in a target language: the train's parameters become argument
names and its ports and conditions parts of function names, so each must be an
identifier of the language and none of its reserved words (a refusal names the symbol,
exit status 2); and the user's texts (train name, source) go into comments, which must
stay comments whatever they hold."""

from __future__ import annotations

import re
import textwrap
from collections.abc import Collection, Iterable

from davies_sym.emit.languages.program import Program
from davies_sym.errors import DerivationError


class RefusedName(DerivationError):
    """A parameter or function name the target language cannot take: ``kind`` (``symbol``
    or ``generated function name``), the ``name``, ``why``, and the ``code`` generated;
    `davies_sym.emit.languages.registry.emit_code` reports it where the file writes the name."""

    def __init__(self, kind: str, name: str, why: str, code: str):
        self.kind, self.name, self.why, self.code = kind, name, why, code
        super().__init__(f"the {kind} {name!r} cannot be a name in the generated {code} ({why}); rename it")


def check_names(
    program: Program,
    language: str,
    reserved: Collection[str],
    extra: Collection[str] = (),
    leading_underscore: bool = True,
) -> None:
    """Refuse a parameter or function name the language cannot take: not an ASCII
    identifier, a reserved word or a name the generated code uses (``reserved``), a name
    the file itself defines besides its functions (``extra``: the module's name, an
    output variable), or, where the language forbids it, one starting with ``_``."""
    functions = [r.name for r in program.routines]
    # Every routine's arguments, not only the choice's: speed_ratio takes geometry alone.
    symbols = dict.fromkeys((*program.parameters, *(a for r in program.routines for a in r.argument_names)))
    for kind, names in (("symbol", tuple(symbols)), ("generated function name", functions)):
        for name in names:
            why = None
            if not (name.isascii() and name.isidentifier()):
                why = "not an ASCII identifier"
            elif name in reserved:
                why = f"a reserved word or a name the generated {language} code uses"
            elif name in extra:
                why = "the name of the generated module"
            elif name.startswith("_") and not leading_underscore:
                why = f"{language} names cannot start with '_'"
            if why:
                raise RefusedName(kind, name, why, f"{language} code")


_CALL = re.compile(r"\b([A-Za-z_][A-Za-z_0-9]*)\s*\.?\(")


def called_names(lines: Iterable[str], functions: Collection[str], comment: str) -> frozenset[str]:
    """Those of ``functions`` (the names a printer may write) that the code ``lines``
    calls, comment lines (opening with ``comment``) left out: a parameter may take the
    name of a function the file does not call (a helix angle ``beta``, a lead angle
    ``gamma``), as it hides nothing there."""
    code = (line for line in lines if not line.lstrip().startswith(comment))
    return frozenset(name for line in code for name in _CALL.findall(line) if name in functions)


def comment_text(line: str) -> str:
    """``line`` with every non-printable character written as its escape, so a comment
    line stays one line."""
    return "".join(ch if ch.isprintable() else ch.encode("unicode_escape").decode("ascii") for ch in line)


def comment_lines(lines: Iterable[str], width: int = 100) -> list[str]:
    """``lines`` as comment text (see `comment_text`) wrapped to ``width``; a wrapped
    line's continuation is indented four spaces more than the line."""
    out: list[str] = []
    for line in lines:
        text = comment_text(line)
        body = text.lstrip(" ")
        indent = " " * (len(text) - len(body))
        out += textwrap.wrap(
            body,
            width,
            initial_indent=indent,
            subsequent_indent=indent + "    ",
            break_long_words=False,
            break_on_hyphens=False,
        ) or [""]
    return out
