"""Polynomials kept as products of factors through the elimination of D_A.

The efficiency of stages in series is a product of stage terms; expanded, its numerator
and denominator grow exponentially with the number of stages (4^k and 8^k terms for
chained two-annulus stages) and factoring them back dominates the derivation.  Here an
entry is ``c * prod f_i^e_i`` with flint-irreducible factors, so products and exact
divisions are bookkeeping, and only the sums the elimination forms are expanded: their
common factors are taken out first and the rest is factored while it is small (larger
rests stay one factor, as expanded elimination would keep them).  The solution leaves
as rational functions whose factorisation is known, so nothing is factored twice.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

from flint import fmpz_mpoly

from davies_sym.algebra.flint_conversion import factor
from davies_sym.algebra.lazy import LazyMapping
from davies_sym.algebra.linalg import Solution, WorkBudget, eliminate_rows
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.products import SMALL_SUM, Product, common, divide, multiply, product_of
from davies_sym.algebra.radicals import radicals_form_a_field


def expansion_work(p: Product) -> int:
    """The products of terms a schoolbook expansion of ``p`` forms (the sizes of its
    factors multiplied): known before it runs, where one expansion can take minutes."""
    work = 1
    for f, e in p.factors:
        work *= len(f) ** e
    return work


def difference(t: Product, u: Product, one: fmpz_mpoly, spent: WorkBudget | None = None) -> Product | None:
    """``t - u`` with their shared factors kept out of the expansion; None when zero.
    The work of the expansions is spent from ``spent`` before they run."""
    g = common(t, u)
    t, u = divide(t, g), divide(u, g)
    if spent is not None:
        spent.spend(expansion_work(t) + expansion_work(u))
    rest = t.expand_in(one) - u.expand_in(one)
    if rest.is_zero():
        return None
    return multiply(g, product_of(rest))


Row = dict[int, Product]


def _content(row: Row, divided: list[fmpz_mpoly] | None = None) -> Row:
    """``row`` divided by the factors and content all its entries share (the factors
    collected in ``divided``: the division holds where none of them vanishes)."""
    entries = iter(row.values())
    shared = next(entries)
    shared = Product(abs(shared.content), shared.factors)
    for value in entries:
        if shared.content == 1 and not shared.factors:
            return row
        shared = common(shared, value)
    if shared.content == 1 and not shared.factors:
        return row
    if divided is not None:
        divided.extend(f for f, _ in shared.factors)
    return {c: divide(v, shared) for c, v in row.items()}


def _eliminate(
    target: Row,
    pivot_row: Row,
    col: int,
    one: fmpz_mpoly,
    divided: list[fmpz_mpoly] | None = None,
    spent: WorkBudget | None = None,
) -> Row:
    g = common(pivot_row[col], target[col])
    p, a = divide(pivot_row[col], g), divide(target[col], g)
    out: Row = {}
    for c in target.keys() | pivot_row.keys():
        if c == col:
            continue
        t = multiply(p, target[c]) if c in target else None
        u = multiply(a, pivot_row[c]) if c in pivot_row else None
        if t is None and u is not None:
            value: Product | None = Product(-u.content, u.factors)
        elif u is None:
            value = t
        else:
            value = difference(t, u, one, spent)  # type: ignore[arg-type]
        if value is not None:
            out[c] = value
    return _content(out, divided) if out else out


def _irreducible(p: Product) -> tuple[int, list[tuple[fmpz_mpoly, int]]]:
    """Content and irreducible factors of ``p`` (its large factors factored now; a factor
    may repeat, `RationalFunction.from_factors` merges them)."""
    content, factors = p.content, list[tuple[fmpz_mpoly, int]]()
    for f, e in p.factors:
        c, parts = factor(f) if len(f) > SMALL_SUM else (1, [(f, 1)])
        content *= c**e
        factors.extend((g, d * e) for g, d in parts)
    return content, factors


def quotient(ring: PolynomialRing, num: Product, den: Product) -> RationalFunction:
    """``num / den`` in lowest terms with its factorisation known."""
    (cn, fn), (cd, fd) = _irreducible(num), _irreducible(den)
    return RationalFunction.from_factors(ring, cn, cd, fn, fd)


@dataclass(frozen=True)
class FactoredElimination:
    """Reduced row echelon form with factored entries: ``pivots[col]`` solves for ``col``.
    ``over_radicals``: the square roots were eliminated as free symbols, so each entry
    of the solution is read back reduced by their relations (`radical_elimination`)."""

    ncols: int
    pivots: Mapping[int, Row]
    over_radicals: bool = False

    @property
    def free(self) -> tuple[int, ...]:
        return tuple(c for c in range(self.ncols) if c not in self.pivots)

    @property
    def rank(self) -> int:
        return len(self.pivots)

    def solution(self, ring: PolynomialRing) -> Solution:
        """The columns in the free ones, ``x_c = -entry / pivot``, each formed when read."""

        def read(num: Product, den: Product) -> RationalFunction:
            if self.over_radicals:
                return RationalFunction.make(ring, _reduced_expansion(ring, num), _reduced_expansion(ring, den))
            return quotient(ring, num, den)

        def column(col: int) -> dict[int, RationalFunction]:
            row = self.pivots.get(col)
            if row is None:
                return {col: RationalFunction.polynomial(ring, ring.one)}
            return {j: read(Product(-v.content, v.factors), row[col]) for j, v in row.items() if j != col}

        return LazyMapping(range(self.ncols), column)


def _reduced_expansion(ring: PolynomialRing, p: Product) -> fmpz_mpoly:
    """``p`` expanded modulo the radical relations, one factor at a time: the same
    canonical polynomial as the whole expansion reduced (reduction is a ring
    homomorphism onto it), without the powers of the roots the whole would form."""
    out = ring.one * p.content
    for f, e in p.factors:
        for _ in range(e):
            out = ring.reduce(out * f)
    return out


def factored_gauss_jordan(
    rows: Iterable[dict[int, fmpz_mpoly]],
    ncols: int,
    one: fmpz_mpoly,
    prefer_free: Iterable[int] = (),
    progress: Callable[[int, int], None] | None = None,
    divided: list[fmpz_mpoly] | None = None,
    budget: int | None = None,
) -> FactoredElimination:
    """Fraction-free Gauss-Jordan elimination as `davies_sym.algebra.linalg.gauss_jordan`
    (the same pivot order: constants first, Markowitz, ``prefer_free`` last), on
    factored entries; ``divided`` collects the factors rows were divided by.
    `WorkExceeded` once its expansions would form more than ``budget`` products of terms
    in all (`expansion_work`)."""
    work = [_content({c: product_of(v) for c, v in r.items()}, divided) for r in rows if r]
    spent = WorkBudget(budget)
    pivots = eliminate_rows(
        work,
        prefer_free,
        lambda v: (not v.is_constant(), v.size),
        lambda row, pivot, col: _eliminate(row, pivot, col, one, divided, spent),
        progress,
    )
    return FactoredElimination(ncols, pivots)


def radical_elimination(
    ring: PolynomialRing,
    rows: Iterable[dict[int, fmpz_mpoly]],
    ncols: int,
    prefer_free: Iterable[int] = (),
    budget: int | None = None,
) -> FactoredElimination | None:
    """The factored elimination with the ring's square roots taken for free symbols:
    entries stay products, where the elimination modulo ``s^2 = m`` expands every
    product and swells. Sound where the radicals generate a field
    (`radicals_form_a_field`) and nothing it divides by (a pivot, a factor shared by a
    row) vanishes modulo their relations: every step is then a step of the elimination
    over that field, with the same rank. None where one of these fails; `WorkExceeded`
    past ``budget`` (`factored_gauss_jordan`)."""
    if not radicals_form_a_field(ring.radicals):
        return None
    reduced = [{c: v for c, v in ((c, ring.reduce(v)) for c, v in r.items()) if not v.is_zero()} for r in rows]
    divided: list[fmpz_mpoly] = []
    elimination = factored_gauss_jordan(reduced, ncols, ring.one, prefer_free, divided=divided, budget=budget)
    divided += [f for col, row in elimination.pivots.items() for f, _ in row[col].factors]
    if any(ring.reduce(f).is_zero() for f in divided):
        return None
    return FactoredElimination(ncols, elimination.pivots, over_radicals=True)
