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
        """Line of ``path`` or of its nearest parent that has one."""
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path.rpartition(".")[0]
        return None


def _convert(node: yaml.Node, path: str, lines: dict[str, int], problems: list[Problem]) -> Any:
    lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        out: dict[str, Any] = {}
        for key_node, value_node in node.value:
            key = str(_scalar(key_node))
            child = f"{path}.{key}" if path else key
            if key in out:
                problems.append(Problem(child, f"duplicate key {key!r}", key_node.start_mark.line + 1))
                continue
            lines[child] = key_node.start_mark.line + 1
            out[key] = _convert(value_node, child, lines, problems)
        return out
    if isinstance(node, yaml.SequenceNode):
        items = []
        for index, item in enumerate(node.value):
            child = f"{path}[{index}]"
            lines[child] = item.start_mark.line + 1
            items.append(_convert(item, child, lines, problems))
        return items
    return _scalar(node)


_CONSTRUCTOR = yaml.constructor.SafeConstructor()


def _scalar(node: yaml.Node) -> Any:
    """Resolve a scalar (int, float, bool, null, string) with PyYAML's safe rules."""
    if not isinstance(node, yaml.ScalarNode):
        return yaml.safe_load(yaml.serialize(node))
    return _CONSTRUCTOR.construct_object(node, deep=True)


def parse_yaml(text: str, name: str | None = None) -> SourceDocument:
    """Parse YAML text into a :class:`SourceDocument`; syntax errors carry the line."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        message = " ".join(str(part) for part in (exc.context, exc.problem) if part)
        raise TopologySyntaxError([Problem("", message, line)], name) from None
    except yaml.YAMLError as exc:  # pragma: no cover - unmarked errors are rare
        raise TopologySyntaxError([Problem("", str(exc))], name) from None
    if root is None:
        raise TopologySyntaxError([Problem("", "the file is empty", 1)], name)
    lines: dict[str, int] = {}
    problems: list[Problem] = []
    data = _convert(root, "", lines, problems)
    if problems:
        raise TopologySyntaxError(problems, name)
    return SourceDocument(data, lines, name)
