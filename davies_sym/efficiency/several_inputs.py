"""Trains driven on several shafts (degrees of freedom > 1): a differential with two
inputs and one loaded output (Mantriota and Pennestri 2003).

The motions are the null space of M_N with the input speeds as primary variables (Laus
eq. (1) for any mobility): every speed, the output's included, is a linear form in them.
The actions are the null space of D_A with the load torque as primary variable; each
mesh takes the signed law T = zeta U (Laus eqs. (63)-(64)) and dependent sources
(viscous, constant drag, eq. (51)) enter the right-hand side.

Which gear drives in a mesh, which way a dragging coupling turns and which ports put
power in are signs of linear forms in the input speeds: each is a *speed condition*, a
line through the origin of the plane of input speeds.  A *region* is one choice of all
signs that admissible designs reach; in it every sign is known, zeta is replaced by the
ordinary efficiency of the driving direction (eqs. (74)-(75)) and the efficiency is
Mantriota and Pennestri's eq. (6), the output's power over the sum of the input shafts'
powers, in closed form; the region also says which ports put power in and which take it
out (a shaft driven backwards by the others takes power, and lowers that sum).
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from itertools import pairwise

import sympy

from davies_sym.algebra.linalg import gauss_jordan
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.parameter_domain import ParameterDomain, efficiency_symbols
from davies_sym.efficiency.virtual_power import MeshPowerFlow, mesh_power_flow
from davies_sym.errors import DerivationError, MobilityError, Problem
from davies_sym.geometry.dependent import resolved_train
from davies_sym.network.analysis import Analysis
from davies_sym.topology.couplings import GearMesh
from davies_sym.topology.model import Train

Progress = Callable[[str], None]

#: The magnitude of the torque the load puts on the output (it resists the output's motion).
LOAD_TORQUE = sympy.Symbol("tau_out", positive=True)


def speed_symbol(port: str) -> sympy.Symbol:
    """The speed of an input port (signed, along the coupling's positive direction); no
    coupling's magnitude is named so (those are t_<coupling>, w_<coupling>, ...)."""
    return sympy.Symbol(f"omega_{port}", real=True)


@dataclass(frozen=True)
class SpeedCondition:
    """The sign of a linear form in the input speeds: ``form`` > 0 or < 0."""

    name: str
    form: sympy.Expr
    #: What the sign decides (an input's direction, a mesh's driver, a dragging coupling).
    decides: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class Region:
    """One power-flow region of the plane of input speeds and its closed forms."""

    number: int
    signs: Mapping[str, int]
    #: Mesh -> True when its first gear drives.
    first_drives: Mapping[str, bool]
    #: Ports that put power in and ports that take it out (lossless power directions).
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    #: Torque the outside applies at each port, in the load torque and the input speeds.
    torques: Mapping[str, RationalFunction] = field(repr=False)
    efficiency_rf: RationalFunction = field(repr=False)
    #: The tooth force of each mesh and the reaction loading each bearing's Coulomb law,
    #: with the sign the region assumes for it: where losses larger than the load reverse
    #: one, the region's formulas do not hold.
    loaded_forces: Mapping[str, tuple[RationalFunction, int]] = field(default_factory=dict, repr=False)

    @property
    def efficiency(self) -> sympy.Expr:
        return self.efficiency_rf.to_expr()


class _SeveralInputAnalysis(Analysis):
    """Davies' method with the input speeds as primary motions: the motion magnitudes are
    linear forms in them (the base class keeps only the first input's share)."""

    @cached_property
    def motion_magnitudes(self) -> dict[str, RationalFunction]:
        net = self.network
        inputs = {net.coupling_motions(p)[0].name: speed_symbol(p) for p in self.train.ports.inputs}
        combinations = self.motions_in(list(inputs))
        free = {name for combo in combinations.values() for name in combo}
        if free != set(inputs):
            extra = sorted(free - set(inputs))
            raise MobilityError([self.train.problem(
                "ports.input", f"the train has {len(free)} degrees of freedom but {len(inputs)} input ports drive "
                "it" + (f" (also free: {', '.join(extra)})" if extra else "; an input port cannot turn on its own"))],
                self.train.path)
        speeds = {name: RationalFunction.polynomial(self.ring, self.ring.gen(s)) for name, s in inputs.items()}
        zero = RationalFunction.polynomial(self.ring, self.ring.zero)
        return {name: sum((c * speeds[j] for j, c in combo.items()), zero) for name, combo in combinations.items()}


@dataclass(frozen=True, eq=False)
class SeveralInputs:
    """Every power-flow region of a train driven on several shafts."""

    train: Train
    analysis: Analysis = field(repr=False)
    speeds: tuple[sympy.Symbol, ...]
    #: Speed of every port (the output's included) in the input speeds.
    port_speeds: Mapping[str, RationalFunction] = field(repr=False)
    conditions: tuple[SpeedCondition, ...]
    regions: tuple[Region, ...]
    #: +1 where a port's torque and speed of one sign put power in.
    pairing: Mapping[str, int] = field(default_factory=dict)

    def region_at(self, values: Mapping[sympy.Symbol, sympy.Expr]) -> Region:
        """The region whose speed conditions hold at ``values`` (an input speed set)."""
        signs = {}
        for c in self.conditions:
            value = sympy.sympify(c.form.subs(values))
            if not value.is_number:
                missing = ", ".join(sorted(map(str, value.free_symbols)))
                raise DerivationError(f"condition {c.name} needs values for {missing}")
            if value == 0:
                raise DerivationError(f"the speeds lie on the boundary {c.name}: {sympy.sstr(c.form)} = 0 "
                                      f"({', '.join(c.decides)})")
            signs[c.name] = 1 if value > 0 else -1
        for r in self.regions:
            if dict(r.signs) == signs:
                return r
        raise DerivationError(f"no region has the signs {signs}: no admissible design reaches them")


def _primitive(form: RationalFunction, analysis: Analysis, speeds: frozenset[sympy.Symbol]) -> tuple[int, sympy.Expr]:
    """A linear form in the input ``speeds`` as (sign of its geometric factors, the factor
    in the speeds)."""
    content, factors = form.factor_list()
    moving = [(f, e) for f, e in factors if f.free_symbols & speeds]
    fixed = [(f, e) for f, e in factors if not f.free_symbols & speeds]
    if len(moving) != 1 or moving[0][1] != 1:
        raise DerivationError(f"expected a speed in the input speeds, got {sympy.sstr(form.to_expr())}")
    sign, undecided = analysis.oracle.classify(content, fixed)
    if sign not in (1, -1):
        raise DerivationError(f"the sign of {sympy.sstr(undecided)} decides a power direction and depends on "
                              "the geometry; give the geometry as numbers")
    return int(sign), sympy.expand(moving[0][0])


class _Conditions:
    """Collects speed conditions, one per line through the origin."""

    def __init__(self) -> None:
        self.forms: list[sympy.Expr] = []
        self.decides: list[list[str]] = []

    def add(self, form: sympy.Expr, what: str) -> tuple[int, int]:
        """(index of the condition, +1 or -1: the sign relating ``form`` to it)."""
        for k, known in enumerate(self.forms):
            ratio = sympy.cancel(form / known)
            if ratio.is_number:
                self.decides[k].append(what)
                return k, 1 if ratio > 0 else -1
        self.forms.append(form)
        self.decides.append([what])
        return len(self.forms) - 1, 1


def derive_several_inputs(train: Train, progress: Progress | None = None, samples: int = 40,
                          seed: int = 0) -> SeveralInputs:
    """Every power-flow region of ``train`` (several input ports) with its closed forms."""
    say = progress or (lambda message: None)
    train = resolved_train(train)
    ports = train.ports
    speeds = tuple(speed_symbol(p) for p in ports.inputs)
    moving = frozenset(speeds)
    etas = efficiency_symbols(train)
    clash = sorted(str(s) for s in (*speeds, LOAD_TORQUE) if str(s) in train.symbols)
    if clash:
        raise MobilityError([Problem("", f"{', '.join(clash)} name the input speeds and the load torque; rename "
                                     "the symbol in the file")], train.path)
    analysis = _SeveralInputAnalysis(train, coulomb_signs="mesh-linear", progress=progress,
                                     extra_symbols=[*etas, *speeds, LOAD_TORQUE])
    net = analysis.network
    say("speeds in the input speeds (null space of M_N)")
    motion = analysis.motion_magnitudes
    port_speeds = {p: motion[net.coupling_motions(p)[0].name] for p in ports.every}
    pairing = {p: analysis.port_power_sign(p) for p in ports.every}
    conditions = _Conditions()
    said: dict[str, tuple[int, int]] = {}
    for p in ports.every:
        sign, form = _primitive(port_speeds[p], analysis, moving)
        k, orientation = conditions.add(form, f"port {p} turns forwards")
        said[f"port {p}"] = (k, sign * orientation)
    say("virtual power through the meshes")
    lossless = analysis.lossless_action_coefficients  # per unit torque of the first input
    load_action = net.port_action(ports.output).name
    flows: dict[str, MeshPowerFlow] = {}
    for law in net.laws:
        mesh = train.coupling(law.coupling)
        if isinstance(mesh, GearMesh) and law.law in ("coulomb", "linear"):
            flows[mesh.name] = flow = mesh_power_flow(analysis, mesh)
            # Lossless tooth force per unit load torque times its power on the first gear's side
            # in the carrier frame (a linear form in the input speeds).
            force = lossless[law.transmitted or ""] / lossless[load_action]
            sign, form = _primitive(force * flow.transmitted_power[0], analysis, moving)
            k, orientation = conditions.add(form, f"mesh {mesh.name}: which gear drives")
            said[f"mesh {mesh.name}"] = (k, sign * orientation)
        elif law.law in ("drag", "coulomb") and f"turn {law.coupling}" not in said:
            # A constant drag and a bearing's Coulomb friction oppose the relative motion.
            sign, form = _primitive(motion[law.motion], analysis, moving)
            k, orientation = conditions.add(form, f"coupling {law.coupling} turns forwards")
            said[f"turn {law.coupling}"] = (k, sign * orientation)
    names = [f"s{k + 1}" for k in range(len(conditions.forms))]
    found = _reached_signs(train, analysis, conditions.forms, speeds, samples, seed)
    regions: list[Region] = []
    for signs in found:
        say(f"region {len(regions) + 1} of {len(found)}")
        regions.append(_region(len(regions) + 1, dict(zip(names, signs, strict=True)), signs, said, analysis,
                               flows, port_speeds, pairing, lossless))
    conds = tuple(SpeedCondition(n, f, tuple(d)) for n, f, d in zip(names, conditions.forms, conditions.decides,
                                                                       strict=True))
    return SeveralInputs(train, analysis, speeds, port_speeds, conds, tuple(regions), pairing)


def _reached_signs(train: Train, analysis: Analysis, forms: list[sympy.Expr], speeds: tuple[sympy.Symbol, ...],
                   samples: int, seed: int) -> list[tuple[int, ...]]:
    """Sign vectors of the conditions that admissible designs reach: for each sampled
    geometry, one direction of input speeds inside every sector between condition lines
    (two inputs), or random directions (more)."""
    domain = ParameterDomain.of(train, analysis.network.layout)
    rng = random.Random(seed)
    out: set[tuple[int, ...]] = set()
    for point in domain.samples(samples, seed=seed):
        fixed = [sympy.expand(f.subs(point)) for f in forms]
        directions: list[tuple[Fraction, ...]] = []
        if len(speeds) == 2:
            angles = sorted({math.atan2(-float(f.coeff(speeds[0])), float(f.coeff(speeds[1]))) % math.pi + k * math.pi
                             for f in fixed for k in (0, 1)})
            angles.append(angles[0] + 2 * math.pi)
            for a, b in pairwise(angles):
                middle = (a + b) / 2
                directions.append((Fraction(math.cos(middle)), Fraction(math.sin(middle))))
        else:
            directions = [tuple(Fraction(rng.uniform(-1, 1)) for _ in speeds) for _ in range(200)]
        for d in directions:
            values = dict(zip(speeds, (sympy.Rational(x.numerator, x.denominator) for x in d), strict=True))
            signs = [sympy.sign(f.subs(values)) for f in fixed]
            if all(s != 0 for s in signs):
                out.add(tuple(int(s) for s in signs))
    return sorted(out, reverse=True)


def _region(number: int, signs: dict[str, int], vector: tuple[int, ...], said: Mapping[str, tuple[int, int]],
            analysis: Analysis, flows: Mapping[str, MeshPowerFlow], port_speeds: Mapping[str, RationalFunction],
            pairing: Mapping[str, int], lossless: Mapping[str, RationalFunction]) -> Region:
    """The closed forms of one region (Laus eq. (51) with the region's signs)."""
    train, net, ring = analysis.train, analysis.network, analysis.ring
    ports = train.ports

    def sign_of(key: str) -> int:
        k, orientation = said[key]
        return vector[k] * orientation

    output_turns = sign_of(f"port {ports.output}")
    load_sign = -pairing[ports.output] * output_turns  # the load resists the output's motion
    first = {m: sign_of(f"mesh {m}") * load_sign > 0 for m in flows}
    names = [v.name for v in net.actions]
    index = {n: j for j, n in enumerate(names)}
    const = len(names)
    rows = analysis.rows(net.network_action_matrix())
    output_action = net.port_action(ports.output).name

    def lossless_sign(action: str) -> int:
        """Sign of an action magnitude without losses (they all scale with the load)."""
        return _sign(lossless[action] / lossless[output_action], analysis) * load_sign

    for law in net.laws:
        if law.coupling in flows:
            mesh = train.coupling(law.coupling)
            assert isinstance(mesh, GearMesh) and mesh.efficiencies is not None
            eta = mesh.efficiencies[0] if first[law.coupling] else mesh.efficiencies[1]
            zeta = flows[law.coupling].friction_for(eta, first[law.coupling])
            # T - zeta U = 0 (signed law), over zeta's denominator.
            rows.append({index[law.variable]: zeta.den, index[law.transmitted or ""]: -zeta.num})
        elif law.law in ("coulomb", "linear"):
            # A bearing: T = -zeta |U| sign(t) (Laus eq. (21)) with the region's signs of the
            # reaction U and the relative motion t; a linear law is T = zeta U as written.
            transmitted = law.transmitted or ""
            factor = (lossless_sign(transmitted) * sign_of(f"turn {law.coupling}") if law.law == "coulomb"
                      else -1)
            value = ring.rational(factor * law.coefficient)
            rows.append({index[law.variable]: value.den, index[transmitted]: value.num})
        elif law.law == "viscous":
            speed = analysis.motion_magnitudes[law.motion] * ring.rational(law.coefficient)
            rows.append({index[law.variable]: speed.den, const: speed.num})  # T = -b t
        else:
            value = ring.rational(law.coefficient * sign_of(f"turn {law.coupling}"))
            rows.append({index[law.variable]: value.den, const: value.num})  # T = -D sign(t)
    rows = [{j: p for j, p in r.items() if not p.is_zero()} for r in rows]
    load = index[net.port_action(ports.output).name]
    elimination = gauss_jordan(rows, const + 1, prefer_free=[load, const], reduce=analysis.reduce)
    if sorted(elimination.free) != [load, const]:
        raise DerivationError("the actions are not determined by the load torque alone")
    solution = elimination.solution(ring)
    zero = RationalFunction.polynomial(ring, ring.zero)
    load_torque = ring.rational(load_sign * LOAD_TORQUE)
    torques = {}
    for p in ports.every:
        j = index[net.port_action(p).name]
        torques[p] = solution[j].get(load, zero) * load_torque + solution[j].get(const, zero)
    powers = {p: torques[p] * port_speeds[p] * ring.rational(pairing[p]) for p in ports.every}
    power_sign = {p: lossless_sign(net.port_action(p).name) * sign_of(f"port {p}") * pairing[p] for p in ports.every}
    inputs = tuple(p for p in ports.every if power_sign[p] > 0)
    outputs = tuple(p for p in ports.every if power_sign[p] < 0)
    # Mantriota and Pennestri eq. (6): the output's power over the sum of the driving
    # shafts' powers, each with its sign (a shaft that takes power lowers the sum).
    p_in = sum((powers[p] for p in ports.inputs), zero)
    forces = {}
    for law in net.laws:
        if law.coupling in flows or law.law == "coulomb":
            j = index[law.transmitted or ""]
            force = solution[j].get(load, zero) * load_torque + solution[j].get(const, zero)
            forces[law.coupling] = (force, lossless_sign(law.transmitted or ""))
    return Region(number, signs, first, inputs, outputs, torques, -(powers[ports.output] / p_in), forces)


def _sign(value: RationalFunction, analysis: Analysis) -> int:
    sign, undecided = analysis.oracle.classify(*value.factor_list())
    if sign not in (1, -1):
        raise DerivationError(f"the sign of {sympy.sstr(undecided)} depends on the geometry")
    return int(sign)
