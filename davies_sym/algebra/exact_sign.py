"""The exact sign of a real number written as a closed form (radicals, trigonometric
values of rational multiples of pi, ...).

A design exactly on a limit (a worm at its self-locking friction, a planet exactly as
large as the gap it fills) gives a value whose floating-point evaluation cannot be told
from zero, and a sympy relational such as ``value > 0`` then has no truth value.  Here a
sign is decided in two steps, never by rounding:

1. evaluation with guaranteed accuracy (sympy's ``evalf(strict=True)`` raises where it
   cannot reach the asked precision): a non-zero result that meets the precision has a
   certain sign;
2. where that fails (cancellation to zero), the minimal polynomial of the algebraic
   number: it is ``x`` exactly when the number is zero.

A number that is neither settled by step 1 nor algebraic raises `UndecidedSign`; the
callers turn that into a refusal, never into a guess.
"""

from __future__ import annotations

import sympy
from sympy.core.evalf import PrecisionExhausted

#: Decimal digits tried in turn by the guaranteed-accuracy evaluation.
_DIGITS = (30, 120)
_X = sympy.Dummy("x")


class UndecidedSign(ValueError):
    """The sign of a number could not be decided exactly."""


def _evaluated_sign(value: sympy.Expr, digits: int) -> int | None:
    """The sign from an evaluation that meets ``digits`` significant digits, or None."""
    try:
        approx = value.evalf(digits, strict=True, maxn=4 * digits)
    except (PrecisionExhausted, ValueError, TypeError):
        return None
    if not approx.is_Float or approx == 0:
        return None
    return 1 if approx > 0 else -1


def number_sign(value: object) -> int:
    """-1, 0 or +1: the exact sign of the real constant ``value``.

    Raises `UndecidedSign` for a non-real or non-number value, and where the sign cannot
    be proved (a transcendental number indistinguishable from zero)."""
    number = sympy.sympify(value)
    if number.is_Rational:
        return int(sympy.sign(number))
    if not number.is_number or number.has(sympy.nan, sympy.zoo) or number.is_extended_real is False:
        raise UndecidedSign(f"{sympy.sstr(number)} is not a real number")
    if number.is_infinite:
        return 1 if number.is_extended_positive else -1
    if number.is_zero:
        return 0
    for digits in _DIGITS:
        sign = _evaluated_sign(number, digits)
        if sign is not None:
            return sign
    try:
        minimal = sympy.minimal_polynomial(number, _X, polys=True)
    except (NotImplementedError, ValueError, TypeError) as exc:
        raise UndecidedSign(f"cannot decide the sign of {sympy.sstr(number)} exactly") from exc
    if minimal.as_expr() == _X:
        return 0
    # Non-zero: an evaluation at enough precision separates it from zero.
    sign = _evaluated_sign(number, 4 * _DIGITS[-1])
    if sign is None:
        raise UndecidedSign(f"cannot decide the sign of {sympy.sstr(number)} exactly")
    return sign


def is_real_number(value: object) -> bool:
    """Whether ``value`` is a finite real constant (not nan, not a pole's infinity)."""
    number = sympy.sympify(value)
    return bool(number.is_number and number.is_finite and number.is_extended_real)
