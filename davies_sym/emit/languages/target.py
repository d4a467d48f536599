"""A target language: its name on the command line, what its choice functions return
where there is no efficiency, and the writer of a program."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from davies_sym.emit.languages.program import Kind, Program, Routine


@dataclass(frozen=True)
class Target:
    name: str
    not_covered: str
    write: Callable[[Program], str]


def indented(text: str, indent: str) -> list[str]:
    """The lines of ``text`` (a printer's block) each behind ``indent``."""
    return [indent + line if line else line for line in text.split("\n")]


def kind_names(kinds: dict[Kind, str], routine: Routine) -> list[tuple[str, str]]:
    """(type, name) of each argument of ``routine`` in a language whose types are ``kinds``."""
    return [(kinds[a.kind], a.name) for a in routine.arguments]
