"""Geometry stage: where every axis and pitch point of a train lies -> `Layout`.

It owns the positions and directions the coupling screws need, the geometric
constraints the loops of meshes imply (Laus section 3.4.1.6: r1 - r3 = r2 - r4) and
the square roots a tilted axis brings (Laus App. C).  Three layouts: trains drawn on
one line (Laus Figs. 5 and 7), planar trains in 2-D (`.plane`) and trains whose
axes meet at one apex (`.cone`, Laus Fig. 9, Chen Fig. 4.10); a worm or crossed
helical mesh places its first gear across the parallel-axis part (`.skew`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import sympy

from davies_sym.algebra.screws import Vector
from davies_sym.caches import IdentityCache
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.axes import axis_structure, spacings
from davies_sym.geometry.cone import conical_layout
from davies_sym.geometry.layout import GeometricConstraint, Layout
from davies_sym.geometry.line import planar_line_layout
from davies_sym.geometry.plane import plane_layout
from davies_sym.geometry.skew import skew_layout
from davies_sym.topology.coupling_kinds import CouplingsByKind, by_kind
from davies_sym.topology.gear_mesh import GearMesh
from davies_sym.topology.model import Train
from davies_sym.topology.toothed_mesh import LocationError, ToothedMesh

__all__ = ["GeometricConstraint", "Layout", "train_layout"]


def train_layout(train: Train) -> Layout:
    """The layout of ``train``: conical when its gears give axis directions, else planar.

    A train in an operating state keeps the geometry of the whole train (its brakes and
    clutches join members without moving an axis), restricted to what the state keeps."""
    return _LAYOUTS.get(train, lambda: _derived_layout(train))


#: The layout of each train, derived once while the train lives.
_LAYOUTS: IdentityCache[Train, Layout] = IdentityCache()


def _derived_layout(train: Train) -> Layout:
    if train.whole is not None:
        layout = _restricted(train_layout(train.whole), train)
    else:
        kinds = by_kind(train.couplings)
        layout = _following(_helical(_layout(train, kinds), kinds.gear, train), kinds.toothed, train)
        # A radius solved from a constraint is a length: its expression is positive.
        facts = tuple(r.expression for r in train.dependent or ())
        layout = replace(layout, positive_facts=layout.positive_facts + facts) if facts else layout
    return layout


def _layout(train: Train, kinds: CouplingsByKind) -> Layout:
    if kinds.skew:
        return skew_layout(train, kinds, _parallel_layout)
    spaced = spacings(train)
    if any(g.axis is not None or g.tilted for g in train.gears):
        return conical_layout(train, spaced)
    # The axis classes are found once and handed to the layout that places them.  A
    # coupling whose centre distance is free (a chain) draws its strand along the
    # placement direction, its second axis across it: such a train is drawn in 2-D.
    structure = axis_structure(train, spaced)
    direction = train.placement
    if direction is None and any(not s.fixed for s in spaced):
        direction = (sympy.Integer(0), sympy.Integer(1))
    if direction is not None:
        return plane_layout(train, direction, structure)
    return planar_line_layout(train, structure)


def _parallel_layout(train: Train) -> Layout:
    """The layout of the parallel-axis part of a train with skew meshes."""
    return _layout(train, by_kind(train.couplings))


def _following(layout: Layout, meshes: Sequence[ToothedMesh], train: Train) -> Layout:
    """``layout`` with the meshes that follow the gears they mesh put where their kinds
    say (a rack beside its pinion): the layouts place the gears, these kinds place
    themselves from them."""
    gears = {g.name: g for g in train.gears}
    points, tangents, normals = dict(layout.coupling_points), dict(layout.mesh_tangents), dict(layout.mesh_normals)
    problems = []
    placed = False
    for mesh in meshes:
        try:
            where = mesh.locate(layout, gears)
        except LocationError as e:
            problems.append(Problem(f"couplings.{mesh.name}.{e.key}", e.message))
            continue
        if where is not None:
            points[mesh.name], tangents[mesh.name], normals[mesh.name] = where.point, where.tangent, where.normal
            placed = True
    if problems:
        raise GeometryError(problems, train.file_lines)
    # A train of gear pairs only keeps the layout its layouts drew.
    return replace(layout, coupling_points=points, mesh_tangents=tangents, mesh_normals=normals) if placed else layout


def _helical(layout: Layout, meshes: Sequence[GearMesh], train: Train) -> Layout:
    """``layout`` marked as carrying thrust when a mesh of ``meshes`` (the train's gear
    meshes) is helical (parallel axes only)."""
    helical = [c for c in meshes if c.helix is not None]
    if not helical:
        return layout
    if layout.gear_axes:
        raise GeometryError(
            [
                Problem(
                    f"couplings.{helical[0].name}.helix_angle",
                    "helical gears are covered on parallel axes; this train has intersecting axes (spiral "
                    "bevel gears are not covered): remove `helix_angle`",
                )
            ],
            train.file_lines,
        )
    return replace(layout, thrust=True)


def _restricted(layout: Layout, train: Train) -> Layout:
    """``layout`` of a whole train, keeping the gears and couplings of ``train`` (one of its
    states) and the constraints among the radii that ``train`` still has."""
    gears = {g.name for g in train.gears}
    couplings = {c.name for c in train.couplings}
    radii: set[sympy.Basic] = set()
    for g in train.gears:
        radii |= g.radius.free_symbols
    radii |= {r.symbol for r in layout.radicals}

    def keep(table: Mapping[str, Vector], names: set[str]) -> dict[str, Vector]:
        return {k: v for k, v in table.items() if k in names}

    return replace(
        layout,
        gear_centres=keep(layout.gear_centres, gears),
        coupling_points=keep(layout.coupling_points, couplings),
        mesh_tangents=keep(layout.mesh_tangents, couplings),
        mesh_normals=keep(layout.mesh_normals, couplings),
        gear_axes=keep(layout.gear_axes, gears),
        coupling_axes=keep(layout.coupling_axes, couplings),
        constraints=tuple(c for c in layout.constraints if c.expression.free_symbols <= radii),
        positive_facts=tuple(f for f in layout.positive_facts if f.free_symbols <= radii),
        side_facts=tuple(f for f in layout.side_facts if f.free_symbols <= radii),
    )
