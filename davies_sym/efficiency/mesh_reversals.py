"""Meshes the losses reverse near a turning condition: a variant of its own region.

A turning condition is the sign of a lossless mesh power (Laus eqs. (86)-(88)).  With
losses the power the driving gear gives in its carrier's frame is that of the action
solution of D_A (eqs. (69)-(73) with the friction in place, `light_load.mesh_power`);
near the condition's boundary its lossless part is small and the friction in the other
meshes can turn it round.  Inside one region the formula and driving gears of another
region's variant then hold (the mesh takes the zeta of its other direction, eqs.
(74)-(75)).  Such a case is a variant of the region it lies in, with the meshes the
losses reverse named: it holds where the region's turning conditions hold and the power
through each loaded mesh has the sign the case needs, the reversed ones their reversed
sign, so that the printed conditions of the variant that holds are true where it holds.

Which cases admissible designs reach is found by sampling: ordinary efficiencies in
(1/2, 1) at the region's sampled geometries and at geometries close to its boundary with
the other region (on segments between the two regions' samples, the crossing found by
bisection).  A case that needs the efficiency to be positive there is kept (a reversal
reached only where the train self-locks adds no formula).  A case missed here is never
a wrong number: where no variant of the region agrees, the answer is refused.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import cast

import numpy as np
import sympy
from flint import fmpq

from davies_sym.algebra.point_values import Args
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.operating_point import INPUT_TORQUE, OPERATING_SYMBOLS
from davies_sym.efficiency.parameter_domain import ParameterDomain, Point, geometry_symbols
from davies_sym.efficiency.region_sampling import Draws, needed_signs
from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.efficiency.variant_result import Variant

#: How far inside the region, as fractions of the way from its sample to the boundary,
#: the points near the boundary lie.
DEPTHS = (sympy.Rational(1, 1000), sympy.Rational(1, 100), sympy.Rational(1, 10), sympy.Rational(1, 3))

#: Bisection steps to the boundary along a segment, and segments tried per pair of regions.
STEPS = 30
SEGMENTS = 3


@dataclass(frozen=True, eq=False)
class MeshReversal:
    """A variant's formula and driving gears (``like``) holding in another region (its
    turning-condition ``signs``), the meshes whose direction there differs from the
    region's lossless one (``reversed``), and sampled points where its forces agree."""

    signs: Mapping[str, int]
    like: Variant
    reversed: frozenset[str]
    samples: tuple[Point, ...]


def near_boundary(
    domain: ParameterDomain, conditions: Sequence[TurningCondition], inside: Point, outside: Point
) -> list[Point]:
    """Admissible points of the region of ``inside`` on the segment towards ``outside``
    (another region's sample), at the `DEPTHS` of the way back from where the segment
    leaves the region (bisection on the conditions' signs, eqs. (86)-(88)).  The
    bisection runs on exact rationals of flint, read from the points once."""
    free = [s for s in geometry_symbols(domain.train) if s in inside and s in outside and s not in domain.eliminated]
    start, end = domain.args(inside), domain.args(outside)
    index = [domain.symbol_index[s] for s in free]
    expressions = [c.expression for c in conditions]
    signs = domain.signs_at(expressions, start)

    def at(t: fmpq) -> Args | None:
        mixed = list(start)
        for k in index:
            a, b = cast(fmpq, start[k]), cast(fmpq, end[k])
            mixed[k] = a + t * (b - a)
        args = domain.completed(mixed)
        return args if args is not None and domain.signs_at(expressions, args) == signs else None

    low, high = fmpq(0), fmpq(1)
    for _ in range(STEPS):
        middle = (low + high) / 2
        low, high = (middle, high) if at(middle) is not None else (low, middle)
    keys = [*(k for k in inside if k not in domain.eliminated), *domain.eliminated]
    points = (at(low * (1 - fmpq(depth.p, depth.q))) for depth in DEPTHS)
    return [domain.point_of(p, keys, inside) for p in points if p is not None]


def reached_points(
    domain: ParameterDomain,
    conditions: Sequence[TurningCondition],
    regions: Mapping[tuple[int, ...], Sequence[Point]],
    key: tuple[int, ...],
) -> Iterator[list[Point]]:
    """Groups of at most four points of the region ``key`` (`sampled_regions`) to draw
    losses at: its own samples, then those near its boundary with each other region."""
    own = list(regions.get(key, ()))
    if own:
        yield own[:4]
    for other, points in sorted(regions.items()):
        if other == key or not points:
            continue
        for inside, outside in list(zip(own, points, strict=False))[:SEGMENTS]:
            near = near_boundary(domain, conditions, inside, outside)
            if near:
                yield near


def reversal_samples(
    candidate: Variant, groups: Sequence[Sequence[Point]], efficiencies: Collection[sympy.Symbol], seed: int
) -> tuple[Point, ...]:
    """Sampled points of ``groups`` (geometry, drawn ordinary efficiencies) where every
    loaded force of ``candidate`` has its sign and its efficiency is positive (the
    variant's own conditions, Laus eqs. (69)-(76)); empty when no draw has them."""
    forces: dict[str, tuple[RationalFunction, int]] = dict(candidate.loaded_forces)
    forces["efficiency"] = (candidate.efficiency_rf, 1)
    for group in groups:
        draws = Draws(group, efficiencies, INPUT_TORQUE, seed, drawn=OPERATING_SYMBOLS)
        agree, finite, free = needed_signs(forces, draws)
        rows = np.flatnonzero(np.all(agree, axis=1) & finite)
        if len(rows):
            used = set(free) | candidate.efficiency_rf.free_symbols
            return tuple(draws.point(int(k), used) for k in rows[:40])
    return ()


def mesh_reversals(
    base: Variant,
    candidates: Sequence[Variant],
    groups: Sequence[Sequence[Point]],
    meshes: Collection[str],
    efficiencies: Collection[sympy.Symbol],
    seed: int,
) -> list[MeshReversal]:
    """The variants of other regions (``candidates``, same input, lossless directions)
    whose forces agree at some sampled point of ``base``'s region (``groups``): each a
    case of that region with the ``meshes`` it drives otherwise than ``base`` reversed."""
    out = []
    for other in candidates:
        turned = frozenset(m for m in meshes if other.first_drives[m] != base.first_drives[m])
        if other is base or not other.loaded_forces or not turned or other.reversed_forces:
            continue
        samples = reversal_samples(other, groups, efficiencies, seed)
        if samples:
            out.append(MeshReversal(dict(base.signs), other, turned, samples))
    return out
