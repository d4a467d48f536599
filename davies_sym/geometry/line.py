"""Layout of planar trains drawn on one line (Laus Figs. 5 and 7).

All gear axes are parallel to z and lie in the plane x = 0; a position is a y value.
Which links share an axis comes from the topology (`.axes`); the meshes then give
the distances between axes: r_g + r_h for an external mesh, R - r for an internal one.
A planet is drawn on the +y side of the gear on its carrier's axis, the pinion of an
internal mesh between two links of one carrier on the +y side of the annulus, and of a
fixed-axis external pair the gear placed second on the +y side of the other.  Meshes are placed in the
order of their names from the main axis outward, and every mesh that closes a loop
gives a geometric constraint (r1 - r3 = r2 - r4, Laus section 3.4.1.6), or an error
when it cannot hold.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.screws import Vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.axes import AxisStructure
from davies_sym.geometry.layout import (
    X_AXIS,
    Y_AXIS,
    Closures,
    Layout,
    line_point,
    loop_through,
)
from davies_sym.topology.coupling_kinds import bearings as all_bearings
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.model import Gear, Train


def side_of_second(mesh: AxisSpacing, structure: AxisStructure, gears: Mapping[str, Gear]) -> int | None:
    """The sign of y_h - y_g the drawing rules give the mesh's gears (g, h), or None for a
    fixed-axis external pair, whose side follows from the positions."""
    frame = structure.meshes[mesh.name]
    if frame.planet is not None:
        return 1 if frame.planet == 1 else -1
    if mesh.internal:
        return 1 if gears[mesh.gears[0]].internal else -1
    return None


def place_classes(
    train: Train,
    structure: AxisStructure,
    meshes: Sequence[AxisSpacing],
    gears: Mapping[str, Gear],
    problems: list[Problem],
    via: dict[str, tuple[str, str]],
) -> dict[str, sympy.Expr]:
    """The y of every axis class: the main axis at 0 and the classes whose bearing gives
    `at` there, then mesh by mesh (in name order) outward; a class nothing reaches is on
    the main axis when no gear turns about it.  ``via`` records which mesh placed each class from which."""
    positions: dict[str, sympy.Expr] = {structure.root: sympy.Integer(0)}
    bearings = sorted((c for c in all_bearings(train.couplings) if c.at is not None), key=lambda c: c.name)
    geared = {structure.axis[g.axis_link] for g in train.gears}
    for c in bearings:  # positions the user gives come first
        if structure.bearing_axis[c.name] not in positions and c.at is not None:
            positions[structure.bearing_axis[c.name]] = c.at
    while True:
        if _place_one(structure, meshes, gears, positions, via):
            continue
        at = next((c for c in bearings if structure.bearing_axis[c.name] not in positions), None)
        if at is not None and at.at is not None:
            positions[structure.bearing_axis[at.name]] = at.at
            continue
        rest = [cls for cls in structure.classes() if cls not in positions]
        if not rest:
            return positions
        if rest[0] in geared:
            gear = next(g for g in train.gears if structure.axis[g.axis_link] == rest[0])
            problems.append(
                Problem(
                    f"gears.{gear.name}",
                    "its position cannot be derived: no mesh connects "
                    "it to the main axis; give a bearing of its link an `at`",
                )
            )
        positions[rest[0]] = sympy.Integer(0)


def _place_one(
    structure: AxisStructure,
    meshes: Sequence[AxisSpacing],
    gears: Mapping[str, Gear],
    positions: dict[str, sympy.Expr],
    via: dict[str, tuple[str, str]],
) -> bool:
    """Place the class of the first mesh (by name) with exactly one end placed."""
    for mesh in meshes:
        ends = [structure.axis[gears[name].axis_link] for name in mesh.gears]
        placed = [end in positions for end in ends]
        if placed[0] == placed[1]:
            continue
        known = 0 if placed[0] else 1
        side = side_of_second(mesh, structure, gears)
        distance = mesh.distance
        # A fixed-axis external pair: the gear placed now goes outward, whichever is written first.
        step = distance if side is None else (side if known == 0 else -side) * distance
        positions[ends[1 - known]] = sympy.expand(positions[ends[known]] + step)
        via[ends[1 - known]] = (mesh.name, ends[known])
        return True
    return False


def planar_line_layout(train: Train, structure: AxisStructure) -> Layout:
    """Derive axis positions, pitch points and geometric constraints of a planar train
    with the axis classes of ``structure``."""
    problems: list[Problem] = []
    meshes = sorted(structure.spacings, key=lambda c: c.name)
    gears = {g.name: g for g in train.gears}
    via: dict[str, tuple[str, str]] = {}
    positions = place_classes(train, structure, meshes, gears, problems, via)
    if problems:
        raise GeometryError(problems, train.file_lines)
    # An annulus is larger than its pinion, and every radius is positive (3 r2 - r1 too):
    # that decides on which side a loop closes.
    oracle = SignOracle([m.distance for m in meshes if m.internal] + [g.radius for g in train.gears])
    centres = {g.name: positions[structure.axis[g.axis_link]] for g in train.gears}
    closures = Closures(oracle, problems)
    drawing = _LineDrawing(structure, gears, centres, via)
    points = {mesh.name: p for mesh in meshes if (p := _pitch_point(drawing, mesh, closures)) is not None}
    points |= _other_points(train, structure, positions, {m.name for m in meshes}, closures)
    if problems:
        raise GeometryError(problems, train.file_lines)
    return Layout(
        gear_centres={name: line_point(y) for name, y in centres.items()},
        coupling_points=points,
        mesh_tangents={m.name: X_AXIS for m in meshes},
        mesh_normals={m.name: Y_AXIS for m in meshes},
        constraints=tuple(closures.constraints),
        positive_facts=tuple(m.distance for m in meshes if m.internal),
        planet_second=structure.planet_second,
    )


@dataclass(frozen=True)
class _LineDrawing:
    """What drawing the meshes on the line reads: the axis classes, the gears, their
    centres (y) and which mesh placed each class from which (``via``)."""

    structure: AxisStructure
    gears: Mapping[str, Gear]
    centres: Mapping[str, sympy.Expr]
    via: Mapping[str, tuple[str, str]]


def _pitch_point(drawing: _LineDrawing, mesh: AxisSpacing, closures: Closures) -> Vector | None:
    """The pitch point of ``mesh`` on its pitch circle towards the other gear (Laus Fig. 5),
    its centre distance closed against the placed centres (r1 - r3 = r2 - r4, Laus section
    3.4.1.6); None, with the problem recorded, where the side of its second gear is unknown."""
    structure, gears, centres = drawing.structure, drawing.gears, drawing.centres
    g, h = gears[mesh.gears[0]], gears[mesh.gears[1]]
    offset = sympy.expand(centres[h.name] - centres[g.name])
    side = side_of_second(mesh, structure, gears)
    if side is None:
        side = closures.oracle.sign(offset) if offset != 0 else None
        if side not in (1, -1):
            closures.problems.append(
                Problem(
                    f"couplings.{mesh.name}",
                    f"cannot tell on which side of gear {g.name!r} gear {h.name!r} lies "
                    f"(centre offset {offset}): the meshes of carrier "
                    f"{structure.meshes[mesh.name].carrier!r} close "
                    "a loop a line cannot draw; draw the train in 2-D with `placement:`",
                )
            )
            return None
    base = gears[mesh.pitch[0]]
    towards = side if base is g else -side
    ends = [structure.axis[gears[name].axis_link] for name in mesh.gears]
    closures.close(side * offset, mesh.distance, mesh.name, loop=loop_through(drawing.via, ends[0], ends[1], mesh.name))
    return line_point(centres[base.name] + towards * base.radius)


def _other_points(
    train: Train,
    structure: AxisStructure,
    positions: Mapping[str, sympy.Expr],
    meshes: set[str],
    closures: Closures,
) -> dict[str, Vector]:
    """A bearing's point on its axis class (its `at`, where the meshes place that axis too,
    closed as a constraint); any other coupling but the meshes at the origin."""
    stated = {c.name: c.at for c in all_bearings(train.couplings)}
    points: dict[str, Vector] = {}
    for c in train.couplings:
        if c.name in structure.bearing_axis:
            y = positions[structure.bearing_axis[c.name]]
            at = stated.get(c.name)
            if at is not None:
                closures.close(
                    y,
                    at,
                    c.name,
                    f"couplings.{c.name}.at",
                    f"inconsistent geometry: `at` is {at} but the gears put this axis at {y}",
                )
            points[c.name] = line_point(y)
        elif c.name not in meshes:
            points[c.name] = line_point(sympy.Integer(0))
    return points
