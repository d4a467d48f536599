"""Exact arithmetic in Q(sqrt(d)): numbers a + b sqrt(d) with rational a, b.

A planar layout whose three centre distances form a triangle of irrational area (the
Ravigneaux set of the ZF 3HP12: 41, 32, 48) has no rational coordinates, but its
coordinates lie in one quadratic field.  :class:`Surd` is that field's arithmetic
(+, -, *, /, powers, exact order) and gives back a plain :class:`~fractions.Fraction`
whenever the irrational part cancels, so squared distances, radii and lever arms that
are rational stay rational.  :func:`solve_linear` is Gauss-Jordan elimination over any
such ordered field (it does not convert its entries to ``Fraction``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Union

Number = Union[Fraction, "Surd"]


def surd(a: Fraction | int, b: Fraction | int, d: int) -> Number:
    """a + b sqrt(d), as a Fraction when b = 0."""
    a, b = Fraction(a), Fraction(b)
    return a if b == 0 else Surd(a, b, d)


def root(d: int, scale: Fraction | int = 1) -> Number:
    """scale * sqrt(d); ``d`` a positive integer that is not a perfect square."""
    if d <= 0 or math.isqrt(d) ** 2 == d:
        raise ValueError(f"sqrt({d}) is rational or not real")
    return surd(0, scale, d)


def _sign(a: Fraction, b: Fraction, d: int) -> int:
    """Sign of a + b sqrt(d), exactly."""
    sa = (a > 0) - (a < 0)
    sb = (b > 0) - (b < 0)
    if sa == sb or sb == 0:
        return sa
    if sa == 0:
        return sb
    # Opposite signs: the larger of |a| and |b| sqrt(d) wins.
    big_a = a * a - b * b * d
    return sa if big_a > 0 else -sa if big_a < 0 else 0


class Surd:
    """a + b sqrt(d) with b != 0 (use :func:`surd` to build one)."""

    __slots__ = ("a", "b", "d")

    def __init__(self, a: Fraction, b: Fraction, d: int):
        self.a, self.b, self.d = a, b, d

    def _parts(self, other: object) -> tuple[Fraction, Fraction] | None:
        if isinstance(other, Surd):
            if other.d != self.d:
                raise ValueError(f"sqrt({self.d}) and sqrt({other.d}) in one expression")
            return other.a, other.b
        if isinstance(other, (int, Fraction)):
            return Fraction(other), Fraction(0)
        return None

    def __add__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        return surd(self.a + p[0], self.b + p[1], self.d)

    __radd__ = __add__

    def __neg__(self) -> Number:
        return Surd(-self.a, -self.b, self.d)

    def __sub__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        return surd(self.a - p[0], self.b - p[1], self.d)

    def __rsub__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        return surd(p[0] - self.a, p[1] - self.b, self.d)

    def __mul__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        a, b = p
        return surd(self.a * a + self.b * b * self.d, self.a * b + self.b * a, self.d)

    __rmul__ = __mul__

    def _inverse(self) -> Number:
        norm = self.a * self.a - self.b * self.b * self.d  # nonzero: sqrt(d) is irrational
        return surd(self.a / norm, -self.b / norm, self.d)

    def __truediv__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        return self * (Surd(p[0], p[1], self.d)._inverse() if p[1] else 1 / p[0])

    def __rtruediv__(self, other: object) -> Number:
        p = self._parts(other)
        if p is None:
            return NotImplemented
        return self._inverse() * p[0]

    def __pow__(self, n: int) -> Number:
        if not isinstance(n, int) or n < 0:
            return NotImplemented
        out: Number = Fraction(1)
        for _ in range(n):
            out = out * self
        return out

    def sign(self) -> int:
        return _sign(self.a, self.b, self.d)

    def _compare(self, other: object) -> int | None:
        p = self._parts(other)
        if p is None:
            return None
        return _sign(self.a - p[0], self.b - p[1], self.d)

    def __eq__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c == 0

    def __ne__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c != 0

    def __lt__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c < 0

    def __le__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c <= 0

    def __gt__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c > 0

    def __ge__(self, other: object) -> bool:
        c = self._compare(other)
        return NotImplemented if c is None else c >= 0

    def __abs__(self) -> Number:
        return -self if self.sign() < 0 else self

    def __hash__(self) -> int:
        return hash((self.a, self.b, self.d))

    def __float__(self) -> float:
        return float(self.a) + float(self.b) * math.sqrt(self.d)

    def __repr__(self) -> str:
        return f"({self.a} + {self.b}*sqrt({self.d}))"


def solve_linear(rows: Sequence[Sequence[Number]], rhs: Sequence[Number], ncols: int) -> list[Number] | None:
    """The unique solution of ``rows x = rhs`` by Gauss-Jordan elimination with exact
    field arithmetic, or None when the system is inconsistent or has a null space (the
    contract of ``oracle.balance.solve_linear``, without converting entries to Fraction)."""
    a: list[list[Number]] = [[*row, b] for row, b in zip(rows, rhs, strict=True)]
    pivots: list[int] = []
    r = 0
    for col in range(ncols):
        piv = next((i for i in range(r, len(a)) if a[i][col] != 0), None)
        if piv is None:
            continue
        a[r], a[piv] = a[piv], a[r]
        inv = 1 / a[r][col]
        a[r] = [v * inv for v in a[r]]
        for i in range(len(a)):
            if i != r and a[i][col] != 0:
                f = a[i][col]
                a[i] = [vi - f * vr for vi, vr in zip(a[i], a[r], strict=True)]
        pivots.append(col)
        r += 1
    if len(pivots) < ncols:
        return None
    if any(row[-1] != 0 for row in a[r:]):
        return None
    x: list[Number] = [Fraction(0)] * ncols
    for i, col in enumerate(pivots):
        x[col] = a[i][-1]
    return x
