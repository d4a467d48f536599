"""The low-level coupling: its unit screws written out (Laus App. B, C)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import TWIST_COORDINATES, WRENCH_COORDINATES, NamedScrew
from davies_sym.errors import shortened
from davies_sym.topology.couplings import Coupling, read_links
from davies_sym.topology.expressions import check_name
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement
from davies_sym.topology.loss_entries import Friction, read_friction
from davies_sym.topology.schema import Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class ScrewCoupling(Coupling):
    """The low-level form: unit motion and action screws written out (Laus App. B, C)."""

    motion_screws: tuple[NamedScrew, ...] = ()
    action_screws: tuple[NamedScrew, ...] = ()

    kind: ClassVar[str] = "screws"
    DOC: ClassVar[str] = (
        "Low-level coupling with explicit unit screws, as in the tables of Laus "
        "appendices B and C. Coordinates not written are zero."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links."),
        Field("motions", "mapping", True, "Unit twists: magnitude name -> {r, s, t, u, v, w} (axis formation)."),
        Field(
            "actions",
            "mapping",
            True,
            "Unit wrenches transmitted: magnitude name -> {R, S, T, U, V, W} (ray formation).",
        ),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> ScrewCoupling | None:
        links = read_links(entry, path, reader)
        motions = (
            _read_screws(entry["motions"], f"{path}.motions", reader, TWIST_COORDINATES) if "motions" in entry else None
        )
        actions = _read_screws(entry.get("actions", {}), f"{path}.actions", reader, WRENCH_COORDINATES)
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name)
        if links is None or motions is None or actions is None:
            return None
        if not motions:
            reader.problem(f"{path}.motions", "a coupling needs at least one motion screw")
            return None
        return cls(name, links, friction, motions, actions)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return tuple(x for s in (*self.motion_screws, *self.action_screws) for x in s.screw)

    def screws(self, place: Placement) -> CouplingScrews:
        """The low-level kind: the screws as written (Laus App. B, C)."""
        return CouplingScrews(self.motion_screws, (), self.action_screws)


def _read_screws(
    value: Any, path: str, reader: EntryReader, coordinates: tuple[str, ...]
) -> tuple[NamedScrew, ...] | None:
    entry = reader.mapping(value, path)
    if entry is None:
        return None
    out = []
    for label, coords in entry.items():
        cpath = f"{path}.{label}"
        # The label names the screw's magnitude, which becomes a symbol of the outputs.
        why = check_name(label)
        if why is not None:
            reader.problem(cpath, f"{why} (a magnitude such as t_C or U_C)")
            continue
        cmap = reader.mapping(coords, cpath)
        if cmap is None:
            continue
        screw = []
        for key in cmap:
            if key not in coordinates:
                reader.problem(f"{cpath}.{key}", f"unknown coordinate {shortened(key)} (use {', '.join(coordinates)})")
        for c in coordinates:
            q = reader.quantity(cmap[c], f"{cpath}.{c}", "position", roots=True) if c in cmap else sympy.Integer(0)
            screw.append(q if q is not None else sympy.Integer(0))
        if all(c == 0 for c in screw):
            reader.problem(cpath, "a unit screw must not be zero")
        base = label.split("_")[0] if "_" in label else label
        out.append(NamedScrew(base, tuple(screw)))
    return tuple(out)
