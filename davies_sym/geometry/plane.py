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

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.radicals import RadicalError, RadicalTable, has_square_root
from davies_sym.algebra.screws import Vector, vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.axes import AxisStructure
from davies_sym.geometry.layout import Closures, Layout
from davies_sym.geometry.line import side_of_second
from davies_sym.topology.coupling_kinds import bearings as all_bearings
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.model import Gear, Train

Point = tuple[sympy.Expr, sympy.Expr]


def plane_layout(train: Train, direction: Point, structure: AxisStructure) -> Layout:
    """Axis positions, pitch points and constraints of a planar train drawn in 2-D with
    the axis classes of ``structure``; ``direction`` (x, y) is the placement direction
    of the planets."""
    problems: list[Problem] = []
    gears = {g.name: g for g in train.gears}
    meshes = sorted(structure.spacings, key=lambda c: c.name)
    # Known positive: the centre distance of an internal pair, and a radius the geometry
    # writes in others (a coaxial planet's r4 = r3 + r5 - r6).
    known = [m.distance for m in structure.spacings if m.internal]
    known += [g.radius for g in train.gears if g.radius is not None and not g.radius.is_Symbol]
    # An axis the file places at a symbolic distance (a free shape of the drawing) may be
    # drawn on either side of a triangle's base: the side taken is a fact of the design.
    free = frozenset(s for c in all_bearings(train.couplings) if c.at is not None for s in c.at.free_symbols)
    radicals = RadicalTable(facts=known, free=free)
    direction = (radicals.absorb(sympy.sympify(direction[0])), radicals.absorb(sympy.sympify(direction[1])))
    length = radicals.sqrt(sympy.expand(direction[0] ** 2 + direction[1] ** 2))
    unit = (radicals.reduce(direction[0] / length), radicals.reduce(direction[1] / length))
    used: set[str] = set()
    drawing = _Drawing(structure, meshes, gears, unit, radicals, problems, used, set())
    positions = _place_classes(train, drawing)
    if problems:
        raise GeometryError(problems, train.file_lines)
    centres = {g.name: positions[structure.axis[g.axis_link]] for g in train.gears}
    closures = Closures(SignOracle(), problems)
    pitch = _PitchPoints(gears, centres, radicals, closures)
    for mesh in meshes:
        pitch.draw(mesh, mesh.name in used)
    points = pitch.points | _other_points(train, structure, positions, unit, pitch)
    if problems:
        raise GeometryError(problems, train.file_lines)
    return Layout(
        gear_centres={name: vector((*p, 0)) for name, p in centres.items()},
        coupling_points=points,
        mesh_tangents=pitch.tangents,
        mesh_normals=pitch.normals,
        constraints=tuple(closures.constraints),
        positive_facts=tuple(pitch.facts) + tuple(r.radicand for r in radicals.radicals),
        side_facts=tuple(drawing.sides) + tuple(radicals.chosen),
        radicals=tuple(radicals.radicals),
        frame=unit,
        planet_second=structure.planet_second,
    )


@dataclass
class _PitchPoints:
    """The pitch points, tooth-force directions and separating directions of the meshes
    of a 2-D drawing, from the placed centres (the line of centres has the mesh's centre
    distance on an admissible design; a mesh that placed no class closes a loop)."""

    gears: Mapping[str, Gear]
    centres: Mapping[str, Point]
    radicals: RadicalTable
    closures: Closures
    points: dict[str, Vector] = field(default_factory=dict)
    tangents: dict[str, Vector] = field(default_factory=dict)
    normals: dict[str, Vector] = field(default_factory=dict)
    facts: list[sympy.Expr] = field(default_factory=list)

    def draw(self, mesh: AxisSpacing, placed: bool) -> None:
        """Draw ``mesh`` (``placed``: it placed one of its classes, so closes no loop). A
        coupling of a free distance (a chain) locates itself; it cannot close a loop."""
        if not mesh.fixed:
            if not placed:
                self.closures.problems.append(
                    Problem(
                        f"couplings.{mesh.name}",
                        f"the {mesh.noun} joins axes the other couplings place already (it closes a loop of "
                        "couplings); its centre distance is free, so it must place one of them: remove the bearing "
                        "`at` or the mesh that places the other axis",
                    )
                )
            return
        radicals, closures = self.radicals, self.closures
        on, other = self.gears[mesh.pitch[0]], self.gears[mesh.pitch[1]]
        if mesh.internal:
            self.facts.append(on.radius - other.radius)
        base, towards, reach = self.centres[on.name], self.centres[other.name], on.radius
        offset = (radicals.reduce(towards[0] - base[0]), radicals.reduce(towards[1] - base[1]))
        if not placed:
            squared = radicals.reduce(offset[0] ** 2 + offset[1] ** 2)
            try:
                actual = radicals.sqrt(squared)
            except RadicalError:
                # The distance of the placed centres is not q * s (nested roots, or a
                # factor of unknown sign): the mesh then constrains the squared distance,
                # the same condition for the positive lengths of an admissible design.
                actual = None
            if actual is None or has_square_root(radicals.restore(actual)):
                closures.close(squared, mesh.distance**2, mesh.name)
            else:
                closures.close(actual, mesh.distance, mesh.name)
        u = (radicals.reduce(offset[0] / mesh.distance), radicals.reduce(offset[1] / mesh.distance))
        self.points[mesh.name] = radicals.reduced((base[0] + reach * u[0], base[1] + reach * u[1], 0))
        self.tangents[mesh.name] = vector((u[1], -u[0], 0))
        self.normals[mesh.name] = vector((u[0], u[1], 0))


