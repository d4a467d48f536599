"""Sparse fraction-free Gauss-Jordan elimination over integer polynomials.

Rows are dicts ``column -> fmpz_mpoly`` holding only non-zero entries.  Pivots are
chosen Markowitz-style, constant entries first (most cutset entries are +-1), and every
row is divided by the gcd of its entries after each step, so entries stay small
without ever forming fractions.  Columns listed in ``prefer_free`` (the primary
variables of Laus, e.g. the input torque T_A) are pivoted last, so they stay free
whenever the system allows it.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass
from typing import Protocol, TypeVar

import sympy
from flint import fmpz_mpoly

from davies_sym.algebra.lazy import LazyMapping
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.square_root_symbol import Radical

Row = dict[int, fmpz_mpoly]
Reduce = Callable[[fmpz_mpoly], fmpz_mpoly]
#: The columns of a solved system in the free ones.
Solution = LazyMapping[int, dict[int, RationalFunction]]


class SolvedSpace(Protocol):
    """A null space solved: which columns stand free, which are pivots, and every column
    in the free ones (`Elimination`, the factored and turned ones, `ExchangedFree`)."""

    @property
    def free(self) -> tuple[int, ...]: ...

    @property
    def pivots(self) -> Collection[int]: ...

    def solution(self, ring: PolynomialRing) -> Solution: ...


def polynomial_rows(ring: PolynomialRing, matrix: sympy.Matrix) -> list[Row]:
    """The sparse polynomial rows of ``matrix``; a row with fractions (pitch points of
    tilted bevel axes) is multiplied by the lcm of its denominators, which leaves its
    equation."""
    # The non-zero entries only, row by row in column order (a dense read compares every zero).
    nonzero: dict[int, dict[int, sympy.Expr]] = {}
    for (i, j), value in sorted(matrix.todok().items()):
        nonzero.setdefault(i, {})[j] = value
    rows = []
    for i in range(matrix.rows):
        entries = {j: ring.rational(value) for j, value in nonzero.get(i, {}).items()}
        common = ring.one
        for rf in entries.values():
            if not rf.den.is_one():
                common = common * (rf.den / common.gcd(rf.den))
        rows.append({j: rf.num * (common / rf.den) for j, rf in entries.items()})
    return rows


def _remove_content(row: Row) -> Row:
    g = None
    # Smallest entries first: their gcd is cheap and is often 1 already.
    for value in sorted(row.values(), key=len):
        g = value if g is None else g.gcd(value)
        if g.is_one():
            return row
    if g is None or g.is_one():
        return row
    if g.leading_coefficient() < 0:
        g = -g
    return {c: v / g for c, v in row.items()}


def _eliminate(target: Row, pivot_row: Row, col: int, reduce: Reduce | None = None) -> Row:
    """``target`` with column ``col`` eliminated by a fraction-free combination;
    ``reduce`` brings entries to canonical form (radical relations) before zero tests."""
    return _remove_content(_combined(target, pivot_row, col, reduce))


def _combined(target: Row, pivot_row: Row, col: int, reduce: Reduce | None = None) -> Row:
    """`_eliminate` before the row's content is divided out."""
    p, a = pivot_row[col], target[col]
    g = p.gcd(a)
    if not g.is_one():
        p, a = p / g, a / g
    out: Row = {}
    for c in target.keys() | pivot_row.keys():
        if c == col:
            continue
        value = p * target[c] if c in target else None
        if c in pivot_row:
            term = a * pivot_row[c]
            value = -term if value is None else value - term
        if value is not None and reduce is not None:
            value = reduce(value)
        if value is not None and not value.is_zero():
            out[c] = value
    return out


@dataclass(frozen=True)
class Elimination:
    """Reduced row echelon form: ``pivots[col]`` is the row that solves for ``col``."""

    ncols: int
    pivots: Mapping[int, Row]

    @property
    def free(self) -> tuple[int, ...]:
        return tuple(c for c in range(self.ncols) if c not in self.pivots)

    @property
    def rank(self) -> int:
        return len(self.pivots)

    def solution(self, ring: PolynomialRing) -> Solution:
        """Every column as a linear combination of the free columns, each formed when first
        read (its coefficients cost a gcd with the pivot each; the efficiency needs the port
        actions only): ``x_c = sum_j coeff[c][j] x_j`` with j free; a free column maps to itself.
        """

        def column(col: int) -> dict[int, RationalFunction]:
            row = self.pivots.get(col)
            if row is None:
                return {col: RationalFunction.polynomial(ring, ring.one)}
            return {j: RationalFunction.make(ring, -v, row[col]) for j, v in row.items() if j != col}

        return LazyMapping(range(self.ncols), column)


