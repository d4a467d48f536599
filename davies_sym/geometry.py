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
from dataclasses import dataclass, field

import sympy

from .coupling_graph import LinkGroups
from .couplings import GearMesh, Revolute
from .errors import GeometryError, Problem
from .model import Gear, Train
from .radicals import Radical, RadicalTable
from .screws import Vector, cross, vector
from .signs import SignOracle

Z_AXIS: Vector = vector((0, 0, 1))
X_AXIS: Vector = vector((1, 0, 0))
Y_AXIS: Vector = vector((0, 1, 0))


@dataclass(frozen=True)
class GeometricConstraint:
    """An equation the radii must satisfy, ``lhs = rhs``, and the mesh that closes it."""

    lhs: sympy.Expr
    rhs: sympy.Expr
    coupling: str

    @property
    def expression(self) -> sympy.Expr:
        """``lhs - rhs``, which must vanish."""
        return sympy.expand(self.lhs - self.rhs)

    def __str__(self) -> str:
        return f"{sympy.sstr(self.lhs)} = {sympy.sstr(self.rhs)}"


@dataclass(frozen=True)
class Layout:
    """Positions and directions the coupling kinds need to write their screws."""

    gear_centres: Mapping[str, Vector]
    coupling_points: Mapping[str, Vector]
    mesh_tangents: Mapping[str, Vector]
    mesh_normals: Mapping[str, Vector]
    constraints: tuple[GeometricConstraint, ...]
    #: Expressions known to be positive, e.g. R - r of every internal mesh.
    positive_facts: tuple[sympy.Expr, ...] = ()
    axis: Vector = Z_AXIS
    #: Axis direction of each gear and of each coupling's rotation, where it is not ``axis``
    #: (intersecting-axis trains).
    gear_axes: Mapping[str, Vector] = field(default_factory=dict)
    coupling_axes: Mapping[str, Vector] = field(default_factory=dict)
    #: Square roots the positions use, as symbols with their radicands (tilted axes).
    radicals: tuple[Radical, ...] = ()


def _point(y: sympy.Expr) -> Vector:
    return vector((0, y, 0))


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
            points[mesh.name] = _point(centres[ann.name] + ann.radius)
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
            points[mesh.name] = _point(centres[g.name] + (side or 1) * g.radius)
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
        gear_centres={name: _point(y) for name, y in centres.items()},
        coupling_points=points,
        mesh_tangents={m.name: X_AXIS for m in meshes},
        mesh_normals={m.name: Y_AXIS for m in meshes},
        constraints=tuple(constraints),
        positive_facts=tuple(facts),
    )


def axis_groups(train: Train) -> tuple[set[str], LinkGroups]:
    """The geared links, and the groups of them that share one axis (joined by a revolute
    that names no axis: coaxial members)."""
    geared = {g.link for g in train.gears}
    groups = LinkGroups(list(train.link_names))
    for c in train.couplings:
        if isinstance(c, Revolute) and c.axis is None and c.links[0] in geared and c.links[1] in geared:
            groups.union(*c.links)
    return geared, groups


def check_placed(train: Train, groups: LinkGroups, positions: Mapping[str, object], problems: list[Problem]) -> None:
    """Every gear's axis group has a position, or the layout fails with all problems."""
    for g in train.gears:
        if groups.find(g.link) not in positions:
            problems.append(train.problem(
                f"gears.{g.name}", "its position cannot be derived: no mesh or revolute with `at` connects it "
                "to the rest of the train"))
    if problems:
        raise GeometryError(problems, train.path)


def constraint_substitutions(constraints: tuple[GeometricConstraint, ...]) -> list[dict[sympy.Symbol, sympy.Expr]]:
    """Every way to eliminate one symbol with one linear constraint: r1 - r3 = r2 - r4
    gives r4 -> r2 + r3 - r1, r1 -> r2 + r3 - r4, ..."""
    out = []
    for c in constraints:
        expr = c.expression
        for s in sorted(expr.free_symbols, key=str):
            if sympy.degree(expr, s) == 1:
                solved = sympy.solve(expr, s)
                if len(solved) == 1:
                    out.append({s: sympy.expand(solved[0])})
    return out


def joint_substitution(constraints: tuple[GeometricConstraint, ...]) -> dict[sympy.Symbol, sympy.Expr]:
    """One symbol eliminated per constraint, all at once (r4 -> r2 + r3 - r1, rb -> ...),
    so that a sign needing several constraints together can be decided."""
    eliminated: dict[sympy.Symbol, sympy.Expr] = {}
    for constraint in constraints:
        # Prefer eliminating a symbol that is a positive combination of the others
        # (the annulus: ra -> sa + 2 pa), so that positivity arguments still apply.
        options = sorted(constraint_substitutions((constraint,)),
                         key=lambda sub: not all(c > 0 for c in sympy.Poly(*sub.values()).coeffs()))
        for substitution in options:
            (symbol, expr), = substitution.items()
            expr = sympy.expand(expr.subs(eliminated))
            if symbol not in eliminated and symbol not in expr.free_symbols:
                eliminated = {k: sympy.expand(v.subs(symbol, expr)) for k, v in eliminated.items()}
                eliminated[symbol] = expr
                break
    return eliminated


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


