"""A rack and its pinion: a gear meshing a toothed bar that slides along its pitch line
(Laus section 3.3.1 with the second gear's radius taken to infinity)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import Screw, Vector, cross, translation_twist, vector
from davies_sym.topology.angles import AngleFunctions, read_angle
from davies_sym.topology.couplings import axis_direction
from davies_sym.topology.entries import describe
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.mesh_entries import read_efficiencies
from davies_sym.topology.schema import Field
from davies_sym.topology.toothed_mesh import LocationError, MeshLocation, ToothedMesh, gear_twist, rolling_screws

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class RackMesh(ToothedMesh):
    """A pinion (a gear of the file) meshing a rack (a link that slides along ``direction``).

    The rack's pitch line is tangent to the pinion's pitch circle and runs along
    ``direction``; the rack lies on the side ``direction x axis`` of the pinion (below it
    for a rack along +x on a pinion turning about +z).  The teeth roll on the pitch line as
    a spur pair's do (`rolling_screws`): the rack is a gear of infinite radius, whose
    motion in the mesh's carrier is a translation along its line instead of a turn about
    an axis.  The edge goes from the pinion's link to the rack.
    """

    pinion: str = ""
    rack: str = ""
    direction: Vector = (sympy.Integer(1), sympy.Integer(0), sympy.Integer(0))
    #: cos and sin of the pressure angle, where the entry gives one (a pressed guide reads it).
    pressure: AngleFunctions | None = None

    kind: ClassVar[str] = "rack"
    member_noun: ClassVar[str] = "member"
    DOC: ClassVar[str] = (
        "A pinion meshing a rack, a link that slides along its pitch line (a guide, a prismatic coupling, "
        "holds it). The edge goes from the pinion's link to the rack."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("pinion", "gear", True, "The gear that meshes the rack."),
        Field("rack", "link", True, "The link that carries the rack's teeth."),
        Field(
            "direction",
            "`x`, `y`, `-x`, `-y` ...",
            True,
            "Direction of the rack's pitch line, normal to the pinion's axis; the rack lies on the side "
            "`direction` x axis of the pinion (below a pinion on z for a rack along x).",
        ),
        Field(
            "efficiency",
            "symbol or number, or a list of two",
            False,
            "Ordinary efficiency of the mesh (the guide and the pinion's bearing held). One value serves both "
            "power directions; a list gives [pinion drives, rack drives]. Default: `eta_<coupling>`.",
        ),
        Field(
            "pressure_angle",
            "symbol or number",
            False,
            "Pressure angle alpha of the teeth (numbers are degrees, symbols radians): the tooth force then "
            "pushes the rack off the pinion by tan(alpha) times its tangential part, which loads a guide "
            "whose friction names this mesh (`pressed_by`). Default: taken as zero, nothing pushes.",
        ),
    )

    @property
    def members(self) -> tuple[str, str]:
        return (self.pinion, self.rack)

    @property
    def sides(self) -> tuple[str, str]:
        return (f"gear {self.pinion}", f"rack {self.rack}")

    @property
    def pair_words(self) -> str:
        return f"gear {self.pinion}, rack {self.rack}"

    @property
    def angles(self) -> tuple[AngleFunctions, ...]:
        return () if self.pressure is None else (self.pressure,)

    @property
    def separating(self) -> sympy.Expr | None:
        return None if self.pressure is None else self.pressure.sin / self.pressure.cos

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return (*super().written_quantities, *self.direction)

    def report_fields(self) -> dict[str, Any]:
        return {"pinion": self.pinion, "rack": self.rack, "direction": [str(v) for v in self.direction]}

    def member_twists(self, place: Placement, gears: Mapping[str, Gear]) -> tuple[Screw, Screw]:
        """The pinion turning about its axis; the rack sliding along its pitch line."""
        return gear_twist(place, self.pinion), translation_twist(self.direction)

    def locate(self, place: Placement, gears: Mapping[str, Gear]) -> MeshLocation:
        """The pitch point one pitch radius from the pinion's centre, across the rack's line."""
        axis = place.gear_axes.get(self.pinion, place.axis)
        normal = cross(self.direction, axis)
        if all(sympy.expand(v) == 0 for v in normal):
            raise LocationError("direction", "the rack must run across the pinion's axis, not along it")
        if sympy.expand(sum(a * b for a, b in zip(self.direction, axis, strict=True))) != 0:
            raise LocationError("direction", "the rack's pitch line must be normal to the pinion's axis")
        centre, radius = place.gear_centres[self.pinion], gears[self.pinion].radius
        point = vector([c + radius * n for c, n in zip(centre, normal, strict=True)])
        return MeshLocation(point, self.direction, normal)

    def screws(self, place: Placement) -> CouplingScrews:
        """The teeth roll on the pitch line, as a spur pair's (Laus Table 3, coupling C)."""
        return rolling_screws(self.name, place)

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> RackMesh | None:
        pinion = reader.name(entry["pinion"], f"{path}.pinion") if "pinion" in entry else None
        if pinion is not None and pinion not in gears:
            reader.unknown(f"{path}.pinion", "gear", pinion)
            pinion = None
        rack = reader.name(entry["rack"], f"{path}.rack") if "rack" in entry else None
        direction = _read_direction(entry["direction"], f"{path}.direction", reader) if "direction" in entry else None
        if pinion is not None and gears[pinion].internal:
            reader.problem(f"{path}.pinion", f"gear {pinion} is internal (an annulus): a rack meshes an external gear")
            pinion = None
        if pinion is not None and rack is not None and gears[pinion].link == rack:
            reader.problem(f"{path}.rack", f"the rack must be another link than the pinion's ({rack})")
            rack = None
        default = Friction(coulomb=reader.quantity(f"zeta_{name}", path, "friction"))
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, default, name)
        efficiencies = read_efficiencies(entry.get("efficiency", f"eta_{name}"), f"{path}.efficiency", reader)
        pressure = None
        if "pressure_angle" in entry:
            meaning = f"the pressure angle of mesh {name}"
            pressure = read_angle(entry["pressure_angle"], f"{path}.pressure_angle", reader, name, "alpha", meaning)
        if pinion is None or rack is None or direction is None:
            return None
        return cls(
            name,
            (gears[pinion].link, rack),
            friction,
            efficiencies=efficiencies,
            pinion=pinion,
            rack=rack,
            direction=direction,
            pressure=pressure,
        )


def _read_direction(value: Any, path: str, reader: EntryReader) -> Vector | None:
    """An axis letter, signed or not: the rack's pitch line along a drawing axis."""
    axis = axis_direction(value)
    if axis is not None:
        return axis
    reader.problem(path, f"expected an axis, `x`, `y`, `-x` or `-y` (or `z`), got {describe(value)}")
    return None
