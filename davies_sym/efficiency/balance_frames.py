"""The members of a train as Chen's virtual-power balance sees them: axes, carriers, arms.

Two geometries, one interface (`Frames`) for the eight steps of
`.virtual_power_balance`:

- `PlanarFrames`: parallel axes (on a line or in 2-D); every member turns about
  its own axis at w, and a carrier-frame speed is w - w_c (Chen eq. (4.6));
- `ConicalFrames`: axes through one apex (bevel, face gears); members on the main
  axis turn at w about it, a planet spins at s about its own axis relative to the
  carrier whose bearing holds it, and the Willis equation of a mesh equates the
  carrier-frame speeds of the pitch point, ``s_p (u_p x P).t = s_q (u_q x P).t``.

Everything is evaluated exactly at one parameter point (square roots by sympy).

Which link carries which planet, and the carrier of each mesh, are found here again,
from the layout's points and axes at that point (`PlanarFrames._carrier` and
`PlanarFrames._carries`, `ConicalFrames.carrier_of`), not taken from the axis structure
(`davies_sym.geometry.axes.axis_structure`) that the layouts, the virtual power of the
meshes and the planet sets share: the balance is a cross-check of that route, so it
shares no code with it.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import sympy

from davies_sym.algebra.screws import Vector, cross
from davies_sym.errors import DerivationError
from davies_sym.geometry.layout import Layout
from davies_sym.topology.coupling_kinds import bearings, gear_meshes, sliders
from davies_sym.topology.gear_mesh import GearMesh
from davies_sym.topology.model import Train

Values = Mapping[sympy.Symbol, sympy.Expr]
Point2 = tuple[sympy.Expr, sympy.Expr]
Row = list[sympy.Expr]


def exact(x: object) -> sympy.Expr:
    """Canonical form of an exact number with square roots: a + b sqrt(m) expanded."""
    return sympy.expand(sympy.radsimp(sympy.sympify(x)))


def is_zero(x: object) -> bool:
    return bool(exact(x) == 0)


def _numbers(layout: Layout, values: Values) -> Callable[[object], sympy.Expr]:
    """Exact value of a layout expression at ``values``, its square roots evaluated by sympy."""
    roots = {r.symbol: sympy.sqrt(r.radicand.subs(values)) for r in layout.radicals}
    return lambda expr: exact(sympy.sympify(expr).subs(values).subs(roots))


def _same(p: Point2, q: Point2) -> bool:
    return all(exact(a - b) == 0 for a, b in zip(p, q, strict=True))


def _parallel(a: tuple[sympy.Expr, ...], b: tuple[sympy.Expr, ...]) -> bool:
    return all(is_zero(x) for x in cross(a, b))


class Frames:
    """What the balance needs of the geometry: meshes with their carriers and arms, how a
    member's carrier-frame speed enters a Willis row, and which mesh torques reach each
    member's balance.  Subclasses fill in the geometry."""

    meshes: list[GearMesh]
    #: Mesh -> the link holding both gear axes.
    carriers: dict[str, str]
    #: Mesh -> (a_p, a_q): pitch-point speed per unit carrier-frame speed of each gear.
    arms: dict[str, tuple[sympy.Expr, sympy.Expr]]
    #: Unknowns beyond the two mesh torques per mesh (e.g. a slider's couple).
    extra_unknowns: int = 0

    def speed(self, row: Row, col: Mapping[str, int], link: str, carrier: str, factor: sympy.Expr) -> None:
        """Add ``factor`` times the carrier-frame speed of ``link`` to the Willis ``row``."""
        if link in col:
            row[col[link]] += factor
        if carrier in col:
            row[col[carrier]] -= factor

    def relative(self, w: Mapping[str, sympy.Expr], link: str, carrier: str) -> sympy.Expr:
        """The carrier-frame speed of ``link`` (Chen eq. (4.6))."""
        return w[link] - w[carrier]

    def extra_kinematics(self, col: Mapping[str, int]) -> list[Row]:
        return []

    def reactions(self, row: Row, link: str, k: int, mesh: GearMesh) -> None:
        """Add the torques of mesh ``k`` on ``link`` about its axis to its balance ``row``."""
        raise NotImplementedError

    def extra_reactions(self, row: Row, link: str, first: int) -> None:
        """Add the extra unknowns (columns from ``first``) acting on ``link``."""


