"""The one fan-out of every command (`davies_sym.fan_out`) and the one progress display
(`davies_sym.progress`): results in the order of the tasks whatever order the workers
finish in, a failed task reported in its place, the count of finished tasks as lines
or as a bar on a terminal."""

from __future__ import annotations

import gc
import io
import re
import sys
import weakref
from dataclasses import dataclass

import pytest

from davies_sym.errors import InputError
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.progress import Display


@dataclass(frozen=True)
class Square:
    """A task: square ``n``; ``n`` = 13 fails."""

    n: int


def square(task: Square) -> int:
    if task.n == 13:
        raise ValueError("thirteen")
    return task.n * task.n


TASKS = [Square(n) for n in range(12)]


@pytest.mark.parametrize("workers", [IN_THIS_PROCESS, Workers(jobs=2)], ids=["here", "two processes"])
def test_results_come_in_the_order_of_the_tasks(workers: Workers) -> None:
    assert list(fan_out(square, TASKS, workers)) == [n * n for n in range(12)]


@pytest.mark.parametrize("workers", [IN_THIS_PROCESS, Workers(jobs=2)], ids=["here", "two processes"])
def test_a_failed_task_stands_in_its_place(workers: Workers) -> None:
    tasks = [Square(12), Square(13), Square(14)]
    got = list(fan_out(square, tasks, workers, failed=lambda task, exc: -task.n if "thirteen" in str(exc) else 0))
    assert got == [144, -13, 196]


@pytest.mark.parametrize("workers", [IN_THIS_PROCESS, Workers(jobs=2)], ids=["here", "two processes"])
def test_without_a_report_the_failure_ends_the_fan_out(workers: Workers) -> None:
    with pytest.raises(ValueError, match="thirteen"):
        list(fan_out(square, [Square(1), Square(13)], workers))


@dataclass
class Held:
    """A result that can be watched for being freed (``weakref``)."""

    n: int


def held(task: Square) -> Held:
    return Held(task.n)


def test_a_result_taken_is_not_kept_by_the_fan_out() -> None:
    """Each future is let go once its result is taken (the same code serves a Dask
    cluster, where a future held pins its result in a worker's memory): after the last
    result is taken, every earlier one the caller dropped is freed."""
    results = fan_out(held, TASKS, Workers(jobs=2))
    watched = []
    for _ in TASKS:
        result = next(results)
        watched.append(weakref.ref(result))
        del result
    gc.collect()
    alive = [ref().n for ref in watched[:-1] if ref() is not None]  # type: ignore[union-attr]
    assert alive == []
    assert list(results) == []


def test_where_tasks_run() -> None:
    assert Workers(jobs=4).here(1) and not Workers(jobs=4).here(2)
    assert not Workers(scheduler="tcp://127.0.0.1:9").here(1)
    assert Workers(jobs=4).describe(3) == "on 3 processes"
    assert IN_THIS_PROCESS.describe(5) == "in this process"


def test_an_unreachable_cluster_is_named_as_the_option() -> None:
    pytest.importorskip("dask.distributed")
    with pytest.raises(
        InputError, match=re.escape("--scheduler: cannot reach a Dask scheduler at 'tcp://127.0.0.1:9'")
    ):
        list(fan_out(square, TASKS, Workers(scheduler="tcp://127.0.0.1:9")))


def test_finished_tasks_count_as_lines_off_a_terminal(capsys: pytest.CaptureFixture[str]) -> None:
    display = Display("derive test")
    counted = Counted(display, "number", lambda r: f"squared to {r}" if r > 50 else None)
    assert list(fan_out(square, TASKS[6:9], IN_THIS_PROCESS, counted)) == [36, 49, 64]
    assert capsys.readouterr().err.splitlines() == ["derive test: [3/3] squared to 64"]
    assert display.last == "[3/3] squared to 64"


def test_quiet_shows_no_count_but_every_note(capsys: pytest.CaptureFixture[str]) -> None:
    display = Display("derive test", quiet=True)
    list(fan_out(square, TASKS[:3], IN_THIS_PROCESS, Counted(display, "number", str)))
    display.note("input error: a.yaml: refused")
    assert capsys.readouterr().err == "input error: a.yaml: refused\n"


def test_a_terminal_gets_one_bar(monkeypatch: pytest.MonkeyPatch) -> None:
    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    display = Display("derive test")
    assert list(fan_out(square, TASKS[:4], IN_THIS_PROCESS, Counted(display, "number", str))) == [0, 1, 4, 9]
    shown = screen.getvalue()
    assert "4/4" in shown and "number" in shown and "[1/4]" not in shown, shown
