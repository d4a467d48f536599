"""The revolute pair (a bearing): one rotation about its axis (Laus Table 3, couplings A, B)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import NamedScrew, rotation_magnitude_name, rotation_twist
from davies_sym.topology.couplings import Coupling, read_links
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.schema import Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class Revolute(Coupling):
    """A revolute pair (bearing): one rotation about the axis through its point."""

    at: sympy.Expr | None = None
    axis: str | None = None

    kind: ClassVar[str] = "revolute"
    located: ClassVar[bool] = True
    DOC: ClassVar[str] = (
        "Revolute pair between two links. Its axis is parallel to the gear "
        "axes; its position is that of the gears of either link, or `at`."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links; the edge goes from the first to the second."),
        Field(
            "at",
            "number or expression",
            False,
            "Position of the axis on the layout line (y), needed only when neither link carries a gear. "
            "In a 2-D drawing a symbol here is a free shape: a planet placed from that axis closes its "
            "triangle on the side where the distance involved is positive (the other side is the mirror "
            "drawing); that side is a fact of the layout.",
        ),
        Field(
            "axis",
            "link",
            False,
            "The link whose gear axis this bearing is on, when both links carry gears but are not "
            "coaxial (a planet pin in a carrier that also has teeth). A third link: the held link turns "
            "about that link's axis (two shafts on one axis, each in a bearing of the frame). Default: "
            "the two links are coaxial.",
        ),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> Revolute | None:
        links = read_links(entry, path, reader)
        at = reader.quantity(entry["at"], f"{path}.at", "position") if "at" in entry else None
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name, on="bearing")
        axis = reader.name(entry["axis"], f"{path}.axis") if "axis" in entry else None
        return None if links is None else cls(name, links, friction, at, axis)

    @property
    def named_links(self) -> tuple[tuple[str, str], ...]:
        return () if self.axis is None or self.axis in self.links else (("axis", self.axis),)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return () if self.at is None else (self.at,)

    def screws(self, place: Placement) -> CouplingScrews:
        """A bearing: one rotation about its axis; forces and torques elsewhere."""
        point, axis = place.coupling_points[self.name], place.coupling_axes.get(self.name, place.axis)
        motion = NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point))
        return CouplingScrews((motion,), (), point_constraints(point, axis=axis))
