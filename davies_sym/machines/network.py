"""The network matrices of a machine (Laus eqs. (1), (2), (19) and App. E).

Motions: one block of d rows per fundamental circuit, ``M_N = sum_j B_ij Mhat_D,j``
(eq. (147)); actions: one block of d rows per fundamental cutset, ``A_N = sum_j Q_ij
Ahat_D,j`` (eq. (19)).  The screw system is planar, ``{t; u, v}`` and ``{T; U, V}``
(Laus sec. 4.2.1), when no freedom has an r, s or w part; otherwise spatial (d = 6).
Constraint actions that vanish in the planar system are the overconstraint the thesis
neglects (sec. 4.2) and are dropped with the friction loads they would carry.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import networkx as nx
import numpy as np
import sympy

from davies_sym.algebra.screws import force_wrench, torque_wrench
from davies_sym.errors import Problem, TopologyError
from davies_sym.machines.joints import (
    FrictionAction,
    JointScrews,
    Screw,
    ZeroTest,
    axis_name,
    exactly_zero,
    friction_name,
    joint_screws,
    numerically_zero,
)
from davies_sym.machines.machine_model import Coupling, Machine, Port
from davies_sym.network.coupling_graph import CouplingGraph

PLANAR = (2, 3, 4)
SPATIAL = (0, 1, 2, 3, 4, 5)


@dataclass(frozen=True)
class PortAction:
    """A port's action variable and the motions its unit wrench does power on."""

    port: str
    action: str
    coupling: str
    #: (unit wrench . unit twist, motion variable) over the coupling's freedoms.
    power_terms: tuple[tuple[sympy.Expr, str], ...]


@dataclass(frozen=True)
class Network:
    """Motion and action variables, the network matrices and what sits on each column."""

    order: int
    coordinates: tuple[int, ...]
    motions: tuple[str, ...]
    actions: tuple[str, ...]
    motion_matrix: Any  # M_N, d*l x F (sympy.Matrix, or a numpy array when numeric)
    action_matrix: Any  # A_N, d*k x C
    ports: dict[str, PortAction]
    friction: tuple[FrictionAction, ...]
    joints: tuple[JointScrews, ...]
    tree: tuple[str, ...]
    #: For a slider's face friction: the A_N column to add times sign(load) (its wrench's
    #: moment moves with the pressed face).
    shifts: dict[str, Any]

    def action_index(self, name: str) -> int:
        return self.actions.index(name)

    def motion_index(self, name: str) -> int:
        return self.motions.index(name)


@dataclass(frozen=True)
class GraphMatrices:
    """The coupling graph's fundamental circuits and cutsets on the tree grown from the
    reference link (Laus eqs. (103) and (104)); they do not change with the position."""

    tree: tuple[str, ...]
    circuits: tuple[tuple[int, ...], ...]
    cutsets: tuple[tuple[int, ...], ...]


def graph_matrices(machine: Machine) -> GraphMatrices:
    graph = CouplingGraph(machine.links, [(c.name, c.links[0], c.links[1]) for c in machine.couplings])
    if not machine.links or not nx.is_weakly_connected(graph.graph):
        raise TopologyError(
            [Problem("links", "the links and couplings do not form one connected machine")], machine.path
        )
    tree = graph.default_tree(machine.reference)

    def rows(matrix: sympy.Matrix) -> tuple[tuple[int, ...], ...]:
        return tuple(tuple(int(matrix[i, j]) for j in range(matrix.cols)) for i in range(matrix.rows))

    return GraphMatrices(tuple(tree), rows(graph.circuit_matrix(tree)), rows(graph.cutset_matrix(tree)))


def _floating(joint: JointScrews) -> JointScrews:
    """The joint's screws, coefficients and load weights as floats (the numeric solution
    never touches a sympy number in its loops)."""

    def screw(values: Screw) -> Screw:
        return tuple(float(v) for v in values)

    return JointScrews(
        joint.coupling,
        tuple((name, screw(s)) for name, s in joint.freedoms),
        tuple((name, screw(s)) for name, s in joint.constraints),
        tuple(
            FrictionAction(
                f.name,
                f.coupling,
                screw(f.screw),
                f.freedom,
                float(f.coefficient),
                tuple((n, float(w)) for n, w in f.load),
                f.resultant,
                None if f.shift is None else screw(f.shift),
            )
            for f in joint.friction
        ),
    )


def _planar(joints: list[JointScrews], zero: ZeroTest) -> bool:
    return all(zero(twist[i]) for j in joints for _, twist in j.freedoms for i in (0, 1, 5))


def _port_wrench(port: Port, joint: JointScrews, at: tuple[sympy.Expr, ...]) -> tuple[str, Screw]:
    if port.action == "freedom":
        name, twist = joint.freedoms[0]
        if twist[:3] == (0, 0, 0):
            return name, force_wrench(tuple(twist[3:]), at)
        return name, torque_wrench(tuple(twist[:3]))
    assert port.direction is not None
    wrench = force_wrench(port.direction, at) if port.action == "force" else torque_wrench(port.direction)
    axis = axis_name(port.direction)
    letters = "UVW" if port.action == "force" else "RST"
    letter = letters["xyz".index(axis)] if axis is not None else ("Q" if port.action == "force" else "P")
    return f"{letter}_{port.coupling}", wrench


