"""A chain or a belt on two sprockets or pulleys: a drive whose members turn the same way
at equal pitch-line speeds, omega_A r_A = omega_B r_B relative to the link that holds
both axes, over a centre distance of its own choosing (Laus section 3.1, Definition 4,
with the taut strand in the place of the tooth force).

The taut strand is a line tangent to both pitch circles on one side: at the distance r_A
from A's axis and r_B from B's, with the same sense of moment about both, as the tooth
force of an internal mesh.  The centre distance L is free, so the layout draws the strand
along its placement direction u: B's centre lies L along u and r_A - r_B across it
(towards w, u turned clockwise) from A's, and the strand is the line through
A + r_A w along u.  Every entry of the layout stays polynomial, and L (the symbol
``L_<coupling>``) cancels from the efficiency: the strand's moments about the two axes
are r_A and r_B per unit tension wherever B lies along it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import (
    NamedScrew,
    Screw,
    Vector,
    cross,
    force_wrench,
    rotation_magnitude_name,
    rotation_twist,
    translation_magnitude_name,
    translation_twist,
    vector,
)
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.mesh_entries import read_efficiencies, read_gear_pair
from davies_sym.topology.schema import Field
from davies_sym.topology.toothed_mesh import MeshLocation, ToothedMesh, gear_twist

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


def _doc(what: str, member: str) -> str:
    """The entry's description of a drive on two ``member``s (``DOC``)."""
    return (
        f"{what} on two {member}s on two links: both turn the same way, their pitch-line speeds equal relative "
        "to the link that holds both axes. The centre distance is free (it does not enter the formulas; the "
        f"layout draws the strand along the placement direction). The edge goes from the first {member}'s link "
        f"to the second's. {member.capitalize()}s written by `teeth` take one `module` (the pitch over pi): the "
        "ratio is then that of their teeth."
    )


def _fields(member: str) -> tuple[Field, ...]:
    """The keys of a drive's entry besides ``type`` and ``friction`` (``FIELDS``)."""
    return (
        Field("gears", "[gear, gear]", True, f"The two {member}s (external gears of the file, on two links)."),
        Field(
            "efficiency",
            "symbol or number, or a list of two",
            False,
            "Ordinary efficiency of the drive (the link holding both axes held). One value serves both power "
            f"directions; a list gives [first {member} drives, second {member} drives]. Default: `eta_<coupling>`.",
        ),
    )


#: The centre distance of a drive built without its entry (every read one names its own).
_UNREAD = sympy.Symbol("L")


