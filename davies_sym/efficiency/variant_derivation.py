"""The steps `davies_sym.efficiency.variants.derive_variants` takes, each a value or an
object of its own: the derivation of each input side (Laus eqs. (78)-(79): the other
input reverses every mesh), the sampled regions of the turning conditions, and the
variants of each side in the order they are numbered (Laus Tables 5 and 6), then those
the losses reach at light load."""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import partial

import sympy

from davies_sym.algebra.linear_regions import Requirement
from davies_sym.efficiency.empty_regions import emptiness_proof
from davies_sym.efficiency.light_load import Derivation, LoadCase, case_draws, reached_cases
from davies_sym.efficiency.mesh_reversals import MeshReversal, mesh_reversals, reached_points
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE, at_operating_point, zeta_forms
from davies_sym.efficiency.parameter_domain import ParameterDomain, Point
from davies_sym.efficiency.turning_conditions import MeshRole, TurningCondition
from davies_sym.efficiency.variant_checks import checked_variant
from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.efficiency.virtual_power import named_mesh_power_flow
from davies_sym.geometry.layout import Layout
from davies_sym.network.analysis import Analysis
from davies_sym.network.analysis_options import AnalysisOptions
from davies_sym.network.friction_laws import CoulombSigns
from davies_sym.progress import Progress
from davies_sym.topology.model import Train

#: (declared input, bearings whose reactions are reversed) -> its derivation.
SideKey = tuple[bool, frozenset[str]]
Proof = tuple[tuple[Requirement, ...], tuple[Requirement, ...]]


@dataclass(frozen=True)
class SideDerivations:
    """The derivation with the declared input or the other one, and the named bearings'
    reactions reversed, each solved once (``solved`` grows as they are asked for)."""

    declared: Analysis
    roles: tuple[MeshRole, ...]
    extra: tuple[sympy.Symbol, ...]
    layout: Layout | None
    progress: Progress | None
    solved: dict[SideKey, Derivation] = field(default_factory=dict)

    def derivation(self, declared_input: bool, bearings: frozenset[str]) -> Derivation:
        key = (declared_input, bearings)
        if key not in self.solved:
            self.solved[key] = self._solve(key)
        return self.solved[key]

    def _solve(self, key: SideKey) -> Derivation:
        side = self.declared
        if key != (True, frozenset()):
            train = self.declared.train
            side = Analysis(
                train.with_ports(train.ports if key[0] else train.ports.swapped()),
                AnalysisOptions(
                    coulomb_signs=CoulombSigns.MESH_LINEAR,
                    extra_symbols=list(self.extra),
                    layout=self.layout,
                    reversed_coulomb=key[1],
                ),
                self.progress,
            )
        flows = (
            {r.coupling: r.flow for r in self.roles}
            if side is self.declared
            else {r.coupling: named_mesh_power_flow(side, r.coupling) for r in self.roles}
        )
        return Derivation(side, at_operating_point(side.efficiency_rf, side), zeta_forms(flows, self.roles), flows)


def sampled_regions(
    domain: ParameterDomain, conditions: Sequence[TurningCondition], count: int, seed: int, extra: list[sympy.Symbol]
) -> dict[tuple[int, ...], list[Point]]:
    """Admissible design points drawn at random, by the signs of the turning conditions
    they give; each with an input torque and speed well above what the small drawn loss
    coefficients take."""
    points = domain.drawn_samples(count, seed, extra)
    operating = random.Random(seed)
    for point in points:
        point.update(
            {
                INPUT_TORQUE: sympy.Integer(operating.randint(50, 500)),
                INPUT_SPEED: sympy.Integer(operating.randint(1, 10)),
            }
        )
    regions: dict[tuple[int, ...], list[Point]] = {}
    expressions = [c.expression for c in conditions]
    for point in points:
        regions.setdefault(domain.signs_at(expressions, domain.args(point)), []).append(point)
    return regions


@dataclass(frozen=True)
class VariantContext:
    """What every variant of a train is derived from."""

    train: Train
    sides: SideDerivations
    conditions: tuple[TurningCondition, ...]
    combos: tuple[dict[str, int], ...]
    regions: Mapping[tuple[int, ...], list[Point]]
    domain: ParameterDomain
    facts: tuple[Requirement, ...]
    etas: tuple[sympy.Symbol, ...]
    #: Laws besides the meshes' own friction change with the input side.
    resolve_again: bool
    seed: int
    say: Progress


