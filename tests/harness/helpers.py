"""Run ``derive`` as a user does and check the refusal contract of its answers to bad input.

Two runners:

- :func:`run_main` calls ``davies_sym.cli.main`` in this process (fast: no interpreter
  and sympy start-up); an exception escaping ``main`` is turned into a result whose
  stderr holds the traceback and whose status is 1, as the interpreter would do, so
  that the assertions read the same for both runners.  A SIGALRM watchdog turns a
  hang into a failure instead of a stuck suite.
- :func:`run_cli` starts ``python -m davies_sym.cli`` in a fresh process with this
  worktree on ``PYTHONPATH`` (crashes, bombs, hangs, huge files), with a hard timeout.

The refusal contract checked by :func:`assert_refused`: exit status 2, nothing
executed, no traceback, one line per problem on stderr of the form
``FILE:LINE: ENTRY: message`` (a prefix such as ``topology error:`` is allowed before
``FILE``), short (no echo of a huge value).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import resource
import signal
import subprocess
import sys
import time
import traceback
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
CATALOG = ROOT / "catalog"
DATA = ROOT / "tests" / "data"

#: Longest acceptable stderr of a refusal: one or a few short lines, never a huge value echoed back.
MAX_STDERR = 2000
#: The default hang guard of both runners: a run still going after this long is stopped and
#: fails.  Never a claim about speed (a busy machine may be slow); the tests bound the work
#: instead (a refusal names the limit it hit).
HANG_GUARD = 120.0


@dataclass
class Result:
    returncode: int | None  # None: killed by the timeout
    stdout: str
    stderr: str
    elapsed: float
    timed_out: bool = False

    def describe(self) -> str:
        status = "TIMEOUT" if self.timed_out else f"exit {self.returncode}"
        return (
            f"{status} after {self.elapsed:.2f} s\n--- stdout (tail) ---\n{self.stdout[-1500:]}\n"
            f"--- stderr (tail) ---\n{self.stderr[-3000:]}"
        )


class Hang(BaseException):
    """The in-process run exceeded its watchdog (a BaseException, as KeyboardInterrupt:
    ``derive`` reports every Exception as an internal error, and a hang is not one)."""


def _on_alarm(signum: int, frame: Any) -> None:
    raise Hang("derive did not finish within the watchdog time")


def run_main(args: Sequence[str], timeout: float = HANG_GUARD) -> Result:
    """``derive ARGS`` in this process; stdout and stderr captured, exceptions rendered as a traceback."""
    from davies_sym import cli

    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    previous = signal.signal(signal.SIGALRM, _on_alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code: int | None = cli.main([str(a) for a in args])
            except SystemExit as exc:  # argparse
                code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
            except Hang:
                return Result(
                    None,
                    out.getvalue(),
                    err.getvalue() + "\n[watchdog: in-process run hung]",
                    time.perf_counter() - start,
                    timed_out=True,
                )
            except BaseException:
                err.write(traceback.format_exc())
                code = 1
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return Result(code, out.getvalue(), err.getvalue(), time.perf_counter() - start)


def run_cli(
    args: Sequence[str],
    timeout: float = HANG_GUARD,
    cwd: str | os.PathLike[str] | None = None,
    memory: int | None = None,
) -> Result:
    """``python -m davies_sym.cli ARGS`` in a fresh process (this worktree first on PYTHONPATH);
    ``memory``: an address-space limit in bytes (a bomb then fails in its own process
    instead of starving the machine)."""

    def limit() -> None:
        if memory is not None:
            resource.setrlimit(resource.RLIMIT_AS, (memory, memory))

    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    start = time.perf_counter()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "davies_sym.cli", *map(str, args)],
            capture_output=True,
            cwd=cwd,
            env=env,
            timeout=timeout,
            check=False,
            preexec_fn=limit,
        )
    except subprocess.TimeoutExpired as exc:
        return Result(None, _text(exc.stdout), _text(exc.stderr), time.perf_counter() - start, timed_out=True)
    return Result(proc.returncode, _text(proc.stdout), _text(proc.stderr), time.perf_counter() - start)


def _text(data: bytes | str | None) -> str:
    if data is None:
        return ""
    return data if isinstance(data, str) else data.decode("utf-8", errors="replace")


def problem_lines(result: Result) -> list[str]:
    return [line for line in result.stderr.splitlines() if line.strip()]


def assert_refused(
    result: Result,
    path: str | os.PathLike[str] | None,
    entries: Iterable[str] = (),
    *,
    line: bool = True,
    max_lines: int | None = 1,
    status: int = 2,
) -> None:
    """The refusal contract (see the module docstring).

    ``path``: the file the message must name (None for command-line-only problems);
    ``entries``: the message must name one of them (an entry path such as
    ``gears.1.radius`` or an option such as ``--eval``); ``line``: the file name is
    followed by ``:LINE:``; ``max_lines``: at most this many problem lines (None: a few).
    """
    why = result.describe()
    assert not result.timed_out, f"no answer in time:\n{why}"
    assert "Traceback" not in result.stderr, f"a traceback instead of a message:\n{why}"
    assert result.returncode == status, f"expected exit {status}:\n{why}"
    assert len(result.stderr) < MAX_STDERR, f"stderr of {len(result.stderr)} characters:\n{why}"
    lines = problem_lines(result)
    assert lines, f"no message on stderr:\n{why}"
    assert len(lines) <= (max_lines or 5), f"{len(lines)} lines for one problem:\n{why}"
    if path is not None:
        name = str(path)
        pattern = re.escape(name) + (r":\d+:" if line else r"(:\d+)?:")
        where = name + (":LINE" if line else "")
        assert re.search(pattern, lines[0]), f"the first line does not give {where}:\n{why}"
        for text in lines:
            assert name in text, f"a line of the refusal does not name the file {name}:\n{why}"
    entries = list(entries)
    if entries:
        assert any(e in result.stderr for e in entries), f"the message names none of {entries}:\n{why}"


def write(folder: Path, text: str, name: str = "train.yaml") -> Path:
    """``text`` written as ``folder/name``."""
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def write_file(folder: Path, name: str, content: str | bytes) -> Path:
    """``content`` (text in UTF-8, or bytes as they are) written as ``folder/name``."""
    path = folder / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return path


def replaced(text: str, old: str, new: str) -> str:
    """``text`` with the first ``old`` (which must be there) replaced by ``new``."""
    assert old in text, old
    return text.replace(old, new, 1)


def line_of(text: str, needle: str) -> int:
    """The line (from 1) of the first line of ``text`` holding ``needle``."""
    return next(k for k, line in enumerate(text.splitlines(), 1) if needle in line)


def assert_at(result: Result, path: Path, line: int, entry: str) -> None:
    """Refused with one line at ``path:line: entry:``."""
    assert_refused(result, path, (entry,))
    assert re.search(re.escape(f"{path}:{line}: {entry}:"), result.stderr), result.describe()


def assert_edit_refused(
    folder: Path, source: str, old: str, new: str, at: str, entry: str, words: str, name: str = "train.yaml"
) -> Result:
    """``source`` with ``old`` replaced by ``new``, written as ``folder/name``, refused by
    ``derive`` with one line at the line holding ``at``, naming ``entry`` and saying ``words``."""
    text = replaced(source, old, new)
    path = write(folder, text, name)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, at), entry)
    assert words in result.stderr, result.describe()
    return result


def assert_not_executed(*markers: Path, result: Result | None = None) -> None:
    for marker in markers:
        assert not marker.exists(), f"PAYLOAD EXECUTED: {marker} was created" + (
            f"\n{result.describe()}" if result is not None else ""
        )


# --- the full run -----------------------------------------------------------------------------------------


def full_run(config: pytest.Config) -> bool:
    """Whether the whole bad-input set runs: ``HOSTILE_FULL=1`` only.

    The README's tiers (the fast one, and the slow one with ``-m slow``, which CI runs) take
    the default cases; the extended ones are tens of thousands and take hours, so they run
    only when asked for."""
    return os.environ.get("HOSTILE_FULL", "") not in ("", "0")


def skip_slow_unless_full(request: pytest.FixtureRequest) -> None:
    if request.node.get_closest_marker("slow") is not None and not full_run(request.config):
        pytest.skip("extended bad-input case: run with HOSTILE_FULL=1")


# --- YAML documents -----------------------------------------------------------------------------------------


def load_yaml(path: str | os.PathLike[str]) -> Any:
    with open(path, encoding="utf-8") as handle:
        return yaml.safe_load(handle)


def catalog(name: str) -> Any:
    """A catalog train as plain data (to mutate and dump)."""
    return load_yaml(CATALOG / f"{name}.yaml")


def dump(data: Any, path: Path) -> Path:
    path.write_text(yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=100000), encoding="utf-8")
    return path


def entry_paths(data: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """The path of every mapping key and list item of ``data``, depth first."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield (*prefix, key)
            yield from entry_paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield (*prefix, index)
            yield from entry_paths(value, (*prefix, index))


