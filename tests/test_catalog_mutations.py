"""Every entry of every catalog file, mutated: ``derive`` answers or refuses, it never crashes.

Each case takes one catalog train (read and written back with PyYAML, the library's YAML),
changes one entry and runs ``derive FILE --quiet``.  Mutations: the key deleted; the value
replaced by a list, a mapping, a number, the string ``xyz``, null, a huge number, a
negative number, a non-ASCII name, or a name that shadows a Python or sympy name
(``lambda``, ``E``, ``I``, ``pi``, ``N``, ``S``, ``oo``, ``zoo``, ``nan``); and every
link, gear, coupling and state renamed (with every reference to it) to those names.

Required: exit status 0 (the mutation was harmless) or 2 (refused); no traceback; at most
a few lines and under 2,000 characters on stderr; a refusal names the file.

The default run (about 360 cases) covers every entry of the fast trains (simple_pair,
planetary_simple) with a spread of the mutation kinds, every top-level entry of the
trains that derive in about a second deleted or nulled, and renames in simple_pair.  The
whole set (about 15,500 cases, the extra ones marked slow) is generated with
``HOSTILE_FULL=1``: it takes a long time (the harmless mutations of Ravigneaux derive
the train again, 7 s each); select a train with ``-k``, e.g. ``-m slow -k tuplin``.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from harness.helpers import CATALOG, MAX_STDERR, dump, full_run, load_yaml, rename_everywhere, run_main

from conftest import TRAIN_FILES

SHADOWING = ["lambda", "E", "I", "pi", "N", "S", "oo", "zoo", "nan"]
NON_ASCII = "Ωμέγα"

#: Value mutations: id -> new value (``DELETE``: remove the key or item).
DELETE = object()
VALUES: dict[str, Any] = {
    "delete": DELETE,
    "list": [1, 2],
    "mapping": {"a": 1},
    "number": 7,
    "string": "xyz",
    "null": None,
    "huge": 10**400,
    "negative": -5,
    "non_ascii": NON_ASCII,
    **{f"name_{n}": n for n in SHADOWING},
}
STRUCTURAL = ("delete", "list", "mapping", "null")
#: Tables whose keys are names: renaming one renames every reference to it.
NAMED_TABLES = ("links", "gears", "couplings", "states")
RENAMES = [NON_ASCII, *SHADOWING]

FAST_TRAINS = ("simple_pair", "planetary_simple")
#: Trains whose harmless mutations cost a full derivation of several seconds: full run only.
SLOW_TRAINS = ("humpage", "ravigneaux", "simpson")
#: Default run: in the fast trains, each entry gets every SPREAD-th mutation kind (shifted per entry,
#: so every kind meets every kind of entry across the file).
SPREAD = 8
#: Per-case watchdog of the in-process run (a hang fails the case instead of stopping the suite).
WATCHDOG = 120.0


def _paths(data: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    if isinstance(data, dict):
        for key, value in data.items():
            yield (*prefix, key)
            yield from _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield (*prefix, index)
            yield from _paths(value, (*prefix, index))


def _id(data: Any, path: tuple[Any, ...]) -> str:
    """``gears.1.radius``, ``couplings.A.links[0]``: list items as indices, mapping keys dotted."""
    out, node = "", data
    for part in path:
        if isinstance(node, list):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
        node = node[part]
    return out


def _mutated_value(data: Any, path: tuple[Any, ...], value: Any) -> Any:
    out = copy.deepcopy(data)
    parent = out
    for part in path[:-1]:
        parent = parent[part]
    if value is DELETE:
        del parent[path[-1]]
    else:
        parent[path[-1]] = copy.deepcopy(value)
    return out


def _default(train: str, depth: int, position: int, kind: str) -> bool:
    """Whether a value mutation is in the default run (see the module docstring)."""
    if train in FAST_TRAINS:
        return (position + list(VALUES).index(kind)) % SPREAD == 0
    return train not in SLOW_TRAINS and depth == 1 and kind in ("delete", "null")


def _cases(full: bool) -> list[Any]:
    cases = []
    for file in sorted(Path(p) for p in TRAIN_FILES):
        train = file.stem
        data = load_yaml(file)
        for position, path in enumerate(_paths(data)):
            for kind in VALUES:
                default = _default(train, len(path), position, kind)
                if default or full:
                    cases.append(
                        pytest.param(
                            train,
                            ("value", path, kind),
                            id=f"{train}:{_id(data, path)}:{kind}",
                            marks=[] if default else [pytest.mark.slow],
                        )
                    )
        for table in NAMED_TABLES:
            entries = data.get(table)
            names = list(entries) if isinstance(entries, dict) else list(entries or [])
            for name in names:
                for new in RENAMES:
                    default = train == "simple_pair" and new in (NON_ASCII, "lambda", "E", "I", "N")
                    if default or full:
                        cases.append(
                            pytest.param(
                                train,
                                ("rename", (table, name), new),
                                id=f"{train}:rename:{table}.{name}->{new}",
                                marks=[] if default else [pytest.mark.slow],
                            )
                        )
    return cases


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """The default run gets the default cases; ``HOSTILE_FULL=1`` every case (the extra ones
    marked slow), so that the plain run neither spends the time nor lists thousands of skips."""
    if metafunc.function.__name__ == "test_mutated_catalog_entry_is_answered_or_refused":
        metafunc.parametrize(("train", "mutation"), _cases(full_run(metafunc.config)))


def test_mutated_catalog_entry_is_answered_or_refused(tmp_path: Path, train: str, mutation: tuple[Any, ...]):
    data = load_yaml(CATALOG / f"{train}.yaml")
    if mutation[0] == "value":
        _, path, kind = mutation
        mutated = _mutated_value(data, path, VALUES[kind])
    else:
        _, (table, old), new = mutation
        mutated = rename_everywhere(data, table, old, new)
    file = dump(mutated, tmp_path / f"{train}.yaml")
    result = run_main([str(file), "--quiet"], timeout=WATCHDOG)
    why = result.describe()
    assert not result.timed_out, f"hung:\n{why}"
    assert "Traceback" not in result.stderr, f"crash:\n{why}"
    assert result.returncode in (0, 2), f"exit {result.returncode}:\n{why}"
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) <= 5, f"{len(lines)} lines on stderr:\n{why}"
    assert len(result.stderr) < MAX_STDERR, f"stderr of {len(result.stderr)} characters:\n{why}"
    if result.returncode == 2:
        assert str(file) in result.stderr, f"the refusal does not name the file:\n{why}"
