"""The gear mesh of two gears on parallel or intersecting axes: spur, helical, bevel
(Laus Table 3, coupling C; section 3.3.1)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import (
    NamedScrew,
    Screw,
    cross,
    force_magnitude_name,
    force_wrench,
    rotation_magnitude_name,
    rotation_twist,
    translation_magnitude_name,
    translation_twist,
    vector,
)
from davies_sym.errors import DerivationError, shortened
from davies_sym.losses.definitions import Definition
from davies_sym.topology.angles import AngleFunctions
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints
from davies_sym.topology.loss_entries import Friction, read_friction, tooth_contact
from davies_sym.topology.mesh_entries import annulus_larger, read_efficiencies, read_gear_pair, read_helix
from davies_sym.topology.schema import Field
from davies_sym.topology.toothed_mesh import ToothedMesh, gear_twist, rolling_screws

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class GearMesh(ToothedMesh):
    """A gear mesh between two gears on different links, external or internal.

    The relative motion is a rotation about the pitch line (Laus Table 3, coupling C);
    the transmitted action is the tooth force along the common tangent at the pitch
    point (pressure angle taken as zero, Laus section 3.3.1), and the friction is a
    torque about the pitch line (Theorem 1).  The separating motion along the centre
    line is a secondary freedom: it is kept in planar systems of order 3.

    Helical gears (``helix``) on parallel axes: the tooth force is normal to the tooth
    line, so besides its tangential part ``F`` it pushes the gears apart along their
    axes by ``F tan(beta)``, the thrust the bearings take; the teeth may slide along the
    tooth line.  ``hand`` is +1 when the first gear is right-handed (the second is then
    left-handed on an external mesh, right-handed on an internal one).
    """

    mesh_gears: tuple[str, str] = ("", "")
    internal: bool = False
    #: cos and sin of the helix angle at the pitch radius (helical gears), else None.
    helix: AngleFunctions | None = None
    #: +1: the first gear is right-handed, -1: left-handed.
    hand: int = 1

    kind: ClassVar[str] = "mesh"
    DOC: ClassVar[str] = (
        "Gear mesh between two gears. The edge goes from the link of the first gear "
        "to the link of the second. External or internal is derived from the gears "
        "(`internal: true` marks an annulus); `mesh` may state it as a check."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("gears", "[gear, gear]", True, "The two meshing gears."),
        Field("mesh", "`external` or `internal`", False, "Checked against the gears."),
        Field(
            "efficiency",
            "symbol or number, a list of two, or a mapping",
            False,
            "Ordinary efficiency of the mesh (carrier held). One value serves both power "
            "directions; a list gives [first gear drives, second gear drives]; a mapping derives both "
            "from the tooth geometry of an external spur mesh (Laus App. A, eq. (136)): "
            "`eta_<coupling>_<gear>_<gear>` (driver first), see *Tooth contact*. "
            "Default: `eta_<coupling>`.",
        ),
        Field(
            "helix_angle",
            "symbol or number",
            False,
            "Helix angle beta of helical gears at the pitch radius, between 0 and 90 degrees (numbers are "
            "degrees, symbols radians): the tooth force then thrusts along the axes by F tan(beta), which "
            "the bearings take (see `thrust` friction). Default: spur gears.",
        ),
        Field(
            "hand",
            "`right` or `left`",
            False,
            "Hand of the first gear's helix (the second gear has the other hand on an external mesh, the "
            "same on an internal one); it sets the direction of the thrust. Default: `right`.",
        ),
    )

    @property
    def gears(self) -> tuple[str, str]:
        return self.mesh_gears

    @property
    def members(self) -> tuple[str, str]:
        return self.mesh_gears

    def member_twists(self, place: Placement, gears: Mapping[str, Gear]) -> tuple[Screw, Screw]:
        """Each gear turning about its own axis (Laus section 3.1, Definition 4)."""
        return gear_twist(place, self.mesh_gears[0]), gear_twist(place, self.mesh_gears[1])

    @property
    def angles(self) -> tuple[AngleFunctions, ...]:
        return () if self.helix is None else (self.helix,)

    def centre_distance(self, gears: Mapping[str, Gear]) -> sympy.Expr:
        """The distance between the gears' axes: r_g + r_h for an external mesh, R - r
        for an internal one (the loops of meshes close on these, Laus section 3.4.1.6).
        Positive for an internal mesh, which the layouts record as a fact."""
        g, h = gears[self.mesh_gears[0]], gears[self.mesh_gears[1]]
        if self.internal:
            ann, pin = (g, h) if g.internal else (h, g)
            return sympy.expand(ann.radius - pin.radius)
        return sympy.expand(g.radius + h.radius)

    def pitch_circle(self, gears: Mapping[str, Gear]) -> tuple[Gear, Gear]:
        """(gear, other): the pitch point lies on ``gear``'s pitch circle, its radius from
        that gear's centre towards the other's (the annulus of an internal mesh, else the
        first gear)."""
        g, h = gears[self.mesh_gears[0]], gears[self.mesh_gears[1]]
        if self.internal and h.internal:
            return h, g
        return g, h

    def spacing(self, gears: Mapping[str, Gear]) -> AxisSpacing:
        """Its gears' axes at the centre distance, the pitch point on the line of centres."""
        on, other = self.pitch_circle(gears)
        return AxisSpacing(
            self.name, self.mesh_gears, self.centre_distance(gears), (on.name, other.name), internal=self.internal
        )

    def report_fields(self) -> dict[str, Any]:
        return {"gears": list(self.gears), "mesh": "internal" if self.internal else "external"}

    def screws(self, place: Placement) -> CouplingScrews:
        """A mesh: the teeth roll on the pitch line (`rolling_screws`); helical teeth
        (`_helical_screws`) slide along the tooth line instead of the axis."""
        if self.helix is not None:
            point, axis = place.coupling_points[self.name], place.coupling_axes.get(self.name, place.axis)
            return self._helical_screws(place, NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point)))
        return rolling_screws(self.name, place)

    def _helical_screws(self, place: Placement, motion: NamedScrew) -> CouplingScrews:
        """A helical mesh on parallel axes, pressure angle zero as for spur gears.

        On the first gear's pitch cylinder the tooth line of a right-hand helix runs
        along ``sin(beta) e_theta + cos(beta) e_z`` (``e_theta`` the direction of the
        gear's rotation about its axis at the pitch point); the tooth force is normal to
        it in the pitch plane, ``cos(beta) e_theta - sin(beta) e_z``.  Its magnitude is
        counted by the tangential part, so the wrench is the tangential unit force plus
        ``tan(beta)`` of it along the axis: the mesh law and its efficiency keep their
        meaning, and the thrust reaches the bearings.  Sliding along the tooth line and
        tilting about the tangent are freedoms the screw system must hold, or the thrust
        would have nowhere to go."""
        assert self.helix is not None
        point, axis = place.coupling_points[self.name], place.coupling_axes.get(self.name, place.axis)
        tangent, normal = place.mesh_tangents[self.name], place.mesh_normals[self.name]
        centre = place.gear_centres[self.gears[0]]
        # +1 when the tangent is the first gear's e_theta at the pitch point, -1 when opposite.
        radial = vector([p - q for p, q in zip(point, centre, strict=True)])
        along = sympy.cancel(sum(a * b for a, b in zip(tangent, cross(axis, radial), strict=True)))
        orientation = sympy.sign(along)
        if orientation not in (1, -1):
            raise DerivationError(
                f"mesh {self.name}: the sense of its first gear's rotation at the pitch point is unknown"
            )
        lean = -int(orientation) * self.hand  # the axial part of e_theta-normal, per unit along the tangent
        cos, sin = self.helix.cos, self.helix.sin
        force = vector([t + lean * sin / cos * a for t, a in zip(tangent, axis, strict=True)])
        tooth_line = vector([-lean * sin * t + cos * a for t, a in zip(tangent, axis, strict=True)])
        sliding = NamedScrew("q", translation_twist(tooth_line))
        tilt = NamedScrew(rotation_magnitude_name(tangent), rotation_twist(tangent, point))
        secondary = (
            NamedScrew(translation_magnitude_name(normal), translation_twist(normal)),
            sliding,
            tilt,
            NamedScrew(rotation_magnitude_name(normal), rotation_twist(normal, point)),
        )
        pressing = NamedScrew(force_magnitude_name(tangent), force_wrench(force, point))
        return CouplingScrews((motion,), secondary, (pressing, *point_constraints(point)), spans=(sliding, tilt))

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> GearMesh | None:
        pair = read_gear_pair(entry, path, reader, gears)
        if pair is None:
            return None
        g1, g2 = pair
        if g1.internal and g2.internal:
            reader.problem(f"{path}.gears", "two internal gears cannot mesh")
            return None
        internal = g1.internal or g2.internal
        if internal and not annulus_larger(g1 if g1.internal else g2, g2 if g1.internal else g1, path, reader):
            return None
        stated = entry.get("mesh")
        if stated is not None and stated not in ("external", "internal"):
            reader.problem(f"{path}.mesh", f"expected `external` or `internal`, got {shortened(str(stated))}")
        elif stated is not None and (stated == "internal") != internal:
            reader.problem(
                f"{path}.mesh",
                f"stated {shortened(str(stated))} but the gears make an {'internal' if internal else 'external'} mesh",
            )
        for own, meaning, role, given in (
            (f"zeta_{name}", "mesh friction coefficient", "friction", "friction" in entry),
            (f"eta_{name}", "ordinary efficiency", "efficiency", "efficiency" in entry),
        ):
            elsewhere = reader.written.get(own)
            if not given and elsewhere is not None and not elsewhere.startswith(path):
                # The mesh's own symbol, already written in another role (a radius called eta_G):
                # said once, where it was written.
                reader.problem(
                    elsewhere, f"{own} is the name of the {meaning} of mesh {name}; give this symbol another name"
                )
                reader.roles[own] = role
        default = Friction(coulomb=reader.quantity(f"zeta_{name}", path, "friction"))
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, default, name)
        value = entry.get("efficiency", f"eta_{name}")
        definitions: tuple[Definition, ...] = ()
        if isinstance(value, Mapping):
            definitions = tooth_contact(value, f"{path}.efficiency", reader, name, (g1, g2))
            efficiencies = (definitions[0].symbol, definitions[1].symbol) if definitions else None
        else:
            efficiencies = read_efficiencies(value, f"{path}.efficiency", reader)
        helix, hand = read_helix(entry, path, reader, name)
        return cls(
            name,
            (g1.link, g2.link),
            friction,
            efficiencies=efficiencies,
            efficiency_definitions=definitions,
            mesh_gears=(g1.name, g2.name),
            internal=internal,
            helix=helix,
            hand=hand,
        )
