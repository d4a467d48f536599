"""The coupling network: unit motion/action matrices and the Davies network matrices.

Implements Laus eqs. (17), (54), (60) (direct-coupling unit matrices M_D, A_D),
App. E (index matrices X_M, X_A and column replication B_M = B X_M, Q_A = Q X_A),
eq. (56) (network unit motion matrix M_N) and eq. (19) (network unit action matrix
A_N).  Action columns of a coupling are ordered port, load-dependent friction,
speed-dependent friction, constraints, as in eqs. (17), (40) and (52).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import sympy

from davies_sym.algebra.radicals import RadicalTable
from davies_sym.algebra.screws import NamedScrew, Screw, action_along_motion, cross, power, torque_magnitude_name
from davies_sym.errors import DerivationError, Problem, TopologyError
from davies_sym.geometry import train_layout
from davies_sym.geometry.layout import Layout
from davies_sym.network.coupling_graph import CouplingGraph
from davies_sym.network.friction_laws import LOSS_ROLES, CoulombLaw, DragLaw, FrictionLaw, LinearLaw, ViscousLaw
from davies_sym.network.pressed_guides import pressed_laws
from davies_sym.network.screw_system import (
    CouplingScrewError,
    ReducedCoupling,
    ScrewSystem,
    essential_twists,
    minimal_screw_system,
    reduce_coupling,
)
from davies_sym.network.shared_screws import coupling_screws, shared_screws, written_square_root
from davies_sym.topology.coupling_kinds import as_bearing, as_written_screws
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.kind_screws import CouplingScrews
from davies_sym.topology.model import Train
from davies_sym.topology.revolute import Revolute
from davies_sym.topology.screw_coupling import ScrewCoupling
from davies_sym.topology.symbols import make_symbol


@dataclass(frozen=True)
class MotionVariable:
    """A motion magnitude (e.g. ``t_A``) with its reduced unit twist."""

    name: str
    coupling: str
    twist: tuple[sympy.Expr, ...]

    @property
    def symbol(self) -> sympy.Symbol:
        return make_symbol(self.name, "magnitude")


@dataclass(frozen=True)
class ActionVariable:
    """An action magnitude (e.g. ``U_C``) with its reduced unit wrench and its role:
    ``port``, ``friction`` (load-dependent law), ``viscous``, ``drag`` or ``constraint``."""

    name: str
    coupling: str
    wrench: tuple[sympy.Expr, ...]
    role: str

    @property
    def symbol(self) -> sympy.Symbol:
        return make_symbol(self.name, "magnitude")


def _unique(names: list[str]) -> list[str]:
    seen: dict[str, int] = {}
    out = []
    for n in names:
        seen[n] = seen.get(n, 0) + 1
        out.append(n if seen[n] == 1 else f"{n}{seen[n]}")
    return out


class Network:
    """All matrices of Davies' method for one train and one choice of spanning trees."""

    def __init__(
        self,
        train: Train,
        tree: Sequence[str] | None = None,
        action_tree: Sequence[str] | None = None,
        layout: Layout | None = None,
    ):
        self.train = train
        self.layout = layout if layout is not None else train_layout(train)
        # A state given its whole's layout takes the screw work its whole train shares, unless
        # square roots are written in its screws: their radical symbols are numbered per train.
        whole = train_layout(train.whole) if layout is None and train.whole is not None else None
        self.graph = CouplingGraph(train.link_names, [(c.name, *c.links) for c in train.couplings])
        self.tree = tuple(tree) if tree is not None else self.graph.default_tree(train.reference)
        self.action_tree = tuple(action_tree) if action_tree is not None else self.tree
        for label, t in (("tree", self.tree), ("action tree", self.action_tree)):
            if not self.graph.is_spanning_tree(t):
                raise DerivationError(f"{label} {list(t)} is not a spanning tree of the coupling graph")
        shared = shared_screws(train, whole) if whole is not None else None
        if shared is not None and not shared.written_square_root(c.name for c in train.couplings):
            full = {c.name: shared.screws(c.name) for c in train.couplings}
            self.system: ScrewSystem = shared.system(tuple(full))
        else:
            shared = None
            full = self._absorb_radicals({c.name: coupling_screws(c, self.layout) for c in train.couplings})
            self.system = minimal_screw_system(
                essential_twists(full.values(), self.layout.spatial), self.layout.radicals
            )
        self._friction_wrenches = {name: s.friction for name, s in full.items() if s.friction is not None}
        self._shared = shared
        self.reduced: dict[str, ReducedCoupling] = {}
        for c in train.couplings:
            written = as_written_screws(c)
            if written is not None:
                _check_reciprocal(train, written, full[c.name])
            try:
                if shared is not None:
                    self.reduced[c.name] = shared.reduced(self.system, c.name)
                else:
                    self.reduced[c.name] = reduce_coupling(self.system, full[c.name], c.name)
            except CouplingScrewError as exc:
                entry = f"couplings.{c.name}" + (".motions" if written is not None else "")
                raise TopologyError([Problem(entry, exc.reason)], train.file_lines) from exc
        self.motions, self.actions, self.laws = self._variables()
        self._check_names()

    def _absorb_radicals(self, full: dict[str, CouplingScrews]) -> dict[str, CouplingScrews]:
        """Square roots written in low-level screws become radical symbols of the layout
        (positive radicands), so the exact algebra treats them like tilted bevel axes."""
        if not any(written_square_root(screws) for screws in full.values()):
            return full
        table = RadicalTable(list(self.layout.radicals))

        def absorb(group: tuple[NamedScrew, ...]) -> tuple[NamedScrew, ...]:
            return tuple(NamedScrew(n.name, tuple(table.absorb(sympy.sympify(x)) for x in n.screw)) for n in group)

        out = {
            name: replace(
                s, motions=absorb(s.motions), secondary=absorb(s.secondary), constraints=absorb(s.constraints)
            )
            for name, s in full.items()
        }
        added = tuple(r for r in table.radicals if r not in self.layout.radicals)
        self.layout = replace(
            self.layout,
            radicals=tuple(table.radicals),
            positive_facts=self.layout.positive_facts + tuple(r.radicand for r in added),
        )
        return out

    # -- variables -------------------------------------------------------------------
    def _variables(self) -> tuple[tuple[MotionVariable, ...], tuple[ActionVariable, ...], tuple[FrictionLaw, ...]]:
        motions: list[MotionVariable] = []
        actions: list[ActionVariable] = []
        laws: list[FrictionLaw] = []
        ports = set(self.train.ports.every)
        for c in self.train.couplings:
            red = self.reduced[c.name]
            names = _unique([m.name for m in red.motions])
            cm = [MotionVariable(f"{n}_{c.name}", c.name, m.screw) for n, m in zip(names, red.motions, strict=True)]
            motions += cm
            needs_axis = c.name in ports or not c.friction.lossless
            # A mesh (a coupling of two gears) has several freedoms; its friction opposes the first.
            if needs_axis and (len(cm) > 1 and not c.meshing):
                raise DerivationError(
                    f"coupling {c.name}: ports and friction need a coupling with one "
                    f"freedom, it has {len(cm)} in this screw system"
                )
            if not needs_axis:
                actions += self._constraint_actions(c, red)
                continue
            given = self._friction_wrenches.get(c.name)
            along, wrench = self._axis_action(c.name, cm[0].twist)
            if given is not None:
                base = given.name
            else:
                base = torque_magnitude_name(along[:3]) if any(v != 0 for v in along[:3]) else "F"
            has_port = c.name in ports
            if has_port:
                actions.append(ActionVariable(f"{base}_{c.name}", c.name, wrench, "port"))
            constraints = self._constraint_actions(c, red, base)
            # The load-dependent law (Coulomb, else linear), then the sources (Laus Table 2).
            loaded = c.friction.loaded
            transmitted = self._transmitted(c, constraints) if loaded is not None else None
            if loaded is not None:
                name = f"{base}star_{c.name}" if has_port else f"{base}_{c.name}"
                kind: type[FrictionLaw] = CoulombLaw if loaded[0] == CoulombLaw.name else LinearLaw
                law: FrictionLaw = kind(c.name, name, loaded[1], cm[0].name, transmitted)
                actions.append(ActionVariable(name, c.name, wrench, law.role))
                laws.append(law)
            if c.friction.viscous is not None:
                name = f"{base}ddag_{c.name}" if (has_port or loaded) else f"{base}_{c.name}"
                law = ViscousLaw(c.name, name, c.friction.viscous, cm[0].name, None)
                actions.append(ActionVariable(name, c.name, wrench, law.role))
                laws.append(law)
            if c.friction.drag is not None:
                others = has_port or loaded or c.friction.viscous is not None
                name = f"{base}drag_{c.name}" if others else f"{base}_{c.name}"
                law = DragLaw(c.name, name, c.friction.drag, cm[0].name, None)
                actions.append(ActionVariable(name, c.name, wrench, law.role))
                laws.append(law)
            actions += constraints
        return tuple(motions), tuple(actions), pressed_laws(self.train, laws)

    def _axis_action(self, name: str, twist: tuple[sympy.Expr, ...]) -> tuple[Screw, tuple[sympy.Expr, ...]]:
        """The unit action along ``twist`` (the friction wrench where one is given), full
        and reduced; formed once for the states that share the screw system."""

        def formed() -> tuple[Screw, tuple[sympy.Expr, ...]]:
            given = self._friction_wrenches.get(name)
            along = given.screw if given is not None else action_along_motion(_lift(self.system, twist))
            return along, self.system.reduce_wrench(along)

        return formed() if self._shared is None else self._shared.formed(self.system, f"axis {name}", formed)

    def _constraint_actions(self, c: Coupling, red: ReducedCoupling, taken: str = "") -> list[ActionVariable]:
        """The constraint actions of ``c``, named apart from each other and from ``taken``
        (the base name of its port or friction torque: a torque about a tilted axis is
        ``P`` both as the port and as the bearing's torque across the axis)."""
        names = _unique([taken, *(w.name for w in red.constraints)])[1:]
        return [
            ActionVariable(f"{n}_{c.name}", c.name, w.screw, "constraint")
            for n, w in zip(names, red.constraints, strict=True)
        ]

    def _transmitted(self, c: Coupling, constraints: list[ActionVariable]) -> str:
        # A mesh loads its friction with the tooth force, its first constraint action.
        if c.meshing:
            return constraints[0].name
        if c.friction.pressed_by is not None:
            return ""  # the mesh's tooth force, set by `pressed_laws` once every action is named
        what = "reaction force"
        bearing = as_bearing(c)
        if bearing is not None:
            loads = self._bearing_loads(bearing, constraints)
            if len(loads) == 1:
                return loads[0].name
            if c.friction.load == "radial" and len(constraints) == 1:
                return constraints[0].name  # the one reaction the screw system leaves it
            if not loads:
                raise TopologyError([self._no_load(bearing)], self.train.file_lines)
            constraints, what = loads, f"{c.friction.load} reaction force"
        elif len(constraints) == 1:
            return constraints[0].name
        raise DerivationError(
            f"coupling {c.name}: a load-dependent friction law needs one {what}, but this coupling "
            f"transmits {', '.join(a.name for a in constraints)} in the screw system of order "
            f"{self.system.order}; use a viscous law or describe the reaction with one force"
        )

    def _no_load(self, c: Revolute) -> Problem:
        """The problem of a bearing law whose load this train never exerts."""
        if c.friction.load == "axial":
            return Problem(
                f"couplings.{c.name}.friction.thrust",
                "no gear of this train thrusts along the axes (spur gears), so a thrust face carries no "
                "load: give the meshes a `helix_angle`, or remove `thrust`",
            )
        return Problem(
            f"couplings.{c.name}.friction",
            "this bearing carries no radial force in this train, so its journal has no load: remove the law",
        )

    def _bearing_loads(self, c: Revolute, constraints: list[ActionVariable]) -> list[ActionVariable]:
        """The reaction forces of bearing ``c`` that load its Coulomb law: the forces across
        its axis (a journal) or the force along it (a thrust face)."""
        axis = self.layout.coupling_axes.get(c.name, self.layout.axis)
        loads = []
        for action, wrench in zip(constraints, self.reduced[c.name].spatial, strict=True):
            force = wrench[3:]
            if all(sympy.expand(f) == 0 for f in force):
                continue  # a torque: the bearing's tilting moment
            axial = all(sympy.expand(v) == 0 for v in cross(force, axis))
            if axial == (c.friction.load == "axial"):
                loads.append(action)
        return loads

    def _check_names(self) -> None:
        """A symbol of the file named like a magnitude of the network (``t_A``) or the sign
        of a Coulomb friction force (``sigma_C``): one name would stand for two quantities."""
        magnitudes = {v.name for v in self.motions} | {v.name for v in self.actions}
        signs = {f"sigma_{law.coupling}" for law in self.laws if isinstance(law, CoulombLaw)}
        clash = (magnitudes | signs) & set(self.train.symbols)
        if clash:
            raise TopologyError(
                [
                    self.train.symbol_problem(
                        n,
                        f"{n} is the name of the "
                        + ("sign of a friction force" if n in signs else "motion or action magnitude")
                        + f" of coupling {n.partition('_')[2]} in the formulas; give this symbol another name",
                    )
                    for n in sorted(clash)
                ],
                self.train.file_lines,
            )

    # -- lookups ---------------------------------------------------------------------
    def motion(self, name: str) -> MotionVariable:
        return next(v for v in self.motions if v.name == name)

    def action(self, name: str) -> ActionVariable:
        return next(v for v in self.actions if v.name == name)

    def port_action(self, coupling: str) -> ActionVariable:
        return next(v for v in self.actions if v.coupling == coupling and v.role == "port")

    def coupling_motions(self, coupling: str) -> list[MotionVariable]:
        return [v for v in self.motions if v.coupling == coupling]

    def coupling_actions(self, coupling: str, lossless: bool = False) -> list[ActionVariable]:
        return [v for v in self.actions if v.coupling == coupling and not (lossless and v.role in LOSS_ROLES)]

    # -- matrices (Laus eqs. (17), (19), (54)-(56), App. E) --------------------------
    @property
    def order(self) -> int:
        return self.system.order

    def unit_motion_matrix(self) -> sympy.Matrix:
        """M_D (d x F), one unit twist per column (eq. (54))."""
        return sympy.Matrix([list(v.twist) for v in self.motions]).T

    def unit_action_matrix(self, lossless: bool = False) -> sympy.Matrix:
        """A_D (d x C), one unit wrench per column (eqs. (17), (60))."""
        cols = self.action_columns(lossless)
        return sympy.Matrix([list(v.wrench) for v in cols]).T

    def action_columns(self, lossless: bool = False) -> list[ActionVariable]:
        return [v for v in self.actions if not (lossless and v.role in LOSS_ROLES)]

    def circuit_matrix(self) -> sympy.Matrix:
        return self.graph.circuit_matrix(self.tree)

    def cutset_matrix(self) -> sympy.Matrix:
        return self.graph.cutset_matrix(self.action_tree)

    def motion_circuit_matrix(self) -> sympy.Matrix:
        """B_M = B X_M, the circuit matrix of the motion graph, X_M (e x F) holding 1 where
        motion alpha belongs to edge j (App. E): B's columns replicated."""
        return _replicated(self.circuit_matrix(), self.graph.edges, [v.coupling for v in self.motions])

    def action_cutset_matrix(self, lossless: bool = False) -> sympy.Matrix:
        """Q_A = Q X_A, the cutset matrix of the action graph, X_A (e x C) holding 1 where
        action alpha belongs to edge j (App. E): Q's columns replicated."""
        return _replicated(self.cutset_matrix(), self.graph.edges, [v.coupling for v in self.action_columns(lossless)])

    def network_motion_matrix(self) -> sympy.Matrix:
        """M_N (dl x F), eq. (56): blocks M_D diag(B_M row i)."""
        return _circuit_blocks(self.unit_motion_matrix(), self.motion_circuit_matrix())

    def network_action_matrix(self, lossless: bool = False) -> sympy.Matrix:
        """A_N (dk x C), eq. (19): blocks A_D diag(Q_A row i)."""
        return _circuit_blocks(self.unit_action_matrix(lossless), self.action_cutset_matrix(lossless))


