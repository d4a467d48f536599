"""The overall efficiency in ordinary mesh efficiencies, in every variant (Laus
sections 3.4.1.5 and 3.5.1.1, Tables 5 and 6).

One derivation gives the efficiency F(zeta) = -P_out / P_in with every mesh on the
signed law T = zeta U (eqs. (63)-(64), (71)).  For each mesh and each power direction
zeta is the solution of the ordinary-efficiency equation (eqs. (74)-(75), (92)-(94));
substituting it gives the variant's formula, put over factored numerator and
denominator (eq. (76)).  A variant is a choice of input port and a sign of every
turning condition; swapping input and output reverses every mesh and inverts the
efficiency (eqs. (78)-(79)).  The losses can turn a small mesh power round near a
turning condition, or any loaded force at light load: every variant carries the signs
its mesh powers and bearing reactions need, and holds where they agree
(`davies_sym.efficiency.variant_choice`).  Each variant is checked by the partial-derivative rule
(section 3.6.2) at a sampled point of its region; regions no sampled geometry reaches
are reported as infeasible, and sampled points where the efficiency is not positive
as self-locking.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.linear_regions import Requirement
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.algebra.radicals import restore
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.design_point import (
    DesignPoint,
    check_constraints,
    check_moving,
    check_working,
    turning_ratio,
)
from davies_sym.efficiency.design_values import design_values
from davies_sym.efficiency.empty_regions import check_facts, geometry_facts
from davies_sym.efficiency.light_load import Derivation
from davies_sym.efficiency.mesh_friction import check_mesh_friction, only_mesh_laws
from davies_sym.efficiency.operating_point import (
    INPUT_TORQUE,
    OPERATING_SYMBOLS,
)
from davies_sym.efficiency.parameter_domain import ParameterDomain, efficiency_symbols
from davies_sym.efficiency.parameter_ranges import OPERATING_PARAMETERS, Parameter, parameters_of_train, range_problem
from davies_sym.efficiency.turning_conditions import MeshRole, TurningCondition, condition_signs, mesh_roles
from davies_sym.efficiency.variant_choice import holding_variant
from davies_sym.efficiency.variant_derivation import SideDerivations, VariantContext, VariantList, sampled_regions
from davies_sym.efficiency.variant_display import variant_latex, variant_set_html
from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.errors import DesignError, InputError, MissingValuesError, Problem, shortened
from davies_sym.geometry.dependent import resolved_train, with_dependent
from davies_sym.geometry.layout import Layout
from davies_sym.losses.definitions import completed, parameters_of
from davies_sym.network.analysis import Analysis
from davies_sym.network.analysis_options import AnalysisOptions
from davies_sym.network.friction_laws import CoulombSigns
from davies_sym.network.motion_singularities import vanishing_denominators
from davies_sym.progress import Progress
from davies_sym.topology.model import State, Train
from davies_sym.topology.states import train_to_derive


@dataclass(frozen=True, eq=False)
class VariantSet:
    """Every variant of one train, its turning conditions and mesh roles."""

    train: Train
    analysis: Analysis = field(repr=False)
    roles: tuple[MeshRole, ...]
    conditions: tuple[TurningCondition, ...]
    variants: tuple[Variant, ...]
    #: The efficiency with the signed friction law, declared input (eq. (71)).
    friction_form: RationalFunction = field(repr=False)
    #: The derivation behind the variants of each input (True: the declared one) with the
    #: reactions of the named bearings reversed; the declared input's without reversal
    #: always, the other input's when friction laws besides the meshes' make it differ.
    derivations: Mapping[tuple[bool, frozenset[str]], Derivation] = field(default_factory=dict, repr=False)
    #: The combinations no admissible geometry reaches, proved so and not derived.
    excluded: tuple[ExcludedVariant, ...] = ()
    #: What every admissible design satisfies (`geometry_facts`): the proofs' facts, and
    #: what evaluated values are checked against.
    facts: tuple[Requirement, ...] = field(default=(), repr=False)

    @property
    def listed(self) -> list[Variant | ExcludedVariant]:
        """Every variant and every excluded combination, by number (the table's order)."""
        return sorted([*self.variants, *self.excluded], key=lambda v: v.number)

    def __repr__(self) -> str:
        """One line per variant (the whole record, with its exact algebra, is no read)."""
        lines = [f"<VariantSet of {self.train.name!r}: {len(self.variants)} variant(s)"]
        lines += [f"  {v!r}" for v in self.variants]
        return "\n".join(lines) + ">"

    def _repr_latex_(self) -> str:
        """Every variant's formula and where it holds, for a notebook."""
        return "\n".join(variant_latex(self.conditions, v) for v in self.variants)

    def _repr_html_(self) -> str:
        return variant_set_html(self.train.name, self.conditions, self.variants)

    @property
    def swapped(self) -> Analysis | None:
        """The derivation with input and output swapped, when friction laws other than the
        meshes' make it differ from the declared one (None otherwise)."""
        other = self.derivations.get((False, frozenset()))
        return None if other is None else other.analysis

    def derivation_of(self, variant: Variant) -> Derivation:
        """The derivation ``variant``'s formula and forces come from (the declared one for
        the other input when only the meshes' friction is present)."""
        declared = variant.input == self.train.ports.input
        bearings = variant.reversed_forces - {r.coupling for r in self.roles}
        return self.derivations.get((declared, bearings), self.derivations[(True, frozenset())])

    @property
    def symbols(self) -> list[sympy.Symbol]:
        """Every symbol a formula or a condition may need, sorted by name."""
        out: set[sympy.Symbol] = set()
        for v in self.variants:
            out |= v.efficiency.free_symbols
        for c in self.conditions:
            out |= c.expression.free_symbols
        return sorted_symbols(out)

    def _completed(self, values: Mapping[sympy.Symbol | str, object]) -> dict[sympy.Symbol, sympy.Expr]:
        """``values`` keyed by symbol, checked against the geometric constraints, with the
        defined symbols (e.g. a mesh efficiency from the tooth geometry) added; values
        outside the admissible geometry (a sun larger than its ring) are refused."""
        given = with_dependent(self.train, design_values(self.train, values))
        check_facts(self.facts, given, self.train.path)
        return completed(given, self.train.definitions)

    def variant_for(self, values: Mapping[sympy.Symbol | str, object], input: str | None = None) -> Variant:
        """The variant whose conditions hold at ``values`` (keyed by symbol or name) with
        ``input`` as input port."""
        return self._variant_at(self._completed(values), input)

    def _variant_at(self, values: Mapping[sympy.Symbol, sympy.Expr], input: str | None) -> Variant:
        port = input or self.train.ports.input
        if port not in (self.train.ports.input, self.train.ports.output):
            raise InputError(
                [
                    Problem(
                        "--input",
                        f"{port!r} is not a port of the train (ports: "
                        f"{self.train.ports.input}, {self.train.ports.output})",
                    )
                ],
                self.train.path,
            )
        return holding_variant(self.variants, self.conditions, port, values, self.train.path, self.excluded)

    @property
    def parameters(self) -> list[sympy.Symbol]:
        """The values a design needs: the symbols of the formulas, the conditions and the
        speed ratio (defined ones replaced by their parameters), sorted by name."""
        return sorted_symbols(parameters_of(self._used, self.train.definitions))

    @property
    def _used(self) -> set[sympy.Symbol]:
        """The symbols of the formulas, the conditions and the speed ratio as written."""
        ratio = restore(self.analysis.speed_ratio().to_expr(), self.analysis.network.layout.radicals)
        used: set[sympy.Symbol] = set(self.symbols) | ratio.free_symbols
        return used

    def missing(self, values: Mapping[sympy.Symbol | str, object]) -> list[str]:
        """The names a design written as ``values`` (a published check) leaves out: the
        parameters of the formulas that are neither given, nor implied by the geometry (a
        dependent radius), nor the operating point (input torque and speed), by name."""
        given = {str(k) for k in values}
        implied = {str(r.symbol) for r in resolved_train(self.train).dependent or ()}
        implied |= {str(s) for s in OPERATING_SYMBOLS}
        definitions = [d for d in self.train.definitions if str(d.symbol) not in given]
        needed = sorted_symbols(parameters_of(self._used, definitions))
        return [str(s) for s in needed if str(s) not in given | implied]

    @property
    def parameter_table(self) -> tuple[Parameter, ...]:
        """Meaning, unit and admissible range of each of `parameters` (the modules' ``PARAMETERS``)."""
        return parameters_of_train(self.train, self.analysis.network.laws, self.parameters, OPERATING_PARAMETERS)

    def design_point(self, values: Mapping[sympy.Symbol | str, object], input: str | None = None) -> DesignPoint:
        """The variant, speed ratio and efficiency at ``values`` (keyed by symbol or name,
        exact when the values are) with ``input`` as input port: the one decision every
        entry point shares.  Refuses (`InputError`, `DesignError`, `NotCoveredError`)
        missing or bad values, an inadmissible geometry, a port that does not turn, a
        train that self-locks there (`davies_sym.efficiency.design_point`)."""
        port = input or self.train.ports.input
        given = self._completed(values)
        # A defined symbol given itself (cos_beta = 3/5) stands for its definition's parameters.
        definitions = [d for d in self.train.definitions if d.symbol not in given]
        missing = [str(s) for s in sorted_symbols(parameters_of(self._used, definitions)) if s not in given]
        if missing:
            raise MissingValuesError([Problem("values", f"missing values for {', '.join(missing)}")], self.train.path)
        outside = [why for p in self.parameter_table if (why := _range_problem(p, given)) is not None]
        if outside:
            raise DesignError([Problem("values", why) for why in outside], self.train.path)
        check_constraints(self.analysis.network.layout.constraints, given, self.train.path)
        ports = self.train.ports
        other = ports.output if port == ports.input else ports.input
        ratio = turning_ratio(self.analysis.speed_ratio().to_expr(), given, port, other, port == ports.input)
        check_moving(vanishing_denominators(self.analysis), given, ports.input)
        variant = self._variant_at(given, port)
        value = sympy.sympify(variant.efficiency.subs(given))
        check_working(value, port, f"variant ({variant.number})", INPUT_TORQUE in variant.efficiency.free_symbols)
        return DesignPoint(port, other, variant, ratio, value)

    def evaluate(self, values: Mapping[sympy.Symbol | str, object], input: str | None = None) -> sympy.Expr:
        """The efficiency at ``values`` (keyed by symbol or name, e.g. ``{"r1": 40}``; exact
        when the values are), right variant chosen; a design `design_point` refuses is
        refused here with the same reason."""
        return self.design_point(values, input).efficiency


def _range_problem(parameter: Parameter, values: Mapping[sympy.Symbol, sympy.Expr]) -> str | None:
    symbol = next((s for s in values if str(s) == parameter.name), None)
    return None if symbol is None else range_problem(parameter, values[symbol])


def derive_variants(
    train: Train,
    progress: Progress | None = None,
    samples: int = 200,
    seed: int = 0,
    layout: Layout | None = None,
    inputs: Sequence[str] | None = None,
    state: State | str | None = None,
) -> VariantSet:
    """Derive every variant of ``train``'s efficiency in ordinary efficiencies
    (``layout``: a geometry other than the one derived from the train; ``inputs``: only
    the variants with these input ports, e.g. for one evaluation; ``state``: the operating
    state, by name or as one of ``train.states``, that a train with states is derived in).
    The steps are those of Laus section 3.1 in order (motions, virtual power through the
    meshes, turning conditions, one variant per region), kept in one function to be read
    as the method; its seven parameters are the public API's keywords."""
    train = _checked_train(train, state, layout, inputs)
    say = progress or (lambda message: None)
    etas = efficiency_symbols(train)
    extra = (*etas, *OPERATING_SYMBOLS)
    options = AnalysisOptions(coulomb_signs=CoulombSigns.MESH_LINEAR, extra_symbols=list(extra), layout=layout)
    analysis = Analysis(train, options, progress)
    say("virtual power flow through the meshes")
    roles, conditions = mesh_roles(analysis)
    sides = SideDerivations(analysis, tuple(roles), extra, layout, progress)
    declared = sides.derivation(True, frozenset())
    domain = ParameterDomain.of(train, analysis.network.layout)
    regions = sampled_regions(domain, conditions, samples, seed, _other_symbols(declared.form, etas, roles))
    combos = tuple(condition_signs(conditions))
    facts = tuple(geometry_facts(train, analysis.network.layout, conditions))
    # Every law but a mesh's own friction (bearings, viscous and drag anywhere, a mesh's
    # too) changes with the input side, and at light load can reverse a loaded force:
    # derive the other side again, and the cases the losses reach.
    again = not only_mesh_laws(analysis.network.laws, {r.coupling for r in roles})
    context = VariantContext(
        train, sides, tuple(conditions), combos, regions, domain, facts, tuple(etas), again, seed, say
    )
    found = VariantList(context)
    found.add_side(True, inputs)
    found.add_side(False, inputs)
    light = found.light_load()
    turned = found.reversed_meshes()
    declared_skipped = train.ports.input not in (inputs or ())
    if found.skipped and ((light and declared_skipped) or turned):
        # The light-load variants are numbered after the declared input's, the reversed
        # meshes' after every light-load one: derive those too.
        return derive_variants(train, progress, samples, seed, layout)
    found.add_light_load(light)
    found.add_reversed_meshes(turned)
    return VariantSet(
        train,
        analysis,
        tuple(roles),
        tuple(conditions),
        tuple(found.variants),
        declared.form,
        sides.solved,
        tuple(found.excluded),
        context.facts,
    )


def _checked_train(
    train: Train, state: State | str | None, layout: Layout | None, inputs: Sequence[str] | None
) -> Train:
    """The train to derive, in ``state``, refused where `derive_variants` cannot derive it
    (input ports, mesh friction, reserved names), with its geometric constraints resolved
    unless a ``layout`` is given."""
    train = train_to_derive(train, state)
    _check_ports(train, inputs)
    check_mesh_friction(train)
    if layout is None:
        train = resolved_train(train)
    _check_reserved(train)
    return train


def _check_ports(train: Train, inputs: Sequence[str] | None) -> None:
    """Refuse input ports that are not ports (as ``--input`` refuses them) and a train
    driven at several ports (its efficiency has power-flow regions, not variants)."""
    ports = (train.ports.input, train.ports.output)
    strangers = [p for p in inputs or () if p not in ports]
    if strangers:
        why = f"{shortened(strangers[0])} is not a port (ports: {', '.join(ports)})"
        raise InputError([Problem("--input", why)], train.path)
    if len(train.ports.inputs) > 1:
        why = (
            f"the train is driven at {', '.join(train.ports.inputs)}: its efficiency depends on the power-flow "
            "region; derive it with davies_sym.derive_several_inputs(train), as the derive command does"
        )
        raise InputError([Problem("ports", why)], train.file_lines)


def _check_reserved(train: Train) -> None:
    """Refuse a file symbol named like the formulas' input torque or speed."""
    taken = sorted(str(s) for s in OPERATING_SYMBOLS if str(s) in train.symbols)
    if taken:
        why = f"{', '.join(taken)} name the input torque and speed of the formulas; rename the symbol in the file"
        raise InputError([Problem("", why)], train.file_lines)


def _other_symbols(
    form: RationalFunction, etas: Sequence[sympy.Symbol], roles: Sequence[MeshRole]
) -> list[sympy.Symbol]:
    """Symbols left in the formulas besides geometry and efficiencies (bearing
    friction, viscous coefficients, input torque and speed)."""
    out = form.free_symbols - set(etas)
    out -= {r.flow.friction_symbol for r in roles}
    return sorted_symbols(out)