class PlanarFrames(Frames):
    """Parallel-axis trains: axes of the members and which carrier holds which planet.

    A lossless prismatic pair (an Oldham coupling) keeps its two links at one angular
    speed and passes a couple between them.
    """

    def __init__(self, train: Train, values: Values, layout: Layout):
        self.train = train
        number = _numbers(layout, values)

        def pt(point: Vector) -> Point2:
            return (number(point[0]), number(point[1]))

        self.meshes = gear_meshes(train.couplings)
        self.sliders = sliders(train.couplings)
        self.revolutes = bearings(train.couplings)
        lossy = [c.name for c in self.sliders if not c.friction.lossless]
        known = {c.name for c in (*self.meshes, *self.sliders, *self.revolutes)}
        others = [c.name for c in train.couplings if c.name not in known]
        if lossy or others:
            raise DerivationError(
                f"virtual-power balance: couplings {lossy + others} are outside its scope "
                "(it covers gear pairs, bearings and lossless sliders)"
            )
        self.extra_unknowns = len(self.sliders)
        self.gear_axis = {g.name: pt(layout.gear_centres[g.name]) for g in train.gears}
        self.pitch = {m.name: pt(layout.coupling_points[m.name]) for m in self.meshes}
        self.tangent = {m.name: pt(layout.mesh_tangents[m.name]) for m in self.meshes}
        self.bearing_axis = {c.name: pt(layout.coupling_points[c.name]) for c in self.revolutes}
        self.axis = self._member_axes()
        self.carriers = {m.name: self._carrier(m) for m in self.meshes}
        # Signed distance from each gear's axis to the pitch point: s_p a_p = s_q a_q (Willis).
        self.arms = {m.name: (self._arm(m.name, m.gears[0]), self._arm(m.name, m.gears[1])) for m in self.meshes}

    def _member_axes(self) -> dict[str, Point2]:
        """A geared link turns about its gears' axis; any other link about the bearing by
        which it is first reached from the reference."""
        train = self.train
        axis: dict[str, Point2] = {}
        for g in train.gears:
            axis.setdefault(g.link, self.gear_axis[g.name])
        axis.setdefault(train.reference, (sympy.Integer(0), sympy.Integer(0)))
        frontier, reached = [train.reference], {train.reference}
        while frontier:
            nxt = []
            for link in frontier:
                for c in self.revolutes:
                    if link in c.links:
                        other = c.links[1] if c.links[0] == link else c.links[0]
                        if other not in reached:
                            reached.add(other)
                            axis.setdefault(other, self.bearing_axis[c.name])
                            nxt.append(other)
            frontier = nxt
        missing = [link for link in train.link_names if link not in reached]
        if missing:
            raise DerivationError(
                f"virtual-power balance: links {missing} hang on no bearing chain from the "
                f"reference {train.reference!r}"
            )
        return axis

    def _arm(self, mesh: str, gear: str) -> sympy.Expr:
        """(z x (P - C)) . t: the pitch-point speed per unit carrier-frame speed of
        ``gear`` along the tooth-force direction (a signed distance on a line layout)."""
        (px, py), (cx, cy), (tx, ty) = self.pitch[mesh], self.gear_axis[gear], self.tangent[mesh]
        return exact(-(py - cy) * tx + (px - cx) * ty)

    def _coaxial_group(self, link: str, axis: Point2) -> set[str]:
        """Links joined to ``link`` by bearings on ``axis``: they hold that axis."""
        group, frontier = {link}, [link]
        while frontier:
            current = frontier.pop()
            for c in self.revolutes:
                if current in c.links and _same(self.bearing_axis[c.name], axis):
                    other = c.links[1] if c.links[0] == current else c.links[0]
                    if other not in group:
                        group.add(other)
                        frontier.append(other)
        return group

    def _carrier(self, mesh: GearMesh) -> str:
        """The link holding both gear axes of ``mesh``."""
        groups = [
            self._coaxial_group(link, self.gear_axis[gear]) - set(mesh.links)
            for gear, link in zip(mesh.gears, mesh.links, strict=True)
        ]
        common = [link for link in self.train.link_names if link in groups[0] and link in groups[1]]
        if not common:
            raise DerivationError(f"virtual-power balance: no carrier found for mesh {mesh.name}")
        return common[0]

    def _carries(self, carrier: str, planet: str) -> bool:
        """Whether ``planet`` turns in a bearing of ``carrier`` off the carrier's axis."""
        return not _same(self.axis[planet], self.axis[carrier]) and any(
            set(c.links) == {carrier, planet} and _same(self.bearing_axis[c.name], self.axis[planet])
            for c in self.revolutes
        )

    def extra_kinematics(self, col: Mapping[str, int]) -> list[Row]:
        rows = []
        for k in self.sliders:
            row: Row = [sympy.Integer(0)] * len(col)
            for link, sign in zip(k.links, (-1, 1), strict=True):
                if link in col:
                    row[col[link]] += sign
            rows.append(row)
        return rows

    def reactions(self, row: Row, link: str, k: int, mesh: GearMesh) -> None:
        for side in (0, 1):
            if mesh.links[side] == link:
                if not _same(self.gear_axis[mesh.gears[side]], self.axis[link]):
                    raise DerivationError(
                        f"virtual-power balance: gear {mesh.gears[side]} is not on the axis of its link {link}"
                    )
                row[2 * k + side] += 1
            planet, partner = mesh.links[side], 1 - side
            # A planet-planet mesh of one carrier acts on it with equal and opposite
            # wrenches: nothing reaches the carrier.
            if (
                planet != link
                and mesh.links[partner] != link
                and self._carries(link, planet)
                and not self._carries(link, mesh.links[partner])
            ):
                if not _same(self.gear_axis[mesh.gears[partner]], self.axis[link]):
                    raise DerivationError(
                        f"virtual-power balance: planet {planet} meshes gear "
                        f"{mesh.gears[partner]}, which is not coaxial with its carrier {link}"
                    )
                row[2 * k + partner] -= 1

    def extra_reactions(self, row: Row, link: str, first: int) -> None:
        for j, k in enumerate(self.sliders):
            for end, sign in zip(k.links, (-1, 1), strict=True):
                if end == link:
                    row[first + j] += sign
                elif link not in k.links and self._carries(link, end):
                    row[first + j] += sign  # the couple on a planet reaches its carrier


