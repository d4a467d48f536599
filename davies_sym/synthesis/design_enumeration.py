"""Every design whose speed ratios lie in their windows, found by joining small tables,
never by the blind product of the tooth-number ranges.

Each window (a state's ratio within its tolerance, a dependent tooth number at least the
minimum) involves a few tooth numbers: a simple set's ratio two, a two-set state's four.
A window's *table* holds the assignments of its tooth numbers that satisfy it: built from
the tables already made for some of them (their rows) and the ranges of the others,
evaluated in one vectorised pass, as long as that pass stays within `MAX_ROWS`.  The
tables are then joined on their shared tooth numbers, smallest result first; after each
join every window whose tooth numbers are all bound filters the rows.  A join that would
exceed `MAX_ROWS` is done in slices, so memory is bounded and no design is lost.  The
float test is widened by `SLACK`; the exact check afterwards decides
(`davies_sym.synthesis.rules`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

#: Relative widening of every window against rounding (the exact check decides).
SLACK = 1e-9
#: The most rows one vectorised pass evaluates (about 8 bytes per row and tooth number).
MAX_ROWS = 2_000_000

Rows = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class Window:
    """``low <= expression <= high``."""

    expression: sympy.Expr
    low: float
    high: float

    @property
    def symbols(self) -> frozenset[sympy.Symbol]:
        return frozenset(self.expression.free_symbols)


@dataclass(frozen=True)
class Table:
    """Assignments (one row each) of ``symbols`` (the columns)."""

    symbols: tuple[sympy.Symbol, ...]
    rows: Rows

    def __len__(self) -> int:
        return int(self.rows.shape[0])

    def column(self, s: sympy.Symbol) -> Rows:
        return self.rows[:, self.symbols.index(s)]


@dataclass(frozen=True)
class Enumeration:
    """The candidates (one row per design, columns in the order of ``free``) and how many
    rows the vectorised passes evaluated to find them."""

    free: tuple[sympy.Symbol, ...]
    candidates: Rows
    examined: int


class WindowFilter:
    """The windows as vectorised tests on the columns of a table."""

    def __init__(self, windows: Sequence[Window]) -> None:
        self.tests = []
        for w in windows:
            symbols = tuple(sorted(w.symbols, key=str))
            function = sympy.lambdify(symbols, w.expression, "numpy")
            low = w.low - SLACK * abs(w.low) if math.isfinite(w.low) else w.low
            high = w.high + SLACK * abs(w.high) if math.isfinite(w.high) else w.high
            self.tests.append((frozenset(symbols), symbols, function, low, high))
        self.examined = 0

    def __call__(self, table: Table) -> Table:
        """The rows of ``table`` that every window bound by its columns admits."""
        keep = np.ones(len(table), dtype=bool)
        bound = frozenset(table.symbols)
        self.examined += len(table)
        for uses, symbols, function, low, high in self.tests:
            if not uses <= bound:
                continue
            with np.errstate(all="ignore"):
                value = np.asarray(function(*(table.column(s)[keep].astype(float) for s in symbols)), dtype=float)
            ok = (value >= low) & (value <= high)
            keep[np.flatnonzero(keep)[~np.broadcast_to(ok, (int(np.count_nonzero(keep)),))]] = False
        return Table(table.symbols, table.rows[keep])


def _grid(symbols: Sequence[sympy.Symbol], bounds: dict[sympy.Symbol, tuple[int, int]]) -> Table:
    axes = [np.arange(bounds[s][0], bounds[s][1] + 1, dtype=np.int64) for s in symbols]
    mesh = np.meshgrid(*axes, indexing="ij") if axes else []
    rows = np.stack([m.reshape(-1) for m in mesh], axis=1) if axes else np.zeros((1, 0), dtype=np.int64)
    return Table(tuple(symbols), rows)


def _project(table: Table, symbols: frozenset[sympy.Symbol]) -> Table:
    """The distinct rows of ``table``'s columns among ``symbols``."""
    kept = tuple(s for s in table.symbols if s in symbols)
    if kept == table.symbols:
        return table
    columns = [table.symbols.index(s) for s in kept]
    return Table(kept, np.unique(table.rows[:, columns], axis=0))


def _keys(table: Table, shared: Sequence[sympy.Symbol]) -> Rows:
    """One integer per row for the values of ``shared`` (tooth numbers are below 2**20)."""
    key = np.zeros(len(table), dtype=np.int64)
    for s in shared:
        key = key * (1 << 20) + table.column(s)
    return key


