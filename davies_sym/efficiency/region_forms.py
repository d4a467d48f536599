"""The closed forms of one power-flow region of a train driven on several shafts: the
action null space of D_A with the region's signs (Laus eq. (51)), each mesh's law in the
ordinary efficiency of its driving direction (eqs. (74)-(75)), each bearing's Coulomb
moment with the region's signs of its reaction and relative motion (eq. (21)), the
dependent sources (viscous, drag) on the right-hand side; then the port torques in the
load torque and Mantriota and Pennestri's efficiency (eq. (6))."""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.algebra.linalg import Row, gauss_jordan
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.mesh_friction import is_mesh_law
from davies_sym.efficiency.power_flow_regions import LOAD_TORQUE, Region
from davies_sym.efficiency.virtual_power import MeshPowerFlow
from davies_sym.errors import DerivationError
from davies_sym.network.analysis import Analysis
from davies_sym.network.friction_laws import CoulombLaw, FrictionLaw, ViscousLaw
from davies_sym.topology.coupling_kinds import as_toothed_mesh


@dataclass(frozen=True, eq=False)
class RegionContext:
    """What every region of one train shares."""

    analysis: Analysis
    #: Key ("port P", "mesh M", "turn C") -> (speed condition index, orientation).
    said: Mapping[str, tuple[int, int]]
    flows: Mapping[str, MeshPowerFlow]
    port_speeds: Mapping[str, RationalFunction]
    pairing: Mapping[str, int]
    #: Lossless action magnitudes per unit torque of the first input.
    lossless: Mapping[str, RationalFunction]


def is_loaded(law: FrictionLaw, meshes: Collection[str]) -> bool:
    """Whether a region assumes the sign of the force loading ``law``: a mesh's tooth force
    (it decides the driving gear) or a bearing's Coulomb reaction (the moment's sense)."""
    return is_mesh_law(law, meshes) or isinstance(law, CoulombLaw)


@dataclass(frozen=True, eq=False)
class _RegionSigns:
    """The signs one region assumes: those of the speed conditions (``vector``, read
    through the context's keys), the load's sense, the lossless actions' and the forces
    loading the friction laws (``reversed_forces``: those the losses reverse)."""

    context: RegionContext
    vector: tuple[int, ...]
    reversed_forces: frozenset[str]

    def of(self, key: str) -> int:
        """The region's sign of the speed condition ``key`` ("port P", "mesh M", "turn C")."""
        k, orientation = self.context.said[key]
        return self.vector[k] * orientation

    @property
    def load(self) -> int:
        """The load's sign: it resists the output's motion."""
        output = self.context.analysis.train.ports.output
        return -self.context.pairing[output] * self.of(f"port {output}")

    def lossless(self, action: str) -> int:
        """Sign of an action magnitude without losses (they all scale with the load)."""
        analysis = self.context.analysis
        output_action = analysis.network.port_action(analysis.train.ports.output).name
        return _sign(self.context.lossless[action] / self.context.lossless[output_action], analysis) * self.load

    def assumed(self, law: FrictionLaw) -> int:
        """The sign the region gives the force loading ``law``."""
        return self.lossless(law.transmitted or "") * (-1 if law.coupling in self.reversed_forces else 1)


