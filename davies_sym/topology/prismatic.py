"""The prismatic pair (a slider): one translation along its direction."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import NamedScrew, Vector, translation_magnitude_name, translation_twist, vector
from davies_sym.topology.couplings import Coupling, read_direction, read_links
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement, point_constraints
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.schema import Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class Prismatic(Coupling):
    """A prismatic pair: one translation along ``direction``."""

    direction: Vector = (sympy.Integer(1), sympy.Integer(0), sympy.Integer(0))

    kind: ClassVar[str] = "prismatic"
    load_dependent_unit: ClassVar[str] = "1"
    DOC: ClassVar[str] = "Prismatic pair between two links: one translation."
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links."),
        Field("direction", "`x`, `y`, `z` or [x, y, z]", True, "Direction of the translation."),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> Prismatic | None:
        links = read_links(entry, path, reader)
        direction = read_direction(entry["direction"], f"{path}.direction", reader) if "direction" in entry else None
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name, on="guide")
        if links is None or direction is None:
            return None
        return cls(name, links, friction, direction)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return tuple(self.direction)

    def screws(self, place: Placement) -> CouplingScrews:
        """A slider: one translation along its direction."""
        motion = NamedScrew(translation_magnitude_name(self.direction), translation_twist(self.direction))
        return CouplingScrews((motion,), (), point_constraints(vector((0, 0, 0))))
