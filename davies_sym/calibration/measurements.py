"""Measured operating points read from a CSV file: one row per point, one column per quantity.

The file is UTF-8 text (a byte-order mark is tolerated) with a header row naming the
columns; blank lines and lines starting with ``#`` are skipped anywhere.  The columns the
caller requires (and the optional ones the header has) must hold a finite number in every
row; other columns are kept in `Measurements.columns` but never read.  Every problem
is collected with its line and column and raised once as a
`MeasurementError`::

    data error: rig.csv:7: column 'T_O': 'abc' is not a number
"""

from __future__ import annotations

import csv
import io
import math
import os
import types
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from davies_sym.errors import MeasurementError, Problem

#: At most this many problems are reported; the rest are counted.
MAX_PROBLEMS = 20

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Measurements:
    """The numeric columns of a measurements file, row by row.

    ``columns`` is the header as written (extra columns included), ``values`` holds a
    read-only float array for each required column and each optional column present,
    ``lines`` the file line of each data row (for messages about a row).
    """

    path: str
    columns: tuple[str, ...]
    values: Mapping[str, FloatArray]
    lines: tuple[int, ...]

    @property
    def rows(self) -> int:
        """The number of data rows."""
        return len(self.lines)

    def __len__(self) -> int:
        return len(self.lines)

    def __contains__(self, name: object) -> bool:
        return name in self.values

    def column(self, name: str) -> FloatArray:
        """The values of column ``name`` (a required column, or an optional one present)."""
        try:
            return self.values[name]
        except KeyError:
            raise KeyError(f"{self.path}: no column {name!r} was read (read: {', '.join(self.values)})") from None

    def subset(self, indices: Sequence[int] | npt.NDArray[np.intp] | npt.NDArray[np.bool_]) -> Measurements:
        """The rows ``indices`` (0-based positions, or a boolean mask), in that order."""
        chosen = np.arange(len(self.lines))[np.asarray(indices)]
        values = {name: _frozen(array[chosen]) for name, array in self.values.items()}
        return Measurements(
            self.path, self.columns, types.MappingProxyType(values), tuple(self.lines[i] for i in chosen.tolist())
        )

    def location(self, row: int) -> str:
        """``path:line`` of data row ``row`` (0-based), for messages."""
        return f"{self.path}:{self.lines[row]}"


def read_measurements(
    path: str | os.PathLike[str], required: Sequence[str], optional: Sequence[str] = ()
) -> Measurements:
    """Read the CSV file ``path``; every name of ``required`` must be a column of it.

    Raises `MeasurementError` with every problem found (at most
    `MAX_PROBLEMS` of them, then a count of the rest).
    """
    source = os.fspath(path)
    text = _read_text(source)
    table = _Table(source)
    table.read(text, tuple(required), tuple(n for n in optional if n not in required))
    return table.result()


def _read_text(source: str) -> str:
    try:
        with open(source, "rb") as handle:
            raw = handle.read()
    except OSError as exc:
        why = exc.strerror or type(exc).__name__
        raise MeasurementError([Problem("", f"cannot read the file: {why}")], source) from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        byte = raw[exc.start : exc.start + 1].hex()
        raise MeasurementError(
            [Problem("", f"not UTF-8 text (byte 0x{byte} at offset {exc.start}); save the file as UTF-8 CSV", line)],
            source,
        ) from None


def _frozen(array: FloatArray) -> FloatArray:
    array.setflags(write=False)
    return array


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _shown(cell: str) -> str:
    """A cell for a message: quoted, a long one by its ends."""
    return repr(cell if len(cell) <= 40 else f"{cell[:25]}...{cell[-10:]}")


