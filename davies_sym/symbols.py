"""Symbols and exact numbers of one train.

One symbol per name, with the assumptions its role implies (radii, friction and
viscous coefficients are positive; action and motion magnitudes are real).  Numbers
written in a topology file are taken exactly: ``0.99`` becomes ``99/100``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from fractions import Fraction
from types import MappingProxyType

import sympy

#: Assumptions per symbol role.
ROLE_ASSUMPTIONS: Mapping[str, Mapping[str, bool]] = MappingProxyType({
    "length": {"positive": True},
    "friction": {"positive": True},
    "viscous": {"positive": True},
    "efficiency": {"positive": True},
    "magnitude": {"real": True},
    "sign": {"nonzero": True, "integer": True},
    "angle": {"real": True},
})

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
_ALLOWED_FUNCTIONS = {"sqrt": sympy.sqrt, "sin": sympy.sin, "cos": sympy.cos,
                      "tan": sympy.tan, "pi": sympy.pi}


def make_symbol(name: str, role: str) -> sympy.Symbol:
    """The symbol ``name`` with the assumptions of ``role`` (see ``ROLE_ASSUMPTIONS``)."""
    return sympy.Symbol(name, **ROLE_ASSUMPTIONS[role])


def exact_number(value: object) -> sympy.Rational | None:
    """``value`` as an exact rational if it is a plain number (int, float, "1/3"), else None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        return sympy.Integer(value)
    if isinstance(value, float):
        # repr gives the shortest decimal that round-trips: 0.99 -> 99/100 exactly.
        return sympy.Rational(repr(value))
    if isinstance(value, str):
        try:
            frac = Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            return None
        return sympy.Rational(frac.numerator, frac.denominator)
    return None


class QuantityError(ValueError):
    """A quantity could not be read as a number or an expression."""


def parse_quantity(value: object, role: str, symbols: dict[str, sympy.Symbol]) -> sympy.Expr:
    """Read a number or an expression of symbols; new names get the assumptions of ``role``.

    ``symbols`` collects the symbols of the train (name -> symbol); it is extended with
    any new name met in ``value``.
    """
    number = exact_number(value)
    if number is not None:
        return number
    if not isinstance(value, str) or not value.strip():
        raise QuantityError(f"expected a number or a symbol expression, got {value!r}")
    local: dict[str, object] = dict(_ALLOWED_FUNCTIONS)
    for name in _IDENTIFIER.findall(value):
        if name in _ALLOWED_FUNCTIONS:
            continue
        if name not in symbols:
            symbols[name] = make_symbol(name, role)
        local[name] = symbols[name]
    try:
        expr = sympy.parse_expr(value, local_dict=local, evaluate=True)
    except (SyntaxError, TypeError, ValueError, sympy.SympifyError) as exc:
        raise QuantityError(f"cannot read {value!r} as an expression ({exc})") from None
    expr = sympy.nsimplify(expr, rational=True) if expr.has(sympy.Float) else expr
    if not isinstance(expr, sympy.Expr):
        raise QuantityError(f"{value!r} is not an arithmetic expression")
    return expr