def _other_points(
    train: Train, structure: AxisStructure, positions: Mapping[str, Point], unit: Point, pitch: _PitchPoints
) -> dict[str, Vector]:
    """A bearing's point on its axis class (its `at` along the placement direction, where
    the meshes place that axis too, closed as a constraint); any other coupling but the
    meshes at the origin (a coupling that follows its gears is located later)."""
    stated = {c.name: c.at for c in all_bearings(train.couplings)}
    radicals, points = pitch.radicals, {}
    for c in train.couplings:
        if c.name in structure.bearing_axis:
            point = positions[structure.bearing_axis[c.name]]
            at = stated.get(c.name)
            if at is not None:
                along = radicals.reduce(point[0] * unit[0] + point[1] * unit[1])
                pitch.closures.close(
                    along,
                    at,
                    c.name,
                    f"couplings.{c.name}.at",
                    f"inconsistent geometry: `at` is {at} but the gears put this axis at {along}",
                )
            points[c.name] = vector((*point, 0))
        elif c.name not in pitch.points:
            points[c.name] = vector((0, 0, 0))
    return points


@dataclass(frozen=True)
class _Drawing:
    """What placing the axis classes of a 2-D drawing reads (the axis structure, the
    meshes in name order, the gears, the placement direction, the square roots so far)
    and collects (``problems``; ``used``: the meshes that placed a class; ``bases``: the
    ordered pairs of centres a triangle has closed on; ``sides``: the triangle
    inequalities of the triangles it closes)."""

    structure: AxisStructure
    meshes: Sequence[AxisSpacing]
    gears: Mapping[str, Gear]
    unit: Point
    radicals: RadicalTable
    problems: list[Problem]
    used: set[str]
    bases: set[tuple[Point, Point]]
    sides: list[sympy.Expr] = field(default_factory=list)


def _place_classes(train: Train, drawing: _Drawing) -> dict[str, Point]:
    """The centre of every axis class: the main axis at the origin and the classes whose
    bearing gives `at` along the placement direction, then outward one class at a time
    (meshes in name order): a class meshing two placed classes with distinct centres
    closes a triangle (counter-clockwise of the first mesh's centre to the second's; the
    other side for a second class on the same two centres), any other goes along the
    placement direction (a planet outward of the gear on its carrier's axis, the pinion
    of an internal pair outward of its annulus); a class nothing reaches is on the main
    axis when no gear turns about it. ``used`` collects the meshes that placed a class
    (the others close loops)."""
    structure, unit = drawing.structure, drawing.unit
    zero = (sympy.Integer(0), sympy.Integer(0))
    positions: dict[str, Point] = {structure.root: zero}
    bearings = sorted((c for c in all_bearings(train.couplings) if c.at is not None), key=lambda c: c.name)
    geared = {structure.axis[g.axis_link] for g in train.gears}
    for c in bearings:  # positions the user gives come first
        if structure.bearing_axis[c.name] not in positions and c.at is not None:
            positions[structure.bearing_axis[c.name]] = (c.at * unit[0], c.at * unit[1])
    while True:
        if _place_one(drawing, positions):
            continue
        at = next((c for c in bearings if structure.bearing_axis[c.name] not in positions), None)
        if at is not None and at.at is not None:
            positions[structure.bearing_axis[at.name]] = (at.at * unit[0], at.at * unit[1])
            continue
        rest = [cls for cls in structure.classes() if cls not in positions]
        if not rest:
            return positions
        if rest[0] in geared:
            gear = next(g for g in train.gears if structure.axis[g.axis_link] == rest[0])
            drawing.problems.append(
                Problem(
                    f"gears.{gear.name}",
                    "its position cannot be derived: no mesh connects "
                    "it to the main axis; give a bearing of its link an `at`",
                )
            )
        positions[rest[0]] = zero


