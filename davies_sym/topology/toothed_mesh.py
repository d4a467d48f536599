"""The base of the meshes whose losses are given as ordinary efficiencies (Laus section
3.3.1, Definition 4): teeth of two members in contact, their friction opposing the
rolling about the pitch line and loaded by the tooth force.

The efficiency stage reads a mesh only through this base: the two members and what the
reports call them (`members`, `sides`), how each turns or slides in the mesh's carrier
(`member_twists`, for the virtual power of Laus eqs. (69)-(73)), and the ordinary
efficiencies.  A kind that follows the gears it meshes (a rack beside its pinion) also
says where the layout puts it (`locate`); the others are drawn by the geometry stage,
whose layouts place the gears from their meshes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import ClassVar

import sympy

from davies_sym.algebra.screws import (
    NamedScrew,
    Screw,
    Vector,
    rotation_magnitude_name,
    rotation_twist,
    translation_magnitude_name,
    translation_twist,
)
from davies_sym.losses.definitions import Definition
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints


@dataclass(frozen=True)
class MeshLocation:
    """Where a mesh that follows its gears lies: its pitch point, the tangent along which
    the tooth force acts and the normal along which the members would separate."""

    point: Vector
    tangent: Vector
    normal: Vector


class LocationError(Exception):
    """A mesh the layout cannot put where its entry says: the entry's key and why."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key, self.message = key, message


@dataclass(frozen=True)
class ToothedMesh(Coupling):
    """Teeth of two members in contact, with an ordinary efficiency per power direction."""

    #: Ordinary efficiencies: (first member drives, second member drives), Laus eqs. (32), (34).
    efficiencies: tuple[sympy.Expr, sympy.Expr] | None = None
    #: The efficiencies as functions of the tooth geometry (Laus App. A), when given so.
    efficiency_definitions: tuple[Definition, ...] = ()

    noun: ClassVar[str] = "mesh"
    located: ClassVar[bool] = True
    meshing: ClassVar[bool] = True
    #: What either of its members is called where both are meant ("either gear driving").
    member_noun: ClassVar[str] = "gear"

    @property
    def members(self) -> tuple[str, str]:
        """The names of its two members as the file writes them (gears, or a gear and a rack)."""
        raise NotImplementedError

    @property
    def sides(self) -> tuple[str, str]:
        """Its two members as the reports name them: ``("gear 1", "gear 3")``."""
        return (f"gear {self.members[0]}", f"gear {self.members[1]}")

    @property
    def pair_words(self) -> str:
        """Its two members in one phrase: ``gears 1, 3``."""
        return f"gears {self.members[0]}, {self.members[1]}"

    def member_twists(self, place: Placement, gears: Mapping[str, Gear]) -> tuple[Screw, Screw]:
        """The unit twists of its two members in its carrier: how each turns about its own
        axis (or slides along its own line) when the carrier holds both (Laus section 3.1)."""
        raise NotImplementedError

    def locate(self, place: Placement, gears: Mapping[str, Gear]) -> MeshLocation | None:
        """Where the layout puts it, for a kind that follows the gears it meshes; None for a
        kind the geometry stage draws (a mesh of two gears places the gears)."""
        return None

    @property
    def definitions(self) -> tuple[Definition, ...]:
        angles = tuple(d for a in self.angles for d in a.definitions)
        return self.friction.definitions + self.efficiency_definitions + angles

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return () if self.efficiencies is None else tuple(self.efficiencies)


def gear_twist(place: Placement, gear: str) -> Screw:
    """The unit twist of a gear about its own axis, through its centre."""
    return rotation_twist(place.gear_axes.get(gear, place.axis), place.gear_centres[gear])


def rolling_screws(name: str, place: Placement) -> CouplingScrews:
    """Teeth rolling on a plane pitch contact (spur gears, a rack and its pinion): rotation
    about the pitch line and the tooth force along the common tangent at the pitch point
    (pressure angle taken as zero, Laus section 3.3.1, Table 3 coupling C); the separating
    motion along the normal is a secondary freedom, kept in planar systems of order 3.
    Where the gears carry thrust or the layout is spatial the teeth touch at the pitch
    point only: the translation along the axis and the tilts about the tangent and the
    normal are freedoms too, so the bearings alone hold the members out of their plane."""
    point, axis = place.coupling_points[name], place.coupling_axes.get(name, place.axis)
    tangent, normal = place.mesh_tangents[name], place.mesh_normals[name]
    motion = NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point))
    separating = [NamedScrew(translation_magnitude_name(normal), translation_twist(normal))]
    if place.spatial or place.thrust:
        separating += [
            NamedScrew(translation_magnitude_name(axis), translation_twist(axis)),
            NamedScrew(rotation_magnitude_name(tangent), rotation_twist(tangent, point)),
            NamedScrew(rotation_magnitude_name(normal), rotation_twist(normal, point)),
        ]
    return CouplingScrews((motion,), tuple(separating), point_constraints(point, (tangent,)))
