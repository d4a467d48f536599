"""Carriers, virtual power flow through the meshes, and ordinary efficiencies.

For a mesh ``X: p -> q`` the carrier is a link c that holds both gear axes: seen from
c, link p turns about the axis of its gear and link q about the axis of its own
(Laus section 3.1, Definition 4; several carriers per train are allowed, section 3.6.5).
The carrier is the one the geometry stage found for the mesh from the topology alone
(`davies_sym.geometry.axes.axis_structure`, the frame the layout placed the mesh in);
the motions confirm it.  With motions relative to c
(`davies_sym.efficiency.absolute_motion`):

* the lossless virtual power ``$_X^a . ^c$_p`` says which gear drives (eqs. (69)-(70),
  (86)-(88)); positive means it flows along the edge, from p to q;
* the ordinary efficiency is the ratio of the virtual powers on the two sides of the
  mesh with friction, ``eta_pq = ($_X^a . ^c$_q) / ($_X^a . ^c$_p)`` (eqs. (72)-(73),
  (89)-(91)).  With the signed law T = zeta U the mesh action is U (w_U + zeta w_T), so
  the ratio holds zeta_X alone and is solved for it (eqs. (33), (35), (74)-(75), (92)-(94)).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.caches import IdentityCache
from davies_sym.efficiency.absolute_motion import Twist, motion_along_path, walk_path
from davies_sym.errors import DerivationError, Problem, TopologyError
from davies_sym.geometry.axes import AxisStructure, axis_structure
from davies_sym.topology.coupling_kinds import as_toothed_mesh
from davies_sym.topology.model import Train
from davies_sym.topology.toothed_mesh import ToothedMesh

if TYPE_CHECKING:
    from davies_sym.network.analysis import Analysis


@dataclass(frozen=True, eq=False)
class MeshPowerFlow:
    """Virtual power through one mesh, measured from its carrier."""

    coupling: str
    carrier: str
    #: Links (p, q) and members (gears, or a gear and a rack) of the edge p -> q.
    links: tuple[str, str]
    gears: tuple[str, str]
    #: The members as the reports name them (``gear 1``, ``rack R``), and both in one
    #: phrase (``gears 1, 3``).
    sides: tuple[str, str]
    pair_words: str
    #: Lossless virtual power through the mesh divided by the input power; positive when
    #: the first gear drives (the flow follows the edge).
    flow_ratio: RationalFunction
    #: w_U . ^c$_s and w_T . ^c$_s for s = p (index 0) and q (index 1): the powers of the
    #: unit transmitted force and unit friction torque on each side.
    transmitted_power: tuple[RationalFunction, RationalFunction]
    friction_power: tuple[RationalFunction, RationalFunction]
    friction_symbol: sympy.Expr

    def ordinary_efficiency(self, first_drives: bool) -> RationalFunction:
        """eta_pq (first gear drives) or eta_qp as a function of zeta (eqs. (32), (34), (72))."""
        ring = self.flow_ratio.ring
        zeta = ring.rational(self.friction_symbol)
        driver, driven = (0, 1) if first_drives else (1, 0)
        return (self.transmitted_power[driven] + zeta * self.friction_power[driven]) / (
            self.transmitted_power[driver] + zeta * self.friction_power[driver]
        )

    def friction_for(self, efficiency: sympy.Expr, first_drives: bool) -> RationalFunction:
        """zeta from the ordinary efficiency of the given direction (eqs. (33), (35), (74))."""
        ring = self.flow_ratio.ring
        eta = ring.rational(efficiency)
        driver, driven = (0, 1) if first_drives else (1, 0)
        num = eta * self.transmitted_power[driver] - self.transmitted_power[driven]
        den = self.friction_power[driven] - eta * self.friction_power[driver]
        if den.is_zero() and all(p.is_zero() for p in (*self.transmitted_power, *self.friction_power)):
            return num  # the mesh does not turn in its carrier (a locked set): no loss, any zeta
        if den.is_zero():
            raise DerivationError(
                f"mesh {self.coupling}: its friction torque does no virtual work seen from carrier {self.carrier!r}"
            )
        return num / den


def _parallel(a: Twist, b: list[RationalFunction]) -> bool:
    """Whether twist ``a`` is a multiple of ``b`` (all 2x2 minors vanish); zero counts: in
    a locked set (a clutch closing it) the gear does not turn in its carrier."""
    n = len(a)
    return all((a[i] * b[j] - a[j] * b[i]).is_zero() for i in range(n) for j in range(i + 1, n))


def _member_twists(analysis: Analysis, mesh: ToothedMesh) -> list[list[RationalFunction]]:
    """The unit twists of the mesh's members in a carrier (a gear about its axis, a rack
    along its line), reduced to the network's screw system."""
    layout, system = analysis.network.layout, analysis.network.system
    gears = {g.name: g for g in analysis.train.gears}
    return [
        [analysis.ring.rational(v) for v in system.reduce_twist(twist)] for twist in mesh.member_twists(layout, gears)
    ]


