"""Tasks spread over workers, the one way every command does it (``derive FILES --out
DIR``, ``derive search``, ``derive atlas``, ``derive search --atlas``, ``derive
shifts``, ``derive calibrate --starts N``): in this process,
on N local processes (``--jobs N``, the standard library's process pool) or on a Dask
cluster (``--scheduler ADDRESS``).  Tasks and results are values that pickle (frozen
dataclasses); the results come back in the order of the tasks, while the progress
counts each one as it finishes."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from typing import Any, TypeVar

from davies_sym.errors import InputError, MissingDependencyError, Problem
from davies_sym.progress import Progress, Tally, silent, tally

Task = TypeVar("Task")
Result = TypeVar("Result")


@dataclass(frozen=True)
class Workers:
    """Where tasks run: ``jobs`` local processes (1: this process) or, when
    ``scheduler`` is given, the Dask cluster whose scheduler listens at that address."""

    jobs: int = 1
    scheduler: str | None = None

    def here(self, count: int) -> bool:
        """Whether ``count`` tasks run in this process (one worker, or one task)."""
        return self.scheduler is None and (self.jobs == 1 or count < 2)

    def describe(self, count: int) -> str:
        """Where ``count`` tasks run, for a progress line."""
        if self.scheduler is not None:
            return f"on the cluster at {self.scheduler}"
        return "in this process" if self.here(count) else f"on {min(self.jobs, count)} processes"


#: One worker: this process.
IN_THIS_PROCESS = Workers()


@dataclass(frozen=True)
class Counted:
    """How a fan-out reports: each finished task as a line (``line`` of its result, None
    for none) or a bar step of ``unit``."""

    progress: Progress = silent
    unit: str = "task"
    line: Callable[[Any], str | None] = lambda result: None


def fan_out(
    work: Callable[[Task], Result],
    tasks: Sequence[Task],
    workers: Workers = IN_THIS_PROCESS,
    counted: Counted | None = None,
    failed: Callable[[Task, Exception], Result] | None = None,
) -> Iterator[Result]:
    """``work`` of every task, in the order of ``tasks``.  A task that raises stands as
    ``failed(task, exception)`` (the others go on), or, without ``failed``, the
    exception ends the fan-out.  ``work`` must be a module-level function when the tasks
    leave this process."""
    counted = counted or Counted()
    with tally(counted.progress, len(tasks), counted.unit) as count:
        if workers.here(len(tasks)):
            yield from _here(work, tasks, failed, count, counted.line)
            return
        submit, finished, close = (
            _cluster(workers.scheduler) if workers.scheduler is not None else _pool(min(workers.jobs, len(tasks)))
        )
        try:
            futures = {submit(work, task): k for k, task in enumerate(tasks)}
            yield from _in_order(futures, finished, tasks, failed, count, counted.line)
        finally:
            close()


def _here(
    work: Callable[[Task], Result],
    tasks: Sequence[Task],
    failed: Callable[[Task, Exception], Result] | None,
    count: Tally,
    line: Callable[[Any], str | None],
) -> Iterator[Result]:
    for task in tasks:
        try:
            result = work(task)
        except Exception as exc:  # the same report as from a worker
            if failed is None:
                raise
            result = failed(task, exc)
        count.finished(line(result))
        yield result


def _in_order(
    futures: dict[Any, int],
    finished: Callable[[Any], Iterator[Any]],
    tasks: Sequence[Task],
    failed: Callable[[Task, Exception], Result] | None,
    count: Tally,
    line: Callable[[Any], str | None],
) -> Iterator[Result]:
    """The results in the order of the tasks, each counted as it arrives.  A future is
    let go as soon as its result is taken: on a cluster a future held keeps its result
    in a worker's memory (and a worker lost or restarted has every result it holds
    computed again); here it would keep every result until the last."""
    waiting: dict[int, Result] = {}
    following = 0
    for future in finished(futures):
        k = futures.pop(future)
        try:
            waiting[k] = future.result()
        except Exception as exc:  # a task that failed, or a worker that died
            if failed is None:
                raise
            waiting[k] = failed(tasks[k], exc)
        count.finished(line(waiting[k]))
        while following in waiting:
            yield waiting.pop(following)
            following += 1


def _pool(jobs: int) -> tuple[Callable[..., Any], Callable[[Any], Iterator[Any]], Callable[[], None]]:
    """Submit, wait and close of a local process pool of ``jobs`` workers."""
    pool = ProcessPoolExecutor(max_workers=jobs)

    def close() -> None:
        # Tasks not started are dropped when the fan-out ends early (an error, Ctrl-C).
        pool.shutdown(wait=True, cancel_futures=True)

    def finished(futures: dict[Future[Any], int]) -> Iterator[Future[Any]]:
        return as_completed(futures)

    return pool.submit, finished, close


def _cluster(address: str) -> tuple[Callable[..., Any], Callable[[Any], Iterator[Any]], Callable[[], None]]:
    """Submit, wait and close of a client of the Dask scheduler at ``address``."""
    try:
        from dask.distributed import Client
        from dask.distributed import as_completed as completed
    except ImportError:
        raise MissingDependencyError("--scheduler needs dask.distributed (pip install 'davies_sym[dask]')") from None
    try:
        client = Client(address, timeout="10s")  # type: ignore[no-untyped-call]
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError([Problem("--scheduler", f"cannot reach a Dask scheduler at {address!r}: {exc}")]) from None

    def submit(work: Callable[..., Any], task: Any) -> Any:
        return client.submit(work, task, pure=False)

    def finished(futures: dict[Any, int]) -> Iterator[Any]:
        return completed(futures)  # type: ignore[no-untyped-call]

    return submit, finished, client.close
