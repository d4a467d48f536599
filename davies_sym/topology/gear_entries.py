"""The ``gears:`` table of a topology file: each gear's link, pitch radius (from
``radius``, or ``teeth`` and ``module``), whether it is internal, and its axis."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy

from davies_sym.topology.couplings import read_direction
from davies_sym.topology.entries import EntryReader, describe
from davies_sym.topology.model import Gear
from davies_sym.topology.schema import GEAR


def read_gears(value: Any, reader: EntryReader, links: set[str]) -> dict[str, Gear]:
    """Every gear of the table that reads, by name; the others are recorded as broken."""
    gears: dict[str, Gear] = {}
    table = reader.mapping(value, "gears")
    if table is None:
        reader.unreadable.add("gear")
    for name, entry in (table or {}).items():
        path = f"gears.{name}"
        if reader.defined_name(name, path, "gear") is None:
            continue
        entry = reader.mapping(entry, path)
        if entry is None:
            reader.broken.add(name)
            continue
        reader.check_keys(entry, path, GEAR)
        link = reader.name(entry["link"], f"{path}.link") if "link" in entry else None
        if link is not None and link not in links:
            reader.unknown(f"{path}.link", "link", link)
        internal = entry.get("internal", False)
        if not isinstance(internal, bool):
            reader.problem(f"{path}.internal", f"expected true or false, got {describe(internal)}")
            internal = False
        radius, teeth, module = _read_size(entry, path, reader)
        tilted = entry.get("axis") == "tilted"
        axis = read_direction(entry["axis"], f"{path}.axis", reader) if "axis" in entry and not tilted else None
        about = reader.name(entry["about"], f"{path}.about") if "about" in entry else None
        if about is not None and about not in links:
            reader.unknown(f"{path}.about", "link", about)
            about = None
        elif about is not None and "axis" in entry:
            reader.problem(
                f"{path}.about", "a gear centred on another link's axis is a parallel-axis gear: drop `axis`"
            )
        if link is not None and radius is not None:
            gears[name] = Gear(name, link, radius, internal, teeth, module, axis, tilted, about)
        else:
            reader.broken.add(name)
    if table and not gears:
        reader.unreadable.add("gear")  # not one gear could be read: the table's problems say it all
    return gears


#: The most teeth a gear may have: far beyond any gear made (rings of a few hundred), and
#: small enough that every number derived from it stays a finite float.
MAX_TEETH = 100_000


def _read_size(
    entry: Mapping[str, Any], path: str, reader: EntryReader
) -> tuple[sympy.Expr | None, int | sympy.Expr | None, sympy.Expr | None]:
    """Pitch radius from ``radius`` or from ``teeth`` and ``module``."""
    has_radius, has_teeth = "radius" in entry, "teeth" in entry
    if has_radius == has_teeth:
        reader.problem(path, "give either `radius` or `teeth` with `module`")
        return None, None, None
    if has_radius:
        # Beside a radius the module still sizes the teeth: the tooth-contact model's addendum.
        module = reader.quantity(entry["module"], f"{path}.module", "length") if "module" in entry else None
        return reader.quantity(entry["radius"], f"{path}.radius", "length"), None, module
    teeth = entry["teeth"]
    if isinstance(teeth, str):
        count = reader.quantity(teeth, f"{path}.teeth", "teeth")  # a tooth number as a symbol, e.g. z1
        if count is None:
            return None, None, None
        if count.is_number and not (count.is_integer and 0 < count <= MAX_TEETH):
            reader.problem(
                f"{path}.teeth", f"expected a whole number of teeth from 1 to {MAX_TEETH}, got {describe(teeth)}"
            )
            return None, None, None
        teeth = count
    elif not isinstance(teeth, int) or isinstance(teeth, bool) or not 0 < teeth <= MAX_TEETH:
        reader.problem(
            f"{path}.teeth",
            f"expected a whole number of teeth from 1 to {MAX_TEETH} or a symbol, got {describe(teeth)}",
        )
        return None, None, None
    if "module" not in entry:
        reader.problem(path, "`teeth` needs `module` to give the pitch radius")
        return None, None, None
    module = reader.quantity(entry["module"], f"{path}.module", "length")
    if module is None:
        return None, None, None
    return module * teeth / 2, teeth, module