def _relative(analysis: Analysis, start: str, end: str) -> Twist:
    return motion_along_path(analysis, walk_path(analysis, start, end))


#: The axis structure of each train whose meshes' carriers are asked, while the train lives.
_STRUCTURES: IdentityCache[Train, AxisStructure] = IdentityCache()


def _carriers(train: Train, mesh: ToothedMesh) -> list[str]:
    """The link the axis structure names as the carrier of ``mesh``; for a mesh it does not
    place (a rack beside its pinion), the links whose bearings hold its members."""
    structure = _STRUCTURES.get(train, lambda: axis_structure(train))
    frame = structure.meshes.get(mesh.name)
    if frame is not None:
        return [frame.carrier]
    return [c for c in dict.fromkeys(structure.parent.get(link) for link in mesh.links) if c is not None]


def find_carrier(analysis: Analysis, mesh: ToothedMesh) -> tuple[str, tuple[Twist, Twist]]:
    """The link holding both members of ``mesh`` (`_carriers`) and the motions of the mesh's
    two links seen from it, in which each member turns about its own axis (or slides along
    its own line); both at rest when the set is locked (`_locked_block_member`)."""
    p, q = mesh.links
    axes = _member_twists(analysis, mesh)
    for c in _carriers(analysis.train, mesh):
        sides = (_relative(analysis, c, p), _relative(analysis, c, q))
        if _parallel(sides[0], axes[0]) and _parallel(sides[1], axes[1]):
            if all(x.is_zero() for twist in sides for x in twist):
                # A locked set is named by a third link at rest with it; with none, a
                # gear's own link would be its carrier (a bearing joining the wrong links).
                named = _locked_block_member(analysis, mesh)
                if named is not None:
                    return named, sides
                continue
            return c, sides
    # A valid file can say this (a bearing joining the wrong links): a located refusal.
    train = analysis.train
    raise TopologyError(
        [
            Problem(
                f"couplings.{mesh.name}",
                "no other link holds the axes of both gears (the "
                "mesh has no carrier), so its ordinary efficiency is not defined; check which "
                "links the bearings join",
            )
        ],
        train.file_lines,
    )


def _locked_block_member(analysis: Analysis, mesh: ToothedMesh) -> str | None:
    """The link the reports name as the carrier of a mesh whose set is locked (it turns as
    one block, so the mesh's links are at rest in every member of the block): the first
    other link, in link order, at rest relative to both, as the reports have always named
    it (the carrier from `_carriers` is one such link)."""
    p, q = mesh.links
    return next(
        (
            c
            for c in analysis.train.link_names
            if c not in (p, q) and all(x.is_zero() for end in (p, q) for x in _relative(analysis, c, end))
        ),
        None,
    )


def named_mesh_power_flow(analysis: Analysis, name: str) -> MeshPowerFlow:
    """`mesh_power_flow` of the mesh called ``name`` in the analysis's train."""
    mesh = as_toothed_mesh(analysis.train.coupling(name))
    if mesh is None:
        raise DerivationError(f"coupling {name} is not a gear mesh: it has no ordinary efficiency")
    return mesh_power_flow(analysis, mesh)


def mesh_power_flow(analysis: Analysis, mesh: ToothedMesh) -> MeshPowerFlow:
    """Carrier, lossless virtual power and the per-side powers of ``mesh``."""
    net = analysis.network
    laws = [law for law in net.laws if law.coupling == mesh.name and law.load_dependent]
    if len(laws) != 1:
        raise DerivationError(
            f"mesh {mesh.name} has no load-dependent friction law to express through an ordinary efficiency"
        )
    law = laws[0]
    lossless = net.coupling_actions(mesh.name, lossless=True)
    if len(lossless) != 1 or law.transmitted != lossless[0].name:
        raise TopologyError(
            [
                Problem(
                    f"couplings.{mesh.name}",
                    f"mesh {mesh.name} transmits {len(lossless)} actions in this screw system; its ordinary "
                    "efficiency needs exactly one (the tooth force): does a coupling move out of the gears' plane?",
                )
            ],
            analysis.train.file_lines,
        )
    carrier, sides = find_carrier(analysis, mesh)
    ring = analysis.ring
    w_u = [ring.rational(v) for v in lossless[0].wrench]
    w_t = [ring.rational(v) for v in net.action(law.variable).wrench]
    transmitted = tuple(analysis.inner(w_u, m) for m in sides)
    friction = tuple(analysis.inner(w_t, m) for m in sides)
    # Lossless flow per unit input power: U_X/T_in * (w_U . ^c$_p) / (w_in . $_in / t_in ...).
    force = analysis.lossless_action_coefficients[lossless[0].name]
    input_power = analysis.lossless_input_power()
    flow_ratio = force * transmitted[0] / input_power
    return MeshPowerFlow(
        mesh.name,
        carrier,
        mesh.links,
        mesh.members,
        mesh.sides,
        mesh.pair_words,
        flow_ratio,
        (transmitted[0], transmitted[1]),
        (friction[0], friction[1]),
        law.coefficient,
    )
