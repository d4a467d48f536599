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

from davies_sym.errors import shortened
from davies_sym.topology.expressions import MAX_BITS, ExpressionError, parse_expression

#: Assumptions per symbol role.
ROLE_ASSUMPTIONS: Mapping[str, Mapping[str, bool]] = MappingProxyType(
    {
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
        # cos and sin of the angles of a skew mesh, which lie strictly between 0 and 90 degrees.
        "angle function": {"positive": True},
    }
)


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
        # repr gives the shortest decimal that round-trips: 0.99 -> 99/100 exactly (of the
        # float itself: numpy's float64 writes its type around the number).
        return sympy.Rational(repr(float(value)))
    if isinstance(value, str):
        text = value.strip()
        if not _PLAIN_NUMBER.fullmatch(text):
            return None
        try:
            frac = Fraction(text)
        except (ValueError, ZeroDivisionError):
            # Shapes the pattern lets through but Fraction refuses ("1.5/3", more digits
            # than int() reads, "1/0"): not a plain number.  parse_quantity then reads the
            # text by the expression grammar ("1.5/3" is 1/2 there, "1/0" is refused).
            return None
        return sympy.Rational(frac.numerator, frac.denominator)
    return None


#: Roles whose numbers must be positive: sizes and loss coefficients.
POSITIVE_ROLES = frozenset({"length", "teeth", "friction", "viscous", "efficiency"})


class QuantityError(ValueError):
    """A quantity could not be read as a number or an expression."""


def parse_quantity(value: object, role: str, symbols: dict[str, sympy.Symbol], roots: bool = False) -> sympy.Expr:
    """Read a number or an expression of symbols; new names get the assumptions of ``role``.

    ``symbols`` collects the symbols of the train (name -> symbol); it is extended with
    any new name met in ``value``.  Text is read by the grammar of
    `davies_sym.topology.expressions`, never evaluated as Python.  The value must be
    one the exact algebra holds (see `inexact`); square roots only where ``roots``
    (directions, which the layouts normalise with radical symbols anyway).
    """
    if isinstance(value, float) and not math.isfinite(value):
        raise QuantityError(f"expected a finite number, got {value!r}")
    number = exact_number(value)
    if number is None and isinstance(value, str):
        try:
            parsed = parse_expression(value, lambda name: train_symbol(name, role, symbols))
        except ExpressionError as exc:
            raise QuantityError(str(exc)) from None
        why = inexact(parsed, roots)
        if why is not None:
            raise QuantityError(f"{shortened(value)}: {why}")
        number = parsed if parsed.is_number else None
        if number is None:
            if role in POSITIVE_ROLES and parsed.is_positive is False:
                raise QuantityError(
                    f"{shortened(value)} is never positive; a size or a coefficient is positive "
                    "(write it without the minus sign, or with positive terms)"
                )
            return parsed
    if number is not None:
        if number.is_Rational and max(abs(number.p).bit_length(), number.q.bit_length()) > MAX_BITS:
            raise QuantityError(
                f"{shortened(str(value))} is too large for a number of a train (at most "
                f"{MAX_BITS} bits); write it in other units"
            )
        if role in POSITIVE_ROLES and not number > 0:
            raise QuantityError(f"{shortened(str(value))} must be positive (a size or a coefficient)")
        return number
    raise QuantityError(f"expected a number or a symbol expression, got {shortened(repr(value))}")


def inexact(expr: sympy.Expr, roots: bool = False) -> str | None:
    """Why the exact polynomial algebra cannot hold ``expr``, or None when it can: it holds
    rational functions of the symbols with rational coefficients and, where ``roots``,
    square roots that are not nested (each becomes a radical symbol).  ``pi`` and the
    sine of most angles are transcendental; sympy has already written the others
    (``cos(pi/6)``) as square roots."""
    if expr.has(sympy.pi):
        return "pi is exact only in an angle of sin, cos or tan (pi/6); write a rational value such as 355/113"
    functions = sorted(expr.atoms(sympy.Function), key=str)
    if functions:
        hint = f" such as {sympy.N(functions[0], 6)}" if functions[0].is_number else ""
        return f"{shortened(str(functions[0]), 30)} has no exact value; write a number{hint} instead"
    for power in sorted(expr.atoms(sympy.Pow), key=str):
        exponent = power.exp
        if not exponent.is_Rational or exponent.is_Integer:
            continue
        if exponent.q != 2:
            return "only square roots are exact; write a number instead"
        if not roots:
            return (
                "a square root is exact only in a direction (axis, placement, screw coordinates); write a "
                "rational expression instead, e.g. a new symbol for this value"
            )
        if any(
            isinstance(p, sympy.Pow) and p.exp.is_Rational and not p.exp.is_Integer
            for p in sympy.preorder_traversal(power.base)
        ):
            return "nested square roots are not exact; write a number instead"
    return None


def train_symbol(name: str, role: str, symbols: dict[str, sympy.Symbol]) -> sympy.Symbol:
    """The train's symbol ``name``, made with the assumptions of ``role`` when new."""
    if name not in symbols:
        symbols[name] = make_symbol(name, role)
    return symbols[name]
