"""Meshes on skew axes: a worm and its wheel, a pair of crossed helical gears.

Beyond the references (Laus leaves non-parallel, non-intersecting axes as future work):
the two gears touch at the pitch point, where the teeth slide along the tooth line, so
the Coulomb friction force ``mu N`` of the sliding contact acts along it.  The entry
gives the angles the screws need (`davies_sym.topology.angles`): the helix angle of
each gear (the lead angle of a worm is its complement), the normal pressure angle, and
the coefficient ``mu``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import (
    AXES,
    UNIT,
    NamedScrew,
    cross,
    force_wrench,
    rotation_magnitude_name,
    rotation_twist,
    translation_twist,
)
from davies_sym.losses.definitions import Definition
from davies_sym.topology.angles import AngleFunctions, read_angle
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.entries import describe
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.mesh_entries import read_gear_pair
from davies_sym.topology.schema import Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader

#: Normal pressure angle of a skew mesh entry that gives none (degrees).
DEFAULT_PRESSURE_ANGLE = 20

PRESSURE_ANGLE = Field(
    "pressure_angle",
    "symbol or number",
    False,
    f"Normal pressure angle alpha_n. Default: {DEFAULT_PRESSURE_ANGLE} degrees.",
)


@dataclass(frozen=True)
class SkewMesh(Coupling):
    """Two gears on skew axes touching at the pitch point (worm and wheel, crossed helical).

    The first gear's axis crosses the second's at the shaft angle beta_1 + beta_2 (the
    helix angles, same hand), at the centre distance r_1 + r_2.  The relative motion
    keeps the tooth surfaces in contact at the pitch point: every motion but the one
    along the common normal (five freedoms); the action is the normal force ``N``
    (pressure angle ``alpha_n`` in the plane normal to the tooth line), and the
    Coulomb friction ``mu |N|`` acts along the tooth line against the sliding.
    """

    mesh_gears: tuple[str, str] = ("", "")
    #: cos and sin of the helix angle of each gear (first, second).
    helix: tuple[AngleFunctions, AngleFunctions] | None = None
    pressure: AngleFunctions | None = None

    DOC: ClassVar[str] = ""

    noun: ClassVar[str] = "mesh"
    meshing: ClassVar[bool] = True

    @property
    def gears(self) -> tuple[str, str]:
        return self.mesh_gears

    @property
    def right_shaft_angle(self) -> bool:
        """Whether the axes cross at a right angle (a worm drive)."""
        return False

    @property
    def angles(self) -> tuple[AngleFunctions, ...]:
        """The independent angles: the normal pressure angle and the helix angles (a worm's
        helix angle is the complement of its lead angle, with the same two symbols)."""
        assert self.helix is not None and self.pressure is not None
        return (self.pressure, self.helix[1]) if self.right_shaft_angle else (self.pressure, *self.helix)

    @property
    def definitions(self) -> tuple[Definition, ...]:
        return self.friction.definitions + tuple(d for a in self.angles for d in a.definitions)

    def screws(self, place: Placement) -> CouplingScrews:
        """A point contact at the pitch point.  The sliding along the tooth line is the
        first motion (the one its friction opposes); the sliding across it and the
        rotations about lines through the pitch point are the other four freedoms; the
        normal force is the action, and the friction force acts along the tooth line at
        the pitch point."""
        point = place.coupling_points[self.name]
        tooth_line, normal = place.mesh_tangents[self.name], place.mesh_normals[self.name]
        sliding = NamedScrew("q", translation_twist(tooth_line))
        across = NamedScrew("q", translation_twist(cross(normal, tooth_line)))
        tilts = tuple(NamedScrew(rotation_magnitude_name(UNIT[a]), rotation_twist(UNIT[a], point)) for a in AXES)
        friction = NamedScrew("F", force_wrench(tooth_line, point))
        pressing = NamedScrew("N", force_wrench(normal, point))
        return CouplingScrews((sliding,), (across, *tilts), (pressing, *point_constraints(point)), friction)

    @classmethod
    def _gear_pair(
        cls, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> tuple[Gear, Gear] | None:
        """The two gears, external (a skew mesh has no annulus)."""
        pair = read_gear_pair(entry, path, reader, gears, cls._pair_words)
        if pair is None:
            return None
        g1, g2 = pair
        internal = [g.name for g in (g1, g2) if g.internal]
        if internal:
            reader.problem(
                f"gears.{internal[0]}.internal",
                f"gear {internal[0]!r} meshes in {path} on skew axes, where gears are external; "
                "remove `internal: true`",
            )
            return None
        return g1, g2

    _pair_words: ClassVar[str] = "first gear, second gear"

    @classmethod
    def _common(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader
    ) -> tuple[Friction, AngleFunctions | None]:
        given = entry.get("friction")
        default = Friction() if given is not None else Friction(coulomb=reader.quantity(f"mu_{name}", path, "friction"))
        friction = read_friction(given, f"{path}.friction", reader, default, name)
        if friction.coulomb is None or friction.linear is not None:
            reader.problem(
                f"{path}.friction",
                "a sliding contact needs a Coulomb law (`coulomb: mu`), which its normal force loads",
            )
        pressure = read_angle(
            entry.get("pressure_angle", DEFAULT_PRESSURE_ANGLE),
            f"{path}.pressure_angle",
            reader,
            name,
            "alpha_n",
            f"the normal pressure angle of mesh {name}",
        )
        return friction, pressure


@dataclass(frozen=True)
class WormMesh(SkewMesh):
    """A worm (first gear) and its wheel on axes crossing at a right angle."""

    kind: ClassVar[str] = "worm"
    DOC: ClassVar[str] = (
        "A worm (first gear) driving or driven by its wheel (second gear) on axes crossing at a right "
        "angle, touching at the pitch point (r_1 is the worm's pitch radius). The teeth slide along the "
        "thread; the Coulomb friction mu N acts along it. Angles written as numbers are in degrees, "
        "symbols stand for radians."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("gears", "[worm, wheel]", True, "The worm, then its wheel."),
        Field(
            "lead_angle",
            "symbol or number",
            True,
            "Lead angle gamma of the worm's thread at the pitch radius, between 0 and 90 degrees "
            "(the wheel's helix angle; the worm's is 90 degrees minus it).",
        ),
        PRESSURE_ANGLE,
    )
    _pair_words: ClassVar[str] = "worm, wheel"

    @property
    def right_shaft_angle(self) -> bool:
        return True

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> WormMesh | None:
        pair = cls._gear_pair(entry, path, reader, gears)
        friction, pressure = cls._common(name, entry, path, reader)
        worm_name = pair[0].name if pair is not None else "1"
        lead = (
            read_angle(
                entry["lead_angle"], f"{path}.lead_angle", reader, name, "gamma", f"the lead angle of worm {worm_name}"
            )
            if "lead_angle" in entry
            else None
        )
        if pair is None or pressure is None or lead is None:
            return None
        # The worm's helix angle is 90 degrees - gamma: its cos is sin(gamma) and its sin cos(gamma).
        worm = AngleFunctions(sympy.pi / 2 - lead.angle, lead.sin, lead.cos, lead.meaning)
        return cls(name, (pair[0].link, pair[1].link), friction, (pair[0].name, pair[1].name), (worm, lead), pressure)


@dataclass(frozen=True)
class CrossedHelicalMesh(SkewMesh):
    """Two helical gears of the same hand on axes crossing at the sum of their helix angles."""

    kind: ClassVar[str] = "crossed_helical"
    DOC: ClassVar[str] = (
        "Two crossed helical gears of the same hand: the shaft angle is the sum of their helix angles, "
        "they touch at the pitch point and slide along the tooth line; the Coulomb friction mu N acts "
        "along it. Angles written as numbers are in degrees, symbols stand for radians."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("gears", "[gear, gear]", True, "The two gears."),
        Field(
            "helix_angles",
            "[symbol or number, symbol or number]",
            True,
            "Helix angle beta of each gear at its pitch radius, each between 0 and 90 degrees "
            "(the shaft angle is their sum).",
        ),
        PRESSURE_ANGLE,
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> CrossedHelicalMesh | None:
        pair = cls._gear_pair(entry, path, reader, gears)
        friction, pressure = cls._common(name, entry, path, reader)
        helix: list[AngleFunctions | None] = []
        value = entry.get("helix_angles")
        if value is not None and not (isinstance(value, list) and len(value) == 2):
            reader.problem(f"{path}.helix_angles", f"expected a list of two angles, got {describe(value)}")
        elif value is not None:
            names = pair[0].name if pair is not None else "1", pair[1].name if pair is not None else "2"
            helix = [
                read_angle(
                    v, f"{path}.helix_angles[{i}]", reader, name, f"beta_{i + 1}", f"the helix angle of gear {g}"
                )
                for i, (v, g) in enumerate(zip(value, names, strict=True))
            ]
        if pair is None or pressure is None or len(helix) != 2 or helix[0] is None or helix[1] is None:
            return None
        return cls(
            name, (pair[0].link, pair[1].link), friction, (pair[0].name, pair[1].name), (helix[0], helix[1]), pressure
        )