def add_constraint(train: Train, constraints: list[GeometricConstraint], problems: list[Problem], offset: sympy.Expr,
                    distance: sympy.Expr, coupling: str, oracle: SignOracle, entry: str | None = None,
                    message: str | None = None) -> None:
    """``offset = distance`` holds, is impossible (a problem), or is a constraint on the radii."""
    difference = sympy.expand(offset - distance)
    if difference == 0:
        return
    if difference.is_number or oracle.sign(difference) in (1, -1):
        problems.append(train.problem(
            entry or f"couplings.{coupling}",
            message or f"inconsistent geometry: the centre distance this coupling needs ({distance}) "
            f"differs from the one the other couplings give ({offset})"))
        return
    constraints.append(GeometricConstraint(offset, sympy.expand(distance), coupling))


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
        return _point(derived[0])
    if c.at is None:
        problems.append(train.problem(
            f"couplings.{c.name}",
            f"neither link {c.links[0]!r} nor {c.links[1]!r} carries a gear: give the position of this "
            "revolute with `at`"))
        return None
    return _point(c.at)


def train_layout(train: Train) -> Layout:
    """The layout of ``train``: conical when its gears give axis directions, else planar."""
    if any(g.axis is not None or g.tilted for g in train.gears):
        return conical_layout(train)
    if train.placement is not None:
        from .plane_layout import plane_layout  # the plane layout builds on this module

        return plane_layout(train, train.placement)
    return planar_line_layout(train)


def _norm_squared(v: Vector) -> sympy.Expr:
    return sympy.expand(sum(x**2 for x in v))


def _unit(v: Vector, radicals: RadicalTable) -> Vector:
    norm = radicals.sqrt(_norm_squared(v))
    return vector([radicals.reduce(x / norm) for x in v])


def _dot(a: Vector, b: Vector) -> sympy.Expr:
    return sympy.expand(sum(x * y for x, y in zip(a, b, strict=True)))


def _link_axes(train: Train, radicals: RadicalTable, problems: list[Problem]) -> dict[str, Vector]:
    """Unit axis direction of every geared link: given ones first, then tilted planets."""
    axes: dict[str, Vector] = {}
    for g in train.gears:
        if g.axis is None:
            continue
        axis = _unit(vector([radicals.absorb(x) for x in g.axis]), radicals)
        previous = axes.get(g.link)
        if previous is not None and any(radicals.reduce(x) != 0 for x in cross(previous, axis)):
            problems.append(train.problem(f"gears.{g.name}.axis", f"gears of link {g.link!r} must share one axis"))
        axes.setdefault(g.link, axis)
    for g in train.gears:
        if g.tilted and g.link not in axes:
            axis = _tilted_axis(train, g, axes, radicals, problems)
            if axis is not None:
                axes[g.link] = axis
    tilted_links = {g.link for g in train.gears if g.tilted}
    for g in train.gears:
        if g.link not in axes and g.link not in tilted_links:  # a failed tilt is reported already
            problems.append(train.problem(f"gears.{g.name}.axis", "in a train with intersecting axes every gear "
                                          "needs its axis direction (a direction, or `tilted`)"))
    return axes