def _replicated(matrix: sympy.Matrix, edges: Sequence[str], couplings: Sequence[str]) -> sympy.Matrix:
    """``matrix X`` for the index matrix X of ``couplings`` over ``edges`` (App. E): each
    variable's column is its edge's column of ``matrix`` (a column of X holds a single 1),
    so the product is read off without forming X."""
    index = {edge: j for j, edge in enumerate(edges)}
    rows = matrix.tolist()
    out = [[row[index[c]] if c in index else 0 for c in couplings] for row in rows]
    return sympy.Matrix(out) if out else sympy.zeros(0, len(couplings))


def _circuit_blocks(unit: sympy.Matrix, incidence: sympy.Matrix) -> sympy.Matrix:
    """The blocks ``unit diag(incidence row i)`` stacked (eqs. (19), (56)): each column of
    the unit screws scaled by the row's entry, built entry by entry (the entries are 0 and
    +-1, so no product of matrices is needed)."""
    unit_rows, incidence_rows = unit.tolist(), incidence.tolist()
    rows = [
        [u * q if q != 0 and u != 0 else 0 for u, q in zip(unit_row, incidence_row, strict=True)]
        for incidence_row in incidence_rows
        for unit_row in unit_rows
    ]
    return sympy.Matrix(rows) if rows else sympy.zeros(0, unit.cols)


def _lift(system: ScrewSystem, reduced: tuple[sympy.Expr, ...]) -> tuple[sympy.Expr, ...]:
    full = system.lift * sympy.Matrix(reduced)
    return tuple(sympy.expand(v) for v in full)


def _check_reciprocal(train: Train, c: ScrewCoupling, screws: CouplingScrews) -> None:
    problems = []
    for a in screws.constraints:
        for m in screws.motions:
            if sympy.expand(power(a.screw, m.screw)) != 0:
                problems.append(
                    Problem(
                        f"couplings.{c.name}.actions",
                        f"action {a.name!r} does work on "
                        f"motion {m.name!r} (power {sympy.expand(power(a.screw, m.screw))}); "
                        "transmitted actions must be reciprocal to the motions",
                    )
                )
    if problems:
        raise TopologyError(problems, train.file_lines)
