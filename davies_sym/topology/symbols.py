"""Symbols and exact numbers of one train.

One symbol per name, with the assumptions its role implies (radii, friction and
viscous coefficients are positive; action and motion magnitudes are real).  Numbers
written in a topology file are taken exactly: ``0.99`` becomes ``99/100``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from fractions import Fraction
from types import MappingProxyType

import sympy

from davies_sym.topology.expressions import ExpressionError, parse_expression, shortened

#: Assumptions per symbol role.
ROLE_ASSUMPTIONS: Mapping[str, Mapping[str, bool]] = MappingProxyType({
    "length": {"positive": True},
    "teeth": {"positive": True},
    # Positions take their names from the radii (at: r1 - r3): the same symbols; only
    # their numbers may be zero or negative.
    "position": {"positive": True},
    "friction": {"positive": True},
    "viscous": {"positive": True},
    "efficiency": {"positive": True},
    "magnitude": {"real": True},
    "sign": {"nonzero": True, "integer": True},
    "angle": {"real": True},
})


#: A plain decimal or fraction with a modest exponent (Fraction would expand 1e999999999).
_PLAIN_NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d{1,3})?(/\d{1,300})?")


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
        if not math.isfinite(value):
            return None
        # repr gives the shortest decimal that round-trips: 0.99 -> 99/100 exactly.
        return sympy.Rational(repr(value))
    if isinstance(value, str):
        text = value.strip()
        if not _PLAIN_NUMBER.fullmatch(text):
            return None
        try:
            frac = Fraction(text)
        except (ValueError, ZeroDivisionError, OverflowError):
            return None
        return sympy.Rational(frac.numerator, frac.denominator)
    return None


#: Roles whose numbers must be positive: sizes and loss coefficients.
POSITIVE_ROLES = frozenset({"length", "teeth", "friction", "viscous", "efficiency"})


class QuantityError(ValueError):
    """A quantity could not be read as a number or an expression."""


def parse_quantity(value: object, role: str, symbols: dict[str, sympy.Symbol]) -> sympy.Expr:
    """Read a number or an expression of symbols; new names get the assumptions of ``role``.

    ``symbols`` collects the symbols of the train (name -> symbol); it is extended with
    any new name met in ``value``.  Text is read by the grammar of
    :mod:`davies_sym.topology.expressions`, never evaluated as Python.
    """
    if isinstance(value, float) and not math.isfinite(value):
        raise QuantityError(f"expected a finite number, got {value!r}")
    number = exact_number(value)
    if number is None and isinstance(value, str):
        try:
            parsed = parse_expression(value, lambda name: _symbol(name, role, symbols))
        except ExpressionError as exc:
            raise QuantityError(str(exc)) from None
        number = parsed if parsed.is_number else None
        if number is None:
            return parsed
    if number is not None:
        if role in POSITIVE_ROLES and not number > 0:
            raise QuantityError(f"{shortened(str(value))} must be positive (a size or a coefficient)")
        return number
    raise QuantityError(f"expected a number or a symbol expression, got {shortened(repr(value))}")


def _symbol(name: str, role: str, symbols: dict[str, sympy.Symbol]) -> sympy.Symbol:
    if name not in symbols:
        symbols[name] = make_symbol(name, role)
    return symbols[name]