def _tilted_axis(train: Train, gear: Gear, axes: Mapping[str, Vector], radicals: RadicalTable,
                 problems: list[Problem]) -> Vector | None:
    """Axis of a bevel planet meshing two coaxial gears A and B that face each other.

    The pitch points on A and B are the ends of a diameter of the planet's pitch circle,
    at r_A and r_B from the main axis, so the diameter makes the angle beta with the
    radial direction e, cos beta = (r_B - r_A) / (2 r_p) (Laus App. C); the planet axis is
    perpendicular to it: p = (sqrt(4 r_p^2 - (r_B - r_A)^2) e - (r_B - r_A) a_B) / (2 r_p).
    """
    entry = f"gears.{gear.name}.axis"
    partners = []
    for c in train.couplings:
        if isinstance(c, GearMesh) and gear.name in c.gears:
            other = train.gear(c.gears[1] if c.gears[0] == gear.name else c.gears[0])
            if other.link in axes:
                partners.append(other)
    if len(partners) != 2:
        problems.append(train.problem(entry, f"a tilted axis needs two meshes with gears of known axes, "
                                      f"found {len(partners)}"))
        return None
    a, b = (axes[p.link] for p in partners)
    if any(radicals.reduce(x + y) != 0 for x, y in zip(a, b, strict=True)):
        problems.append(train.problem(entry, f"a tilted axis needs gears {partners[0].name!r} and "
                                      f"{partners[1].name!r} on one axis, facing each other "
                                      "(opposite axis directions)"))
        return None
    radial = Y_AXIS if any(x != 0 for x in cross(b, Y_AXIS)) else X_AXIS
    radial = vector([sympy.expand(x - _dot(radial, b) * y) for x, y in zip(radial, b, strict=True)])
    step = sympy.expand(partners[1].radius - partners[0].radius)
    rp = gear.radius
    try:
        rise = radicals.sqrt(4 * rp**2 - step**2)
    except ValueError as exc:
        problems.append(train.problem(entry, f"the cone geometry cannot be built: {exc}"))
        return None
    return vector([radicals.reduce((rise * e - step * z) / (2 * rp)) for e, z in zip(radial, b, strict=True)])


def conical_layout(train: Train) -> Layout:
    """Bevel and face-gear trains whose axes all meet at the origin (Laus section 3.5).

    A mesh of gears with unit axes a, b and pitch radii r_a, r_b has its pitch point in the
    plane of the axes, at r_a from axis a and r_b from axis b: P = (r_b a + r_a b) / sin S,
    S the angle between the axes (Laus eqs. (80)-(84), App. C).  The relative motion is a
    rotation about the line OP (the pitch cones roll), the tooth force acts at P along
    a x b, and a bearing turns about the axis of the gears of its link.  Square roots
    (tilted axes) stay exact as radical symbols; a gear meshing twice must have both
    pitch points on one pitch circle (equal cone distances).
    """
    problems: list[Problem] = []
    radicals = RadicalTable()
    axes = _link_axes(train, radicals, problems)
    if problems:
        raise GeometryError(problems, train.path)
    gear_axes = {g.name: axes[g.link] for g in train.gears}
    origin = vector((0, 0, 0))
    points: dict[str, Vector] = {}
    coupling_axes: dict[str, Vector] = {}
    tangents: dict[str, Vector] = {}
    cone_distance: dict[str, tuple[str, sympy.Expr]] = {}
    for c in train.couplings:
        if isinstance(c, GearMesh):
            g, h = (train.gear(n) for n in c.gears)
            a, b = gear_axes[g.name], gear_axes[h.name]
            normal = vector([radicals.reduce(x) for x in cross(a, b)])
            if all(x == 0 for x in normal):
                problems.append(train.problem(f"couplings.{c.name}", "the gear axes are parallel: give the train "
                                              "without axis directions (planar layout)"))
                continue
            sin = radicals.sqrt(_norm_squared(normal))
            pitch = vector([radicals.reduce((h.radius * x + g.radius * y) / sin) for x, y in zip(a, b, strict=True)])
            points[c.name] = pitch
            coupling_axes[c.name] = pitch
            tangents[c.name] = vector([radicals.reduce(x / sin) for x in normal])
            distance = radicals.reduce(_norm_squared(pitch))
            for gear in (g, h):
                if gear.name in cone_distance:
                    other, previous = cone_distance[gear.name]
                    if radicals.reduce(distance - previous) != 0:
                        problems.append(train.problem(
                            f"couplings.{c.name}",
                            f"inconsistent geometry: gear {gear.name!r} meshes here at cone distance "
                            f"sqrt({radicals.restore(distance)}) and in {other!r} at "
                            f"sqrt({radicals.restore(previous)}); one gear has one pitch circle"))
                else:
                    cone_distance[gear.name] = (c.name, distance)
        elif isinstance(c, Revolute):
            on = [c.axis] if c.axis is not None else [link for link in c.links if link in axes]
            if not on or on[0] not in axes:
                problems.append(train.problem(f"couplings.{c.name}", "neither link carries a gear: this bearing's "
                                              "axis direction is unknown"))
                continue
            points[c.name] = origin
            coupling_axes[c.name] = axes[on[0]]
        else:
            points[c.name] = origin
    if problems:
        raise GeometryError(problems, train.path)
    return Layout(
        gear_centres={g.name: origin for g in train.gears},
        coupling_points=points,
        mesh_tangents=tangents,
        mesh_normals={name: p for name, p in coupling_axes.items() if name in tangents},
        constraints=(),
        positive_facts=tuple(r.radicand for r in radicals.radicals),
        gear_axes=gear_axes,
        coupling_axes=coupling_axes,
        radicals=tuple(radicals.radicals),
    )
