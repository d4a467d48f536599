"""Vector expressions of a machine file: points and directions built from others.

A vector is written as a list of three scalar expressions (``[a1*cos(theta), 0, 0]``)
or as one text combining named vectors: ``+``, ``-``, a scalar times or over a vector,
``unit(v)``, ``cross(a, b)`` and the scalars ``dot(a, b)`` and ``norm(v)``.  Scalar parts
are read by the same grammar as every other expression (`parse_expression`), so nothing
is evaluated as Python.
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Mapping
from typing import Any

import sympy

from davies_sym.algebra.screws import cross
from davies_sym.topology.expressions import MAX_LENGTH, ExpressionError, parse_expression

Vector = tuple[sympy.Expr, sympy.Expr, sympy.Expr]
#: A scalar (sympy expression) or a vector (a tuple of three).
Value = Any

#: The coordinate unit vectors, always available by name.
AXES: dict[str, Vector] = {
    "x": (sympy.Integer(1), sympy.Integer(0), sympy.Integer(0)),
    "y": (sympy.Integer(0), sympy.Integer(1), sympy.Integer(0)),
    "z": (sympy.Integer(0), sympy.Integer(0), sympy.Integer(1)),
}
_SCALAR_FUNCTIONS = {"sqrt": sympy.sqrt, "sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan}


def dot(a: Vector, b: Vector) -> sympy.Expr:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(a: Vector) -> Vector:
    """``a`` over its length; a vector that is zero whatever the values is refused."""
    length2 = sympy.expand(dot(a, a))
    if length2 == 0:
        raise ExpressionError("unit() of a zero vector")
    length = sympy.sqrt(length2)
    return (a[0] / length, a[1] / length, a[2] / length)


def is_vector(value: Value) -> bool:
    return isinstance(value, tuple)


class _VectorBuilder:
    def __init__(self, text: str, vectors: Mapping[str, Vector], symbol: Callable[[str], sympy.Symbol]):
        self.text = text.strip()
        self.vectors = vectors
        self.symbol = symbol

    def scalar_leaf(self, node: ast.expr) -> sympy.Expr:
        return parse_expression(ast.get_source_segment(self.text, node) or "", self.symbol)

    def build(self, node: ast.expr) -> Value:
        if isinstance(node, ast.Name):
            if node.id in self.vectors:
                return self.vectors[node.id]
            return self.scalar_leaf(node)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            value = self.build(node.operand)
            if isinstance(node.op, ast.UAdd):
                return value
            return tuple(-c for c in value) if isinstance(value, tuple) else -value
        if isinstance(node, ast.BinOp):
            return self.binary(node)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
            return self.call(node.func.id, [self.build(arg) for arg in node.args], node)
        return self.scalar_leaf(node)

    def binary(self, node: ast.BinOp) -> Value:
        left, right = self.build(node.left), self.build(node.right)
        lv, rv = isinstance(left, tuple), isinstance(right, tuple)
        if not lv and not rv:
            return self.scalar_leaf(node) if not self.has_vector(node) else self.scalar_op(node.op, left, right)
        if isinstance(node.op, (ast.Add, ast.Sub)) and lv and rv:
            sign = 1 if isinstance(node.op, ast.Add) else -1
            return tuple(a + sign * b for a, b in zip(left, right, strict=True))
        if isinstance(node.op, ast.Mult) and lv != rv:
            vec, factor = (left, right) if lv else (right, left)
            return tuple(factor * c for c in vec)
        if isinstance(node.op, ast.Div) and lv and not rv:
            if right == 0:
                raise ExpressionError(f"{self.text} divides by zero")
            return tuple(c / right for c in left)
        raise ExpressionError(
            f"{self.text}: cannot combine a vector and a scalar with {type(node.op).__name__} "
            "(add vectors to vectors; multiply or divide a vector by a scalar)"
        )

    def scalar_op(self, op: ast.operator, left: sympy.Expr, right: sympy.Expr) -> sympy.Expr:
        if isinstance(op, ast.Add):
            return left + right
        if isinstance(op, ast.Sub):
            return left - right
        if isinstance(op, ast.Mult):
            return left * right
        if isinstance(op, ast.Div):
            return left / right
        if isinstance(op, ast.Pow) and right.is_Rational:
            return left**right
        raise ExpressionError(f"{self.text}: the operator {type(op).__name__} is not allowed here")

    def has_vector(self, node: ast.AST) -> bool:
        return any(
            (isinstance(n, ast.Name) and n.id in self.vectors)
            or (isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in {"dot", "norm"})
            for n in ast.walk(node)
        )

    def call(self, name: str, args: list[Value], node: ast.Call) -> Value:
        vectors = [a for a in args if isinstance(a, tuple)]
        if name == "unit" and len(args) == 1 and len(vectors) == 1:
            return unit(vectors[0])
        if name == "cross" and len(args) == 2 and len(vectors) == 2:
            return cross(vectors[0], vectors[1])
        if name == "dot" and len(args) == 2 and len(vectors) == 2:
            return dot(vectors[0], vectors[1])
        if name == "norm" and len(args) == 1 and len(vectors) == 1:
            return sympy.sqrt(dot(vectors[0], vectors[0]))
        if name in _SCALAR_FUNCTIONS and len(args) == 1 and not vectors:
            if not self.has_vector(node):
                return self.scalar_leaf(node)
            return _SCALAR_FUNCTIONS[name](args[0])
        raise ExpressionError(
            f"{self.text}: {name}() is not a vector function here (write unit(v), cross(a, b), dot(a, b), "
            "norm(v), or sqrt, sin, cos, tan of a scalar)"
        )


def parse_vector(written: object, vectors: Mapping[str, Vector], symbol: Callable[[str], sympy.Symbol]) -> Vector:
    """A vector written as a list of three scalars or as one vector expression."""
    if isinstance(written, list):
        if len(written) != 3:
            raise ExpressionError(f"a vector has three coordinates [x, y, z], got {len(written)}")
        return tuple(parse_expression(str(c), symbol) for c in written)
    if not isinstance(written, str):
        raise ExpressionError(f"expected a vector ([x, y, z] or an expression of vectors), got {written!r}")
    if len(written) > MAX_LENGTH:
        raise ExpressionError(f"a vector expression has at most {MAX_LENGTH} characters")
    try:
        tree = ast.parse(written.strip(), mode="eval")
    except SyntaxError:
        raise ExpressionError(f"cannot read {written!r} as a vector expression") from None
    value = _VectorBuilder(written, {**AXES, **vectors}, symbol).build(tree.body)
    if not isinstance(value, tuple):
        raise ExpressionError(f"{written!r} is a scalar, a vector is wanted here ([x, y, z] or unit(...), ...)")
    return value


def parse_scalar(written: object, vectors: Mapping[str, Vector], symbol: Callable[[str], sympy.Symbol]) -> sympy.Expr:
    """A scalar that may use ``dot`` and ``norm`` of named vectors."""
    text = str(written)
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        return parse_expression(text, symbol)  # its own message
    value = _VectorBuilder(text, {**AXES, **vectors}, symbol).build(tree.body)
    if isinstance(value, tuple):
        raise ExpressionError(f"{text!r} is a vector, a scalar is wanted here")
    return value
