"""Bounds of a rational function of tooth numbers over a box, for pruning a search.

The natural interval extension (Moore's interval arithmetic on the expression tree):
every operation on intervals gives an interval holding every value the operation takes on
them, so the result holds every value of the function on the box; it may be wider, which
costs pruning, never a design.  Intervals are numpy arrays of lower and upper bounds, so
one evaluation bounds the function for every value of one tooth number at once.
Rounding is covered by the slack the caller adds to its window.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

Floats = NDArray[np.float64]


@dataclass(frozen=True)
class Interval:
    """Lower and upper bounds, element by element (broadcast together)."""

    low: Floats
    high: Floats

    @staticmethod
    def point(value: float | Floats) -> Interval:
        v = np.asarray(value, dtype=float)
        return Interval(v, v)

    def __add__(self, other: Interval) -> Interval:
        return Interval(self.low + other.low, self.high + other.high)

    def __mul__(self, other: Interval) -> Interval:
        with np.errstate(invalid="ignore"):
            products = np.stack(
                np.broadcast_arrays(
                    self.low * other.low, self.low * other.high, self.high * other.low, self.high * other.high
                )
            )
        # 0 * inf is NaN: the product may then be anything.
        products = np.where(np.isnan(products), np.inf, products)
        low = np.where(np.isinf(products).any(axis=0), -np.inf, products.min(axis=0))
        high = np.where(np.isinf(products).any(axis=0), np.inf, products.max(axis=0))
        return Interval(low, high)

    def reciprocal(self) -> Interval:
        """1/x: unbounded where the interval holds 0."""
        spans_zero = (self.low <= 0) & (self.high >= 0)
        with np.errstate(divide="ignore"):
            low = np.where(spans_zero, -np.inf, 1 / self.high)
            high = np.where(spans_zero, np.inf, 1 / self.low)
        return Interval(low, high)

    def power(self, n: int) -> Interval:
        """x**n for a whole n (a square is never negative)."""
        if n < 0:
            return self.power(-n).reciprocal()
        if n == 0:
            return Interval.point(np.ones(np.broadcast_shapes(self.low.shape, self.high.shape)))
        a, b = self.low**n, self.high**n
        if n % 2:
            return Interval(a, b)
        holds_zero = (self.low <= 0) & (self.high >= 0)
        return Interval(np.where(holds_zero, 0.0, np.minimum(a, b)), np.maximum(a, b))


Bounder = Callable[[Mapping[sympy.Symbol, Interval]], Interval]


def interval_function(expr: sympy.Expr) -> Bounder:
    """A function that bounds ``expr`` (a rational function with rational coefficients)
    over the intervals given for its symbols."""
    expr = sympy.sympify(expr)
    if expr.is_Symbol:
        return lambda box: box[expr]
    if expr.is_Rational:
        value = float(expr)
        return lambda box: Interval.point(value)
    if expr.is_Add or expr.is_Mul:
        parts = [interval_function(a) for a in expr.args]
        combine = Interval.__add__ if expr.is_Add else Interval.__mul__

        def folded(box: Mapping[sympy.Symbol, Interval]) -> Interval:
            out = parts[0](box)
            for part in parts[1:]:
                out = combine(out, part(box))
            return out

        return folded
    if expr.is_Pow and expr.exp.is_Integer:
        base, n = interval_function(expr.base), int(expr.exp)
        return lambda box: base(box).power(n)
    raise ValueError(f"{expr} is not a rational function of the tooth numbers")
