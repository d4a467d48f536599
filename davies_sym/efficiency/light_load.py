"""Variants of a one-input train at light load: the losses reverse a loaded force.

A variant fixes which gear drives in each mesh from the lossless power flow (Laus eqs.
(69)-(75)) and the sense of each bearing's Coulomb moment from the lossless reaction
(eq. (21)).  A constant drag, viscous or bearing friction does not scale with the
load: where the input torque is small against it (the planet's drag of a planetary
larger than the ring's share of the load), a tooth force or a bearing reaction changes
sign.  The mesh's driving gear, or the bearing moment's sense, is then the other one,
and the formula is that of another case of the same derivation: the mesh takes the zeta
of the other direction (eqs. (74)-(75)); the bearing's action null space is solved
again with its Coulomb sign reversed.

Every case holds where each loaded force (the action solution of D_A, ``Analysis.
action_solution``, at the operating point) has the sign it assumes: a closed form in
the input torque, the speed and the losses.  Which cases admissible designs reach is
found by sampling losses and input torque over decades at the variant's sampled
geometries, starting from the lossless directions and following the forces that
disagree.  A case missed here is never a wrong number: where no case's forces agree,
the answer is refused.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.mesh_friction import is_mesh_law
from davies_sym.efficiency.operating_point import INPUT_TORQUE, OPERATING_SYMBOLS, at_operating_point, substituted
from davies_sym.efficiency.region_sampling import Draws, Point, needed_signs
from davies_sym.efficiency.turning_conditions import MeshRole
from davies_sym.network.analysis import Analysis
from davies_sym.network.matrices import FrictionLaw

#: A loaded force at the operating point and the sign a case needs it to have.
LoadedForces = Mapping[str, tuple[RationalFunction, int]]

#: At most this many reversal cases are derived per variant (each bearing reversal is a
#: new solution of D_A); the sampling visits the most frequent first.
CASE_LIMIT = 16


@dataclass(frozen=True, eq=False)
class Derivation:
    """One solved action null space: the efficiency at the operating point with the
    meshes' zeta symbols in it, and each mesh's zeta in ordinary efficiencies."""

    analysis: Analysis
    form: RationalFunction
    zetas: Mapping[tuple[str, bool], RationalFunction]


@dataclass(frozen=True, eq=False)
class LoadCase:
    """One case of a variant: the loaded forces the losses reverse, each mesh's driving
    gear, the derivation, the loaded forces with the signs they need, and sampled points
    (geometry, losses, input torque and speed) where they have them."""

    reversed: frozenset[str]
    first_drives: Mapping[str, bool]
    derivation: Derivation
    #: The case's formula (Laus eq. (76) with its meshes' directions).
    efficiency: RationalFunction
    forces: LoadedForces
    samples: tuple[Point, ...]


def loaded_laws(analysis: Analysis, roles: Sequence[MeshRole]) -> list[FrictionLaw]:
    """The laws whose force a case assumes the sign of: each power-carrying mesh's own
    friction (its tooth force decides the driving gear) and each bearing's Coulomb law
    (its reaction decides the moment's sense)."""
    meshes = {r.coupling for r in roles if not r.idle}
    every = {r.coupling for r in roles}
    return [
        law
        for law in analysis.network.laws
        if is_mesh_law(law, meshes) or (law.law == "coulomb" and not is_mesh_law(law, every))
    ]


def loaded_forces(
    derivation: Derivation, roles: Sequence[MeshRole], first: Mapping[str, bool], reversed_forces: Collection[str]
) -> dict[str, tuple[RationalFunction, int]]:
    """Each loaded force of a case at the operating point, with the sign the case needs:
    that of its lossless value, the other for the couplings in ``reversed_forces``.  A
    force whose lossless sign the geometry does not decide is given times that value."""
    analysis = derivation.analysis
    torque = analysis.ring.rational(analysis.input_action.symbol)
    out = {}
    for law in loaded_laws(analysis, roles):
        transmitted = law.transmitted or ""
        a, b = analysis.action_solution[transmitted]
        # Without dependent sources the force is proportional to the input torque: it is
        # given per unit input torque, so that it needs no operating point.
        force = a * analysis.ring.rational(analysis.input_power_sign) if b.is_zero() else a * torque + b
        force = at_operating_point(substituted(force, roles, derivation.zetas, first), analysis)
        lossless = analysis.lossless_action_coefficients[transmitted] * analysis.ring.rational(
            analysis.input_power_sign
        )
        sign, _ = analysis.oracle.classify(*lossless.factor_list())
        flip = -1 if law.coupling in reversed_forces else 1
        out[law.coupling] = (force, int(sign) * flip) if sign in (1, -1) else (force * lossless, flip)
    return out


def reached_cases(
    first: Mapping[str, bool],
    derive: Callable[[frozenset[str]], Derivation],
    roles: Sequence[MeshRole],
    points: Sequence[Point],
    efficiencies: Collection[sympy.Symbol],
    seed: int,
) -> list[LoadCase]:
    """The variant's lossless case, then every reversal sampled losses and input torques
    reach at ``points`` (``derive``: the derivation with the named bearings' reactions
    reversed)."""
    bearings = {law.coupling for law in loaded_laws(derive(frozenset()).analysis, roles)} - {r.coupling for r in roles}
    draws = Draws(points, efficiencies, INPUT_TORQUE, seed, drawn=OPERATING_SYMBOLS) if points else None
    out: list[LoadCase] = []
    queue: list[frozenset[str]] = [frozenset()]
    seen = set(queue)
    while queue and len(seen) <= CASE_LIMIT:
        reversal = queue.pop(0)
        derivation = derive(reversal & bearings)
        case_first = {m: f != (m in reversal) for m, f in first.items()}
        forces = loaded_forces(derivation, roles, case_first, reversal)
        efficiency = substituted(derivation.form, roles, derivation.zetas, case_first)
        samples: tuple[Point, ...] = ()
        if draws is not None and forces:
            agree, finite, free = needed_signs(forces, draws)
            every = np.all(agree, axis=1) & finite
            used = set(free) | set(efficiency.to_expr().free_symbols)
            samples = tuple(draws.point(int(k), used) for k in np.flatnonzero(every)[:40])
            # Follow the forces that disagree, the most frequent pattern first.
            names = list(forces)
            patterns: dict[frozenset[str], int] = {}
            for row in agree[finite & ~every]:
                key = frozenset(n for n, ok in zip(names, row, strict=True) if not ok)
                patterns[key] = patterns.get(key, 0) + 1
            for pattern, _ in sorted(patterns.items(), key=lambda kv: (-kv[1], sorted(kv[0]))):
                following = reversal ^ pattern
                if following not in seen:
                    seen.add(following)
                    queue.append(following)
        if not reversal or samples:
            out.append(LoadCase(reversal, case_first, derivation, efficiency, forces, samples))
    return out
