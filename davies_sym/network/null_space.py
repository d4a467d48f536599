"""The null spaces of M_N, A_N and D_A, and the equations of a turned drawing solved in
the drawing's own frame.

The elimination runs in flint: factored entries where stages in series multiply, plain
fraction-free rows reduced by the radical relations where the layout has square roots
(whose relations the factors would not respect).

A planar train drawn in 2-D along a placement direction other than +y (`placement: 30`,
`placement: [px, py]`) is the upright drawing turned: every pitch point, tangent and
bearing point carries the direction's cosine and sine (square roots, or symbols).  The
entries of M_N, A_N and D_A then mix both, and the fraction-free elimination drags them
through minors far larger than the upright drawing's (a locked Ravigneaux state: pivots
of 31,728 terms against 234).  No magnitude depends on the direction: turning the
velocity and force rows (u, v) of every circuit and cutset block back is a row
operation, and turning each bearing's pair of reaction forces (along x and y) with them
is a change of variables undone on the solution, so the turned equations are the
upright drawing's and their solution is the same rational functions.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.exchanged_free import exchanged
from davies_sym.algebra.factored import FactoredElimination, factored_gauss_jordan, radical_elimination
from davies_sym.algebra.lazy import LazyMapping
from davies_sym.algebra.linalg import (
    Elimination,
    Row,
    Solution,
    SolvedSpace,
    WorkExceeded,
    gauss_jordan,
    polynomial_rows,
)
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.caches import IdentityCache
from davies_sym.network.matrices import ActionVariable, Network
from davies_sym.topology.model import Train

#: The twist coordinates (t; u, v) of a planar train: within a block of three rows of
#: M_N or A_N, the second and third rows are the ones a turn of the drawing mixes.
PLANAR = (2, 3, 4)


@dataclass(frozen=True)
class Frame:
    """The turn taking the placement direction (cos, sin) to +y: (x, y) -> (sin x - cos y,
    cos x + sin y)."""

    cos: sympy.Expr
    sin: sympy.Expr

    def turn_rows(self, matrix: sympy.Matrix, blocks: int) -> sympy.Matrix:
        """``matrix`` with the rows (u, v) of its first ``blocks`` blocks of three turned."""
        out = matrix.copy()
        for b in range(blocks):
            u, v = matrix.row(3 * b + 1), matrix.row(3 * b + 2)
            out[3 * b + 1, :] = self.sin * u - self.cos * v
            out[3 * b + 2, :] = self.cos * u + self.sin * v
        return out

    def turn_columns(self, matrix: sympy.Matrix, pairs: Sequence[tuple[int, int]]) -> sympy.Matrix:
        """``matrix`` with each pair of columns (force along x, along y) replaced by the
        forces along the turned axes (`TurnedElimination.solution` gives the drawing's back)."""
        out = matrix.copy()
        for i, j in pairs:
            x, y = matrix.col(i), matrix.col(j)
            out[:, i] = self.sin * x - self.cos * y
            out[:, j] = self.cos * x + self.sin * y
        return out


def drawing_frame(network: Network) -> Frame | None:
    """The frame of ``network``'s drawing, or None where it is upright or not a planar
    train drawn in the plane (the screw system {t; u, v}, kept coordinates)."""
    cos, sin = network.layout.frame
    if cos == 0 and sin == 1:
        return None
    system = network.system
    if network.layout.spatial or system.coordinates != PLANAR:
        return None
    if any(system.lift[i, k] != (1 if i == c else 0) for i in range(6) for k, c in enumerate(PLANAR)):
        return None  # the kept coordinates do not lift to themselves
    return Frame(cos, sin)


def force_pairs(columns: Sequence[ActionVariable]) -> tuple[tuple[int, int], ...]:
    """The columns of each coupling's pair of forces along x and y (a bearing's reaction)."""
    along: dict[tuple[str, tuple[int, int]], int] = {}
    for k, v in enumerate(columns):
        for force in ((1, 0), (0, 1)):
            if (v.wrench[1], v.wrench[2]) == force:
                along.setdefault((v.coupling, force), k)
    return tuple(
        (i, along[(coupling, (0, 1))])
        for (coupling, force), i in along.items()
        if force == (1, 0) and (coupling, (0, 1)) in along
    )


@dataclass(frozen=True)
class TurnedElimination:
    """The elimination of turned equations, its solution given back in the variables of
    the drawing (``pairs``: the columns turned by `Frame.turn_columns`)."""

    inner: Elimination | FactoredElimination
    frame: Frame
    pairs: tuple[tuple[int, int], ...]

    @property
    def pivots(self) -> Mapping[int, object]:
        return self.inner.pivots

    @property
    def free(self) -> tuple[int, ...]:
        return self.inner.free

    def solution(self, ring: PolynomialRing) -> Solution:
        """Every column in the free ones (none of them turned): a turned pair gives
        x = sin y_1 + cos y_2 along x and -cos y_1 + sin y_2 along y."""
        turned = self.inner.solution(ring)
        if not self.pairs:
            return turned
        cos, sin = ring.rational(self.frame.cos), ring.rational(self.frame.sin)
        weights: dict[int, tuple[tuple[RationalFunction, int], tuple[RationalFunction, int]]] = {}
        for i, j in self.pairs:
            weights[i] = ((sin, i), (cos, j))
            weights[j] = ((-cos, i), (sin, j))

        def column(col: int) -> dict[int, RationalFunction]:
            if col not in weights:
                return turned[col]
            out: dict[int, RationalFunction] = {}
            for weight, source in weights[col]:
                for free, value in turned[source].items():
                    term = weight * value
                    out[free] = out[free] + term if free in out else term
            # In lowest terms, as the elimination gives every other column.
            return {k: RationalFunction.make(ring, v.num, v.den) for k, v in out.items() if not v.is_zero()}

        return LazyMapping(list(turned), column)


#: Terms the elimination modulo the radical relations may form before the factored one,
#: the square roots taken for free symbols, is tried instead: work bounded by size.
RADICAL_WORK = 300_000

#: Work the elimination over the square roots (factored, then reduced) may do with one
#: choice of free column before another is tried (`null_space`'s ``instead``): products
#: of terms its expansions form, counted before each runs (`expansion_work`; about a
#: minute at most). The most a 7-link file takes is 0.82 billion (atlas7_r92_d23); an
#: 8-link state that takes 1.7 billion and then 11.5 with the carrier's torque free
#: (8 GB) takes 0.54 with the output's, and one step of forming atlas8_r239_d67 would
#: have taken 149 billion.
ROUTE_WORK = 1_500_000_000

#: Terms the reduced elimination may form where the factored one is not sound (its
#: entries are expanded: terms, not products, count); the 7-link files form 5.6 million
#: at most.
REDUCED_ROUTE_WORK = 12_000_000


@dataclass(frozen=True)
class Swelling:
    """Which kinds of matrix (``key``: the couplings a state keeps, the matrix's shape
    and law rows) swelled past `RADICAL_WORK` in the elimination modulo the radical
    relations, in a state of one whole train (``known``): its other states skip that
    attempt.  Both routes are exact; this only spares the attempt bound to fail."""

    known: set[Hashable]
    key: Hashable


def eliminate(
    ring: PolynomialRing,
    rows: list[Row],
    ncols: int,
    prefer: list[int],
    bounded: bool = False,
    swelling: Swelling | None = None,
) -> Elimination | FactoredElimination:
    """Stages in series multiply: factored entries keep them apart. With radicals the
    elimination reduces every entry modulo their relations; where its entries swell past
    `RADICAL_WORK` terms (planet triangles of several square roots), the factored
    elimination over the roots as free symbols takes over when it is sound there
    (`radical_elimination`), else the reduced elimination runs to its end; ``bounded``:
    these two past `ROUTE_WORK` and `REDUCED_ROUTE_WORK` raise `WorkExceeded`;
    ``swelling``: where the same kind of matrix swelled before, straight to the second."""
    if not ring.radicals:
        return factored_gauss_jordan(rows, ncols, ring.one, prefer_free=prefer)
    if swelling is None or swelling.key not in swelling.known:
        try:
            return gauss_jordan(rows, ncols, prefer_free=prefer, reduce=ring.reduce, budget=RADICAL_WORK)
        except WorkExceeded:
            if swelling is not None:
                swelling.known.add(swelling.key)
    factored = radical_elimination(ring, rows, ncols, prefer, ROUTE_WORK if bounded else None)
    if factored is not None:
        return factored
    budget = REDUCED_ROUTE_WORK if bounded else None
    return gauss_jordan(rows, ncols, prefer_free=prefer, reduce=ring.reduce, budget=budget)


def null_space(
    network: Network,
    ring: PolynomialRing,
    matrix: sympy.Matrix,
    prefer: list[int],
    columns: Sequence[ActionVariable] = (),
    laws: int = 0,
    instead: Sequence[int] = (),
) -> SolvedSpace:
    """The null space of ``matrix``: blocks of d circuit or cutset rows, then ``laws`` rows
    (D_A's constitutive and source rows); the columns ``prefer`` free where the system
    allows.  A turned drawing is solved turned back, ``columns`` naming the action
    variables whose reaction pairs turn with it.  Where the route with ``prefer[0]``
    free swells past its bound, each column of ``instead`` is tried free in its
    place and the solution read back in ``prefer[0]`` (`ExchangedFree`); `WorkExceeded`
    when every one swells so."""
    try:
        return _null_space(network, ring, matrix, prefer, columns, laws, bounded=bool(instead))
    except WorkExceeded:
        if not instead:
            raise
    for other in instead:
        try:
            solved = _null_space(network, ring, matrix, [other, *prefer[1:]], columns, laws, bounded=True)
        except WorkExceeded:
            continue
        found = exchanged(solved, ring, prefer[0], other, prefer[1:])
        if found is not None:
            return found
    raise WorkExceeded("every column tried free swells past the bound")


def _null_space(
    network: Network,
    ring: PolynomialRing,
    matrix: sympy.Matrix,
    prefer: list[int],
    columns: Sequence[ActionVariable],
    laws: int,
    bounded: bool,
) -> SolvedSpace:
    frame = drawing_frame(network)
    whole = network.train.whole
    known = _SWELLED.get(whole, set) if whole is not None else None
    kept = tuple(c.name for c in network.train.couplings)

    def swelling(turned: bool) -> Swelling | None:
        return None if known is None else Swelling(known, (kept, matrix.shape, laws, bounded, turned))

    if frame is not None:
        pairs = force_pairs(columns)
        turned = frame.turn_columns(frame.turn_rows(matrix, (matrix.rows - laws) // 3), pairs)
        elimination = eliminate(ring, polynomial_rows(ring, turned), matrix.cols, prefer, bounded, swelling(True))
        # Only where the free columns are the preferred ones, as the plain elimination
        # leaves them (a free turned force would write the solution in other variables).
        if set(elimination.free) <= set(prefer):
            return TurnedElimination(elimination, frame, pairs)
    return eliminate(ring, polynomial_rows(ring, matrix), matrix.cols, prefer, bounded, swelling(False))


#: The kinds of matrix whose elimination modulo the radical relations swelled, in some
#: state of each whole train (`Swelling`), while the train lives.
_SWELLED: IdentityCache[Train, set[Hashable]] = IdentityCache()
