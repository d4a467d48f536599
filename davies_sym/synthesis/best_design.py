"""The chosen design as a train file with numbers: the file's own data with every tooth
symbol of the search replaced by its whole number, and those symbols taken off
``independent:``.  It derives as written, to the efficiency the search ranked it by."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import yaml


def best_design_text(source_text: str, teeth: Mapping[str, int], note: str) -> str:
    """The YAML of the design with ``teeth`` (every tooth number by symbol name)."""
    data: Any = yaml.safe_load(source_text)
    for entry in (data.get("gears") or {}).values():
        if isinstance(entry, dict) and str(entry.get("teeth")) in teeth:
            entry["teeth"] = teeth[str(entry["teeth"])]
    kept = [s for s in data.get("independent") or () if str(s) not in teeth]
    if kept:
        data["independent"] = kept
    else:
        data.pop("independent", None)
    header = "".join(f"# {line}\n" for line in note.splitlines())
    return header + yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=1000)
