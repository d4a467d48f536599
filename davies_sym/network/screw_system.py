"""The screw system of order d that the motions span (Laus sections 2.2 and 3.3.1).

The essential unit twists of all couplings span a subspace of the 6-D twist space.
When that subspace is a coordinate subspace (the usual case: ``{t; u}`` for planar
trains drawn on a line, ``{t; u, v}`` for planar linkages), twists keep those
coordinates and wrenches keep the dual ones (``{T; U}``), exactly as in the thesis.
Otherwise a lift ``L`` (6 x d) with ``twist = L @ reduced_twist`` is used and wrenches
reduce to ``L^T @ wrench``, which keeps every power unchanged.

Wrench components reciprocal to the whole system do no work and are the
overconstraint actions the thesis drops; each coupling keeps an independent set of
d - f constraint wrenches reciprocal to its own twists.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.linalg import exact_rank
from davies_sym.algebra.polynomials import PolynomialRing
from davies_sym.algebra.radicals import RadicalTable
from davies_sym.algebra.screws import TWIST_COORDINATES, WRENCH_COORDINATES, NamedScrew, Screw, power
from davies_sym.algebra.square_root_symbol import Radical
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.errors import DerivationError
from davies_sym.topology.kind_screws import CouplingScrews


@dataclass(frozen=True)
class ScrewSystem:
    """A screw system of order ``d``: which coordinates are kept and how they lift, and
    the square roots of the layout its screws may hold (for exact zero tests)."""

    coordinates: tuple[int, ...]
    lift: sympy.Matrix  # 6 x d, twist = lift * reduced twist
    radicals: tuple[Radical, ...] = ()

    @property
    def order(self) -> int:
        return len(self.coordinates)

    @property
    def twist_names(self) -> tuple[str, ...]:
        return tuple(TWIST_COORDINATES[i] for i in self.coordinates)

    @property
    def wrench_names(self) -> tuple[str, ...]:
        return tuple(WRENCH_COORDINATES[i] for i in self.coordinates)

    def reduce_twist(self, twist: Screw) -> tuple[sympy.Expr, ...]:
        return tuple(twist[i] for i in self.coordinates)

    def reduce_wrench(self, wrench: Screw) -> tuple[sympy.Expr, ...]:
        reduced = self.lift.T * sympy.Matrix(wrench)
        return tuple(expanded(v) for v in reduced)

    def contains(self, twist: Screw) -> bool:
        """Whether ``twist`` lies in the system (its lift reproduces it)."""
        back = self.lift * sympy.Matrix(self.reduce_twist(twist))
        return all(self.is_zero(a - b) for a, b in zip(back, twist, strict=True))

    def rank(self, rows: Sequence[Sequence[sympy.Expr]]) -> int:
        """The exact rank of ``rows`` (`exact_rank`, the layout's radicals reduced)."""
        return exact_rank(sympy.Matrix(rows), self.radicals)

    def is_zero(self, value: sympy.Expr) -> bool:
        """Whether ``value`` vanishes, its radicals reduced."""
        value = sympy.expand(value)
        return value == 0 or (bool(self.radicals) and RadicalTable(list(self.radicals)).reduce(value) == 0)


def expanded(value: sympy.Expr) -> sympy.Expr:
    """``value`` expanded; a quotient (a moment about a planet centre placed in 2-D, whose
    coordinates are fractions with square roots) as its reduced numerator over its
    denominator, each expanded, by flint: ``sympy.expand`` would spread the denominator
    over every term of the numerator, tens of thousands of operations for one moment."""
    if not any(p.exp.is_negative and p.base.free_symbols for p in value.atoms(sympy.Pow)):
        return sympy.expand(value)
    return PolynomialRing(sorted_symbols(value.free_symbols)).rational(value).to_expr(factored=False)


def essential_twists(screws: Iterable[CouplingScrews], spatial: bool) -> list[Screw]:
    """The twists the screw system must span: every coupling's motions and the freedoms
    it needs (``spans``); on skew axes every freedom of a point contact counts too, so
    the system is space itself."""
    screws = tuple(screws)
    essential = [m.screw for s in screws for m in (*s.motions, *s.spans)]
    if spatial:
        essential += [m.screw for s in screws for m in s.secondary]
    return essential


def minimal_screw_system(essential: Sequence[Screw], radicals: Iterable[Radical] = ()) -> ScrewSystem:
    """The screw system spanned by ``essential`` twists (``radicals``: the square roots
    of the layout they are written in)."""
    radicals = tuple(radicals)
    W = sympy.Matrix([list(t) for t in essential]).T  # 6 x m
    used = [i for i in range(6) if any(W[i, j] != 0 for j in range(W.cols))]
    rank = exact_rank(W, radicals)
    if rank == 0:
        raise DerivationError("no coupling allows any motion")
    if len(used) == rank:
        lift = sympy.zeros(6, rank)
        for k, i in enumerate(used):
            lift[i, k] = 1
        return ScrewSystem(tuple(used), lift, radicals)
    # General case: keep independent coordinate rows, express the others through them.
    chosen: list[int] = []
    for i in used:
        if exact_rank(sympy.Matrix([W.row(k) for k in [*chosen, i]]), radicals) > len(chosen):
            chosen.append(i)
        if len(chosen) == rank:
            break
    WI = sympy.Matrix([W.row(k) for k in chosen])
    lift = sympy.zeros(6, rank)
    for k, i in enumerate(chosen):
        lift[i, k] = 1
    gram_inv = (WI * WI.T).inv()
    for i in range(6):
        if i not in chosen and i in used:
            coeffs = (W.row(i) * WI.T * gram_inv).applyfunc(sympy.cancel)
            for k in range(rank):
                lift[i, k] = coeffs[0, k]
    return ScrewSystem(tuple(chosen), lift, radicals)


class CouplingScrewError(DerivationError):
    """A coupling's own screws are inconsistent (dependent motions, too few constraints);
    the caller, which knows the file, locates it."""

    def __init__(self, coupling: str, message: str):
        self.coupling = coupling
        self.reason = message
        super().__init__(f"coupling {coupling}: {message}")


@dataclass(frozen=True)
class ReducedCoupling:
    """A coupling's kept unit twists and its independent constraint wrenches (reduced),
    with each constraint's wrench in full 6-D coordinates (``spatial``)."""

    motions: tuple[NamedScrew, ...]
    constraints: tuple[NamedScrew, ...]
    spatial: tuple[Screw, ...] = ()


def reduce_coupling(system: ScrewSystem, screws: CouplingScrews, name: str) -> ReducedCoupling:
    """Keep the coupling's freedoms that lie in the system and pick d - f constraints."""
    motions = list(screws.motions) + [s for s in screws.secondary if system.contains(s.screw)]
    reduced_motions = sympy.Matrix([list(system.reduce_twist(m.screw)) for m in motions])
    freedom = system.rank(reduced_motions.tolist())
    if freedom != len(motions):
        raise CouplingScrewError(
            name, "its unit motion screws are not independent; give screws that span different motions"
        )
    chosen: list[NamedScrew] = []
    spatial: list[Screw] = []
    rows: list[list[sympy.Expr]] = []
    for candidate in screws.constraints:
        if any(not system.is_zero(power(candidate.screw, m.screw)) for m in motions):
            continue
        row = list(system.reduce_wrench(candidate.screw))
        if system.rank([*rows, row]) > len(rows):
            rows.append(row)
            chosen.append(NamedScrew(candidate.name, tuple(row)))
            spatial.append(candidate.screw)
        if len(chosen) == system.order - freedom:
            break
    if len(chosen) != system.order - freedom:
        raise CouplingScrewError(
            name,
            f"found {len(chosen)} independent constraint actions reciprocal to its "
            f"motions, need {system.order - freedom}",
        )
    kept = tuple(NamedScrew(m.name, system.reduce_twist(m.screw)) for m in motions)
    return ReducedCoupling(kept, tuple(chosen), tuple(spatial))
