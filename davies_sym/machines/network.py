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
from dataclasses import dataclass, replace
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
from davies_sym.machines.model import Coupling, Machine, Port
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
    d = len(coords)

    motions: list[str] = []
    twist_columns: list[tuple[int, Screw]] = []
    actions: list[str] = []
    wrench_columns: list[tuple[int, Screw]] = []
    ports: dict[str, PortAction] = {}
    friction: list[FrictionAction] = []
    shift_columns: dict[str, tuple[int, Screw]] = {}
    for j, (coupling, joint) in enumerate(zip(couplings, joints, strict=True)):
        for name, twist in joint.freedoms:
            motions.append(name)
            twist_columns.append((j, twist))
        kept = []
        for name, wrench in joint.constraints:
            if not all(zero(wrench[i]) for i in coords):
                actions.append(name)
                wrench_columns.append((j, wrench))
                kept.append(name)
        for port in (p for p in machine.ports if p.coupling == coupling.name):
            freedom, wrench = _port_wrench(port, joint, coupling.at)
            name = freedom[0].upper() + freedom[1:] if port.action == "freedom" else freedom
            actions.append(name)
            wrench_columns.append((j, wrench))
            terms = tuple((sympy.expand(sum(wrench[i] * twist[i] for i in range(6))), m) for m, twist in joint.freedoms)
            ports[port.name] = PortAction(port.name, name, coupling.name, tuple(t for t in terms if t[0] != 0))
        faces = [f for f in joint.friction if f.shift is not None and any(n in kept for n, _ in f.load)]
        for f in joint.friction:
            load = tuple((name, w) for name, w in f.load if name in kept)
            if f.shift is not None and not load:
                continue  # the face of a force the screw system drops carries nothing
            if f.shift is not None and sum(1 for g in faces if g.freedom == f.freedom) == 1:
                f = replace(f, name=friction_name(f.freedom))  # one face left: no number
            friction.append(replace(f, load=load))
            actions.append(f.name)
            wrench_columns.append((j, f.screw))
            if f.shift is not None:
                shift_columns[f.name] = (j, f.shift)

    def blocks(matrix: tuple[tuple[int, ...], ...], columns: list[tuple[int, Screw]]) -> Any:
        out = np.zeros((len(matrix) * d, len(columns))) if numeric else sympy.zeros(len(matrix) * d, len(columns))
        for i, row in enumerate(matrix):
            for c, (j, screw) in enumerate(columns):
                if row[j]:
                    for r, k in enumerate(coords):
                        out[i * d + r, c] = row[j] * screw[k]
        return out

    return Network(
        order=d,
        coordinates=coords,
        motions=tuple(motions),
        actions=tuple(actions),
        motion_matrix=blocks(graph.circuits, twist_columns),
        action_matrix=blocks(graph.cutsets, wrench_columns),
        ports=ports,
        friction=tuple(friction),
        joints=tuple(joints),
        tree=graph.tree,
        shifts={name: blocks(graph.cutsets, [column]) for name, column in shift_columns.items()},
    )