class ConicalFrames(Frames):
    """Trains whose axes meet at one apex: moments about each member's axis; a planet's
    speed is its spin about its own axis relative to the carrier that holds it."""

    def __init__(self, train: Train, values: Values, layout: Layout):
        number = _numbers(layout, values)

        def vec(v: Vector) -> tuple[sympy.Expr, ...]:
            return tuple(number(x) for x in v)

        main = vec(layout.axis)
        self.meshes = gear_meshes(train.couplings)
        known = {c.name for c in (*self.meshes, *bearings(train.couplings))}
        others = [c.name for c in train.couplings if c.name not in known]
        if others:
            raise DerivationError(f"virtual-power balance: couplings {others} are outside its scope in a bevel train")
        axis = {g.link: vec(layout.gear_axes[g.name]) for g in train.gears}
        self.carrier_of: dict[str, str] = {}
        for c in bearings(train.couplings):
            bearing = vec(layout.coupling_axes[c.name])
            for planet, holder in (c.links, c.links[::-1]):
                if planet in axis and not _parallel(axis[planet], main) and _parallel(bearing, axis[planet]):
                    self.carrier_of[planet] = holder
        self.carriers, self.arms = {}, {}
        for m in self.meshes:
            point, tangent = vec(layout.coupling_points[m.name]), vec(layout.mesh_tangents[m.name])
            held = {self.carrier_of[link] for link in m.links if link in self.carrier_of}
            if len(held) != 1:
                raise DerivationError(
                    f"virtual-power balance: mesh {m.name} needs exactly one carrier in a bevel train"
                )
            self.carriers[m.name] = held.pop()
            first, second = (
                exact(
                    sum(
                        x * t
                        for x, t in zip(
                            cross(axis[link] if link in self.carrier_of else main, point), tangent, strict=True
                        )
                    )
                )
                for link in m.links
            )
            self.arms[m.name] = (first, second)

    def speed(self, row: Row, col: Mapping[str, int], link: str, carrier: str, factor: sympy.Expr) -> None:
        if link not in self.carrier_of:
            super().speed(row, col, link, carrier, factor)
            return
        if self.carrier_of[link] != carrier:
            raise DerivationError(f"virtual-power balance: planet {link} meshes in a frame other than its carrier")
        row[col[link]] += factor

    def relative(self, w: Mapping[str, sympy.Expr], link: str, carrier: str) -> sympy.Expr:
        return w[link] if link in self.carrier_of else w[link] - w[carrier]

    def reactions(self, row: Row, link: str, k: int, mesh: GearMesh) -> None:
        for side in (0, 1):
            if mesh.links[side] == link:
                row[2 * k + side] += 1
            partner = mesh.links[1 - side]
            # The planet's bearing passes to its carrier the mesh's moment about the
            # main axis: minus the moment on the partner gear, which turns about it.
            if self.carrier_of.get(mesh.links[side]) == link and partner != link and partner not in self.carrier_of:
                row[2 * k + 1 - side] -= 1
