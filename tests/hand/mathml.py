"""Presentation MathML read back into a formula, so a test compares what the browser
renders with the formula it should show.

:func:`math_elements` finds the ``<math>`` elements of an HTML page (Python's own HTML
parser: entities such as ``&InvisibleTimes;`` are decoded); :func:`read_mathml` reads one
element's presentation part: ``mrow`` sequences of operands and ``mo`` operators (``+``,
``-``, the minus sign, invisible times, parentheses, ``=``), ``mfrac``, ``msup``, ``msubsup``,
``msqrt``, ``mn``, and symbols as ``mi`` or ``msub`` of a letter and its subscript.  A
symbol is found by a rule of this file: the letter (a Greek letter by its name) followed
by the subscript, with or without an underscore (``r`` with ``p1`` is ``rp1``, ``eta``
with ``C`` is ``eta_C``, ``eta`` with ``C,1`` is ``eta_C_1``).  Anything else raises :class:`MathMLError`.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from html.parser import HTMLParser

import sympy

_GREEK = {
    "α": "alpha",
    "β": "beta",
    "γ": "gamma",
    "δ": "delta",
    "ε": "epsilon",
    "ζ": "zeta",
    "η": "eta",
    "θ": "theta",
    "κ": "kappa",
    "λ": "lambda",
    "μ": "mu",
    "ν": "nu",
    "ξ": "xi",
    "π": "pi",
    "ρ": "rho",
    "σ": "sigma",
    "τ": "tau",
    "φ": "phi",
    "χ": "chi",
    "ψ": "psi",
    "ω": "omega",
}
_TIMES = {"\u2062", "·", "×", "⋅"}
_MINUS = {"-", "\u2212"}


class MathMLError(ValueError):
    """The element is not a formula in the given symbols."""


@dataclass
class Node:
    tag: str
    attrs: dict[str, str | None]
    children: list[Node] = field(default_factory=list)
    text: str = ""

    def elements(self) -> list[Node]:
        return [c for c in self.children if c.tag != "#text"]


class _Tree(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.root = Node("#root", {})
        self.stack = [self.root]

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        node = Node(tag, dict(attrs))
        self.stack[-1].children.append(node)
        self.stack.append(node)

    def handle_endtag(self, tag: str) -> None:
        for i in range(len(self.stack) - 1, 0, -1):
            if self.stack[i].tag == tag:
                del self.stack[i:]
                return

    def handle_data(self, data: str) -> None:
        self.stack[-1].children.append(Node("#text", {}, text=data))
        self.stack[-1].text += data


def _walk(node: Node) -> Iterable[Node]:
    yield node
    for child in node.children:
        yield from _walk(child)


def math_elements(page: str) -> list[Node]:
    """Every ``<math>`` element of an HTML page, in order."""
    tree = _Tree()
    tree.feed(page)
    tree.close()
    return [n for n in _walk(tree.root) if n.tag == "math"]


def annotation(element: Node) -> str:
    """The LaTeX annotation of a ``<math>`` element (empty when it has none)."""
    return next((n.text for n in _walk(element) if n.tag == "annotation"), "")


def text_of(node: Node) -> str:
    return "".join(n.text for n in _walk(node) if n.tag == "#text").strip()


class _Reader:
    def __init__(self, symbols: Iterable[sympy.Symbol]):
        self.symbols = {s.name: s for s in symbols}

    def symbol(self, base: str, sub: str = "") -> sympy.Symbol:
        base = _GREEK.get(base, base)
        sub = sub.replace(",", "_")  # eta with "C,1" is eta_C_1
        for name in (base + sub, f"{base}_{sub}"):
            if name in self.symbols:
                return self.symbols[name]
        raise MathMLError(f"unknown symbol {base!r} with subscript {sub!r}")

    def node(self, node: Node) -> sympy.Expr:
        kids = node.elements()
        if node.tag in ("mrow", "semantics", "math", "mstyle"):
            return self.inner([k for k in kids if k.tag != "annotation"])
        if node.tag == "mn":
            return sympy.Rational(text_of(node))
        if node.tag == "mi":
            return self.symbol(text_of(node))
        if node.tag == "msub":
            base, sub = kids
            if base.tag != "mi":
                raise MathMLError(f"subscript on {base.tag}")
            return self.symbol(text_of(base), text_of(sub))
        if node.tag == "mfrac":
            num, den = kids
            return self.node(num) / self.node(den)
        if node.tag == "msup":
            base, exp = kids
            return self.node(base) ** self.node(exp)
        if node.tag == "msubsup":  # a power of a subscripted symbol
            base, sub, exp = kids
            if base.tag != "mi":
                raise MathMLError(f"subscript on {base.tag}")
            return self.symbol(text_of(base), text_of(sub)) ** self.node(exp)
        if node.tag == "msqrt":
            return sympy.sqrt(self.inner(kids))
        raise MathMLError(f"unexpected element <{node.tag}>")

    def inner(self, items: list[Node]) -> sympy.Expr:
        """A nested row, read by a reader of its own (this one's place is kept)."""
        return _Reader(self.symbols.values()).row(items)

    def row(self, items: list[Node]) -> sympy.Expr:
        self.items, self.pos = items, 0
        value = self.sum()
        if self.pos != len(items):
            raise MathMLError(f"left over: <{items[self.pos].tag}> {text_of(items[self.pos])!r}")
        return value

    def peek_op(self) -> str | None:
        if self.pos < len(self.items) and self.items[self.pos].tag == "mo":
            return text_of(self.items[self.pos])
        return None

    def sum(self) -> sympy.Expr:
        sign = 1
        if self.peek_op() in _MINUS:
            self.pos += 1
            sign = -1
        value = sign * self.product()
        while (op := self.peek_op()) in _MINUS | {"+"}:
            self.pos += 1
            term = self.product()
            value = value + term if op == "+" else value - term
        return value

    def product(self) -> sympy.Expr:
        value = self.factor()
        while self.pos < len(self.items):
            op = self.peek_op()
            if op in _TIMES:
                self.pos += 1
            elif op is not None and op != "(":
                break
            value = value * self.factor()
        return value

    def factor(self) -> sympy.Expr:
        op = self.peek_op()
        if op == "(":
            self.pos += 1
            items, pos = self.items, self.pos
            depth, end = 1, pos
            while depth:
                if end >= len(items):
                    raise MathMLError("unbalanced parenthesis")
                inner = text_of(items[end]) if items[end].tag == "mo" else None
                depth += {"(": 1, ")": -1}.get(inner or "", 0)
                end += 1
            value = self.inner(items[pos : end - 1])
            self.items, self.pos = items, end
            return value
        if op is not None:
            raise MathMLError(f"operator {op!r} where a factor belongs")
        if self.pos >= len(self.items):
            raise MathMLError("a factor is missing")
        node = self.items[self.pos]
        self.pos += 1
        function = text_of(node) if node.tag == "mi" else ""
        if function in ("cos", "sin") and self.pos < len(self.items):
            # cos(gamma): the function's name, then its argument in parentheses.
            argument = self.items[self.pos]
            self.pos += 1
            return getattr(sympy, function)(self.node(argument))
        return self.node(node)


def read_mathml(element: Node, symbols: Iterable[sympy.Symbol]) -> sympy.Expr:
    """The formula of a ``<math>`` element; of an equation ``lhs = rhs``, the right side."""
    reader = _Reader(symbols)
    semantics = [k for k in element.elements() if k.tag == "semantics"]
    body = semantics[0] if semantics else element
    rows = [k for k in body.elements() if k.tag != "annotation"]
    if len(rows) == 1 and rows[0].tag == "mrow":
        rows = rows[0].elements()
    equals = [i for i, k in enumerate(rows) if k.tag == "mo" and text_of(k) == "="]
    if equals:
        rows = rows[equals[-1] + 1 :]
    return reader.row(rows)
