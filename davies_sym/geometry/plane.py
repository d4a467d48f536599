"""Layout of planar trains in their true 2-D arrangement (Laus section 2.2, {t; u, v}).

Planet-planet meshes (Ravigneaux sets, double-pinion planetaries) put planet centres off
the line through the main axis.  Axis positions follow from the meshes: a gear link
meshing one placed gear goes along the placement direction (the angle at which the
planet set is drawn); one meshing two placed gears with distinct centres closes a
triangle (centre distances r_g + r_h external, R - r internal, counter-clockwise side).
A mesh that closes a loop otherwise gives a geometric constraint, as on the line.
Square roots of the triangles stay exact as radical symbols.  Pitch point, tooth-force
direction (normal to the line of centres) and separating direction follow from the
centres, so every screw lies in the planar 3-system {t; u, v}: the efficiency must not
depend on the placement direction.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.algebra.radicals import RadicalTable, has_square_root
from davies_sym.algebra.screws import Vector, vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.layout import GeometricConstraint, Layout, add_constraint, axis_groups, check_placed
from davies_sym.topology.couplings import GearMesh, Revolute
from davies_sym.topology.link_groups import LinkGroups
from davies_sym.topology.model import Gear, Train

Point = tuple[sympy.Expr, sympy.Expr]


def _centre_distance(mesh: GearMesh, gears: Mapping[str, Gear]) -> sympy.Expr:
    g, h = gears[mesh.gears[0]], gears[mesh.gears[1]]
    if mesh.internal:
        ann, pin = (g, h) if g.internal else (h, g)
        return sympy.expand(ann.radius - pin.radius)
    return sympy.expand(g.radius + h.radius)


def plane_layout(train: Train, direction: Point) -> Layout:
    """Axis positions, pitch points and constraints of a planar train drawn in 2-D;
    ``direction`` (x, y) is the placement direction of the planets."""
    problems: list[Problem] = []
    radicals = RadicalTable()
    direction = (radicals.absorb(sympy.sympify(direction[0])), radicals.absorb(sympy.sympify(direction[1])))
    length = radicals.sqrt(sympy.expand(direction[0] ** 2 + direction[1] ** 2))
    unit = (radicals.reduce(direction[0] / length), radicals.reduce(direction[1] / length))
    geared, groups = axis_groups(train)
    gears = {g.name: g for g in train.gears}
    meshes = [c for c in train.couplings if isinstance(c, GearMesh)]
    positions: dict[str, Point] = {}
    root = train.reference if train.reference in geared else (train.gears[0].link if train.gears else None)
    if root is not None:
        positions[groups.find(root)] = (sympy.Integer(0), sympy.Integer(0))
    for c in train.couplings:
        if isinstance(c, Revolute) and c.at is not None and c.axis is None:
            for link in c.links:
                if link in geared and groups.find(link) not in positions:
                    positions[groups.find(link)] = (c.at * unit[0], c.at * unit[1])
    used = _place(meshes, gears, groups, positions, unit, radicals, train, problems)
    check_placed(train, groups, positions, problems)
    oracle = SignOracle()
    centres = {g.name: positions[groups.find(g.link)] for g in train.gears}
    points: dict[str, Vector] = {}
    tangents: dict[str, Vector] = {}
    normals: dict[str, Vector] = {}
    constraints: list[GeometricConstraint] = []
    facts: list[sympy.Expr] = []
    for mesh in meshes:
        g, h = gears[mesh.gears[0]], gears[mesh.gears[1]]
        distance = _centre_distance(mesh, gears)
        if mesh.internal:
            ann, pin = (g, h) if g.internal else (h, g)
            facts.append(ann.radius - pin.radius)
            base, towards, reach = centres[ann.name], centres[pin.name], ann.radius
        else:
            base, towards, reach = centres[g.name], centres[h.name], g.radius
        offset = (radicals.reduce(towards[0] - base[0]), radicals.reduce(towards[1] - base[1]))
        if mesh.name not in used:
            squared = radicals.reduce(offset[0] ** 2 + offset[1] ** 2)
            try:
                actual = radicals.sqrt(squared)
            except ValueError:
                actual = None
            if actual is None or has_square_root(radicals.restore(actual)):
                add_constraint(train, constraints, problems, squared, distance**2, mesh.name, oracle)
            else:
                add_constraint(train, constraints, problems, actual, distance, mesh.name, oracle)
        # The line of centres has length `distance` on an admissible design.
        u = (radicals.reduce(offset[0] / distance), radicals.reduce(offset[1] / distance))
        points[mesh.name] = vector((radicals.reduce(base[0] + reach * u[0]),
                                    radicals.reduce(base[1] + reach * u[1]), 0))
        tangents[mesh.name] = vector((u[1], -u[0], 0))
        normals[mesh.name] = vector((u[0], u[1], 0))
    for c in train.couplings:
        if isinstance(c, Revolute):
            on = [c.axis] if c.axis is not None else list(c.links)
            placed = [positions[groups.find(link)] for link in on if link in geared]
            if placed:
                points[c.name] = vector((*placed[0], 0))
            elif c.at is not None:
                points[c.name] = vector((c.at * unit[0], c.at * unit[1], 0))
            else:
                problems.append(train.problem(f"couplings.{c.name}", f"neither link {c.links[0]!r} nor "
                                              f"{c.links[1]!r} carries a gear: give the position of this revolute "
                                              "with `at`"))
        elif not isinstance(c, GearMesh):
            points[c.name] = vector((0, 0, 0))
    if problems:
        raise GeometryError(problems, train.path)
    return Layout(
        gear_centres={name: vector((*p, 0)) for name, p in centres.items()},
        coupling_points=points,
        mesh_tangents=tangents,
        mesh_normals=normals,
        constraints=tuple(constraints),
        positive_facts=tuple(facts) + tuple(r.radicand for r in radicals.radicals),
        radicals=tuple(radicals.radicals),
    )


def _place(meshes: list[GearMesh], gears: Mapping[str, Gear], groups: LinkGroups, positions: dict[str, Point],
           unit: Point, radicals: RadicalTable, train: Train, problems: list[Problem]) -> set[str]:
    """Place axis groups outward from the placed ones; returns the meshes used."""
    used: set[str] = set()
    progress = True
    while progress:
        progress = False
        reach: dict[str, list[tuple[Point, sympy.Expr, str]]] = {}
        for mesh in meshes:
            ends = [groups.find(gears[name].link) for name in mesh.gears]
            for here, there in (ends, ends[::-1]):
                if here not in positions and there in positions:
                    reach.setdefault(here, []).append((positions[there], _centre_distance(mesh, gears), mesh.name))
        # Triangles first: a group that meshes two placed gears on distinct axes.
        for group, options in sorted(reach.items(), key=lambda item: -len({o[0] for o in item[1]})):
            distinct = []
            for option in options:
                if all(any(radicals.reduce(a - b) != 0 for a, b in zip(option[0], o[0], strict=True))
                       for o in distinct):
                    distinct.append(option)
            if len(distinct) >= 2:
                point = _triangle(distinct[0], distinct[1], radicals, train, problems)
                if point is None:
                    continue
                positions[group] = point
                used |= {distinct[0][2], distinct[1][2]}
            else:
                (centre, distance, name) = options[0]
                positions[group] = (radicals.reduce(centre[0] + distance * unit[0]),
                                    radicals.reduce(centre[1] + distance * unit[1]))
                used.add(name)
            progress = True
            break
    return used


def _triangle(first: tuple[Point, sympy.Expr, str], second: tuple[Point, sympy.Expr, str], radicals: RadicalTable,
              train: Train, problems: list[Problem]) -> Point | None:
    """The point at distance d_A from A and d_B from B, counter-clockwise of A -> B."""
    (a, da, mesh_a), (b, db, mesh_b) = first, second
    ab = (radicals.reduce(b[0] - a[0]), radicals.reduce(b[1] - a[1]))
    length = radicals.sqrt(radicals.reduce(ab[0] ** 2 + ab[1] ** 2))
    along = radicals.reduce((da**2 - db**2 + length**2) / (2 * length))
    roots = {r.symbol for r in radicals.radicals}
    if (sympy.sympify(along).free_symbols | sympy.sympify(length).free_symbols) & roots:
        problems.append(train.problem(f"couplings.{mesh_b}", "this planet would sit on nested square roots; "
                                      "give the train another placement"))
        return None
    try:
        height = radicals.sqrt(radicals.reduce(da**2 - along**2))
    except ValueError as exc:
        problems.append(train.problem(f"couplings.{mesh_b}", f"the meshes {mesh_a} and {mesh_b} cannot close a "
                                      f"triangle: {exc}"))
        return None
    u = (radicals.reduce(ab[0] / length), radicals.reduce(ab[1] / length))
    return (radicals.reduce(a[0] + along * u[0] - height * u[1]), radicals.reduce(a[1] + along * u[1] + height * u[0]))
