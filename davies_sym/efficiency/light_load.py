"""Where a variant of a one-input train holds beyond its turning conditions: every mesh
gives power the way the variant assumes, and every bearing's moment has its sense.

A variant fixes which gear drives in each mesh from the lossless power flow (Laus eqs.
(69)-(75)) and the sense of each bearing's Coulomb moment from the lossless reaction
(eq. (21)).  Losses move both.  Near a turning condition the mesh power is small, and
the friction in the other meshes can reverse it: the lossless rule says the first gear
drives while, with losses, the power crosses the other way (the boundary between two
variants moves with the mesh efficiencies).  A constant drag, viscous or bearing
friction does not scale with the load: at light load it reverses a tooth force or a
bearing reaction anywhere.  The formula is then that of another case: the mesh takes the
zeta of its other direction (eqs. (74)-(75)); a bearing's action null space is solved
again with its Coulomb sign reversed.

A case holds where its assumptions agree with its own solution: the power each driving
gear gives in its carrier's frame (the tooth force and friction moment of the action
solution of D_A, ``Analysis.action_solution``, on the driving side) is positive, and
each bearing's reaction has the sign it assumes.  Both are closed forms in the geometry,
the losses and the operating point.  The mesh conditions do not depend on the region,
so the formula of a neighbouring region holds where the losses move a turning point past
the lossless boundary: that case is a variant of the region it lies in, with the mesh
reversed (`davies_sym.efficiency.mesh_reversals`).  Which bearing reversals admissible designs reach is found by
sampling losses and input torque over decades at the variant's sampled geometries,
starting from the lossless directions and following the forces that disagree.  A case
missed here is never a wrong number: where no case agrees, the answer is refused.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.mesh_friction import is_mesh_law
from davies_sym.efficiency.operating_point import INPUT_TORQUE, OPERATING_SYMBOLS, at_operating_point, substituted
from davies_sym.efficiency.region_sampling import Draws, Point, needed_signs
from davies_sym.efficiency.turning_conditions import MeshRole
from davies_sym.efficiency.virtual_power import MeshPowerFlow
from davies_sym.network.analysis import Analysis
from davies_sym.network.friction_laws import CoulombLaw, FrictionLaw
from davies_sym.topology.coupling_kinds import as_bearing

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
    #: Each mesh's carrier-frame powers in this derivation's ring.
    flows: Mapping[str, MeshPowerFlow]
    #: Substitutions already made (what, driving gears) -> result: the other input's
    #: variants ask for the same driving gears as the declared input's.
    solved: dict[tuple[str, tuple[tuple[str, bool], ...]], RationalFunction] = field(default_factory=dict, repr=False)

    def form_with(self, roles: Sequence[MeshRole], first: Mapping[str, bool]) -> RationalFunction:
        """The efficiency form with each mesh's zeta of the direction ``first`` gives it."""
        key = ("", tuple(sorted(first.items())))
        if key not in self.solved:
            self.solved[key] = substituted(self.form, roles, self.zetas, first)
        return self.solved[key]


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
        if is_mesh_law(law, meshes) or (isinstance(law, CoulombLaw) and not is_mesh_law(law, every))
    ]


def loaded_forces(
    derivation: Derivation,
    roles: Sequence[MeshRole],
    first: Mapping[str, bool],
    reversed_forces: Collection[str],
    swapped: bool = False,
) -> dict[str, tuple[RationalFunction, int]]:
    """Each loaded force of a case at the operating point, with the sign the case needs.

    For a mesh, the sign of the power its driving gear gives (`mesh_power`): positive
    where the first gear drives; given as the product of its factors the geometry does not
    decide, which has the same sign.  For a bearing, the reaction: the sign of its
    lossless value, the other for the couplings in ``reversed_forces``; a reaction whose
    lossless sign the geometry does not decide is given times its relative motion, whose
    product has the sign the analysis took.  ``swapped``:
    the derivation is the declared input's, read for the other input (only the meshes'
    own friction, so one solution serves both inputs).
    A mesh power whose sign the geometry and the losses' ranges decide as needed is left
    out: it cannot disagree."""
    analysis = derivation.analysis
    meshes = {r.coupling for r in roles if not r.idle}
    torque = analysis.ring.rational(analysis.input_action.symbol)
    out = {}
    for law in loaded_laws(analysis, roles):
        if law.coupling in meshes:
            power = mesh_power(derivation, roles, first, law)
            if swapped:
                # The solution has the declared input's power positive; the other input's
                # power is -F times it (F the declared formula): scaled so that it is positive.
                power = power * -derivation.form_with(roles, first)
            needed = 1 if first[law.coupling] else -1
            # Only the sign counts: the factors the geometry decides go (as for the
            # turning conditions, Laus eq. (86)), and denominators count as factors.
            sign, reduced = analysis.oracle.classify(*power.factor_list())
            if sign != needed:
                out[law.coupling] = (analysis.ring.rational(reduced), needed)
            continue
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
        if sign in (1, -1) and analysis.oracle.classify(*force.factor_list())[0] == sign * flip:
            continue  # the force provably points as needed: no condition
        if sign in (1, -1):
            out[law.coupling] = (force, int(sign) * flip)
        else:
            # The geometry decides the lossless sense (opposed thrusts); the analysis took
            # the Coulomb sign flip: reaction times relative motion must have it.
            out[law.coupling] = (force * analysis.motion_coefficients[law.motion], flip)
    return out


