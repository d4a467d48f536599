"""A null space solved with another column free, read back in the wanted one.

Which column stays free decides the route of a fraction-free elimination, and over the
square roots of a 2-D drawing the routes differ by orders of magnitude: with the
carrier's torque free, the actions with friction of an 8-link train swell past 8 GB;
with the output's torque free, they solve in seconds.  The space is the same, so the
solution in the column taken free converts exactly to the wanted one.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from davies_sym.algebra.lazy import LazyMapping
from davies_sym.algebra.linalg import Solution, SolvedSpace
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction


@dataclass(frozen=True)
class ExchangedFree:
    """``inner`` solved with ``taken`` free where ``wanted`` is to be: every column
    ``x_c = a_c t + b`` in the taken column ``t`` (and the other free columns, ``b``)
    becomes ``x_c = (a_c / a_w) w + (b_c - a_c b_w / a_w)`` in the wanted one ``w``
    (``a_w`` is not zero: `exchanged` checks it). ``read``: the inner solution, its
    wanted column already formed (over square roots that reading takes seconds)."""

    inner: SolvedSpace
    wanted: int
    taken: int
    read: Solution

    @property
    def free(self) -> tuple[int, ...]:
        return tuple(sorted(self.wanted if c == self.taken else c for c in self.inner.free))

    @property
    def pivots(self) -> frozenset[int]:
        return frozenset(c for c in self.inner.pivots if c != self.wanted) | {self.taken}

    def solution(self, ring: PolynomialRing) -> Solution:
        inner = self.read
        wanted = inner[self.wanted]
        scale = wanted[self.taken].inverse()
        zero = RationalFunction.polynomial(ring, ring.zero)

        def column(col: int) -> dict[int, RationalFunction]:
            row = inner[col]
            along = row.get(self.taken, zero) * scale
            out = {self.wanted: along} if not along.is_zero() else {}
            for other, value in row.items():
                if other == self.taken:
                    continue
                moved = value - along * wanted.get(other, zero)
                if not moved.is_zero():
                    out[other] = moved
            for other, value in wanted.items():
                if other != self.taken and other not in row:
                    moved = -(along * value)
                    if not moved.is_zero():
                        out[other] = moved
            return out

        return LazyMapping(list(inner), column)


def exchanged(
    solved: SolvedSpace, ring: PolynomialRing, wanted: int, taken: int, others: Iterable[int] = ()
) -> ExchangedFree | None:
    """``solved`` read back with the wanted column free in place of the taken one, or None
    where it cannot be: the taken column must stand free with none but ``others``, and
    the wanted one must move with it."""
    if taken not in solved.free or not set(solved.free) - {taken} <= set(others):
        return None
    read = solved.solution(ring)
    if read[wanted].get(taken, RationalFunction.polynomial(ring, ring.zero)).is_zero():
        return None
    return ExchangedFree(solved, wanted, taken, read)
