"""Seconds per operating state of the atlas of N links, as ``derive FILES --json`` spends
them: each file derived in a worker (``--jobs N``), each state timed from the step that
starts it to the next one, the file's JSON document shared out evenly over its states.
Reports, for the trains drawn on a line and those drawn in 2-D apart: the median, the
quartiles, the 90th percentile and the largest per-state time, the wall time of the
whole and the ten slowest states.

    python benchmarks/atlas_states.py [LINKS] [--jobs N] [--sample K] [--seed S]
                                      [--scheduler ADDRESS | --local-cluster N]
                                      [--every M] [--log FILE [--resume]]

``--sample K`` forms and derives K displacement graphs drawn at random (seed S), for
atlases too big to derive whole on one machine (8 links); the whole is extrapolated from
them.  ``--scheduler ADDRESS`` derives the files on a Dask cluster (one file per task, as
``derive FILES --scheduler ADDRESS`` does); ``--local-cluster N`` starts a cluster of N
local worker processes for the run and derives there.  A long run reports as it goes:
the figures so far after every M files (``--every``), and each file's state times as a
line of ``--log FILE`` (tab-separated: file, state, seconds, exit status, how it is
drawn) as soon as it is derived, so that a run stopped early still tells what it
measured; ``--resume`` reads the files already in the log, forms and derives only the
others (appending to the log) and reports on all of them (the wall time is this run's).
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import tempfile
import time
from contextlib import ExitStack
from typing import TextIO

from davies_sym.atlas.atlas_entries import GraphPlace, entry, places
from davies_sym.cli.many_files import Task, derive_task
from davies_sym.fan_out import Workers, fan_out

Timed = tuple[str, list[tuple[str, float]], int, tuple[str, ...]]
Formed = tuple[str, str | None, str | None]


def formed_file(place: GraphPlace) -> Formed:
    """One displacement graph's train file: its name, its text (None where it is not
    drawn) and the reason it is not drawn."""
    e = entry(place)
    return e.name, None if e.not_drawable else e.train_text(), e.not_drawable


def timed_file(task: Task) -> Timed:
    """Seconds of each state of one file: from its ``state NAME`` step to the next one
    (the last to the ``writing the report`` step), with the file's reading and its
    document's writing shared evenly; with the file's exit status and messages (a state
    refused is listed, not fatal)."""
    marks: list[tuple[str, float]] = []
    report: list[float] = []

    def progress(text: str) -> None:
        if text.startswith("state "):
            marks.append((text[len("state ") :], time.perf_counter()))
        elif text == "writing the report":
            report.append(time.perf_counter())

    start = time.perf_counter()
    derived = derive_task(task, progress)
    end = time.perf_counter()
    told = (derived.status, derived.messages)
    if not marks:  # a train without states: the file is one state
        return task.stem, [("", end - start)], *told
    last = report[0] if report else end
    ends = [t for _, t in marks[1:]] + [last]
    # The file's own work (read before the first state, its document after the last) is
    # shared out evenly.
    overhead = (marks[0][1] - start + end - last) / len(marks)
    return task.stem, [(name, e - t + overhead) for (name, t), e in zip(marks, ends, strict=True)], *told


def _report(kind: str, results: list[Timed], wall: float, total_files: int | None) -> None:
    """Median, quartiles, 90th percentile, largest and slowest ten of the states so far,
    with the files refused."""
    times = sorted((s, f"{stem} {state}") for stem, states, _, _ in results for state, s in states)
    values = [s for s, _ in times]
    if not values:
        return
    q = statistics.quantiles(values, n=20, method="inclusive") if len(values) > 1 else values * 19
    of = "" if total_files is None else f" of {total_files}"
    print(
        f"  drawn {kind}: {len(results)}{of} files, {len(values)} states in {wall:.0f} s wall "
        f"({wall / len(values):.3f} s per state)"
    )
    print(
        f"    per state: median {statistics.median(values):.3f} s, quartiles {q[4]:.3f} / {q[14]:.3f} s, "
        f"90th percentile {q[17]:.3f} s, largest {values[-1]:.2f} s"
    )
    print("    slowest: " + ", ".join(f"{name} {s:.2f} s" for s, name in reversed(times[-10:])))
    for stem, _, status, messages in results:
        if status != 0:
            print(f"    {stem}: exit status {status}: " + " | ".join(messages))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("links", type=int, nargs="?", default=7)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--sample", type=int, default=None, help="displacement graphs drawn at random")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--every", type=int, default=500, metavar="M", help="report the figures so far every M files")
    p.add_argument("--log", default=None, metavar="FILE", help="each state's seconds, one line each, as derived")
    p.add_argument("--resume", action="store_true", help="derive only the files not in the log yet")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", default=None, help="address of a Dask scheduler")
    where.add_argument("--local-cluster", type=int, default=None, metavar="N", help="a local Dask cluster of N")
    args = p.parse_args()
    with ExitStack() as stack:
        scheduler = args.scheduler
        if args.local_cluster is not None:
            from dask.distributed import LocalCluster

            cluster = stack.enter_context(LocalCluster(n_workers=args.local_cluster, threads_per_worker=1))
            scheduler = cluster.scheduler_address
        logged = _logged(args.log) if args.resume else {}
        log = stack.enter_context(open(args.log, "a" if args.resume else "w", encoding="utf-8")) if args.log else None
        _measure(args, Workers(jobs=args.jobs, scheduler=scheduler), log, logged)


def _logged(path: str) -> dict[str, tuple[str, Timed]]:
    """The files a log of an earlier run holds: how each is drawn and its result (no
    messages)."""
    found: dict[str, tuple[str, Timed]] = {}
    with open(path, encoding="utf-8") as handle:
        for line in handle:
            stem, state, seconds, status, kind = line.rstrip("\n").split("\t")
            _, (_, states, _, _) = found.setdefault(stem, (kind, (stem, [], int(status), ())))
            states.append((state, float(seconds)))
    return found


def _derived(
    tasks: list[Task], workers: Workers, kind: str, every: int, log: TextIO | None, logged: list[Timed]
) -> list[Timed]:
    """Each file's state times after those ``logged`` already, logged as it comes and
    summed up every ``every`` files."""
    results = list(logged)
    total = len(tasks) + len(logged)
    start = time.perf_counter()
    for result in fan_out(timed_file, tasks, workers):
        results.append(result)
        stem, states, status, _ = result
        if log is not None:
            log.write("".join(f"{stem}\t{state}\t{s:.4f}\t{status}\t{kind}\n" for state, s in states))
            log.flush()
        if len(results) % every == 0 and len(results) < total:
            print(f"  so far ({len(results)} of {total} files):")
            _report(kind, results, time.perf_counter() - start, total)
    return results


def _measure(
    args: argparse.Namespace, workers: Workers, log: TextIO | None, logged: dict[str, tuple[str, Timed]]
) -> None:
    start = time.perf_counter()
    found = places(args.links)
    chosen = found if args.sample is None else random.Random(args.seed).sample(found, min(args.sample, len(found)))
    chosen = [place for place in chosen if place.name not in logged]
    print(f"{args.links} links: {len(found)} displacement graphs enumerated in {time.perf_counter() - start:.0f} s")
    start = time.perf_counter()
    files = list(fan_out(formed_file, chosen, workers))
    formed = time.perf_counter() - start
    drawn = [(name, text) for name, text, _ in files if text is not None]
    where = workers.describe(len(chosen))
    print(f"  {len(drawn)} drawable train files of {len(chosen)} formed in {formed:.0f} s ({where})")
    for name, _, reason in files:
        if reason is not None:
            print(f"    {name} not drawn: {reason}")
    whole = formed * len(found) / max(1, len(chosen))
    with tempfile.TemporaryDirectory() as folder:
        kinds: dict[str, list[Task]] = {"on a line": [], "in 2-D": []}
        for name, text in drawn:
            path = os.path.join(folder, f"{name}.yaml")
            kinds["in 2-D" if "\nplacement:" in text else "on a line"].append(Task(path, text.encode(), name, "json"))
        for kind, tasks in kinds.items():
            start = time.perf_counter()
            before = [timed for drawn_so, timed in logged.values() if drawn_so == kind]
            results = _derived(tasks, workers, kind, args.every, log, before)
            wall = time.perf_counter() - start
            whole += wall * len(found) / max(1, len(chosen))
            _report(kind, results, wall, None if args.sample is None else len(tasks))
    if args.sample is not None:
        print(
            f"  the whole atlas ({len(found)} graphs), extrapolated from the sample: files formed and "
            f"derived in {whole / 3600:.1f} h on this machine (the derivations {workers.describe(len(found))})"
        )


if __name__ == "__main__":
    main()
