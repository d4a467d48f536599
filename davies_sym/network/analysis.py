"""Motions, actions, powers and efficiency of a train (Laus Algorithm 1, steps 1-30).

The solution runs on exact polynomials (python-flint); results are converted to sympy
expressions only when asked for.  Primary variables are the input port magnitudes:
the input speed (e.g. ``t_A``) for motions and the input torque (e.g. ``T_A``) for
actions, as in Laus eqs. (16) and (23).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cached_property, partial

import sympy

from davies_sym.algebra.lazy import LazyMapping
from davies_sym.algebra.linalg import Reduce, Row, SolvedSpace, WorkExceeded, polynomial_rows
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.screws import power
from davies_sym.algebra.signs import SignOracle
from davies_sym.errors import BeyondWorkBound, DerivationError, MobilityError
from davies_sym.geometry.dependent import resolved_train
from davies_sym.geometry.layout import Layout, constraint_substitutions, joint_substitution
from davies_sym.network.action_nullity import action_nullity_problems
from davies_sym.network.analysis_display import analysis_html, analysis_latex
from davies_sym.network.analysis_options import AnalysisOptions
from davies_sym.network.condensed_screws import condensed_screw, inner_product
from davies_sym.network.friction_laws import CoulombLaw, CoulombSigns, FrictionLaw, coulomb_mode
from davies_sym.network.matrices import ActionVariable, Network
from davies_sym.network.mobility import mobility_problems
from davies_sym.network.null_space import ROUTE_WORK, null_space
from davies_sym.network.sign_condition import SignCondition
from davies_sym.progress import Progress
from davies_sym.topology.coupling_kinds import as_toothed_mesh
from davies_sym.topology.model import State, Train
from davies_sym.topology.states import train_to_derive
from davies_sym.topology.symbols import make_symbol


class Analysis:
    """Davies' method on one train: build with `davies_sym.analyse`.

    ``coulomb_signs='resolve'`` (default) fixes every Coulomb sign from the lossless
    solution with positive input power and keeps a sign symbol only where the sign
    depends on the geometry; ``'symbolic'`` keeps a symbol for every Coulomb law
    (the ``c`` and ``a`` of Laus eqs. (22)-(26)); ``'mesh-linear'`` writes every gear
    mesh as the signed linear law T = zeta U of eqs. (63)-(64), so that one formula
    covers both power directions (zeta < 0 when the flow reverses, section 3.3.5), and
    resolves the other Coulomb laws.  ``extra_symbols`` join the polynomial ring (the
    ordinary efficiencies substituted later).  ``layout`` replaces the one derived from
    the train (to study a geometry given otherwise, e.g. a published screw table).
    ``reversed_coulomb`` names bearings whose reaction the losses reverse (a drag larger
    than the load): their resolved Coulomb sign is taken the other way.  These choices
    travel together as `AnalysisOptions`.
    """

    def __init__(self, train: Train, options: AnalysisOptions | None = None, progress: Progress | None = None):
        options = options or AnalysisOptions()
        mode = coulomb_mode(options.coulomb_signs)
        if options.layout is None:
            train = resolved_train(train)  # the formulas hold on the geometric constraints
        self.train = train
        self.options = options
        self.coulomb_signs = mode
        self.reversed_coulomb = options.reversed_coulomb
        self._progress = progress or (lambda message: None)
        self._progress("building the coupling network")
        self.network = Network(train, options.tree, options.action_tree, options.layout)
        net = self.network
        self.input_motion = net.coupling_motions(train.ports.input)[0]
        self.input_action = net.port_action(train.ports.input)
        self.output_action = net.port_action(train.ports.output)
        constraints = net.layout.constraints
        substitutions = constraint_substitutions(constraints)
        if len(constraints) > 1:
            substitutions.append(joint_substitution(constraints))
        self.oracle = SignOracle(net.layout.positive_facts, substitutions)
        self.sign_symbols = {
            law.coupling: make_symbol(f"sigma_{law.coupling}", "sign")
            for law in net.laws
            if isinstance(law, CoulombLaw)
        }
        symbols = set(train.symbols.values()) | set(self.sign_symbols.values())
        symbols |= {self.input_motion.symbol, self.input_action.symbol} | set(options.extra_symbols)
        for law in net.laws:
            symbols |= law.coefficient.free_symbols
        self.ring = PolynomialRing(symbols, net.layout.radicals)
        self._reduce = self.ring.reduce if self.ring.radicals else None
        # The condensed motion screws, each formed once: the reports read them per mesh.
        self._twists: dict[str, tuple[RationalFunction, ...]] = {}

    # -- helpers ---------------------------------------------------------------------
    @property
    def reduce(self) -> Reduce | None:
        """Reduction of polynomials modulo the layout's radical relations (None without radicals)."""
        return self._reduce

    def _rf(self, expr: sympy.Expr) -> RationalFunction:
        return self.ring.rational(expr)

    def rows(self, matrix: sympy.Matrix) -> list[Row]:
        return polynomial_rows(self.ring, matrix)

    def _solve(
        self,
        matrix: sympy.Matrix,
        prefer: list[int],
        columns: Sequence[ActionVariable] = (),
        laws: int = 0,
        instead: Sequence[int] = (),
        what: str = "",
    ) -> SolvedSpace:
        """`null_space` of ``matrix``: circuit or cutset blocks, then ``laws`` rows; the
        columns ``instead`` taken free for the first of ``prefer`` where its route swells
        (``what``: the null space, for the reason when every route does)."""
        try:
            return null_space(self.network, self.ring, matrix, prefer, columns, laws, instead)
        except WorkExceeded as exc:
            raise BeyondWorkBound(
                f"{what}: the elimination over the square roots of the "
                f"2-D drawing swells past {ROUTE_WORK:,} products of terms with the input's variable free and with the "
                "output's; the closed form is not derived"
            ) from exc

    # -- motions (eqs. (1), (56)-(59)) -----------------------------------------------
    @cached_property
    def motion_coefficients(self) -> dict[str, RationalFunction]:
        """psi_alpha / t_in for every motion magnitude."""
        return self._motion_solution[1]

    @cached_property
    def _motion_solution(self) -> tuple[int, dict[str, RationalFunction]]:
        """The mobility (nullity of M_N) and psi_alpha / t_in; raises on a mismatch."""
        self._progress("solving the motions (null space of M_N)")
        net = self.network
        index = net.motions.index(self.input_motion)
        output = net.motions.index(net.coupling_motions(self.train.ports.output)[0])
        elimination = self._solve(net.network_motion_matrix(), [index], instead=[output], what="the motions")
        free = elimination.free
        problems = mobility_problems(self.train, net, free, index)
        if problems:
            raise MobilityError(problems, self.train.file_lines)
        solution = elimination.solution(self.ring)
        zero = RationalFunction.polynomial(self.ring, self.ring.zero)
        return len(free), {v.name: solution[k].get(index, zero) for k, v in enumerate(net.motions)}

    @cached_property
    def motion_basis(self) -> dict[str, dict[str, RationalFunction]]:
        """Every motion magnitude as a combination of the primary ones (the free
        variables of Null(M_N), the input speed first): eq. (1) for any mobility."""
        _ = self._motion_solution  # the mobility check
        net = self.network
        # Primary speeds: the input, then the other couplings on the reference (shaft speeds).
        on_reference = [
            net.motions.index(v)
            for c in self.train.couplings
            if self.train.reference in c.links
            for v in net.coupling_motions(c.name)
            if v is not self.input_motion
        ]
        return self.motions_in([self.input_motion.name, *(net.motions[j].name for j in on_reference)])

    def motions_in(self, preferred: Sequence[str]) -> dict[str, dict[str, RationalFunction]]:
        """Every motion magnitude as a combination of the free ones of Null(M_N), chosen
        among ``preferred`` (motion names) first: eq. (1) for any mobility."""
        net = self.network
        prefer = [net.motions.index(net.motion(name)) for name in preferred]
        elimination = self._solve(net.network_motion_matrix(), prefer)
        solution = elimination.solution(self.ring)
        return {v.name: {net.motions[j].name: c for j, c in solution[k].items()} for k, v in enumerate(net.motions)}

    @property
    def degrees_of_freedom(self) -> int:
        """Net degree of freedom F_N, the nullity of M_N (eq. (1))."""
        return self._motion_solution[0]

    @cached_property
    def motion_magnitudes(self) -> dict[str, RationalFunction]:
        """Every motion magnitude in terms of the input speed."""
        t_in = RationalFunction.polynomial(self.ring, self.ring.gen(self.input_motion.symbol))
        return {name: c * t_in for name, c in self.motion_coefficients.items()}

    def speed_ratio(self) -> RationalFunction:
        """Input speed over output speed, t_in / t_out (the transmission ratio)."""
        out = self.network.coupling_motions(self.train.ports.output)[0]
        return self.motion_coefficients[out.name].inverse()

    # -- lossless actions (eqs. (2), (60)-(62)) --------------------------------------
    @cached_property
    def lossless_action_coefficients(self) -> Mapping[str, RationalFunction]:
        """Psi_alpha / T_in of the lossless network (friction columns removed)."""
        _ = self._motion_solution  # check the mobility before the actions
        self._progress("solving the lossless actions (null space of A_N)")
        net = self.network
        cols = net.action_columns(lossless=True)
        index = cols.index(self.input_action)
        output = cols.index(self.output_action)
        elimination = self._solve(
            net.network_action_matrix(lossless=True), [index], cols, instead=[output], what="the lossless actions"
        )
        self._check_action_nullity(elimination.free, index, cols)
        solution = elimination.solution(self.ring)
        zero = RationalFunction.polynomial(self.ring, self.ring.zero)
        column = {v.name: k for k, v in enumerate(cols)}
        return LazyMapping(list(column), lambda name: solution[column[name]].get(index, zero))

    def _check_action_nullity(self, free: tuple[int, ...], index: int, cols: list[ActionVariable]) -> None:
        problems = action_nullity_problems(self.train, free, index, cols)
        if problems:
            raise MobilityError(problems, self.train.file_lines)

    # -- friction signs (eqs. (21), (24), (41)) --------------------------------------
    def _input_pairing(self) -> sympy.Expr:
        return power(self.input_action.wrench, self.input_motion.twist)

    @property
    def input_power_sign(self) -> int:
        """+1 when the input torque and speed magnitudes of equal sign put power in."""
        return self.port_power_sign(self.train.ports.input)

    def port_power_sign(self, port: str) -> int:
        """+1 when a port's torque and speed magnitudes of equal sign put power in."""
        net = self.network
        return 1 if power(net.port_action(port).wrench, net.coupling_motions(port)[0].twist) > 0 else -1

    @property
    def coulomb_sign_values(self) -> dict[str, sympy.Expr]:
        """sign(transmitted force) * sign(relative motion) of every Coulomb law, with
        positive input power, or its sign symbol where the ports do not decide it."""
        return self._coulomb_signs[0]

    @property
    def sign_conditions(self) -> list[SignCondition]:
        """The Coulomb signs left as symbols, each with the expression that decides it."""
        return list(self._coulomb_signs[1])

    @cached_property
    def _coulomb_signs(self) -> tuple[dict[str, sympy.Expr], tuple[SignCondition, ...]]:
        out: dict[str, sympy.Expr] = {}
        conditions: list[SignCondition] = []
        for law in self.network.laws:
            if not isinstance(law, CoulombLaw):
                continue
            symbol = self.sign_symbols[law.coupling]
            if self.coulomb_signs is CoulombSigns.SYMBOLIC:
                out[law.coupling] = symbol
                continue
            mesh = as_toothed_mesh(self.train.coupling(law.coupling)) is not None
            if self.coulomb_signs is CoulombSigns.MESH_LINEAR and mesh:
                out[law.coupling] = sympy.Integer(-1)  # T + (-1) zeta U = 0, i.e. T = zeta U
                continue
            assert law.transmitted is not None
            alpha = self.lossless_action_coefficients[law.transmitted]
            beta = self.motion_coefficients[law.motion]
            content, factors = (alpha * beta * self._rf(self._input_pairing())).factor_list()
            sign, undecided = self.oracle.classify(content, factors)
            flip = -1 if law.coupling in self.reversed_coulomb else 1
            if sign in (1, -1):
                out[law.coupling] = sympy.Integer(sign * flip)
            elif self.coulomb_signs is CoulombSigns.MESH_LINEAR:  # geometry decides: variants derive both senses
                out[law.coupling] = sympy.Integer(flip)
            else:
                out[law.coupling] = flip * symbol
                conditions.append(SignCondition(law.coupling, symbol, undecided))
        return out, tuple(conditions)

    # -- augmented action matrix (eqs. (22), (40), (51)-(52)) ------------------------
    def _law_row(self, law: FrictionLaw) -> dict[str, sympy.Expr]:
        sign = self.coulomb_sign_values[law.coupling] if isinstance(law, CoulombLaw) else sympy.Integer(1)
        return law.row(sign)

    @cached_property
    def augmented_action_matrix(self) -> sympy.Matrix:
        """D_A: A_N stacked over the constitutive rows, then the source rows."""
        net = self.network
        names = [v.name for v in net.actions]
        rows = []
        ordered = [law for law in net.laws if not law.source] + [law for law in net.laws if law.source]
        for law in ordered:
            entries = self._law_row(law)
            rows.append([entries.get(n, 0) for n in names])
        extra = sympy.Matrix(rows) if rows else sympy.zeros(0, len(names))
        return sympy.Matrix.vstack(net.network_action_matrix(), extra)

    @cached_property
    def dependent_sources(self) -> sympy.Matrix:
        """nu: right-hand side of the source rows, T = -b t (eqs. (50)-(51), (53)), and
        T = -D sign(t) for a constant drag."""
        values = []
        for law in self.network.laws:  # in the order of the source rows of D_A
            if law.source:
                speed = self.motion_magnitudes[law.motion].to_expr
                values.append(law.source_term(speed, partial(self._direction, law)))
        return sympy.Matrix(values)

    def _direction(self, law: FrictionLaw) -> int:
        """sign(t) of a drag law's coupling with the input turning forwards (t_in > 0):
        the constant torque opposes it."""
        sign, undecided = self.oracle.classify(*self.motion_coefficients[law.motion].factor_list())
        if sign not in (1, -1):
            raise DerivationError(
                f"coupling {law.coupling}: which way it turns depends on the geometry (the sign of "
                f"{sympy.sstr(undecided)}), so its constant drag has no single closed form; give its losses as "
                "a viscous law, or fix the geometry so the direction is known"
            )
        return int(sign)

    @cached_property
    def action_solution(self) -> Mapping[str, tuple[RationalFunction, RationalFunction]]:
        """Every action magnitude as ``(a, b)`` with Psi = a T_in + b (b from sources)."""
        _ = self._coulomb_signs  # decide the signs before forming D_A
        self._progress("solving the actions with friction (null space of D_A)")
        net = self.network
        D = self.augmented_action_matrix
        nu = self.dependent_sources
        ncols = D.cols
        const = ncols  # an extra column multiplying the constant 1
        sources = sympy.zeros(D.rows, 1)
        for k in range(nu.rows):
            sources[D.rows - nu.rows + k] = -nu[k]
        index = net.actions.index(self.input_action)
        output = net.actions.index(self.output_action)
        elimination = self._solve(
            D.row_join(sources), [index, const], net.actions, len(net.laws), [output], "the actions with friction"
        )
        free = [j for j in elimination.free if j != const]
        self._check_action_nullity(tuple(free), index, list(net.actions))
        if const in elimination.pivots:
            raise DerivationError("the dependent sources are inconsistent with the network")
        solution = elimination.solution(self.ring)
        zero = RationalFunction.polynomial(self.ring, self.ring.zero)
        column = {v.name: k for k, v in enumerate(net.actions)}
        return LazyMapping(
            list(column), lambda n: (solution[column[n]].get(index, zero), solution[column[n]].get(const, zero))
        )

    @cached_property
    def action_magnitudes(self) -> Mapping[str, RationalFunction]:
        """Every action magnitude in terms of the input torque (and speed, with sources),
        each formed when first read."""
        T_in = RationalFunction.polynomial(self.ring, self.ring.gen(self.input_action.symbol))
        pairs = self.action_solution
        return LazyMapping(list(pairs), lambda n: pairs[n][0] * T_in + pairs[n][1])

    # -- condensed screws and powers (eqs. (25)-(31), (45)-(49), (59), (65)) ---------
    def coupling_twist(self, coupling: str) -> list[RationalFunction]:
        """Condensed motion screw of a coupling (a column of M, eq. (59))."""
        known = self._twists.get(coupling)
        if known is None:
            units = [(v.name, v.twist) for v in self.network.coupling_motions(coupling)]
            known = self._twists[coupling] = tuple(
                condensed_screw(self.ring, self.network.order, self.motion_magnitudes, units)
            )
        return list(known)

    def action_wrench(self, names: Sequence[str]) -> list[RationalFunction]:
        """Sum of the wrenches of the given action variables."""
        units = [(name, self.network.action(name).wrench) for name in names]
        return condensed_screw(self.ring, self.network.order, self.action_magnitudes, units)

    def coupling_wrench(self, coupling: str) -> list[RationalFunction]:
        """Condensed action screw of a coupling (a column of A, eqs. (26), (65))."""
        return self.action_wrench([v.name for v in self.network.coupling_actions(coupling)])

    def inner(self, wrench: list[RationalFunction], twist: list[RationalFunction]) -> RationalFunction:
        """The power of ``wrench`` on ``twist``."""
        return inner_product(self.ring, wrench, twist)

    def lossless_input_power(self) -> RationalFunction:
        """Input power of the lossless network per unit input torque (T_in = 1)."""
        return self._lossless_input_power

    @cached_property
    def _lossless_input_power(self) -> RationalFunction:
        wrench = [self._rf(v) for v in self.input_action.wrench]
        return self.inner(wrench, self.coupling_twist(self.train.ports.input))

    def power_rf(self, coupling: str, actions: Sequence[str] | None = None) -> RationalFunction:
        """Power through ``coupling`` (all its actions, or only ``actions``), eq. (5)."""
        names = [v.name for v in self.network.coupling_actions(coupling)] if actions is None else list(actions)
        return self.inner(self.action_wrench(names), self.coupling_twist(coupling))

    def power(self, coupling: str, actions: Sequence[str] | None = None) -> sympy.Expr:
        """Power through a coupling as a sympy expression (eqs. (27)-(29))."""
        return self.power_rf(coupling, actions).to_expr()

    def port_power_rf(self, coupling: str) -> RationalFunction:
        """Power of the port action alone on its coupling (``S_TA . S_A`` of eq. (45))."""
        return self.power_rf(coupling, [self.network.port_action(coupling).name])

    @cached_property
    def efficiency_rf(self) -> RationalFunction:
        """Overall efficiency -P_out / P_in (Definition 5, eqs. (32), (49), (71))."""
        self._progress("forming the efficiency")
        p_in = self.port_power_rf(self.train.ports.input)
        p_out = self.port_power_rf(self.train.ports.output)
        return -(p_out / p_in)

    @property
    def efficiency(self) -> sympy.Expr:
        """The efficiency in friction coefficients, numerator and denominator factored."""
        return self.efficiency_rf.to_expr()

    def _repr_latex_(self) -> str:
        return analysis_latex(*self._display())

    def _repr_html_(self) -> str:
        return analysis_html(*self._display())

    def _display(self) -> tuple[int, tuple[str, str], sympy.Expr | None, sympy.Expr | None]:
        one = self.degrees_of_freedom == 1
        ports = (self.train.ports.input, self.train.ports.output)
        return (
            self.degrees_of_freedom,
            ports,
            self.speed_ratio().to_expr() if one else None,
            self.efficiency if one else None,
        )


def analyse(
    train: Train,
    *,
    tree: Sequence[str] | None = None,
    action_tree: Sequence[str] | None = None,
    coulomb_signs: CoulombSigns | str = CoulombSigns.RESOLVE,
    progress: Progress | None = None,
    extra_symbols: Sequence[sympy.Symbol] = (),
    layout: Layout | None = None,
    state: State | str | None = None,
) -> Analysis:
    """Run Davies' method on ``train`` (see `Analysis` for the options; ``state``: the
    operating state, by name or as one of ``train.states``, of a train with states).

    Its seven keywords are the public API's (documented in docs/capabilities.md), so
    they stay separate here and travel on as one `AnalysisOptions`."""
    options = AnalysisOptions(tree, action_tree, coulomb_signs, extra_symbols, layout)
    return Analysis(train_to_derive(train, state), options, progress)
