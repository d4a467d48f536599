"""Layout of trains whose gear axes meet at one apex: bevel and face-gear trains
(Laus section 3.4.2 and App. C, Chen Fig. 4.10).

The pitch point of each mesh lies on both pitch cones; the relative rotation is about
the line from the apex to it, the tooth force along the common normal.  A tilted planet
(``axis: tilted``) takes its axis from the two coaxial gears it meshes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.radicals import RadicalError, RadicalTable
from davies_sym.algebra.screws import Vector, cross, vector
from davies_sym.errors import GeometryError, Problem
from davies_sym.geometry.axes import axis_structure
from davies_sym.geometry.layout import X_AXIS, Y_AXIS, Layout
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.model import Gear, Train


def _norm_squared(v: Vector) -> sympy.Expr:
    return sympy.expand(sum(x**2 for x in v))


def _unit(v: Vector, radicals: RadicalTable) -> Vector:
    squared = _norm_squared(v)
    norm = radicals.sqrt(squared)
    return radicals.reduced(x / norm for x in v)


def _dot(a: Vector, b: Vector) -> sympy.Expr:
    return sympy.expand(sum(x * y for x, y in zip(a, b, strict=True)))


def _link_axes(
    train: Train,
    gears: Mapping[str, Gear],
    spaced: Sequence[AxisSpacing],
    radicals: RadicalTable,
    problems: list[Problem],
) -> dict[str, Vector]:
    """Unit axis direction of every geared link (``gears``: the train's, by name;
    ``spaced``: its `spacings`): given ones first, then tilted planets."""
    axes: dict[str, Vector] = {}
    for g in train.gears:
        if g.axis is None:
            continue
        axis = _unit(vector([radicals.absorb(x) for x in g.axis]), radicals)
        previous = axes.get(g.link)
        if previous is not None and any(radicals.reduce(x) != 0 for x in cross(previous, axis)):
            problems.append(Problem(f"gears.{g.name}.axis", f"gears of link {g.link!r} must share one axis"))
        axes.setdefault(g.link, axis)
    for g in train.gears:
        if g.tilted and g.link not in axes:
            tilted = _tilted_axis(spaced, gears, g, axes, radicals, problems)
            if tilted is not None:
                axes[g.link] = tilted
    tilted_links = {g.link for g in train.gears if g.tilted}
    for g in train.gears:
        if g.link not in axes and g.link not in tilted_links:  # a failed tilt is reported already
            problems.append(
                Problem(
                    f"gears.{g.name}.axis",
                    "in a train with intersecting axes every gear needs its axis direction (a direction, or `tilted`)",
                )
            )
    return axes


def _tilted_axis(
    spaced: Sequence[AxisSpacing],
    gears: Mapping[str, Gear],
    gear: Gear,
    axes: Mapping[str, Vector],
    radicals: RadicalTable,
    problems: list[Problem],
) -> Vector | None:
    """Axis of a bevel planet meshing two coaxial gears A and B that face each other.

    The pitch points on A and B are the ends of a diameter of the planet's pitch circle,
    at r_A and r_B from the main axis, so the diameter makes the angle beta with the
    radial direction e, cos beta = (r_B - r_A) / (2 r_p) (Laus App. C); the planet axis is
    perpendicular to it: p = (sqrt(4 r_p^2 - (r_B - r_A)^2) e - (r_B - r_A) a_B) / (2 r_p).
    """
    entry = f"gears.{gear.name}.axis"
    partners = []
    for c in spaced:
        if gear.name in c.gears:
            other = gears[c.gears[1] if c.gears[0] == gear.name else c.gears[0]]
            if other.link in axes:
                partners.append(other)
    if len(partners) != 2:
        problems.append(
            Problem(entry, f"a tilted axis needs two meshes with gears of known axes, found {len(partners)}")
        )
        return None
    a, b = (axes[p.link] for p in partners)
    if any(radicals.reduce(x + y) != 0 for x, y in zip(a, b, strict=True)):
        problems.append(
            Problem(
                entry,
                f"a tilted axis needs gears {partners[0].name!r} and "
                f"{partners[1].name!r} on one axis, facing each other "
                "(opposite axis directions)",
            )
        )
        return None
    radial = Y_AXIS if any(x != 0 for x in cross(b, Y_AXIS)) else X_AXIS
    radial = vector([sympy.expand(x - _dot(radial, b) * y) for x, y in zip(radial, b, strict=True)])
    step = sympy.expand(partners[1].radius - partners[0].radius)
    rp = gear.radius
    try:
        rise = radicals.sqrt(4 * rp**2 - step**2)
    except RadicalError as exc:
        problems.append(Problem(entry, f"the cone geometry cannot be built: {exc}"))
        return None
    return radicals.reduced((rise * e - step * z) / (2 * rp) for e, z in zip(radial, b, strict=True))


def conical_layout(train: Train, spaced: Sequence[AxisSpacing]) -> Layout:
    """Bevel and face-gear trains whose axes all meet at the origin (Laus section 3.5).

    A mesh of gears with unit axes a, b and pitch radii r_a, r_b has its pitch point in the
    plane of the axes, at r_a from axis a and r_b from axis b: P = (r_b a + r_a b) / sin S,
    S the angle between the axes (Laus eqs. (80)-(84), App. C).  The relative motion is a
    rotation about the line OP (the pitch cones roll), the tooth force acts at P along
    a x b, and a bearing turns about the axis of the gears of its link.  Square roots
    (tilted axes) stay exact as radical symbols; a gear meshing twice must have both
    pitch points on one pitch circle (equal cone distances).  ``spaced``: the train's
    `spacings`.
    """
    problems: list[Problem] = []
    radicals = RadicalTable()
    gears = {g.name: g for g in train.gears}
    axes = _link_axes(train, gears, spaced, radicals, problems)
    if problems:
        raise GeometryError(problems, train.file_lines)
    cones = _Cones(gears, {g.name: axes[g.link] for g in train.gears}, radicals, problems)
    meshes = {m.name: m for m in spaced}
    structure = axis_structure(train, spaced)
    origin = vector((0, 0, 0))
    for c in train.couplings:
        if c.name in meshes:
            cones.draw(meshes[c.name])
        elif c.name in structure.bearing_axis:
            # The bearing turns about the axis of the link it holds (its axis class).
            holder = next(
                (link for link in sorted(axes) if structure.axis[link] == structure.bearing_axis[c.name]), None
            )
            if holder is None:
                problems.append(
                    Problem(f"couplings.{c.name}", "no gear turns about this bearing's axis: its direction is unknown")
                )
                continue
            cones.points[c.name] = origin
            cones.coupling_axes[c.name] = axes[holder]
        else:
            cones.points[c.name] = origin
    if problems:
        raise GeometryError(problems, train.file_lines)
    return Layout(
        gear_centres={g.name: origin for g in train.gears},
        coupling_points=cones.points,
        mesh_tangents=cones.tangents,
        mesh_normals={name: p for name, p in cones.coupling_axes.items() if name in cones.tangents},
        constraints=(),
        positive_facts=tuple(r.radicand for r in radicals.radicals),
        gear_axes=cones.gear_axes,
        coupling_axes=cones.coupling_axes,
        radicals=tuple(radicals.radicals),
    )


@dataclass
class _Cones:
    """The pitch points, rolling axes and tooth-force directions of the meshes of a train
    whose axes meet at the origin, and the cone distance at which each gear meshes."""

    gears: Mapping[str, Gear]
    gear_axes: dict[str, Vector]
    radicals: RadicalTable
    problems: list[Problem]
    points: dict[str, Vector] = field(default_factory=dict)
    coupling_axes: dict[str, Vector] = field(default_factory=dict)
    tangents: dict[str, Vector] = field(default_factory=dict)
    cone_distance: dict[str, tuple[str, sympy.Expr]] = field(default_factory=dict)

    def draw(self, mesh: AxisSpacing) -> None:
        """The pitch point P = (r_b a + r_a b) / sin S of ``mesh`` (Laus eqs. (80)-(84)), the
        rolling axis OP and the tooth force along a x b; a problem where the axes are
        parallel or the coupling joins parallel axes only (a chain)."""
        radicals, name = self.radicals, mesh.name
        g, h = (self.gears[n] for n in mesh.gears)
        a, b = self.gear_axes[g.name], self.gear_axes[h.name]
        normal = radicals.reduced(cross(a, b))
        if not mesh.intersecting:
            self.problems.append(
                Problem(
                    f"couplings.{name}",
                    f"a {mesh.noun} joins parallel axes only; this train has intersecting axes: give it without "
                    "axis directions (planar layout)",
                )
            )
            return
        if all(x == 0 for x in normal):
            self.problems.append(
                Problem(
                    f"couplings.{name}",
                    "the gear axes are parallel: give the train without axis directions (planar layout)",
                )
            )
            return
        sin = radicals.sqrt(_norm_squared(normal))
        pitch = radicals.reduced((h.radius * x + g.radius * y) / sin for x, y in zip(a, b, strict=True))
        self.points[name] = pitch
        self.coupling_axes[name] = pitch
        self.tangents[name] = radicals.reduced(x / sin for x in normal)
        self._check_cone_distance(name, (g, h), radicals.reduce(_norm_squared(pitch)))

    def _check_cone_distance(self, name: str, gears: tuple[Gear, Gear], distance: sympy.Expr) -> None:
        """A gear meshing twice has both pitch points on its one pitch circle."""
        restore = self.radicals.restore
        for gear in gears:
            if gear.name not in self.cone_distance:
                self.cone_distance[gear.name] = (name, distance)
                continue
            other, previous = self.cone_distance[gear.name]
            if self.radicals.reduce(distance - previous) != 0:
                self.problems.append(
                    Problem(
                        f"couplings.{name}",
                        f"inconsistent geometry: gear {gear.name!r} meshes here at cone distance "
                        f"sqrt({restore(distance)}) and in {other!r} at "
                        f"sqrt({restore(previous)}); one gear has one pitch circle",
                    )
                )