def _join_slice(left: Table, right: Table) -> Table:
    """Every pair of rows that agree on the shared tooth numbers."""
    shared = [s for s in left.symbols if s in right.symbols]
    extra = [k for k, s in enumerate(right.symbols) if s not in left.symbols]
    symbols = (*left.symbols, *(right.symbols[k] for k in extra))
    lk, rk = _keys(left, shared), _keys(right, shared)
    order = np.argsort(rk, kind="stable")
    sorted_keys = rk[order]
    start = np.searchsorted(sorted_keys, lk, side="left")
    stop = np.searchsorted(sorted_keys, lk, side="right")
    counts = stop - start
    left_index = np.repeat(np.arange(len(left)), counts)
    offsets = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    right_index = order[np.repeat(start, counts) + offsets]
    rows = np.concatenate([left.rows[left_index], right.rows[right_index][:, extra]], axis=1)
    return Table(symbols, rows)


def _size(left: Table, right: Table) -> int:
    """The rows of the join of ``left`` and ``right``, counted without forming it."""
    shared = [s for s in left.symbols if s in right.symbols]
    if not shared or not len(left) or not len(right):
        return len(left) * len(right)  # an empty table (a window no row meets) joins to none
    lk, rk = _keys(left, shared), _keys(right, shared)
    values, counts = np.unique(rk, return_counts=True)
    where = np.clip(np.searchsorted(values, lk), 0, len(values) - 1)
    return int(counts[where][values[where] == lk].sum())


def _join(left: Table, right: Table, check: WindowFilter) -> Table:
    """The join of two tables, filtered by every window it binds, in slices of `MAX_ROWS`."""
    if len(right) > len(left):
        left, right = right, left
    step = max(1, MAX_ROWS // max(1, len(right)))
    parts = [check(_join_slice(Table(left.symbols, left.rows[k : k + step]), right)) for k in range(0, len(left), step)]
    symbols = parts[0].symbols if parts else (*left.symbols, *(s for s in right.symbols if s not in left.symbols))
    rows = np.concatenate([p.rows for p in parts]) if parts else np.zeros((0, len(symbols)), dtype=np.int64)
    return Table(symbols, rows)


def enumerate_designs(
    free: Sequence[sympy.Symbol],
    bounds: dict[sympy.Symbol, tuple[int, int]],
    windows: Sequence[Window],
    progress: Callable[[str], None] | None = None,
) -> Enumeration:
    """Every whole assignment of ``free`` within ``bounds`` that no window excludes (up to
    `SLACK`)."""
    say = progress or (lambda message: None)
    check = WindowFilter(windows)
    tables: list[Table] = []
    # Each window's table, smallest first: from the tables that cover some of its tooth
    # numbers and the ranges of the rest, while one pass stays within MAX_ROWS.
    pending = sorted(windows, key=lambda w: math.prod(bounds[s][1] - bounds[s][0] + 1 for s in w.symbols))
    for w in pending:
        table = _grid((), bounds)
        for t in sorted((_project(t, w.symbols) for t in tables if set(t.symbols) & w.symbols), key=len):
            if set(t.symbols) <= set(table.symbols):
                continue
            if _size(table, t) <= MAX_ROWS:
                table = _join(table, t, check)
        rest = sorted(w.symbols - set(table.symbols), key=str)
        if len(table) * math.prod(bounds[s][1] - bounds[s][0] + 1 for s in rest) > MAX_ROWS:
            continue  # this window filters the joins below instead
        table = check(_join_slice(table, _grid(rest, bounds)) if rest else table)
        tables = [t for t in tables if not set(t.symbols) <= set(table.symbols)] + [table]
        say(f"{len(table)} assignment(s) of {', '.join(map(str, table.symbols))}")
    covered = {s for t in tables for s in t.symbols}
    tables += [check(_grid((s,), bounds)) for s in free if s not in covered]
    # Join everything: tables that share tooth numbers first, the smallest result first.
    while len(tables) > 1:
        pairs = [(a, b) for a in range(len(tables)) for b in range(a + 1, len(tables))]
        a, b = min(
            pairs,
            key=lambda ab: (
                not set(tables[ab[0]].symbols) & set(tables[ab[1]].symbols),
                _size(tables[ab[0]], tables[ab[1]]),
            ),
        )
        joined = _join(tables[a], tables[b], check)
        tables = [t for k, t in enumerate(tables) if k not in (a, b)] + [joined]
        say(f"{len(joined)} assignment(s) of {len(joined.symbols)} tooth numbers")
    final = tables[0]
    columns = [final.symbols.index(s) for s in free]
    return Enumeration(tuple(free), final.rows[:, columns], check.examined)