@dataclass
class VariantList:
    """The variants in the order they are numbered: each input side's, one per choice of
    turning-condition signs (a region proven empty is excluded, a side not asked for
    keeps its numbers taken), then the light-load variants the losses reach."""

    context: VariantContext
    variants: list[Variant] = field(default_factory=list)
    excluded: list[ExcludedVariant] = field(default_factory=list)
    skipped: int = 0
    light: list[tuple[str, str, dict[str, int], LoadCase]] = field(default_factory=list)
    proofs: dict[tuple[int, ...], Proof | None] = field(default_factory=dict)
    #: One stream for the checks, drawn in the order the variants are numbered.
    rng: random.Random = field(init=False)

    def __post_init__(self) -> None:
        self.rng = random.Random(self.context.seed)

    @property
    def next_number(self) -> int:
        return len(self.variants) + len(self.excluded) + self.skipped + 1

    def add_side(self, declared_input: bool, inputs: Sequence[str] | None) -> None:
        """Every variant with the declared input port, or with the other one."""
        ctx = self.context
        ports = ctx.train.ports
        port_in, port_out = (ports.input, ports.output) if declared_input else (ports.output, ports.input)
        if inputs is not None and port_in not in inputs:
            self.skipped += len(ctx.combos)  # their numbers stay taken: a variant keeps its number
            return
        for signs in ctx.combos:
            self._add(declared_input, port_in, port_out, signs)

    def _add(self, declared_input: bool, port_in: str, port_out: str, signs: dict[str, int]) -> None:
        ctx = self.context
        roles = ctx.sides.roles
        number, total = self.next_number, 2 * len(ctx.combos)
        first = {r.coupling: r.first_drives(signs, declared_input) for r in roles}
        key = tuple(signs[c.name] for c in ctx.conditions)
        region = ctx.regions.get(key, [])
        if not region:
            # No sample in the region: prove it empty before building anything there.
            if key not in self.proofs:
                self.proofs[key] = emptiness_proof(ctx.facts, ctx.conditions, signs)
            proof = self.proofs[key]
            if proof is not None:
                ctx.say(f"variant {number} of {total}: input {port_in}, no admissible geometry")
                self.excluded.append(ExcludedVariant(number, port_in, port_out, signs, first, *proof))
                return
        ctx.say(f"variant {number} of {total}: input {port_in}")
        if ctx.resolve_again:
            derive = partial(ctx.sides.derivation, declared_input)
            base, *reversals = reached_cases(first, derive, roles, case_draws(region, ctx.etas, ctx.seed))
        else:
            # Only the meshes' own friction: one solution serves both inputs.
            same = partial(_same, ctx.sides.derivation(True, frozenset()))
            draws = case_draws(region, ctx.etas, ctx.seed)
            base, *reversals = reached_cases(first, same, roles, draws, not declared_input)
        variant = Variant(
            number, port_in, port_out, signs, first, base.efficiency, bool(region), loaded_forces=base.forces
        )
        analysis = base.derivation.analysis
        self.variants.append(checked_variant(variant, region, ctx.etas, analysis, ctx.conditions, self.rng))
        self.light += [(port_in, port_out, signs, case) for case in reversals]

    def light_load(self) -> list[tuple[str, str, dict[str, int], LoadCase]]:
        """The reversals the losses reach that no variant of a region assumes already."""
        roles = self.context.sides.roles
        return [item for item in self.light if not _assumed_elsewhere(item[3], item[0], self.variants, roles)]

    def add_light_load(self, light: Sequence[tuple[str, str, dict[str, int], LoadCase]]) -> None:
        """The variants of the ``light`` reversals, numbered after the regions'."""
        ctx = self.context
        for port_in, port_out, signs, case in light:
            number = self.next_number
            ctx.say(f"variant {number}: input {port_in}, the losses reverse {', '.join(sorted(case.reversed))}")
            variant = Variant(
                number,
                port_in,
                port_out,
                signs,
                case.first_drives,
                case.efficiency,
                True,
                reversed_forces=case.reversed,
                loaded_forces=case.forces,
            )
            analysis = case.derivation.analysis
            self.variants.append(checked_variant(variant, case.samples, ctx.etas, analysis, ctx.conditions, self.rng))

    def reversed_meshes(self) -> list[tuple[str, str, MeshReversal]]:
        """The cases where the losses turn a mesh's power round against its lossless
        direction (`davies_sym.efficiency.mesh_reversals`): for each region's variant, the
        other regions' variants of its input whose forces agree at some sampled point of
        its region."""
        ctx = self.context
        meshes = [r.coupling for r in ctx.sides.roles]
        plain = [v for v in self.variants if not v.reversed_forces]
        out = []
        for base in plain:
            key = tuple(base.signs[c.name] for c in ctx.conditions)
            others = [v for v in plain if v.input == base.input and dict(v.signs) != dict(base.signs)]
            if not others or not ctx.regions.get(key):
                continue
            groups = list(reached_points(ctx.domain, ctx.conditions, ctx.regions, key))
            for case in mesh_reversals(base, others, groups, meshes, ctx.etas, ctx.seed):
                out.append((base.input, base.output, case))
        return out

    def add_reversed_meshes(self, cases: Sequence[tuple[str, str, MeshReversal]]) -> None:
        """The variants of the mesh reversals ``cases``, numbered after the others: the
        formula and driving gears of the variant they are like, the signs of their own
        region, the reversed meshes named."""
        ctx = self.context
        analysis = ctx.sides.derivation(True, frozenset()).analysis
        for port_in, port_out, case in cases:
            number = self.next_number
            ctx.say(f"variant {number}: input {port_in}, the losses reverse {', '.join(sorted(case.reversed))}")
            like = case.like
            variant = Variant(
                number,
                port_in,
                port_out,
                dict(case.signs),
                like.first_drives,
                like.efficiency_rf,
                True,
                reversed_forces=case.reversed,
                loaded_forces=like.loaded_forces,
            )
            self.variants.append(checked_variant(variant, case.samples, ctx.etas, analysis, ctx.conditions, self.rng))


def _same(derivation: Derivation, bearings: frozenset[str]) -> Derivation:
    """``derivation`` whatever bearings are named (a train without bearing friction)."""
    return derivation


def _assumed_elsewhere(case: LoadCase, port: str, variants: Sequence[Variant], roles: Sequence[MeshRole]) -> bool:
    """Whether ``case`` only reverses meshes into the driving gears of another region's
    variant: that variant, with the same forces, holds where the case would."""
    meshes = {r.coupling for r in roles}
    return case.reversed <= meshes and any(
        v.input == port and not v.reversed_forces and dict(v.first_drives) == dict(case.first_drives) for v in variants
    )
