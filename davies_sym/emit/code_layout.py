"""Python source from ``ast`` nodes, laid out within a line width.

``ast.unparse`` writes each statement on one line; this module breaks the statements a
generated formula module holds (assignments, returns, function definitions with a
docstring, data literals) at the syntax tree: one element of a tuple, list, dict or
call per line, long strings as adjacent literals.  The text is made from nodes only, so
it is valid Python by construction, and `module_source` checks that it parses back
to the very same tree.
"""

from __future__ import annotations

import ast
import math
import textwrap
from collections.abc import Sequence

WIDTH = 120
_STEP = "    "


class LayoutError(RuntimeError):
    """The laid-out text does not parse back to the tree it was made from."""


def docstring(text: str, indent: str) -> ast.Expr:
    """A docstring node whose text is ``text`` wrapped to the width at ``indent``.

    Non-printable characters become spaces, so the text is one paragraph per line of
    ``text``; quotes and backslashes are written escaped by `_docstring_lines`."""
    clean = ["".join(ch if ch.isprintable() else " " for ch in line) for line in text.split("\n")]
    lines: list[str] = []
    for paragraph in clean:
        lines += textwrap.wrap(paragraph, WIDTH - len(indent) - 6) or [""]
    body = (
        lines[0] if len(lines) == 1 else "\n".join([lines[0], *(indent + ln if ln else "" for ln in lines[1:]), indent])
    )
    return ast.Expr(ast.Constant(body))


def _docstring_lines(text: str, indent: str) -> list[str]:
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    first, *rest = escaped.split("\n")
    if not rest:
        return [f'{indent}"""{first}"""']
    return [f'{indent}"""{first}', *rest[:-1], f'{rest[-1]}"""']


def _fits(indent: str, text: str) -> bool:
    return len(indent) + len(text) <= WIDTH


def _string_pieces(value: str, room: int) -> list[str]:
    """``value`` cut into pieces whose literals fit in ``room`` (at spaces when possible)."""
    pieces: list[str] = []
    rest = value
    while rest:
        cut = len(rest)
        while len(repr(rest[:cut])) > room and cut > 1:
            space = rest.rfind(" ", 0, cut - 1)
            cut = space + 1 if space > 0 else cut - 1
        pieces.append(rest[:cut])
        rest = rest[cut:]
    return pieces


def expression(node: ast.expr, indent: str, prefix: str = "", suffix: str = "") -> list[str]:
    """``prefix`` + the expression + ``suffix`` at ``indent``, broken over lines if needed."""
    flat = ast.unparse(node)
    if _fits(indent, prefix + flat + suffix):
        return [indent + prefix + flat + suffix]
    inner = indent + _STEP
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        opening, closing = {ast.Tuple: ("(", ")"), ast.List: ("[", "]"), ast.Set: ("{", "}")}[type(node)]
        lines = [indent + prefix + opening]
        for element in node.elts:
            lines += expression(element, inner, suffix=",")
        return [*lines, indent + closing + suffix]
    if isinstance(node, ast.Dict):
        lines = [indent + prefix + "{"]
        for key, value in zip(node.keys, node.values, strict=True):
            head = "**" if key is None else ast.unparse(key) + ": "
            if key is not None and not _fits(inner, head + "("):
                # A long key on lines of its own, the value below it (brackets join the lines).
                lines += expression(key, inner, suffix=":")
                lines += expression(value, inner + _STEP, suffix=",")
                continue
            lines += expression(value, inner, head, ",")
        return [*lines, indent + "}" + suffix]
    if isinstance(node, ast.Call) and (node.args or node.keywords):
        lines = [indent + prefix + ast.unparse(node.func) + "("]
        for arg in node.args:
            lines += expression(arg, inner, suffix=",")
        for keyword in node.keywords:
            lines += expression(keyword.value, inner, f"{keyword.arg}=" if keyword.arg else "**", ",")
        return [*lines, indent + ")" + suffix]
    if isinstance(node, ast.Constant) and isinstance(node.value, str) and len(node.value) > 1:
        pieces = _string_pieces(node.value, WIDTH - len(inner))
        if all(len(repr(p)) <= WIDTH - len(inner) for p in pieces):
            return [indent + prefix + "(", *(inner + repr(p) for p in pieces), indent + ")" + suffix]
    # An expression without a place to break (formulas are kept short upstream).
    return [indent + prefix + flat + suffix + "  # noqa: E501"]


def _arguments(args: ast.arguments) -> list[str]:
    """Each parameter of a keyword-only signature as ``name: annotation[ = default]``."""
    out = []
    defaults = [None] * (len(args.kwonlyargs) - len(args.kw_defaults)) + list(args.kw_defaults)
    for arg, default in zip(args.kwonlyargs, defaults, strict=True):
        text = arg.arg + (f": {ast.unparse(arg.annotation)}" if arg.annotation else "")
        if default is not None:
            text += f" = {ast.unparse(default)}" if arg.annotation else f"={ast.unparse(default)}"
        out.append(text)
    return out