def region_forms(
    context: RegionContext,
    number: int,
    signs: dict[str, int],
    vector: tuple[int, ...],
    reversed_forces: frozenset[str] = frozenset(),
) -> Region:
    """The closed forms of one region (Laus eq. (51) with the region's signs): the speed
    conditions' signs ``vector`` and the couplings whose loaded force is reversed."""
    analysis, flows, pairing = context.analysis, context.flows, context.pairing
    net, ring, ports = analysis.network, analysis.ring, analysis.train.ports
    region = _RegionSigns(context, vector, reversed_forces)
    load_sign = region.load
    # A reversed tooth force swaps the driving gear of its mesh.
    first = {m: (region.of(f"mesh {m}") * load_sign > 0) != (m in reversed_forces) for m in flows}
    index = {v.name: j for j, v in enumerate(net.actions)}
    const = len(net.actions)
    rows = analysis.rows(net.network_action_matrix())
    rows += [_law_row(context, region, first, law, index) for law in net.laws]
    rows = [{j: p for j, p in r.items() if not p.is_zero()} for r in rows]
    load = index[net.port_action(ports.output).name]
    elimination = gauss_jordan(rows, const + 1, prefer_free=[load, const], reduce=analysis.reduce)
    if sorted(elimination.free) != [load, const]:
        raise DerivationError("the actions are not determined by the load torque alone")
    solution = elimination.solution(ring)
    zero = RationalFunction.polynomial(ring, ring.zero)
    load_torque = ring.rational(load_sign * LOAD_TORQUE)

    def magnitude(action: str) -> RationalFunction:
        """An action magnitude in the load torque (and the input speeds, with sources)."""
        j = index[action]
        return solution[j].get(load, zero) * load_torque + solution[j].get(const, zero)

    torques = {p: magnitude(net.port_action(p).name) for p in ports.every}
    powers = {p: torques[p] * context.port_speeds[p] * ring.rational(pairing[p]) for p in ports.every}
    power_sign = {
        p: region.lossless(net.port_action(p).name) * region.of(f"port {p}") * pairing[p] for p in ports.every
    }
    inputs = tuple(p for p in ports.every if power_sign[p] > 0)
    outputs = tuple(p for p in ports.every if power_sign[p] < 0)
    # Mantriota and Pennestri eq. (6): the output's power over the sum of the driving
    # shafts' powers, each with its sign (a shaft that takes power lowers the sum).
    p_in = sum((powers[p] for p in ports.inputs), zero)
    forces = {
        law.coupling: (magnitude(law.transmitted or ""), region.assumed(law))
        for law in net.laws
        if is_loaded(law, flows)
    }
    return Region(
        number, signs, first, inputs, outputs, torques, -(powers[ports.output] / p_in), forces, reversed_forces
    )


def _law_row(
    context: RegionContext, region: _RegionSigns, first: Mapping[str, bool], law: FrictionLaw, index: Mapping[str, int]
) -> Row:
    """The constitutive row of ``law`` in the region (columns: ``index`` of the actions,
    then the constant): a mesh's in the ordinary efficiency of its driving direction
    (``first``: whether its first gear drives), a bearing's with the region's signs."""
    analysis = context.analysis
    ring, const = analysis.ring, len(analysis.network.actions)
    if is_mesh_law(law, context.flows):
        mesh = as_toothed_mesh(analysis.train.coupling(law.coupling))
        assert mesh is not None and mesh.efficiencies is not None
        eta = mesh.efficiencies[0] if first[law.coupling] else mesh.efficiencies[1]
        zeta = context.flows[law.coupling].friction_for(eta, first[law.coupling])
        # T - zeta U = 0 (signed law), over zeta's denominator.
        return {index[law.variable]: zeta.den, index[law.transmitted or ""]: -zeta.num}
    if law.load_dependent:
        # A bearing: T = -zeta |U| sign(t) (Laus eq. (21)) with the region's signs of the
        # reaction U and the relative motion t; a linear law is T = zeta U as written.
        transmitted = law.transmitted or ""
        factor = region.assumed(law) * region.of(f"turn {law.coupling}") if isinstance(law, CoulombLaw) else -1
        value = ring.rational(factor * law.coefficient)
        return {index[law.variable]: value.den, index[transmitted]: value.num}
    if isinstance(law, ViscousLaw):
        speed = analysis.motion_magnitudes[law.motion] * ring.rational(law.coefficient)
        return {index[law.variable]: speed.den, const: speed.num}  # T = -b t
    value = ring.rational(law.coefficient * region.of(f"turn {law.coupling}"))
    return {index[law.variable]: value.den, const: value.num}  # T = -D sign(t)


def _sign(value: RationalFunction, analysis: Analysis) -> int:
    sign, undecided = analysis.oracle.classify(*value.factor_list())
    if sign not in (1, -1):
        raise DerivationError(f"the sign of {sympy.sstr(undecided)} depends on the geometry")
    return int(sign)