class WorkExceeded(Exception):
    """The elimination formed more terms than its budget allowed."""


class WorkBudget:
    """Terms an elimination may form (None: no bound); `spend` raises `WorkExceeded`
    past it, so work is bounded by size, the same on every machine."""

    def __init__(self, terms: int | None) -> None:
        self.terms = terms
        self.formed = 0

    def spend(self, terms: int) -> None:
        self.formed += terms
        if self.terms is not None and self.formed > self.terms:
            raise WorkExceeded(f"more than {self.terms} terms formed")


def gauss_jordan(
    rows: Iterable[Row],
    ncols: int,
    prefer_free: Iterable[int] = (),
    progress: Callable[[int, int], None] | None = None,
    reduce: Reduce | None = None,
    budget: int | None = None,
) -> Elimination:
    """Fraction-free Gauss-Jordan elimination of sparse polynomial ``rows``; ``reduce``
    (the ring's radical relations) keeps entries canonical, so zero tests are exact.
    `WorkExceeded` once the rows it forms hold more than ``budget`` terms in all (work
    bounded by its size, the same on every machine)."""
    if reduce is not None:
        rows = [{c: v for c, v in ((c, reduce(v)) for c, v in r.items()) if not v.is_zero()} for r in rows]
    work = [_remove_content(dict(r)) for r in rows if r]
    spent = WorkBudget(budget)

    def eliminate(row: Row, pivot: Row, col: int) -> Row:
        out = _combined(row, pivot, col, reduce)
        # Counted before the content is divided out: the gcd of swollen entries is the
        # work (entries of 10^5 terms sharing a factor of 10^5).
        spent.spend(sum(len(v) for v in out.values()))
        return _remove_content(out)

    pivots = eliminate_rows(work, prefer_free, lambda v: (not v.is_constant(), len(v)), eliminate, progress)
    return Elimination(ncols, pivots)


def exact_rank(matrix: sympy.Matrix, radicals: Iterable[Radical] = ()) -> int:
    """The rank of a matrix of rational expressions, exactly: fraction-free elimination in
    flint, entries reduced by the radicals' relations ``s^2 = m`` before every zero test.
    (sympy's ``rank(simplify=True)`` decides zeros by ``simplify`` and numeric probes,
    seconds per entry on rotated layouts, and takes a radical symbol for a free one.)"""
    if all(x == 0 for x in matrix):
        return 0
    symbols = set().union(*(sympy.sympify(x).free_symbols for x in matrix))
    ring = PolynomialRing(symbols, radicals)
    return gauss_jordan(polynomial_rows(ring, matrix), matrix.cols, reduce=ring.reduce).rank


Entry = TypeVar("Entry")


def eliminate_rows(
    work: list[dict[int, Entry]],
    prefer_free: Iterable[int],
    weight: Callable[[Entry], tuple[bool, int]],
    eliminate: Callable[[dict[int, Entry], dict[int, Entry], int], dict[int, Entry]],
    progress: Callable[[int, int], None] | None = None,
) -> dict[int, dict[int, Entry]]:
    """The pivot rows of a Gauss-Jordan elimination of ``work`` (changed in place), by
    column: Markowitz pivots, entries light by ``weight`` (constants, then few terms)
    first, the ``prefer_free`` columns last; ``eliminate(row, pivot_row, col)`` clears a
    column from a row."""
    late = set(prefer_free)
    pivot_row_of: dict[int, int] = {}
    pending = list(range(len(work)))
    total = len(pending)
    while pending:
        col_count: dict[int, int] = {}
        for i in pending:
            for c in work[i]:
                col_count[c] = col_count.get(c, 0) + 1
        best = None
        for i in pending:
            row = work[i]
            for c, v in row.items():
                heavy, size = weight(v)
                score = (c in late, heavy, (len(row) - 1) * (col_count[c] - 1), size, c)
                if best is None or score < best[0]:
                    best = (score, i, c)
        if best is None:
            break
        _, i, col = best
        pending.remove(i)
        for j, row in enumerate(work):
            if j != i and col in row:
                work[j] = eliminate(row, work[i], col)
        pivot_row_of[col] = i
        pending = [j for j in pending if work[j]]
        if progress is not None:
            progress(total - len(pending), total)
    return {col: work[i] for col, i in pivot_row_of.items()}
