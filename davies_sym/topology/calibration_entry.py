"""The ``calibrate`` entry of a train file: which loss parameters ``derive calibrate``
fits when the command line names none, and where the fit starts."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from davies_sym.topology.entries import describe
from davies_sym.topology.schema import CALIBRATE
from davies_sym.topology.symbols import exact_number

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class CalibrationDefaults:
    """Parameters to fit and their start values (symbol names)."""

    fit: tuple[str, ...]
    start: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))
    #: The measurements fitted to and those predicted, as the file writes them (relative
    #: to the file), each with its entry.
    data: tuple[str, str] | None = None
    predict: tuple[tuple[str, str], ...] = ()


def read_calibrate(value: Any, reader: EntryReader) -> CalibrationDefaults | None:
    """The ``calibrate`` mapping; its names are checked against the file's symbols."""
    entry = reader.mapping(value, "calibrate")
    if entry is None:
        return None
    reader.check_keys(entry, "calibrate", CALIBRATE)
    names = reader.items(entry.get("fit", []), "calibrate.fit", "a list of parameter names")  # `fit: mu` is [mu]
    if names is None:
        return None
    if not names or not all(isinstance(n, str) for n in names):
        reader.problem("calibrate.fit", f"expected a list of parameter names, got {describe(names)}")
        return None
    for i, name in enumerate(names):
        if name not in reader.symbols:
            reader.problem(
                f"calibrate.fit[{i}]",
                f"{name!r} is not a symbol of the file (symbols: {', '.join(sorted(reader.symbols))})",
            )
    start = reader.mapping(entry.get("start", {}), "calibrate.start") or {}
    values: dict[str, float] = {}
    for name, v in start.items():
        number = exact_number(v)
        if name not in names:
            reader.problem(f"calibrate.start.{name}", f"{name!r} is not among the parameters to fit")
        elif number is None or not number > 0 or not math.isfinite(float(number)):
            reader.problem(f"calibrate.start.{name}", f"expected a positive number, got {describe(v)}")
        elif reader.roles.get(str(name)) == "efficiency" and number > 1:
            reader.problem(f"calibrate.start.{name}", f"{name} is an efficiency: start it in (0, 1], got {describe(v)}")
        else:
            values[str(name)] = float(number)
    data = _file(entry["data"], "calibrate.data", reader) if "data" in entry else None
    listed = reader.items(entry.get("predict", []), "calibrate.predict", "a list of files") or []
    predict = [_file(v, f"calibrate.predict[{i}]", reader) for i, v in enumerate(listed)]
    return CalibrationDefaults(
        tuple(names),
        MappingProxyType(values),
        data,
        tuple(p for p in predict if p is not None),
    )


def _file(value: Any, path: str, reader: EntryReader) -> tuple[str, str] | None:
    """A file name of the entry at ``path``, with that entry."""
    if not isinstance(value, str) or not value.strip():
        reader.problem(path, f"expected a file name (relative to this file), got {describe(value)}")
        return None
    return value, path
