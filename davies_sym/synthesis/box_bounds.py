"""Rigorous ranges of a rational function of the tooth numbers over boxes of them: what
the best-first search prunes by (`davies_sym.synthesis.best_first`).

Tooth numbers are positive, and on a box of non-negative numbers every monomial increases
with each variable.  A polynomial written as ``P = P+ - P-`` (its terms of positive and
of negative coefficient) therefore lies in ``[P+(lo) - P-(hi), P+(hi) - P-(lo)]``: the
natural interval extension, exact at a single point and tighter as the box shrinks.  A
quotient's range follows from those of its numerator and denominator where the
denominator keeps its sign over the box; elsewhere nothing is claimed (the whole line).
Every range is widened by `WIDENING` against rounding, so a pruning decision never
rests on the last bit of a float.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

#: Relative (and absolute, near zero) widening of every range against rounding.
WIDENING = 1e-9

Floats = NDArray[np.float64]


@dataclass(frozen=True)
class PolynomialRange:
    """A polynomial in ``len(exponents[0])`` positive variables, term by term."""

    exponents: NDArray[np.int64]
    coefficients: Floats

    @classmethod
    def of(cls, expression: sympy.Expr, symbols: Sequence[sympy.Symbol]) -> PolynomialRange:
        terms = sympy.Poly(expression, *symbols).terms() if expression != 0 else []
        exponents = np.array([e for e, _ in terms], dtype=np.int64).reshape(len(terms), len(symbols))
        return cls(exponents, np.array([float(c) for _, c in terms], dtype=float))

    def _monomials(self, corner: Floats) -> Floats:
        """Every term's monomial at every box's corner (boxes x terms): each variable's
        powers computed once per box and gathered by the terms' exponents (a power 0 is
        exactly 1, so the products are those of the used powers alone)."""
        out = np.ones((corner.shape[0], len(self.coefficients)))
        for k in range(self.exponents.shape[1]):
            column = self.exponents[:, k]
            top = int(column.max()) if len(column) else 0
            if top > 0:
                out *= (corner[:, k : k + 1] ** np.arange(top + 1))[:, column]
        return out

    def range(self, low: Floats, high: Floats) -> tuple[Floats, Floats]:
        """The polynomial's least and greatest value over each box ``low <= x <= high``
        (rows: boxes; columns: variables, none negative)."""
        positive = np.where(self.coefficients > 0, self.coefficients, 0.0)
        negative = np.where(self.coefficients < 0, self.coefficients, 0.0)
        at_low, at_high = self._monomials(low), self._monomials(high)
        least = at_low @ positive + at_high @ negative
        greatest = at_high @ positive + at_low @ negative
        slack = WIDENING * (at_high @ np.abs(self.coefficients) + 1.0)
        return least - slack, greatest + slack


@dataclass(frozen=True)
class RationalRange:
    """``numerator / denominator``, each a `PolynomialRange`."""

    numerator: PolynomialRange
    denominator: PolynomialRange

    @classmethod
    def of(cls, expression: sympy.Expr, symbols: Sequence[sympy.Symbol]) -> RationalRange:
        numerator, denominator = sympy.fraction(sympy.together(expression))
        return cls(PolynomialRange.of(numerator, symbols), PolynomialRange.of(denominator, symbols))

    def range(self, low: Floats, high: Floats) -> tuple[Floats, Floats]:
        """Least and greatest value over each box; ``(-inf, inf)`` where the denominator
        may vanish in the box."""
        n_low, n_high = self.numerator.range(low, high)
        d_low, d_high = self.denominator.range(low, high)
        signed = (d_low > 0) | (d_high < 0)
        with np.errstate(all="ignore"):
            quotients = np.stack([n_low / d_low, n_low / d_high, n_high / d_low, n_high / d_high])
        least = np.where(signed, quotients.min(axis=0), -np.inf)
        greatest = np.where(signed, quotients.max(axis=0), np.inf)
        return least, greatest
