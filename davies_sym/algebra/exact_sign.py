"""The exact sign of a real number written as a closed form (radicals, trigonometric
values of rational multiples of pi, ...).

A design exactly on a limit (a worm at its self-locking friction, a planet exactly as
large as the gap it fills) gives a value whose floating-point evaluation cannot be told
from zero, and a sympy relational such as ``value > 0`` then has no truth value.  Here a
sign is decided in two steps, never by rounding:

1. evaluation with guaranteed accuracy (sympy's ``evalf(strict=True)`` raises where it
   cannot reach the asked precision): a non-zero result that meets the precision has a
   certain sign;
2. where that fails (cancellation to zero), the numerator and denominator are split into
   factors and each factor's minimal polynomial is computed: it is ``x`` exactly when the
   factor is zero (the work bounded by the factor's size, `MAX_OPERATIONS`).

A number that is neither settled by step 1 nor algebraic raises `UndecidedSign`; the
callers turn that into a refusal, never into a guess.
"""

from __future__ import annotations

import math

import sympy
from sympy.core.evalf import PrecisionExhausted
from sympy.polys.polyerrors import BasePolynomialError

#: Decimal digits tried in turn by the guaranteed-accuracy evaluation.
_DIGITS = (30, 120)
_X = sympy.Dummy("x")
#: The largest factor (in sympy operations) whose minimal polynomial is computed: a bound on
#: the work, beyond which the sign is reported undecided instead of searched for.
MAX_OPERATIONS = 80
#: The largest degree of the number field a factor may lie in (`_degree_bound`): the
#: minimal polynomial of cos(389 pi/3600) alone has a degree in the hundreds.
MAX_DEGREE = 256


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
    be proved (a transcendental number indistinguishable from zero, or a factor too large
    for its minimal polynomial: `MAX_OPERATIONS`)."""
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
    # Cancellation: the sign is the product of the signs of the factors of the numerator
    # and the denominator, each decided on its own (smaller minimal polynomials).
    numerator, denominator = sympy.fraction(sympy.together(number))
    sign = 1
    for part in (numerator, denominator):
        for factor in sympy.Mul.make_args(part):
            base, exponent = factor.as_base_exp()
            if exponent.is_Integer:
                sign *= _factor_sign(base, number) ** int(exponent)
            else:
                sign *= _factor_sign(factor, number)
            if sign == 0:
                return 0
    return sign


def _factor_sign(factor: sympy.Expr, whole: sympy.Expr) -> int:
    """The sign of one factor: evaluation first, then its minimal polynomial."""
    if factor.is_Rational:
        return int(sympy.sign(factor))
    for digits in _DIGITS:
        sign = _evaluated_sign(factor, digits)
        if sign is not None:
            return sign
    if _vanishes_on_the_circle(factor):
        return 0
    if sympy.count_ops(factor) > MAX_OPERATIONS or _degree_bound(factor) > MAX_DEGREE:
        raise UndecidedSign(f"cannot decide the sign of {sympy.sstr(whole)} exactly (too large a closed form)")
    try:
        minimal = sympy.minimal_polynomial(factor, _X, polys=True)
    except (NotImplementedError, ValueError, TypeError, BasePolynomialError) as exc:  # NotAlgebraic: log 2
        raise UndecidedSign(f"cannot decide the sign of {sympy.sstr(whole)} exactly") from exc
    if minimal.as_expr() == _X:
        return 0
    # Non-zero: an evaluation at enough precision separates it from zero.
    sign = _evaluated_sign(factor, 4 * _DIGITS[-1])
    if sign is None:
        raise UndecidedSign(f"cannot decide the sign of {sympy.sstr(whole)} exactly")
    return sign


def _vanishes_on_the_circle(factor: sympy.Expr) -> bool:
    """Whether ``factor``, written in sines, cosines and tangents of rational angles (in
    radians: a worm's lead angle of 0.1) and algebraic numbers, is exactly zero.

    Every angle is a whole multiple of one angle t (the greatest common divisor of the
    rationals); the factor becomes a rational function of s = sin t and c = cos t
    (multiple-angle formulas), and its numerator, reduced by c^2 = 1 - s^2, is a + b c.
    It vanishes at t exactly when a = b = 0 identically: otherwise a^2 = b^2 (1 - s^2)
    would make sin t algebraic, which it is not for a rational t != 0
    (Lindemann-Weierstrass).  False means "not shown zero" (other forms keep their route)."""
    functions = factor.atoms(sympy.sin, sympy.cos, sympy.tan)
    angles = {f.args[0] for f in functions}
    if not angles or not all(a.is_Rational and a != 0 for a in angles) or factor.has(sympy.pi, sympy.E):
        return False
    rationals = [sympy.Rational(a) for a in angles]
    step = sympy.Rational(math.gcd(*(int(r.p) for r in rationals)), math.lcm(*(int(r.q) for r in rationals)))
    if any(abs(r / step) > 64 for r in rationals):  # bounded work: multiple-angle formulas of degree <= 64
        return False
    t, sin_t, cos_t = sympy.Dummy("t"), sympy.Dummy("s"), sympy.Dummy("c")
    expanded = factor.subs({f: sympy.expand_trig(type(f)(f.args[0] / step * t)) for f in functions})
    expanded = expanded.subs({sympy.tan(t): sympy.sin(t) / sympy.cos(t)}).subs(
        {sympy.sin(t): sin_t, sympy.cos(t): cos_t}
    )
    if expanded.has(t) or not expanded.free_symbols <= {sin_t, cos_t}:
        return False
    numerator = sympy.fraction(sympy.together(expanded))[0]
    remainder = sympy.rem(sympy.expand(numerator), cos_t**2 + sin_t**2 - 1, cos_t)
    return bool(sympy.expand(remainder) == 0)


def _degree_bound(factor: sympy.Expr) -> int:
    """A bound on the degree of the number field ``factor`` lies in: each square root
    at most doubles it, and the sines, cosines and tangents of rational multiples p/q of
    pi all lie in the cyclotomic field of the 4 L-th roots of unity, L the least common
    multiple of the q, whose degree is phi(4 L)."""
    bound = 1
    for atom in factor.atoms(sympy.Pow):
        if atom.exp.is_Rational and not atom.exp.is_Integer:
            bound *= int(atom.exp.q)
    denominators = [sympy.Integer(1)]
    for function in factor.atoms(sympy.sin, sympy.cos, sympy.tan):
        coefficient = function.args[0] / sympy.pi
        if not coefficient.is_Rational:
            return MAX_DEGREE + 1  # not a rational multiple of pi: not algebraic
        denominators.append(sympy.Integer(coefficient.q))
    if len(denominators) > 1:
        bound *= int(sympy.totient(4 * sympy.ilcm(*denominators)))
    return bound


def is_real_number(value: object) -> bool:
    """Whether ``value`` is a finite real constant (not nan, not a pole's infinity)."""
    number = sympy.sympify(value)
    return bool(number.is_number and number.is_finite and number.is_extended_real)
