"""Layout of planar trains drawn on one line (Laus Figs. 5 and 7).

All gear axes are parallel to z and lie in the plane x = 0; a position is a y value.
Gears on one link share its axis; a revolute between two geared links makes them
coaxial.  Axis positions follow from the meshes: external mesh, centre distance
r_g + r_h; internal mesh, R - r with the pinion on the +y side of the annulus centre.
A mesh that closes a loop gives a geometric constraint such as r1 - r3 = r2 - r4
(Laus section 3.4.1.6), or an error when it cannot hold.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.algebra.screws import Vector, vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.layout import (
    X_AXIS,
    Y_AXIS,
    GeometricConstraint,
    Layout,
    add_constraint,
    axis_groups,
    check_placed,
    line_point,
)
from davies_sym.topology.couplings import GearMesh, Revolute
from davies_sym.topology.link_groups import LinkGroups
from davies_sym.topology.model import Gear, Train


def planar_line_layout(train: Train) -> Layout:
    """Derive axis positions, pitch points and geometric constraints of a planar train."""
    problems: list[Problem] = []
    geared, groups = axis_groups(train)
    meshes = [c for c in train.couplings if isinstance(c, GearMesh)]
    gears = {g.name: g for g in train.gears}
    positions: dict[str, sympy.Expr] = {}
    root = _root_link(train, geared)
    if root is not None:
        positions[groups.find(root)] = sympy.Integer(0)
    # A bearing with `at` fixes its geared link's axis (a ring on the main axis); the
    # meshes then place the rest and any mesh that closes a loop gives a constraint.
    for c in train.couplings:
        if isinstance(c, Revolute) and c.at is not None and c.axis is None:
            for link in c.links:
                if link in geared and groups.find(link) not in positions:
                    positions[groups.find(link)] = c.at
    tree_meshes = _place_by_meshes(meshes, gears, groups, positions)
    for c in train.couplings:
        if isinstance(c, Revolute) and c.at is not None:
            for link in c.links:
                if link in geared and groups.find(link) not in positions:
                    positions[groups.find(link)] = c.at
                    tree_meshes |= _place_by_meshes(meshes, gears, groups, positions)
    check_placed(train, groups, positions, problems)
    oracle = SignOracle()
    centres = {g.name: positions[groups.find(g.link)] for g in train.gears}
    points: dict[str, Vector] = {}
    constraints: list[GeometricConstraint] = []
    facts: list[sympy.Expr] = []
    for mesh in meshes:
        g, h = gears[mesh.gears[0]], gears[mesh.gears[1]]
        if mesh.internal:
            ann, pin = (g, h) if g.internal else (h, g)
            facts.append(ann.radius - pin.radius)
            offset = sympy.expand(centres[pin.name] - centres[ann.name])
            points[mesh.name] = line_point(centres[ann.name] + ann.radius)
            if mesh.name not in tree_meshes:
                add_constraint(train, constraints, problems, offset, ann.radius - pin.radius, mesh.name, oracle)
        else:
            offset = sympy.expand(centres[h.name] - centres[g.name])
            side = oracle.sign(offset) if offset != 0 else 0
            if mesh.name not in tree_meshes:
                if side is None or side == 0:
                    problems.append(train.problem(
                        f"couplings.{mesh.name}",
                        f"cannot tell on which side gear {h.name!r} lies from gear {g.name!r} (centre offset "
                        f"{offset}); this mesh closes a loop that the line layout cannot decide"))
                    continue
                add_constraint(train, constraints, problems, side * offset, g.radius + h.radius, mesh.name, oracle)
            points[mesh.name] = line_point(centres[g.name] + (side or 1) * g.radius)
    for c in train.couplings:
        if isinstance(c, Revolute):
            point = _revolute_point(train, c, geared, groups, positions, problems, constraints, oracle)
            if point is not None:
                points[c.name] = point
        elif not isinstance(c, GearMesh):
            points[c.name] = vector((0, 0, 0))
    if problems:
        raise GeometryError(problems, train.path)
    return Layout(
        gear_centres={name: line_point(y) for name, y in centres.items()},
        coupling_points=points,
        mesh_tangents={m.name: X_AXIS for m in meshes},
        mesh_normals={m.name: Y_AXIS for m in meshes},
        constraints=tuple(constraints),
        positive_facts=tuple(facts),
    )


def _root_link(train: Train, geared: set[str]) -> str | None:
    if train.reference in geared:
        return train.reference
    return train.gears[0].link if train.gears else None


def _place_by_meshes(meshes: list[GearMesh], gears: Mapping[str, Gear], groups: LinkGroups,
                     positions: dict[str, sympy.Expr]) -> set[str]:
    """Place axis groups outward from the placed ones; returns the meshes used."""
    used: set[str] = set()
    progress = True
    while progress:
        progress = False
        for mesh in meshes:
            g, h = gears[mesh.gears[0]], gears[mesh.gears[1]]
            ag, ah = groups.find(g.link), groups.find(h.link)
            if (ag in positions) == (ah in positions):
                continue
            if mesh.internal:
                ann, pin = (g, h) if g.internal else (h, g)
                a_ann, a_pin = groups.find(ann.link), groups.find(pin.link)
                distance = ann.radius - pin.radius
                if a_ann in positions:
                    positions[a_pin] = sympy.expand(positions[a_ann] + distance)
                else:
                    positions[a_ann] = sympy.expand(positions[a_pin] - distance)
            elif ag in positions:
                positions[ah] = sympy.expand(positions[ag] + g.radius + h.radius)
            else:
                positions[ag] = sympy.expand(positions[ah] - g.radius - h.radius)
            used.add(mesh.name)
            progress = True
    return used


def _revolute_point(train: Train, c: Revolute, geared: set[str], groups: LinkGroups,
                    positions: Mapping[str, sympy.Expr], problems: list[Problem],
                    constraints: list[GeometricConstraint], oracle: SignOracle) -> Vector | None:
    on = [c.axis] if c.axis is not None else c.links
    derived = [positions[groups.find(link)] for link in on if link in geared]
    if derived:
        if c.at is not None:
            # Where the meshes leave the axis open, the bearing's `at` is a constraint.
            add_constraint(train, constraints, problems, derived[0], c.at, c.name, oracle, f"couplings.{c.name}.at",
                            f"inconsistent geometry: `at` is {c.at} but the gears put this axis at {derived[0]}")
        return line_point(derived[0])
    if c.at is None:
        problems.append(train.problem(
            f"couplings.{c.name}",
            f"neither link {c.links[0]!r} nor {c.links[1]!r} carries a gear: give the position of this "
            "revolute with `at`"))
        return None
    return line_point(c.at)
