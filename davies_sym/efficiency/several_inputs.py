"""Trains driven on several shafts (degrees of freedom > 1): a differential with two
inputs and one loaded output (Mantriota and Pennestri 2003).

The motions are the null space of M_N with the input speeds as primary variables (Laus
eq. (1) for any mobility): every speed, the output's included, is a linear form in them.
The actions are the null space of D_A with the load torque as primary variable; each
mesh takes the signed law T = zeta U (Laus eqs. (63)-(64)) and dependent sources
(viscous, constant drag, eq. (51)) enter the right-hand side.

Which gear drives in a mesh, which way a coupling with drag or bearing friction turns
and which ports put power in are, without losses, signs of linear forms in the input
speeds: each is a *speed condition*, a line through the origin of the plane of input
speeds.  A *region* (`davies_sym.efficiency.power_flow_regions`) is one choice of
all signs that admissible designs reach, and of the loaded forces that losses larger
than the load reverse; in it zeta is replaced by the ordinary efficiency of the driving
direction (eqs. (74)-(75)) and the efficiency is Mantriota and Pennestri's eq. (6), the
output's power over the sum of the input shafts' powers, in closed form
(`davies_sym.efficiency.region_forms`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cached_property
from itertools import combinations

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.mesh_friction import check_mesh_friction, only_mesh_laws
from davies_sym.efficiency.parameter_domain import efficiency_symbols
from davies_sym.efficiency.power_flow_regions import LOAD_TORQUE, Region, SeveralInputs, SpeedCondition, speed_symbol
from davies_sym.efficiency.region_forms import RegionContext, is_loaded, region_forms
from davies_sym.efficiency.region_sampling import Point, holds_somewhere, reached_signs
from davies_sym.efficiency.virtual_power import MeshPowerFlow, mesh_power_flow
from davies_sym.errors import DerivationError, MobilityError, Problem
from davies_sym.geometry.dependent import resolved_train
from davies_sym.network.analysis import Analysis
from davies_sym.network.analysis_options import AnalysisOptions
from davies_sym.network.friction_laws import CoulombLaw, CoulombSigns, DragLaw
from davies_sym.progress import Progress
from davies_sym.topology.coupling_kinds import as_toothed_mesh
from davies_sym.topology.model import Train

__all__ = ["LOAD_TORQUE", "Region", "SeveralInputs", "SpeedCondition", "derive_several_inputs", "speed_symbol"]


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
            raise MobilityError(
                [
                    Problem(
                        "ports.input",
                        f"the train has {len(free)} degrees of freedom but {len(inputs)} input ports drive "
                        "it"
                        + (f" (also free: {', '.join(extra)})" if extra else "; an input port cannot turn on its own"),
                    )
                ],
                self.train.file_lines,
            )
        speeds = {name: RationalFunction.polynomial(self.ring, self.ring.gen(s)) for name, s in inputs.items()}
        zero = RationalFunction.polynomial(self.ring, self.ring.zero)
        return {name: sum((c * speeds[j] for j, c in combo.items()), zero) for name, combo in combinations.items()}


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
        raise DerivationError(
            f"the sign of {sympy.sstr(undecided)} decides a power direction and depends on "
            "the geometry; give the geometry as numbers"
        )
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


def derive_several_inputs(
    train: Train, progress: Progress | None = None, samples: int = 40, seed: int = 0
) -> SeveralInputs:
    """Every power-flow region of ``train`` (several input ports) with its closed forms."""
    say = progress or (lambda message: None)
    check_mesh_friction(train)
    train = resolved_train(train)
    ports = train.ports
    speeds = tuple(speed_symbol(p) for p in ports.inputs)
    moving = frozenset(speeds)
    etas = efficiency_symbols(train)
    _check_speed_names(train, speeds)
    options = AnalysisOptions(coulomb_signs=CoulombSigns.MESH_LINEAR, extra_symbols=[*etas, *speeds, LOAD_TORQUE])
    analysis = _SeveralInputAnalysis(train, options, progress)
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
    flows = _law_conditions(analysis, moving, conditions, said)
    names = [f"s{k + 1}" for k in range(len(conditions.forms))]
    found = reached_signs(train, analysis, conditions.forms, speeds, samples, seed)
    context = RegionContext(analysis, said, flows, port_speeds, pairing, analysis.lossless_action_coefficients)
    regions = _regions(context, found, names, etas, seed, say)
    conds = tuple(
        SpeedCondition(n, f, tuple(d)) for n, f, d in zip(names, conditions.forms, conditions.decides, strict=True)
    )
    return SeveralInputs(train, analysis, speeds, port_speeds, conds, tuple(regions), pairing)


def _check_speed_names(train: Train, speeds: tuple[sympy.Symbol, ...]) -> None:
    """Refuse a train whose own symbols take the names of the input speeds or the load torque."""
    clash = sorted(str(s) for s in (*speeds, LOAD_TORQUE) if str(s) in train.symbols)
    if clash:
        raise MobilityError(
            [
                Problem(
                    "", f"{', '.join(clash)} name the input speeds and the load torque; rename the symbol in the file"
                )
            ],
            train.file_lines,
        )


def _law_conditions(
    analysis: Analysis, moving: frozenset[sympy.Symbol], conditions: _Conditions, said: dict[str, tuple[int, int]]
) -> dict[str, MeshPowerFlow]:
    """The speed conditions the friction laws add to ``conditions`` (each entered in
    ``said``): which gear drives in each loaded mesh, which way each coupling with a drag
    or a bearing's Coulomb friction turns; the meshes' virtual power flows."""
    net, train = analysis.network, analysis.train
    motion = analysis.motion_magnitudes
    lossless = analysis.lossless_action_coefficients  # per unit torque of the first input
    load_action = net.port_action(train.ports.output).name
    flows: dict[str, MeshPowerFlow] = {}
    for law in net.laws:
        mesh = as_toothed_mesh(train.coupling(law.coupling))
        if mesh is not None and law.load_dependent:
            flows[mesh.name] = flow = mesh_power_flow(analysis, mesh)
            # Lossless tooth force per unit load torque times its power on the first gear's side
            # in the carrier frame (a linear form in the input speeds).
            force = lossless[law.transmitted or ""] / lossless[load_action]
            sign, form = _primitive(force * flow.transmitted_power[0], analysis, moving)
            k, orientation = conditions.add(form, f"mesh {mesh.name}: which gear drives")
            said[f"mesh {mesh.name}"] = (k, sign * orientation)
        elif isinstance(law, (DragLaw, CoulombLaw)) and f"turn {law.coupling}" not in said:
            # A constant drag and a bearing's Coulomb friction oppose the relative motion.
            sign, form = _primitive(motion[law.motion], analysis, moving)
            k, orientation = conditions.add(form, f"coupling {law.coupling} turns forwards")
            said[f"turn {law.coupling}"] = (k, sign * orientation)
    return flows


def _regions(
    context: RegionContext,
    found: Mapping[tuple[int, ...], list[Point]],
    names: list[str],
    etas: Sequence[sympy.Symbol],
    seed: int,
    say: Progress,
) -> list[Region]:
    """The regions of each speed sector ``found`` reached (with its sampled points): the
    lossless one, then each with reversed loaded forces that holds at one of the points."""
    net, flows = context.analysis.network, context.flows
    loaded = [law.coupling for law in net.laws if is_loaded(law, flows)]
    # Only losses that do not scale with the tooth forces (drag, viscous, bearing friction)
    # can reverse a loaded force.
    reversible = [] if only_mesh_laws(net.laws, flows) else loaded
    reversals = [frozenset(c) for size in range(1, len(reversible) + 1) for c in combinations(reversible, size)]
    regions: list[Region] = []
    for k, (signs, points) in enumerate(found.items()):
        say(f"power-flow regions of speed sector {k + 1} of {len(found)}")
        named = dict(zip(names, signs, strict=True))
        regions.append(region_forms(context, len(regions) + 1, named, signs))
        for reversal in reversals:
            candidate = region_forms(context, len(regions) + 1, named, signs, reversal)
            if holds_somewhere(candidate, points, etas, seed=seed + len(regions)):
                regions.append(candidate)
    return regions
