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

from davies_sym.errors import Problem, TopologySyntaxError


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
    """The document expands to too many nodes or nests too deeply (``line``: where)."""

    def __init__(self, message: str, line: int | None = None):
        super().__init__(message)
        self.line = line


def _convert(
    node: yaml.Node, path: str, lines: dict[str, int], problems: list[Problem], budget: list[int], depth: int = 0
) -> Any:
    budget[0] -= 1
    if budget[0] < 0:
        raise _TooLarge(f"the document expands to more than {MAX_NODES} entries (aliases used as a bomb?)")
    if depth > MAX_DEPTH:
        raise _TooLarge(_TOO_DEEP, node.start_mark.line + 1)
    lines.setdefault(path, node.start_mark.line + 1)
    if node.tag not in _PLAIN_TAGS:
        problems.append(
            Problem(
                path,
                f"the YAML tag {node.tag!r} is not part of the language; write plain values",
                node.start_mark.line + 1,
            )
        )
        return None
    if isinstance(node, yaml.MappingNode):
        out: dict[str, Any] = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                problems.append(
                    Problem(
                        path,
                        "merge keys (<<) are not part of the language; write the entries out",
                        key_node.start_mark.line + 1,
                    )
                )
                continue
            if not isinstance(key_node, yaml.ScalarNode):
                problems.append(Problem(path, "a key must be a plain name", key_node.start_mark.line + 1))
                continue
            key = str(_scalar(key_node))
            child = f"{path}.{key}" if path else key
            if key in out:
                problems.append(Problem(child, f"duplicate key {key!r}", key_node.start_mark.line + 1))
                continue
            lines[child] = key_node.start_mark.line + 1
            out[key] = _convert(value_node, child, lines, problems, budget, depth + 1)
        return out
    if isinstance(node, yaml.SequenceNode):
        items = []
        for index, item in enumerate(node.value):
            child = f"{path}[{index}]"
            lines[child] = item.start_mark.line + 1
            items.append(_convert(item, child, lines, problems, budget, depth + 1))
        return items
    return _scalar(node)


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


_CONSTRUCTOR = yaml.constructor.SafeConstructor()
_PLAIN_TAGS = {f"tag:yaml.org,2002:{t}" for t in ("str", "int", "float", "bool", "null", "map", "seq")}


def _scalar(node: yaml.Node) -> Any:
    """Resolve a scalar (int, float, bool, null, string) with PyYAML's safe rules."""
    return _CONSTRUCTOR.construct_object(node, deep=True)


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
        data = _convert(root, "", lines, problems, [MAX_NODES])
    except _TooLarge as exc:
        raise TopologySyntaxError([Problem("", str(exc), exc.line)], name) from None
    except (yaml.YAMLError, ValueError) as exc:
        raise TopologySyntaxError([Problem("", f"a value cannot be read: {str(exc)[:200]}")], name) from None
    if problems:
        raise TopologySyntaxError(problems, name)
    return SourceDocument(data, lines, name)
