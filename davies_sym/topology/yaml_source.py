"""Read a YAML document keeping the line of every entry, for error messages.

The document is composed into nodes (PyYAML), turned into plain Python data, and every
mapping key / sequence item gets its line recorded under a dotted path such as
``couplings.C.gears``.  Scalars stay strings, ints, floats or booleans; duplicate
mapping keys are reported instead of silently overwritten.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import yaml

from davies_sym.errors import Problem, TopologySyntaxError, shortened


@dataclass(frozen=True)
class SourceDocument:
    """Plain data of a YAML file plus the line of each dotted entry path."""

    data: Any
    lines: dict[str, int] = field(default_factory=dict)
    name: str | None = None

    def line(self, path: str) -> int | None:
        """Line of ``path`` or of its nearest parent that has one (the document's first line
        for a top-level key that is missing)."""
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path.rpartition(".")[0]
        return self.lines.get("")


#: Most nodes a document may expand to (aliases count each time they are used).
MAX_NODES = 100_000
#: Deepest nesting of mappings and lists.
MAX_DEPTH = 50


class _TooLarge(Exception):
    """The document expands to too many nodes or nests too deeply (``line``, ``entry``: where)."""

    def __init__(self, message: str, line: int | None = None, entry: str = ""):
        super().__init__(message)
        self.message = message
        self.line = line
        self.entry = entry


@dataclass
class _Count:
    """The nodes a conversion may still make, and how it met aliases: the nodes it made
    again through an alias (``expanded``) and where an alias was first used."""

    left: int = MAX_NODES
    seen: set[int] = field(default_factory=set)
    expanded: int = 0
    alias_line: int | None = None
    alias_entry: str = ""


#: What each plain tag holds, for a message (``!!int abc``: "an integer").
_TAG_KINDS = {
    "str": "text",
    "int": "an integer",
    "float": "a number",
    "bool": "true or false",
    "null": "nothing",
    "map": "a mapping",
    "seq": "a list",
}


def _short_tag(tag: str) -> str:
    return "!!" + tag.rpartition(":")[2] if tag.startswith("tag:yaml.org,2002:") else tag


def _tag_problem(node: yaml.Node, path: str) -> Problem | None:
    """Why the tag of ``node`` is refused (not a plain tag, or one that does not fit the
    node: ``!!int [1]``), or None."""
    line = node.start_mark.line + 1
    if node.tag not in _PLAIN_TAGS:
        return Problem(path, f"the YAML tag {node.tag!r} is not part of the language; write plain values", line)
    kind = node.tag.rpartition(":")[2]
    fits = {"map": yaml.MappingNode, "seq": yaml.SequenceNode}.get(kind, yaml.ScalarNode)
    if not isinstance(node, fits):
        kinds: dict[type[yaml.Node], str] = {yaml.MappingNode: "a mapping", yaml.SequenceNode: "a list"}
        written = kinds.get(type(node), "a plain value")
        return Problem(
            path, f"the tag {_short_tag(node.tag)} ({_TAG_KINDS[kind]}) is put on {written}; delete the tag", line
        )
    return None


def _plain(node: yaml.ScalarNode, path: str, problems: list[Problem]) -> tuple[bool, Any]:
    """(True, the value) of a scalar, or (False, None) with the problem recorded: a tag the
    value does not fit (``!!int abc``, ``!!bool maybe``) is reported at its line."""
    try:
        return True, _scalar(node)
    except (ValueError, KeyError, TypeError, OverflowError, yaml.YAMLError):
        kind = _TAG_KINDS.get(node.tag.rpartition(":")[2], "a value")
        problems.append(
            Problem(
                path,
                f"{shortened(str(node.value), 40)} is not {kind}, as its tag {_short_tag(node.tag)} says; "
                "write the value without the tag",
                node.start_mark.line + 1,
            )
        )
        return False, None


def _too_many(node: yaml.Node, path: str, line: int, count: _Count) -> _TooLarge:
    """The refusal of a document that expands past `MAX_NODES`, at the innermost list or
    mapping where the count ran out (``line``: its entry's): an alias bomb when aliases
    made most of the nodes, else too many items."""
    if count.expanded > MAX_NODES // 2:
        return _TooLarge(
            f"the document expands to more than {MAX_NODES} entries through aliases (the first one here): an "
            "alias bomb; write the entries out without anchors and aliases",
            count.alias_line,
            count.alias_entry,
        )
    kind = "list" if isinstance(node, yaml.SequenceNode) else "mapping"
    return _TooLarge(
        f"too many items: the file holds more than {MAX_NODES} entries in all (this {kind} has "
        f"{len(node.value)}); a train file has a few hundred, delete the rest",
        line,
        path,
    )


def _convert(
    node: yaml.Node, path: str, lines: dict[str, int], problems: list[Problem], count: _Count, depth: int = 0
) -> Any:
    count.left -= 1
    if count.left < 0:
        raise _TooLarge("")  # located by the list or mapping that holds the node (`_too_many`)
    if depth > MAX_DEPTH:
        raise _TooLarge(_TOO_DEEP, node.start_mark.line + 1)
    if id(node) in count.seen:  # an alias: the node is made again
        count.expanded += 1
        if count.alias_line is None:
            count.alias_line, count.alias_entry = node.start_mark.line + 1, path
    count.seen.add(id(node))
    lines.setdefault(path, node.start_mark.line + 1)
    refused = _tag_problem(node, path)
    if refused is not None:
        problems.append(refused)
        return None
    try:
        if isinstance(node, yaml.MappingNode):
            return _mapping(node, path, lines, problems, count, depth)
        if isinstance(node, yaml.SequenceNode):
            items = []
            for index, item in enumerate(node.value):
                child = f"{path}[{index}]"
                lines[child] = item.start_mark.line + 1
                items.append(_convert(item, child, lines, problems, count, depth + 1))
            return items
    except _TooLarge as exc:
        if exc.message:
            raise
        raise _too_many(node, path, lines.get(path, node.start_mark.line + 1), count) from None
    assert isinstance(node, yaml.ScalarNode)
    return _plain(node, path, problems)[1]


def _mapping(
    node: yaml.MappingNode, path: str, lines: dict[str, int], problems: list[Problem], count: _Count, depth: int
) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key_node, value_node in node.value:
        line = key_node.start_mark.line + 1
        if key_node.tag == "tag:yaml.org,2002:merge":
            problems.append(Problem(path, "merge keys (<<) are not part of the language; write the entries out", line))
            continue
        if not isinstance(key_node, yaml.ScalarNode):
            problems.append(Problem(path, "a key must be a plain name", line))
            continue
        written = f"{path}.{key_node.value}" if path else str(key_node.value)  # the entry, as far as it reads
        refused = _tag_problem(key_node, written)
        if refused is not None:
            problems.append(refused)
            continue
        readable, value = _plain(key_node, written, problems)
        if not readable:
            continue
        if value is None or isinstance(value, bool):
            # ~, null, true as a key would read as the name 'None' or 'True'.
            problems.append(Problem(path, f"{key_node.value!r} is not a name for a key: write a name", line))
            continue
        key = str(value)
        child = f"{path}.{key}" if path else key
        if key in out:
            problems.append(Problem(child, f"duplicate key {key!r}", line))
            continue
        lines[child] = line
        out[key] = _convert(value_node, child, lines, problems, count, depth + 1)
    return out


_TOO_DEEP = f"the document nests deeper than {MAX_DEPTH} levels; a train file needs a few"


def _deep_line(text: str) -> int | None:
    """The line where the nesting first exceeds ``MAX_DEPTH``, from the parser's events
    (an event stream, not a recursion, so any depth can be scanned)."""
    depth = 0
    try:
        for event in yaml.parse(text, Loader=yaml.SafeLoader):
            if isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
                depth += 1
                if depth > MAX_DEPTH:
                    mark = event.start_mark
                    return None if mark is None else int(mark.line) + 1
            elif isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
                depth -= 1
    except yaml.YAMLError:
        # Only the line is sought here: a syntax error met on the way leaves it unknown,
        # and the nesting is reported without a line.
        return None
    return None


_PLAIN_TAGS = {f"tag:yaml.org,2002:{t}" for t in ("str", "int", "float", "bool", "null", "map", "seq")}


def _scalar(node: yaml.Node) -> Any:
    """Resolve a scalar (int, float, bool, null, string) with PyYAML's safe rules.  A
    constructor of its own: a constructor keeps every node it has built, so one shared
    by the process would keep every file it ever read (a worker deriving thousands)."""
    return yaml.constructor.SafeConstructor().construct_object(node, deep=True)


def parse_yaml(text: str, name: str | None = None) -> SourceDocument:
    """Parse YAML text into a `SourceDocument`; syntax errors carry the line."""
    if text.startswith("\ufeff"):
        raise TopologySyntaxError(
            [
                Problem(
                    "", "the file starts with a byte-order mark (U+FEFF); save it as UTF-8 without a byte-order mark", 1
                )
            ],
            name,
        )
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except RecursionError:
        raise TopologySyntaxError([Problem("", _TOO_DEEP, _deep_line(text))], name) from None
    except yaml.reader.ReaderError as exc:
        line = text.count("\n", 0, exc.position) + 1
        code = exc.character if isinstance(exc.character, int) else ord(exc.character)
        raise TopologySyntaxError(
            [
                Problem(
                    "", f"the character U+{code:04X} (a control character) is not allowed in YAML text; delete it", line
                )
            ],
            name,
        ) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        message = " ".join(str(part) for part in (exc.context, exc.problem) if part)
        raise TopologySyntaxError([Problem("", message, mark.line + 1 if mark is not None else None)], name) from None
    except yaml.YAMLError as exc:  # pragma: no cover - unmarked errors are rare
        raise TopologySyntaxError([Problem("", str(exc))], name) from None
    if root is None:
        raise TopologySyntaxError([Problem("", "the file is empty", 1)], name)
    lines: dict[str, int] = {}
    problems: list[Problem] = []
    try:
        data = _convert(root, "", lines, problems, _Count())
    except _TooLarge as exc:
        raise TopologySyntaxError([Problem(exc.entry, exc.message, exc.line)], name) from None
    except (yaml.YAMLError, ValueError) as exc:
        raise TopologySyntaxError([Problem("", f"a value cannot be read: {str(exc)[:200]}")], name) from None
    if problems:
        raise TopologySyntaxError(problems, name)
    return SourceDocument(data, lines, name)