def _place_one(drawing: _Drawing, positions: dict[str, Point]) -> bool:
    """Place one class; False when no mesh reaches an unplaced class."""
    structure, gears, unit, radicals = drawing.structure, drawing.gears, drawing.unit, drawing.radicals
    reach: dict[str, list[tuple[Point, sympy.Expr, str]]] = {}
    first: tuple[str, Point, str] | None = None
    for mesh in drawing.meshes:
        ends = [structure.axis[gears[name].axis_link] for name in mesh.gears]
        for k in (0, 1):
            here, there = ends[1 - k], ends[k]
            if here in positions or there not in positions:
                continue
            if mesh.fixed:  # a free distance (a chain) closes no triangle
                reach.setdefault(here, []).append((positions[there], mesh.distance, mesh.name))
            if first is None:
                # ``here`` lies on the side the drawing rules give the mesh's second gear,
                # across the placement direction where the coupling says so (a chain's strand).
                side = side_of_second(mesh, structure, gears)
                step = mesh.distance if side is None else (side if k == 0 else -side) * mesh.distance
                across = mesh.across if k == 0 else -mesh.across
                x, y = positions[there]
                x, y = x + step * unit[0] + across * unit[1], y + step * unit[1] - across * unit[0]
                first = (here, (radicals.reduce(x), radicals.reduce(y)), mesh.name)
    if first is None:
        return False
    # Triangles first: a class that meshes two placed classes on distinct axes.
    for group, options in sorted(reach.items(), key=lambda item: (-len({o[0] for o in item[1]}), item[0])):
        distinct: list[tuple[Point, sympy.Expr, str]] = []
        for option in options:
            if all(any(radicals.reduce(a - b) != 0 for a, b in zip(option[0], o[0], strict=True)) for o in distinct):
                distinct.append(option)
        if len(distinct) >= 2:
            base, other = distinct[0], distinct[1]
            if (base[0], other[0]) in drawing.bases:
                # A second planet meshing the same two gears goes on the other side of
                # their line of centres: the four axes form a convex quadrilateral.
                base, other = other, base
            drawing.bases.add((base[0], other[0]))
            point = _triangle(base, other, radicals, drawing.problems, drawing.sides)
            if point is None:
                return False
            positions[group] = point
            drawing.used.update({distinct[0][2], distinct[1][2]})
            return True
        break
    positions[first[0]] = first[1]
    drawing.used.add(first[2])
    return True


def _triangle(
    first: tuple[Point, sympy.Expr, str],
    second: tuple[Point, sympy.Expr, str],
    radicals: RadicalTable,
    problems: list[Problem],
    sides: list[sympy.Expr],
) -> Point | None:
    """The point at distance d_A from A and d_B from B, counter-clockwise of A -> B; the
    triangle's inequalities (the sum of two sides less the third, positive) go to
    ``sides``."""
    (a, da, mesh_a), (b, db, mesh_b) = first, second
    ab = (radicals.reduce(b[0] - a[0]), radicals.reduce(b[1] - a[1]))
    try:
        length = radicals.sqrt(radicals.reduce(ab[0] ** 2 + ab[1] ** 2))
    except RadicalError as exc:
        problems.append(
            Problem(
                f"couplings.{mesh_b}",
                f"the meshes {mesh_a} and {mesh_b} would close a "
                f"triangle whose side is not known to be real ({exc}); give the radii as "
                "numbers, or draw the train with another placement",
            )
        )
        return None
    along = radicals.reduce((da**2 - db**2 + length**2) / (2 * length))
    roots = {r.symbol for r in radicals.radicals}
    if (sympy.sympify(along).free_symbols | sympy.sympify(length).free_symbols) & roots:
        problems.append(
            Problem(
                f"couplings.{mesh_b}", "this planet would sit on nested square roots; give the train another placement"
            )
        )
        return None
    try:
        height = radicals.sqrt(radicals.reduce(da**2 - along**2))
    except RadicalError as exc:
        problems.append(
            Problem(f"couplings.{mesh_b}", f"the meshes {mesh_a} and {mesh_b} cannot close a triangle: {exc}")
        )
        return None
    for side, others in ((length, da + db), (da, db + length), (db, da + length)):
        excess = sympy.expand(radicals.reduce(others - side))
        if not excess.is_number:
            sides.append(excess)
    u = (radicals.reduce(ab[0] / length), radicals.reduce(ab[1] / length))
    return (radicals.reduce(a[0] + along * u[0] - height * u[1]), radicals.reduce(a[1] + along * u[1] + height * u[0]))