def mesh_power(
    derivation: Derivation, roles: Sequence[MeshRole], first: Mapping[str, bool], law: FrictionLaw
) -> RationalFunction:
    """The power the driving gear gives in the mesh whose own friction is ``law``, seen
    from the carrier, per unit input power, at the operating point: U (w_U + zeta w_T) .
    ^c$_driver over the input power,
    with the friction of every mesh in the directions ``first`` (Laus eqs. (69)-(73) with
    the action of D_A in place of the lossless one).  Positive where the power crosses
    from the first gear to the second; the lossless value is the mesh's flow ratio."""
    analysis = derivation.analysis
    mesh = law.coupling
    key = (mesh, tuple(sorted(first.items())))
    if key in derivation.solved:
        return derivation.solved[key]
    flow = derivation.flows[mesh]
    ring = analysis.ring
    torque = ring.rational(analysis.input_action.symbol)
    side = 0 if first[mesh] else 1
    a, b = analysis.action_solution[law.transmitted or ""]
    zeta = ring.rational(flow.friction_symbol)
    on_driver = flow.transmitted_power[side] + zeta * flow.friction_power[side]
    power = (a * torque + b) * on_driver / (torque * analysis.lossless_input_power())
    derivation.solved[key] = at_operating_point(substituted(power, roles, derivation.zetas, first), analysis)
    return derivation.solved[key]


def case_draws(points: Sequence[Point], efficiencies: Collection[sympy.Symbol], seed: int) -> Draws | None:
    """The sampled losses and input torques at ``points`` that `reached_cases` reads
    (``efficiencies``: the ordinary ones; None without points)."""
    return Draws(points, efficiencies, INPUT_TORQUE, seed, drawn=OPERATING_SYMBOLS) if points else None


def reached_cases(
    first: Mapping[str, bool],
    derive: Callable[[frozenset[str]], Derivation],
    roles: Sequence[MeshRole],
    draws: Draws | None,
    swapped: bool = False,
) -> list[LoadCase]:
    """The variant's lossless case, then every reversal the sampled losses and input
    torques ``draws`` (`case_draws`) reach (``derive``: the derivation with the named
    bearings' reactions reversed; ``swapped``: the declared input's derivation, read for
    the other input)."""
    bearings = {law.coupling for law in loaded_laws(derive(frozenset()).analysis, roles)} - {r.coupling for r in roles}
    out: list[LoadCase] = []
    queue: list[frozenset[str]] = [frozenset()]
    seen = set(queue)
    while queue and len(seen) <= CASE_LIMIT:
        reversal = queue.pop(0)
        derivation = derive(reversal & bearings)
        case_first = {m: f != (m in reversal) for m, f in first.items()}
        forces = loaded_forces(derivation, roles, case_first, reversal, swapped)
        efficiency = derivation.form_with(roles, case_first)
        # Swapping input and output inverts the efficiency (Laus eqs. (78)-(79)).
        efficiency = efficiency.inverse() if swapped else efficiency
        samples: tuple[Point, ...] = ()
        if draws is not None and forces:
            agree, finite, free = needed_signs(forces, draws)
            every = np.all(agree, axis=1) & finite
            if reversal:
                # A reversal the losses reach only where the train self-locks adds no formula:
                # there the lossless case's value already says it locks.
                working, _, _ = needed_signs({"efficiency": (efficiency, 1)}, draws)
                every &= working[:, 0]
            used = set(free) | efficiency.free_symbols
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


def bearings_agree(
    loaded_forces: Mapping[str, tuple[RationalFunction, int]], analysis: Analysis, values: Mapping[sympy.Symbol, object]
) -> bool:
    """Whether each bearing reaction of a variant (its ``loaded_forces``) has the sense the
    variant takes at ``values``: where the geometry reverses one (opposed helical thrusts)
    another variant holds, and the value there says nothing of self-locking."""
    for name, (force, needed) in loaded_forces.items():
        if as_bearing(analysis.train.coupling(name)) is None:
            continue
        try:
            if (force.evaluate(values) > 0) != (needed > 0):
                return False
        except ZeroDivisionError:
            continue
    return True
