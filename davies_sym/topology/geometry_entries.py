"""The entries of a train file that choose its geometry: ``placement`` (the direction the
planets of a 2-D drawing lie along) and ``independent`` (which sizes the geometric
constraints leave free)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import sympy

from davies_sym.topology.entries import describe
from davies_sym.topology.symbols import exact_number

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


def read_placement(value: Any, reader: EntryReader) -> tuple[sympy.Expr, sympy.Expr] | None:
    """``[x, y]`` (exact) or an angle in degrees whose sine and cosine are square roots."""
    if isinstance(value, list) and len(value) == 2:
        parts = [reader.quantity(v, f"placement[{i}]", "position", roots=True) for i, v in enumerate(value)]
        if any(p is None for p in parts):
            return None
        if all(p == 0 for p in parts):
            reader.problem("placement", "the direction must not be zero")
            return None
        return (parts[0], parts[1])
    angle = exact_number(value)
    if angle is None:
        reader.problem("placement", f"expected [x, y] or an angle in degrees, got {describe(value)}")
        return None
    radians = angle * sympy.pi / 180
    cos, sin = sympy.cos(radians), sympy.sin(radians)
    if any(p.has(sympy.cos, sympy.sin) for p in (cos, sin)):
        reader.problem(
            "placement",
            f"the sine and cosine of {angle} degrees are not square roots; give the direction as [x, y] instead",
        )
        return None
    return (cos, sin)


def read_independent(value: Any, reader: EntryReader) -> tuple[str, ...] | None:
    """``independent: [r1, r2, r3]``: symbols of the file that stay free."""
    # One symbol written without brackets is the list of it; a problem with it is at the key.
    bare = not isinstance(value, list)
    value = reader.items(value, "independent", "a list of symbols")
    if value is None:
        return None
    if not value:
        reader.problem("independent", "expected a list of symbols, got an empty list")
        return None
    names: list[str] = []
    for i, item in enumerate(value):
        entry = "independent" if bare else f"independent[{i}]"
        if not isinstance(item, str) or item not in reader.symbols:
            known = ", ".join(sorted(reader.symbols)[:20])
            reader.problem(entry, f"{describe(item)} is not a symbol of the train (symbols: {known})")
        elif item in names:
            reader.problem(entry, f"{item!r} is written twice: write each symbol once")
        elif reader.roles.get(item) not in GEOMETRY_ROLES:
            # The geometric constraints tie sizes; a loss coefficient or an angle stays free anyway.
            reader.problem(entry, f"{item!r} is no size of the geometry: list radii, tooth numbers or positions")
        else:
            names.append(item)
    return tuple(names)


#: The roles of the symbols the geometric constraints tie (``independent:`` chooses among them).
GEOMETRY_ROLES = frozenset({"length", "teeth", "position"})