def _function(node: ast.FunctionDef, indent: str) -> list[str]:
    if node.args.args or node.args.posonlyargs or node.args.vararg or node.args.kwarg:
        raise LayoutError(f"{node.name}: generated functions take keyword-only arguments")
    params = _arguments(node.args)
    returns = f" -> {ast.unparse(node.returns)}" if node.returns else ""
    one = f"def {node.name}(*, {', '.join(params)}){returns}:" if params else f"def {node.name}(){returns}:"
    if _fits(indent, one):
        lines = [indent + one]
    else:
        lines = [
            f"{indent}def {node.name}(",
            f"{indent}{_STEP}*,",
            *(f"{indent}{_STEP}{p}," for p in params),
            f"{indent}){returns}:",
        ]
    for statement in node.body:
        lines += statement_lines(statement, indent + _STEP)
    return lines


def statement_lines(node: ast.stmt, indent: str = "") -> list[str]:
    """The lines of one statement of a generated module."""
    if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str):
        return _docstring_lines(node.value.value, indent)
    if isinstance(node, ast.FunctionDef):
        return _function(node, indent)
    if isinstance(node, ast.Assign) and len(node.targets) == 1:
        return expression(node.value, indent, ast.unparse(node.targets[0]) + " = ")
    if isinstance(node, ast.AnnAssign) and node.value is not None:
        head = f"{ast.unparse(node.target)}: {ast.unparse(node.annotation)} = "
        return expression(node.value, indent, head)
    if isinstance(node, ast.Return) and node.value is not None:
        return expression(node.value, indent, "return ")
    if isinstance(node, ast.Expr):
        return expression(node.value, indent)
    flat = ast.unparse(node)
    if "\n" in flat or not _fits(indent, flat):
        raise LayoutError(f"no layout for a {type(node).__name__} statement")
    return [indent + flat]


def literal(value: object) -> ast.expr:
    """The node of a Python data value (str, int, float, bool, None, tuple, list, dict)
    that parses back to itself: negative numbers as a minus sign, infinities as
    ``float('inf')``."""
    if isinstance(value, float) and math.isinf(value):
        node: ast.expr = ast.Call(ast.Name("float", ast.Load()), [ast.Constant("inf")], [])
        return node if value > 0 else ast.UnaryOp(ast.USub(), node)
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value < 0:
        return ast.UnaryOp(ast.USub(), ast.Constant(-value))
    if value is None or isinstance(value, (str, int, float, bool)):
        return ast.Constant(value)
    if isinstance(value, tuple):
        return ast.Tuple([literal(v) for v in value], ast.Load())
    if isinstance(value, list):
        return ast.List([literal(v) for v in value], ast.Load())
    if isinstance(value, dict):
        return ast.Dict([literal(k) for k in value], [literal(v) for v in value.values()])
    raise TypeError(f"no literal for {type(value).__name__}")


def keyword_function(
    name: str,
    params: Sequence[ast.arg],
    defaults: Sequence[ast.expr | None],
    body: Sequence[ast.stmt],
    returns: ast.expr | None,
) -> ast.FunctionDef:
    """``def name(*, params...) -> returns: body`` as a complete node on every Python.

    Each field the running version defines is given (3.12 added ``type_params``), so the
    node dumps exactly as the parse of its text does, which `module_source` checks."""
    arguments = ast.arguments(
        posonlyargs=[],
        args=[],
        vararg=None,
        kwonlyargs=list(params),
        kw_defaults=list(defaults),
        kwarg=None,
        defaults=[],
    )
    node = ast.FunctionDef(
        name=name, args=arguments, body=list(body), decorator_list=[], returns=returns, type_comment=None
    )
    if "type_params" in ast.FunctionDef._fields:
        setattr(node, "type_params", [])  # noqa: B010 (a field of Python 3.12 and later only)
    return node


def module_source(items: Sequence[tuple[int, str | ast.stmt]]) -> str:
    """The module of ``items``, each (blank lines before it, statement): a statement node
    laid out here, or source text copied as it is (hand-written code).  Raises
    `LayoutError` unless the text parses back to exactly these statements."""
    parts: list[str] = []
    statements: list[ast.stmt] = []
    for gap, item in items:
        if parts:
            parts += [""] * gap
        if isinstance(item, str):
            parts += item.rstrip("\n").split("\n")
            statements += ast.parse(item).body
        else:
            parts += statement_lines(item)
            statements.append(item)
    source = "\n".join(parts) + "\n"
    if ast.dump(ast.parse(source)) != ast.dump(ast.Module(body=statements, type_ignores=[])):
        raise LayoutError("the laid-out module does not parse back to its tree")
    return source
