"""Readers of a mesh entry's parts, shared by the spur and bevel meshes
(`davies_sym.topology.couplings.GearMesh`) and the skew meshes
(`davies_sym.topology.skew_mesh`): the two gears, an annulus larger than its pinion,
the ordinary efficiencies, and the helix of helical gears."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy

from davies_sym.errors import shortened
from davies_sym.topology.angles import AngleFunctions, read_angle
from davies_sym.topology.entries import EntryReader, describe
from davies_sym.topology.gear import Gear


def read_helix(
    entry: Mapping[str, Any], path: str, reader: EntryReader, name: str
) -> tuple[AngleFunctions | None, int]:
    """The helix angle and hand of a mesh entry (None and +1 for spur gears)."""
    hand = entry.get("hand", "right")
    if hand not in ("right", "left"):
        reader.problem(f"{path}.hand", f"expected `right` or `left`, got {describe(hand)}")
    if "helix_angle" not in entry:
        if "hand" in entry:
            reader.problem(f"{path}.hand", "a hand needs helical gears: give `helix_angle` too, or remove `hand`")
        return None, 1
    meaning = f"the helix angle of mesh {name}"
    helix = read_angle(entry["helix_angle"], f"{path}.helix_angle", reader, name, "beta", meaning)
    return helix, -1 if hand == "left" else 1


def read_gear_pair(
    entry: Mapping[str, Any],
    path: str,
    reader: EntryReader,
    gears: Mapping[str, Gear],
    words: str = "",
    noun: str = "mesh",
) -> tuple[Gear, Gear] | None:
    """The two gears a mesh entry names in ``gears:``, on different links, or None with the
    problem recorded (``words`` says what the two are, e.g. "worm, wheel"; ``noun`` what
    joins them, a mesh or a chain)."""
    if "gears" not in entry:
        return None  # reported as a missing required key
    pair = entry["gears"]
    if not isinstance(pair, list) or len(pair) != 2:
        reader.problem(f"{path}.gears", "expected a list of two gear names" + (f" [{words}]" if words else ""))
        return None
    first, second = (reader.name(g, f"{path}.gears[{i}]") for i, g in enumerate(pair))
    if first is None or second is None:
        return None
    missing = [g for g in (first, second) if g not in gears]
    for g in missing:
        reader.unknown(f"{path}.gears", "gear", g)
    if missing:
        return None
    g1, g2 = gears[first], gears[second]
    if g1.link == g2.link:
        reader.problem(
            f"{path}.gears",
            f"gears {g1.name!r} and {g2.name!r} are both on link "
            f"{g1.link!r}: a {noun} must join gears on different links",
        )
        return None
    return g1, g2


def annulus_larger(annulus: Gear, pinion: Gear, path: str, reader: EntryReader) -> bool:
    """Whether an annulus may be larger than the gear it meshes (refused when its radius is
    known to be smaller or equal: the pinion would not fit inside)."""
    if sympy.expand(annulus.radius - pinion.radius).is_positive is not False:
        return True
    sizes = [shortened(sympy.sstr(g.radius), 30) for g in (annulus, pinion)]
    reader.problem(
        f"{path}.gears",
        f"the annulus {annulus.name!r} (radius {sizes[0]}) is not larger than the gear "
        f"{pinion.name!r} inside it (radius {sizes[1]}); give the annulus the larger radius",
    )
    return False


def read_efficiencies(value: Any, path: str, reader: EntryReader) -> tuple[sympy.Expr, sympy.Expr] | None:
    """The ordinary efficiencies of a mesh entry: one for both directions, or a list of two."""
    values = value if isinstance(value, list) else [value]
    if len(values) not in (1, 2):
        reader.problem(path, f"expected one efficiency or a list of two, got {len(values)}")
        return None
    read = [reader.quantity(v, f"{path}[{i}]" if len(values) > 1 else path, "efficiency") for i, v in enumerate(values)]
    if any(r is None for r in read):
        return None
    for i, r in enumerate(read):
        if r is not None and r.is_number and not 0 < r <= 1:
            reader.problem(path, f"an ordinary efficiency must lie in (0, 1], got {describe(values[i])}")
            return None
    first = read[0]
    second = read[-1]
    assert first is not None and second is not None
    return first, second