def build_network(
    machine: Machine,
    couplings: Sequence[Coupling] | None = None,
    graph: GraphMatrices | None = None,
    numeric: bool = False,
) -> Network:
    """Assemble M_N and A_N of ``machine`` on the spanning tree grown from its reference.

    ``couplings``: the machine's couplings at one position with numbers in place of
    expressions (``numeric``: the matrices are numpy arrays, zero tests to rounding)."""
    couplings = tuple(couplings if couplings is not None else machine.couplings)
    zero = numerically_zero if numeric else exactly_zero
    graph = graph or graph_matrices(machine)
    joints = [joint_screws(c, coordinate_names=False, zero=zero) for c in couplings]
    planar = _planar(joints, zero)
    if planar:
        joints = [joint_screws(c, coordinate_names=True, zero=zero) for c in couplings]
    if numeric:
        joints = [_floating(j) for j in joints]
    coords = PLANAR if planar else SPATIAL
    columns = _Columns()
    for j, (coupling, joint) in enumerate(zip(couplings, joints, strict=True)):
        for name, twist in joint.freedoms:
            columns.motions.append(name)
            columns.twists.append((j, twist))
        kept = columns.add_constraints(j, joint, zero, coords)
        for port in (p for p in machine.ports if p.coupling == coupling.name):
            columns.add_port(j, port, coupling, joint)
        columns.add_friction(j, joint, kept)

    def blocks(matrix: tuple[tuple[int, ...], ...], screws: list[tuple[int, Screw]]) -> Any:
        return _blocks(matrix, screws, coords, numeric)

    return Network(
        order=len(coords),
        coordinates=coords,
        motions=tuple(columns.motions),
        actions=tuple(columns.actions),
        motion_matrix=blocks(graph.circuits, columns.twists),
        action_matrix=blocks(graph.cutsets, columns.wrenches),
        ports=columns.ports,
        friction=tuple(columns.friction),
        joints=tuple(joints),
        tree=graph.tree,
        shifts={name: blocks(graph.cutsets, [column]) for name, column in columns.shifts.items()},
    )


@dataclass
class _Columns:
    """The network's variables in column order, each with its joint's index and its unit
    screw (``twists`` for the ``motions``, ``wrenches`` for the ``actions``); the port
    actions, the friction actions kept, and the shift column of a slider's face friction."""

    motions: list[str] = field(default_factory=list)
    twists: list[tuple[int, Screw]] = field(default_factory=list)
    actions: list[str] = field(default_factory=list)
    wrenches: list[tuple[int, Screw]] = field(default_factory=list)
    ports: dict[str, PortAction] = field(default_factory=dict)
    friction: list[FrictionAction] = field(default_factory=list)
    shifts: dict[str, tuple[int, Screw]] = field(default_factory=dict)

    def add_action(self, name: str, j: int, wrench: Screw) -> None:
        """An action column: ``name`` on joint ``j`` with its unit ``wrench``."""
        self.actions.append(name)
        self.wrenches.append((j, wrench))

    def add_constraints(self, j: int, joint: JointScrews, zero: ZeroTest, coords: tuple[int, ...]) -> list[str]:
        """The constraint actions of joint ``j`` that do not vanish in the screw system
        (``coords``); their names."""
        kept = []
        for name, wrench in joint.constraints:
            if not all(zero(wrench[i]) for i in coords):
                self.add_action(name, j, wrench)
                kept.append(name)
        return kept

    def add_port(self, j: int, port: Port, coupling: Coupling, joint: JointScrews) -> None:
        """The action of ``port`` on joint ``j`` and the power its wrench does on the freedoms."""
        freedom, wrench = _port_wrench(port, joint, coupling.at)
        name = freedom[0].upper() + freedom[1:] if port.action == "freedom" else freedom
        self.add_action(name, j, wrench)
        terms = tuple((sympy.expand(sum(wrench[i] * twist[i] for i in range(6))), m) for m, twist in joint.freedoms)
        self.ports[port.name] = PortAction(port.name, name, coupling.name, tuple(t for t in terms if t[0] != 0))

    def add_friction(self, j: int, joint: JointScrews, kept: list[str]) -> None:
        """The friction actions of joint ``j``, loaded by the constraint actions ``kept``."""
        faces = [f for f in joint.friction if f.shift is not None and any(n in kept for n, _ in f.load)]
        for f in joint.friction:
            load = tuple((name, w) for name, w in f.load if name in kept)
            if f.shift is not None and not load:
                continue  # the face of a force the screw system drops carries nothing
            if f.shift is not None and sum(1 for g in faces if g.freedom == f.freedom) == 1:
                f = replace(f, name=friction_name(f.freedom))  # one face left: no number
            self.friction.append(replace(f, load=load))
            self.add_action(f.name, j, f.screw)
            if f.shift is not None:
                self.shifts[f.name] = (j, f.shift)


def _blocks(
    matrix: tuple[tuple[int, ...], ...], columns: list[tuple[int, Screw]], coords: tuple[int, ...], numeric: bool
) -> Any:
    """``sum_j matrix_ij screw_j``: one block of d rows per row of the circuit or cutset
    ``matrix``, the screws' components ``coords`` (numpy when ``numeric``)."""
    d = len(coords)
    out = np.zeros((len(matrix) * d, len(columns))) if numeric else sympy.zeros(len(matrix) * d, len(columns))
    for i, row in enumerate(matrix):
        for c, (j, screw) in enumerate(columns):
            if row[j]:
                for r, k in enumerate(coords):
                    out[i * d + r, c] = row[j] * screw[k]
    return out
