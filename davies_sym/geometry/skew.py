"""Layout of trains with a mesh on skew axes (worm and wheel, crossed helical gears).

The gears on parallel axes are laid out as usual (on a line or in the plane, axes along
z).  The first gear of each skew mesh (the worm) sits on a link of its own, whose axis
crosses the second gear's (the wheel's) at the shaft angle beta_1 + beta_2, at the
centre distance r_1 + r_2 along x from the wheel's axis: the pitch point is on the
wheel's pitch cylinder at +x.  There the tooth line makes the helix angle beta_2 with
the wheel's axis, and the normal leans by the normal pressure angle out of the pitch
plane (the plane normal to x).  The network then needs every screw: the layout is
spatial, and a spur mesh becomes a point contact (`Layout.spatial`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace

import sympy

from davies_sym.algebra.screws import Vector, vector
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.layout import X_AXIS, Layout
from davies_sym.topology.coupling_kinds import CouplingsByKind
from davies_sym.topology.model import Gear, Train
from davies_sym.topology.revolute import Revolute
from davies_sym.topology.skew_mesh import SkewMesh


def skew_layout(train: Train, kinds: CouplingsByKind, parallel: Callable[[Train], Layout]) -> Layout:
    """The layout of ``train`` (its couplings split by ``kinds``): its parallel-axis part by
    ``parallel``, then each worm link placed across its wheel's axis."""
    meshes = sorted(kinds.skew, key=lambda c: c.name)
    gears = {g.name: g for g in train.gears}
    worms = {gears[m.gears[0]].link: m for m in meshes}
    _check_worm_links(train, kinds.bearings, gears, meshes, worms)
    rest = _parallel_part(train, set(worms))
    layout = parallel(rest)
    if layout.axis != vector((0, 0, 1)) or layout.gear_axes:
        raise GeometryError(
            [Problem(f"couplings.{meshes[0].name}", "a skew mesh needs a wheel on a parallel-axis train")],
            train.file_lines,
        )
    centres, gear_axes = dict(layout.gear_centres), dict(layout.gear_axes)
    points, coupling_axes = dict(layout.coupling_points), dict(layout.coupling_axes)
    tangents, normals = dict(layout.mesh_tangents), dict(layout.mesh_normals)
    for link, mesh in worms.items():
        worm, wheel = gears[mesh.gears[0]], gears[mesh.gears[1]]
        assert mesh.helix is not None and mesh.pressure is not None
        first, second = mesh.helix
        centre = centres[wheel.name]
        pitch_point = _plus(centre, wheel.radius, X_AXIS)
        worm_centre = _plus(centre, sympy.expand(wheel.radius + worm.radius), X_AXIS)
        # The shaft angle is beta_1 + beta_2; its cos and sin in the helix angles' functions.
        sin_shaft = sympy.Integer(1) if mesh.right_shaft_angle else first.sin * second.cos + first.cos * second.sin
        cos_shaft = sympy.Integer(0) if mesh.right_shaft_angle else first.cos * second.cos - first.sin * second.sin
        worm_axis = vector((0, sin_shaft, cos_shaft))
        tooth_line = vector((0, second.sin, second.cos))
        in_pitch_plane = vector((0, second.cos, -second.sin))
        c, s = mesh.pressure.cos, mesh.pressure.sin
        normal = vector((s, c * in_pitch_plane[1], c * in_pitch_plane[2]))
        centres[worm.name], gear_axes[worm.name] = worm_centre, worm_axis
        points[mesh.name], tangents[mesh.name], normals[mesh.name] = pitch_point, tooth_line, normal
        for bearing in _bearings(kinds.bearings, link):
            points[bearing.name], coupling_axes[bearing.name] = worm_centre, worm_axis
    return replace(
        layout,
        gear_centres=centres,
        gear_axes=gear_axes,
        coupling_points=points,
        coupling_axes=coupling_axes,
        mesh_tangents=tangents,
        mesh_normals=normals,
        spatial=True,
    )


def _plus(point: Vector, distance: sympy.Expr, direction: Vector) -> Vector:
    return vector([sympy.expand(p + distance * d) for p, d in zip(point, direction, strict=True)])


def _bearings(bearings: Sequence[Revolute], link: str) -> list[Revolute]:
    return [c for c in bearings if link in c.links]


def _check_worm_links(
    train: Train,
    revolutes: Sequence[Revolute],
    gears: Mapping[str, Gear],
    meshes: list[SkewMesh],
    worms: dict[str, SkewMesh],
) -> None:
    """A worm's link carries that worm only and turns in bearings on the worm's axis; the
    wheel is on the parallel-axis part of the train."""
    problems: list[Problem] = []
    seen: dict[str, str] = {}
    allowed = {c.name for c in revolutes} | {m.name for m in meshes}
    for mesh in meshes:
        worm, wheel = gears[mesh.gears[0]], gears[mesh.gears[1]]
        entry = f"couplings.{mesh.name}.gears"
        if worm.link in seen:
            problems.append(
                Problem(entry, f"link {worm.link!r} already carries the first gear of mesh {seen[worm.link]}")
            )
            continue
        seen[worm.link] = mesh.name
        if worm.link == train.reference:
            problems.append(
                Problem(entry, f"the first gear {worm.name!r} is on the reference link; write the wheel first")
            )
        others = [g.name for g in train.gears if g.link == worm.link and g.name != worm.name]
        if others:
            problems.append(
                Problem(
                    entry,
                    f"link {worm.link!r} of the first gear {worm.name!r} also carries {', '.join(others)}: put the "
                    "worm (or first crossed helical gear) on a link of its own, joined to its shaft by a revolute",
                )
            )
        if wheel.link in worms:
            problems.append(
                Problem(entry, f"the second gear {wheel.name!r} is on the worm link of mesh {worms[wheel.link].name}")
            )
        bearings = _bearings(revolutes, worm.link)
        if not bearings:
            problems.append(Problem(entry, f"link {worm.link!r} of {worm.name!r} needs a revolute (its bearing)"))
        for bearing in bearings:
            other = bearing.links[1] if bearing.links[0] == worm.link else bearing.links[0]
            if other in worms:
                problems.append(
                    Problem(f"couplings.{bearing.name}", "a revolute between two worm links is not supported")
                )
        for c in train.couplings:
            if worm.link in c.links and c.name not in allowed:
                problems.append(
                    Problem(f"couplings.{c.name}", f"link {worm.link!r} of a worm joins only revolutes and its mesh")
                )
    if problems:
        raise GeometryError(problems, train.file_lines)


def _parallel_part(train: Train, worm_links: set[str]) -> Train:
    """``train`` without the worm links, their gears and their couplings (its ports may
    name a removed coupling: the layout never reads them)."""
    return replace(
        train,
        links=tuple(k for k in train.links if k.name not in worm_links),
        gears=tuple(g for g in train.gears if g.link not in worm_links),
        couplings=tuple(c for c in train.couplings if not set(c.links) & worm_links),
        states=(),
    )