class _Table:
    """The reading of one file: rows parsed, problems collected."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.problems: list[Problem] = []
        self.columns: tuple[str, ...] = ()
        self.numbers: dict[str, list[float]] = {}
        self.lines: list[int] = []

    def problem(self, entry: str, message: str, line: int | None = None) -> None:
        self.problems.append(Problem(entry, message, line))

    def read(self, text: str, required: tuple[str, ...], optional: tuple[str, ...]) -> None:
        if not text.strip():
            self.problem("", "the file is empty (expected a header row naming the columns, then one row per point)")
            return
        rows = _rows(text)
        try:
            header = next(rows, None)
            if header is None:
                self.problem("", "no header row: the file has only comments and blank lines")
                return
            header_line, names = header
            self.columns = tuple(name.strip() for name in names)
            read = self._check_header(header_line, required, optional)
            for line, cells in rows:
                self._read_row(line, cells, read)
        except _NotCsv as exc:
            self.problem("", f"not readable as CSV: {exc.why}", exc.line)
            return
        if not self.lines and not self.problems:
            self.problem("", f"no data rows (only the header, on line {header_line})")

    def _check_header(self, line: int, required: tuple[str, ...], optional: tuple[str, ...]) -> dict[str, int]:
        """Which position each column to read has; problems for missing and repeated names."""
        positions: dict[str, list[int]] = {}
        for index, name in enumerate(self.columns):
            if name:  # an unnamed column (a trailing comma) is an ignored extra
                positions.setdefault(name, []).append(index)
        for name, where in positions.items():
            if len(where) > 1:
                numbers = [str(i + 1) for i in where]
                self.problem(
                    "header",
                    f"column {name!r} appears {len(where)} times (columns {', '.join(numbers[:-1])} and {numbers[-1]})",
                    line,
                )
        present = ", ".join(repr(n) for n in self.columns if n) or "none"
        missing = [name for name in required if name not in positions]
        if missing and all(_is_number(n) for n in self.columns):
            self.problem(
                "header",
                "the first row holds numbers, not column names: begin the file with a header "
                f"row naming the columns ({', '.join(required)})",
                line,
            )
            missing = []
        for name in missing:
            self.problem("header", f"required column {name!r} is missing (columns present: {present})", line)
        read = {name: positions[name][0] for name in (*required, *optional) if name in positions}
        self.numbers = {name: [] for name in read}
        return read

    def _read_row(self, line: int, cells: list[str], read: dict[str, int]) -> None:
        if len(cells) != len(self.columns):
            self.problem("", f"the row has {len(cells)} fields but the header has {len(self.columns)}", line)
            return
        self.lines.append(line)
        for name, index in read.items():
            cell = cells[index].strip()
            value = math.nan
            if not cell:
                self.problem(f"column {name!r}", "empty cell (every row needs a value here)", line)
            else:
                try:
                    value = float(cell)
                except ValueError:
                    self.problem(f"column {name!r}", f"{_shown(cell)} is not a number", line)
                else:
                    if not math.isfinite(value):
                        self.problem(f"column {name!r}", f"{_shown(cell)} is not a finite number", line)
                    elif name == "eta" and not 0 < value <= 1:
                        self.problem(
                            f"column {name!r}",
                            f"{_shown(cell)} is not an efficiency: a measured efficiency lies in (0, 1]; "
                            "correct the row or remove it",
                            line,
                        )
            self.numbers[name].append(value)

    def result(self) -> Measurements:
        if self.problems:
            shown = self.problems[:MAX_PROBLEMS]
            if len(self.problems) > MAX_PROBLEMS:
                more = len(self.problems) - MAX_PROBLEMS
                shown.append(Problem("", f"... and {more} more problem{'s' if more > 1 else ''}"))
            raise MeasurementError(shown, self.source)
        values = {name: _frozen(np.array(numbers, dtype=np.float64)) for name, numbers in self.numbers.items()}
        return Measurements(self.source, self.columns, types.MappingProxyType(values), tuple(self.lines))


def _rows(text: str) -> Iterator[tuple[int, list[str]]]:
    """(first line, cells) of each record of ``text``, comment and blank lines skipped.

    Comment lines are dropped before the CSV reader sees them, so a quote in a comment
    cannot swallow the data after it.
    """
    numbers: list[int] = []

    def kept() -> Iterator[str]:
        for number, line in enumerate(io.StringIO(text, newline=""), start=1):
            if not line.lstrip().startswith("#"):
                numbers.append(number)
                yield line

    # Spaces after a comma are skipped, so a hand-written `1, "a, b"` quotes as meant.
    reader = csv.reader(kept(), skipinitialspace=True)
    consumed = 0
    while True:
        try:
            cells = next(reader)
        except StopIteration:
            return
        except csv.Error as exc:
            raise _NotCsv(numbers[min(consumed, len(numbers) - 1)], str(exc)) from None
        first, consumed = numbers[consumed], reader.line_num
        # A blank line, or a row of empty cells a spreadsheet leaves after the data.
        if any(cell.strip() for cell in cells):
            yield first, cells


class _NotCsv(Exception):
    """A line the CSV reader cannot read (e.g. a field over its size limit)."""

    def __init__(self, line: int, why: str) -> None:
        super().__init__(why)
        self.line = line
        self.why = why
