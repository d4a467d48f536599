"""Small texts the programs share: names made from what the user wrote (ports, file
names) and the lines of the opening comment that list the parameters."""

from __future__ import annotations

import os
import re
from collections.abc import Sequence

from davies_sym.efficiency.parameter_ranges import Parameter


def identifier_part(text: str) -> str:
    """``text`` with every character but letters, digits and ``_`` replaced by ``_`` (a
    port ``A'`` gives ``A_``), to follow ``efficiency_from_``."""
    return "".join(ch if (ch.isascii() and ch.isalnum()) or ch == "_" else "_" for ch in text)


def module_name(path: str | None, state: str | None, fallback: str) -> str:
    """A CamelCase identifier for the namespace of the generated file: the topology file's
    name and the state (``simpson.yaml``, state ``first``: ``SimpsonFirst``), else the
    ``fallback`` (the train's name)."""
    stem = os.path.splitext(os.path.basename(path))[0] if path else fallback
    words = re.split(r"[^A-Za-z0-9]+", f"{stem} {state or ''}")
    name = "".join(w[:1].upper() + w[1:] for w in words if w)
    if not name or not name[0].isalpha():
        name = "Train" + name
    return name


def origin_text(path: str | None, state: str | None) -> str:
    """``tuplin.yaml``, ``simpson.yaml (state first)``."""
    origin = os.path.basename(path) if path else "a topology file"
    return origin + (f" (state {state})" if state else "")


def parameter_lines(table: Sequence[Parameter], names: Sequence[str]) -> list[str]:
    """``  eta_C in (0, 1]: ordinary efficiency of mesh C ... [1]`` for each of ``names``."""
    by_name = {p.name: p for p in table}
    out = []
    for n in names:
        p = by_name[n]
        unit = f" [{p.unit}]" if p.unit else ""
        out.append(f"  {n} in {p.range_text}: {p.meaning}{unit}")
    return out