@dataclass(frozen=True)
class ChainDrive(ToothedMesh):
    """A chain on two sprockets (gears of the file) on two links; the edge goes from the
    first sprocket's link to the second's.

    Relative to the link that holds both axes the sprockets turn the same way, with the
    ratio of their pitch radii (or tooth numbers); the chain's ordinary efficiency applies
    to the power through it in that link, as a mesh's does (Laus section 3.1, Tables 5
    and 6: the driving member decides eta or 1/eta).  Its screws are those of a rolling
    contact (`rolling_screws`) at the strand's tangent point on the first sprocket: the
    tension along the strand is its one action, and the two members may turn about any
    point of the strand relative to each other.
    """

    drive_gears: tuple[str, str] = ("", "")
    #: The free centre distance, the symbol ``L_<coupling>``: the formulas must not hold it.
    free_distance: sympy.Symbol = _UNREAD

    kind: ClassVar[str] = "chain"
    noun: ClassVar[str] = "chain drive"
    member_noun: ClassVar[str] = "sprocket"
    #: Its Coulomb coefficient is a fraction of the tension lost along the strand.
    load_dependent_unit: ClassVar[str] = "1"
    DOC: ClassVar[str] = _doc("A chain", "sprocket")
    FIELDS: ClassVar[tuple[Field, ...]] = _fields("sprocket")

    @property
    def gears(self) -> tuple[str, str]:
        return self.drive_gears

    @property
    def members(self) -> tuple[str, str]:
        return self.drive_gears

    @property
    def sides(self) -> tuple[str, str]:
        return (f"{self.member_noun} {self.drive_gears[0]}", f"{self.member_noun} {self.drive_gears[1]}")

    @property
    def pair_words(self) -> str:
        return f"{self.member_noun}s {self.drive_gears[0]}, {self.drive_gears[1]}"

    @property
    def free_lengths(self) -> tuple[sympy.Symbol, ...]:
        return (self.free_distance,)

    def spacing(self, gears: Mapping[str, Gear]) -> AxisSpacing:
        """B's axis L along the placement direction and r_A - r_B across it from A's."""
        a, b = (gears[name] for name in self.drive_gears)
        across = sympy.expand(a.radius - b.radius)
        free = self.free_distance
        return AxisSpacing(
            self.name,
            self.drive_gears,
            free,
            self.drive_gears,
            across=across,
            free=(free,),
            intersecting=False,
            noun=self.noun,
        )

    def locate(self, place: Placement, gears: Mapping[str, Gear]) -> MeshLocation:
        """The strand along the placement direction u, through A + r_A w (w: u turned
        clockwise), its tangent point on A's pitch circle; B's centre lies r_B from it on
        A's side, as the layout placed it (`spacing`)."""
        ux, uy = place.frame
        first = self.drive_gears[0]
        centre, radius = place.gear_centres[first], gears[first].radius
        across = vector((uy, -ux, 0))
        point = vector([sympy.expand(c + radius * w) for c, w in zip(centre, across, strict=True)])
        return MeshLocation(point, vector((ux, uy, 0)), across)

    def member_twists(self, place: Placement, gears: Mapping[str, Gear]) -> tuple[Screw, Screw]:
        """Each sprocket turning about its own axis (Laus section 3.1, Definition 4)."""
        return gear_twist(place, self.drive_gears[0]), gear_twist(place, self.drive_gears[1])

    def screws(self, place: Placement) -> CouplingScrews:
        """The tension along the strand, and the freedoms reciprocal to it (Laus Tables 3-4).

        The first freedom is the relative motion the chain makes, r_A $_B - r_B $_A for
        unit rotations $_A, $_B about the two axes (its magnitude the strand's speed over
        r_A r_B, never zero while the chain runs, even on equal sprockets); the rotation
        about the strand's tangent point is the second.  The friction acts on the first
        motion as a force along the strand's normal through A's axis, of moment r_B about
        B's axis and none about A's: the loss is zeta times the tension times the strand's
        speed, whatever the centre distance.  Out of the plane (a spatial or thrust-bearing
        layout) the members may also slide along the axes and tilt, as a spur pair's."""
        a, b = self.drive_gears
        axis = place.gear_axes.get(a, place.axis)
        centre_a, centre_b = place.gear_centres[a], place.gear_centres[b]
        point, tangent = place.coupling_points[self.name], place.mesh_tangents[self.name]
        normal = place.mesh_normals[self.name]
        # The strand lies r_A from A's axis and r_B from B's, both on the side -normal of it.
        r_a, r_b = (_dot(vector([p - c for p, c in zip(point, o, strict=True)]), normal) for o in (centre_a, centre_b))
        about_a, about_b = rotation_twist(axis, centre_a), rotation_twist(axis, centre_b)
        turning = tuple(sympy.expand(r_a * q - r_b * p) for p, q in zip(about_a, about_b, strict=True))
        motion = NamedScrew("p", (*turning,))
        secondary = [NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point))]
        if place.spatial or place.thrust:
            secondary += [
                NamedScrew(translation_magnitude_name(axis), translation_twist(axis)),
                NamedScrew(rotation_magnitude_name(tangent), rotation_twist(tangent, point)),
                NamedScrew(rotation_magnitude_name(normal), rotation_twist(normal, point)),
            ]
        # (A - B) x (f n) . axis = r_B fixes the force's size f.
        arm = _dot(cross(vector([p - q for p, q in zip(centre_a, centre_b, strict=True)]), normal), axis)
        size = sympy.cancel(r_b / arm)
        friction = NamedScrew("F", force_wrench(vector([size * n for n in normal]), centre_a))
        return CouplingScrews((motion,), tuple(secondary), point_constraints(point, (tangent,)), friction=friction)

    def report_fields(self) -> dict[str, Any]:
        return {"gears": list(self.drive_gears)}

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> ChainDrive | None:
        pair = _read_members(cls, entry, path, reader, gears)
        default = Friction(coulomb=reader.quantity(f"zeta_{name}", path, "friction"))
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, default, name)
        efficiencies = read_efficiencies(entry.get("efficiency", f"eta_{name}"), f"{path}.efficiency", reader)
        own = f"L_{name}"
        elsewhere = reader.written.get(own)
        if elsewhere is not None and not elsewhere.startswith(path):
            # The drive's own symbol, already written in another role: said once, where it was written.
            reader.problem(
                elsewhere,
                f"{own} is the name of the free centre distance of {cls.noun} {name}; give this symbol another name",
            )
        distance = reader.quantity(own, path, "position")
        if pair is None or not isinstance(distance, sympy.Symbol):
            return None
        a, b = pair
        return cls(
            name,
            (a.link, b.link),
            friction,
            efficiencies=efficiencies,
            drive_gears=(a.name, b.name),
            free_distance=distance,
        )


def _dot(a: Vector, b: Vector) -> sympy.Expr:
    return sympy.expand(sum(x * y for x, y in zip(a, b, strict=True)))


def _read_members(
    kind: type[ChainDrive], entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
) -> tuple[Gear, Gear] | None:
    """The two sprockets or pulleys: gears of the file on two links, neither an annulus."""
    member = kind.member_noun
    pair = read_gear_pair(entry, path, reader, gears, f"{member}, {member}", kind.kind)
    for gear in pair or ():
        if gear.internal:
            reader.problem(
                f"{path}.gears",
                f"gear {gear.name!r} is internal (an annulus): a {kind.kind} runs on external {member}s; "
                "remove `internal: true`",
            )
            return None
    return pair


@dataclass(frozen=True)
class BeltDrive(ChainDrive):
    """A belt on two pulleys: as a chain (`ChainDrive`), its slip taken into its ordinary
    efficiency."""

    kind: ClassVar[str] = "belt"
    noun: ClassVar[str] = "belt drive"
    member_noun: ClassVar[str] = "pulley"
    DOC: ClassVar[str] = _doc("A belt", "pulley")
    FIELDS: ClassVar[tuple[Field, ...]] = _fields("pulley")