def rename_key(mapping: dict[Any, Any], old: Any, new: Any) -> dict[Any, Any]:
    """``mapping`` with the key ``old`` renamed ``new``, order kept."""
    return {(new if k == old else k): v for k, v in mapping.items()}


def replace_scalars(data: Any, old: Any, new: Any) -> Any:
    """Every scalar equal to ``old`` (as text) replaced by ``new``, through lists and mapping values."""
    if isinstance(data, dict):
        return {k: replace_scalars(v, old, new) for k, v in data.items()}
    if isinstance(data, list):
        return [replace_scalars(v, old, new) for v in data]
    if not isinstance(data, bool) and isinstance(data, (str, int)) and str(data) == str(old):
        return new
    return data


def rename_everywhere(data: dict[str, Any], table: str, old: Any, new: Any) -> dict[str, Any]:
    """Rename the entry ``old`` of ``data[table]`` (a link, gear, coupling or state) and every reference to it."""
    out = replace_scalars(data, old, new)
    if isinstance(out.get(table), dict):
        out[table] = rename_key(out[table], old, new)
    elif isinstance(out.get(table), list):
        pass  # replace_scalars renamed the list item
    return out


def run_main_in(folder: str | os.PathLike[str], args: Sequence[str], timeout: float = HANG_GUARD) -> Result:
    """``derive ARGS`` in this process (as `run_main`), with ``folder`` as the working
    directory for the run."""
    previous = os.getcwd()
    os.chdir(folder)
    try:
        return run_main(args, timeout)
    finally:
        os.chdir(previous)


def unheard(*message: object) -> None:
    """An FMI logger for every FMPy run: its logger proxy keeps the last logger a run gave
    it, and a later run without one logged through it after it was freed (a crash)."""
