"""Reading entries of a topology file: every problem is collected with its location."""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Iterable, Mapping
from dataclasses import replace
from typing import Any

import sympy

from davies_sym.errors import Problem, shortened
from davies_sym.topology.schema import Field
from davies_sym.topology.symbols import QuantityError, parse_quantity
from davies_sym.topology.yaml_source import SourceDocument

#: Names that definitions may take, by kind, and how the rule reads in a message.
NAME_PATTERNS: dict[str, tuple[re.Pattern[str], str]] = {
    "link": (
        re.compile(r"[A-Za-z0-9_](?:[A-Za-z0-9_/.+ -]{0,38}[A-Za-z0-9_/.+-])?"),
        "ASCII letters, digits, spaces and _ / . + -",
    ),
    "gear": (
        re.compile(r"[A-Za-z0-9_](?:[A-Za-z0-9_/.+ -]{0,38}[A-Za-z0-9_/.+-])?"),
        "ASCII letters, digits, spaces and _ / . + -",
    ),
    "coupling": (re.compile(r"[A-Za-z0-9_]{1,40}"), "ASCII letters, digits and underscores"),
    "state": (re.compile(r"[A-Za-z0-9_]{1,40}"), "ASCII letters, digits and underscores"),
}


class EntryReader:
    """Collects problems (with line numbers) and the symbols of one topology file."""

    def __init__(self, document: SourceDocument):
        self.document = document
        self.problems: list[Problem] = []
        self.symbols: dict[str, sympy.Symbol] = {}
        #: Names whose definition was refused: references to them are not reported again.
        self.broken: set[str] = set()
        #: Kinds of names (``link``, ``gear``, ``coupling``) whose table is missing or
        #: unreadable: the table's own problem says it all, references are not reported.
        self.unreadable: set[str] = set()
        #: Kinds whose optional table is absent: the first reference says so, once.
        self.absent: set[str] = set()
        #: The entry where each symbol is first written (``r1`` -> ``gears.1.radius``).
        self.written: dict[str, str] = {}
        #: The role each symbol was first read in (``r1`` -> ``length``).
        self.roles: dict[str, str] = {}
        #: (kind, name) of each unknown name reported: its problem's index, message and other places.
        self._unknown: dict[tuple[str, str], tuple[int, str, list[str]]] = {}

    def problem(self, path: str, message: str) -> None:
        self.problems.append(Problem(path, message, self.document.line(path)))

    def mapping(self, value: Any, path: str) -> Mapping[str, Any] | None:
        if isinstance(value, Mapping):
            return value
        self.problem(path, f"expected a mapping, got {describe(value)}")
        return None

    def unknown(self, path: str, kind: str, name: str, message: str | None = None) -> None:
        """Report a reference to an undefined name, unless its definition or its whole table
        was refused already (one problem per cause)."""
        if name in self.broken or kind in self.unreadable:
            return
        if kind in self.absent:
            self.unreadable.add(kind)
            self.problem(
                path,
                f"unknown {kind} {shortened(name)}: the file has no `{kind}s` table; add one "
                f"that defines every {kind} the file names",
            )
            return
        text = message or f"unknown {kind} {shortened(name)}{self._known(kind, name)}"
        first = self._unknown.get((kind, name))
        if first is None:
            self._unknown[(kind, name)] = (len(self.problems), text, [])
            self.problem(path, text)
            return
        # The same missing name again: one problem, which lists where else it is used.
        index, text, also = first
        also.append(path)
        shown = ", ".join(also[:3]) + (f" and {len(also) - 3} more" if len(also) > 3 else "")
        self.problems[index] = replace(self.problems[index], message=f"{text} (also in {shown})")

    def _known(self, kind: str, name: str) -> str:
        """What to write instead of an unknown name: the closest defined ones, or all of
        them (the table of ``kind`` as the file writes it: a mapping or a list of names)."""
        table = self.document.data.get(f"{kind}s") if isinstance(self.document.data, Mapping) else None
        names = [str(n) for n in (table if isinstance(table, (Mapping, list)) else ()) if not isinstance(n, Mapping)]
        if not names:
            return ""
        close = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        shown = ", ".join(repr(n) for n in names[:12]) + (" ..." if len(names) > 12 else "")
        hint = f"did you mean {' or '.join(repr(n) for n in close)}? " if close else ""
        return f" ({hint}the {kind}s are {shown})"

    def check_keys(self, entry: Mapping[str, Any], path: str, fields: Iterable[Field]) -> None:
        """Report unknown and missing keys of ``entry`` against ``fields``."""
        fields = tuple(fields)
        known = {f.key for f in fields}
        previous: tuple[str, Any] | None = None
        for key, value in entry.items():
            if key not in known:
                # A top-level key is its own entry (``gear_ratio``, at its own line).
                self.problem(
                    f"{path}.{key}" if path else key,
                    f"unknown key {key!r} (known: {', '.join(sorted(known))})" + _split_by_comma(key, value, previous),
                )
            previous = (key, value)
        for f in fields:
            if f.required and f.key not in entry:
                self.problem(path or f.key, f"missing required key {f.key!r}: add `{f.key}:` ({f.kind})")

    def items(self, value: Any, path: str, what: str) -> list[Any] | None:
        """A list entry (``what`` it holds, for the message): a list, or one item written
        without brackets, read as the list of that item (``brake: c2`` is ``brake: [c2]``);
        None, with the problem recorded, for anything else."""
        if isinstance(value, list):
            return value
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            return [value]
        self.problem(path, f"expected {what}, got {describe(value)}")
        return None

    def name(self, value: Any, path: str) -> str | None:
        """A name (of a link, gear or coupling): strings and integers are accepted."""
        if isinstance(value, bool) or value is None or isinstance(value, (list, dict, float)):
            self.problem(path, f"expected a name, got {describe(value)}")
            return None
        return str(value)

    def defined_name(self, value: Any, path: str, kind: str) -> str | None:
        """The name a link, gear, coupling or state is defined under, checked against ``NAME_PATTERNS``.

        Coupling and state names become parts of symbols, function and file names of the
        outputs, so they are identifiers; links and gears may also hold spaces and ``/ . + -``
        (``3/4``, ``Planet A``).
        """
        name = self.name(value, path)
        if name is None:
            return None
        pattern, allowed = NAME_PATTERNS[kind]
        if not pattern.fullmatch(name):
            self.broken.add(name)
            self.problem(path, f"{shortened(name)} is not a valid {kind} name: use {allowed} (at most 40)")
            return None
        return name

    def quantity(self, value: Any, path: str, role: str, roots: bool = False) -> sympy.Expr | None:
        """``value`` read as a quantity of ``role`` (square roots only where ``roots``), or None
        with the problem recorded."""
        known = set(self.symbols)
        try:
            read = parse_quantity(value, role, self.symbols, roots)
        except QuantityError as exc:
            self.problem(path, str(exc))
            return None
        for new in self.symbols.keys() - known:
            self.written.setdefault(new, path)
            self.roles.setdefault(new, role)
        # An ordinary efficiency is a number in (0, 1], a length is not: one symbol is not both.
        for name in sorted(str(s) for s in read.free_symbols) if isinstance(read, sympy.Basic) else ():
            first = self.roles.get(name)
            if first is not None and first != role and "efficiency" in (first, role):
                self.problem(
                    path,
                    f"{name} is written as {_a(first)} at {self.written.get(name, '?')} and here as {_a(role)}: "
                    "one symbol has one meaning; give one of them another name",
                )
        return read


def _a(role: str) -> str:
    return f"{'an' if role[0] in 'aeiou' else 'a'} {role}"


def describe(value: Any) -> str:
    """``value`` for a message, as written in YAML and shortened (a huge value is shown by its ends)."""
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return shortened(value, 40)
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:18]} ... {text[-17:]} ({len(text)} characters)"


def _split_by_comma(key: Any, value: Any, previous: tuple[str, Any] | None) -> str:
    """The hint for an unknown key that is the rest of the text before it: in ``{description:
    front carrier, rear annulus}`` YAML ends the text at the comma and reads ``rear annulus``
    as a key without a value."""
    if value is not None or previous is None or not isinstance(previous[1], str):
        return ""
    whole = json.dumps(f"{previous[1]}, {key}", ensure_ascii=False)
    return f"; a comma ends a value inside {{...}}: quote it, {previous[0]}: {whole}"
