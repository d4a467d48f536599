"""Exact values of a rational function of the tooth numbers at whole tooth numbers: the
numerator and denominator as integer polynomials (denominators cleared once), evaluated
in Python integers, so a ratio on the edge of its window is decided exactly."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import sympy
from numpy.typing import NDArray

#: Magnitudes int64 holds with room for one more product of small numbers.
_INT64_ROOM = 2**62


@dataclass(frozen=True)
class IntegerPolynomial:
    """sum of coefficient * prod(x_k ** e_k) over ``terms``."""

    terms: tuple[tuple[int, tuple[int, ...]], ...]

    def rows(self, columns: Sequence[NDArray[np.int64]]) -> NDArray[np.int64] | NDArray[np.object_]:
        """The value at every row (one array per symbol), in int64 where no term can
        overflow it, else in Python integers."""
        largest = max((int(np.abs(c).max()) if len(c) else 0 for c in columns), default=0)
        bound = sum(abs(k) * largest ** sum(e) for k, e in self.terms)
        kind: type = np.int64 if bound < _INT64_ROOM else object
        size = len(columns[0]) if columns else 1
        total: NDArray[np.int64] | NDArray[np.object_] = np.zeros(size, dtype=kind)
        for coefficient, exponents in self.terms:
            term: NDArray[np.int64] | NDArray[np.object_] = np.full(size, coefficient, dtype=kind)
            for x, e in zip(columns, exponents, strict=True):
                if e:
                    term = term * x.astype(kind) ** e
            total = total + term
        return total

    def __call__(self, point: Sequence[int]) -> int:
        total = 0
        for coefficient, exponents in self.terms:
            term = coefficient
            for x, e in zip(point, exponents, strict=True):
                if e:
                    term *= x**e
            total += term
        return total


@dataclass(frozen=True)
class ExactRational:
    """A rational function of ``symbols`` evaluated exactly at whole points."""

    symbols: tuple[sympy.Symbol, ...]
    numerator: IntegerPolynomial
    denominator: IntegerPolynomial

    @staticmethod
    def of(expr: sympy.Expr, symbols: Sequence[sympy.Symbol]) -> ExactRational:
        num, den = sympy.fraction(sympy.cancel(sympy.together(expr)))
        gens = tuple(symbols)
        p, q = sympy.Poly(num, *gens, domain="QQ"), sympy.Poly(den, *gens, domain="QQ")
        scale = sympy.ilcm(*(c.q for c in (*p.coeffs(), *q.coeffs())))
        terms = []
        for poly in (p, q):
            terms.append(IntegerPolynomial(tuple((int(c * scale), tuple(int(e) for e in m)) for m, c in poly.terms())))
        return ExactRational(gens, terms[0], terms[1])

    def __call__(self, values: Mapping[sympy.Symbol, int]) -> Fraction | None:
        """The value at ``values``; None where the denominator vanishes."""
        point = [values[s] for s in self.symbols]
        den = self.denominator(point)
        return None if den == 0 else Fraction(self.numerator(point), den)

    def rows(self, columns: Sequence[NDArray[np.int64]]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """Numerator and denominator at every row, the denominator made non-negative."""
        num, den = self.numerator.rows(columns), self.denominator.rows(columns)
        sign = np.where(den < 0, -1, 1)
        return num * sign, den * sign

    def within_rows(self, columns: Sequence[NDArray[np.int64]], low: Fraction, high: Fraction) -> NDArray[np.bool_]:
        """Where ``low <= value <= high`` exactly (False where the denominator vanishes)."""
        num, den = self.rows(columns)
        ok = (
            (den != 0)
            & (num * low.denominator >= low.numerator * den)
            & (num * high.denominator <= high.numerator * den)
        )
        return np.asarray(ok, dtype=bool)

    def whole_rows(self, columns: Sequence[NDArray[np.int64]]) -> tuple[NDArray[np.bool_], NDArray[np.int64]]:
        """Where the value is a whole number, and the value there (0 elsewhere)."""
        num, den = self.rows(columns)
        safe = np.where(den == 0, 1, den)
        whole = (den != 0) & (num % safe == 0)
        return np.asarray(whole, dtype=bool), np.where(whole, num // safe, 0).astype(np.int64)
