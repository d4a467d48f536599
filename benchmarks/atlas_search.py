"""Seconds per train of ``derive search --atlas`` over the trains of exactly N links, as
its workers spend them: a graph whose every use idles a gear at generic ratios skipped
(`davies_sym.atlas.idle_meshes`), any other formed (its drawing and admissible choices),
then every direction of every loaded choice searched for the tooth numbers that reach the
target, each feasible one's efficiency derived.  Reports the median, the 90th percentile
and the largest time per train, how many were formed, the share of trains with a feasible
design, the slowest five, and the whole search of N links extrapolated to ``--jobs``
workers.

    python benchmarks/atlas_search.py [LINKS] [--sample K] [--seed S] [--target R]

The question is that of docs/atlas.md: ratio 12.5 within 0.2, teeth 17 to 40.
"""

from __future__ import annotations

import argparse
import random
import statistics
import time
from fractions import Fraction

from davies_sym.atlas.atlas_entries import entry, places
from davies_sym.atlas.idle_meshes import loadable_uses
from davies_sym.atlas.search import AtlasQuestion, SearchTask, _entry_designs


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("links", type=int, nargs="?", default=7)
    p.add_argument("--sample", type=int, default=None, help="trains drawn at random (default: all)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--target", default="12.5")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    question = AtlasQuestion(Fraction(args.target), Fraction("0.2"), (17, 40), None, 17)
    start = time.perf_counter()
    found = places(args.links)
    print(f"{args.links} links: {len(found)} displacement graphs enumerated in {time.perf_counter() - start:.0f} s")
    chosen = found if args.sample is None else random.Random(args.seed).sample(found, min(args.sample, len(found)))
    timed: list[tuple[float, float, str, int]] = []
    skipped = 0
    for place in chosen:
        task = SearchTask(place, question)
        start = time.perf_counter()
        if not loadable_uses(place.graph):
            skipped += 1
            timed.append((time.perf_counter() - start, 0.0, place.name, 0))
            continue
        e = entry(task.place)
        formed = time.perf_counter() - start
        designs = [] if e.not_drawable else _entry_designs(e, task.question).designs
        timed.append((time.perf_counter() - start, formed, e.name, len(designs)))
    seconds = sorted(t for t, _, _, _ in timed)
    forming = sum(f for _, f, _, _ in timed)
    q = statistics.quantiles(seconds, n=10, method="inclusive") if len(seconds) > 1 else seconds * 9
    print(
        f"  {len(timed)} trains searched: median {statistics.median(seconds):.2f} s, 90th percentile {q[8]:.2f} s, "
        f"largest {seconds[-1]:.1f} s; {len(timed) - skipped} formed (the others idle a gear in every use), "
        f"forming {100 * forming / sum(seconds):.0f} % of the time; "
        f"{sum(1 for *_, n in timed if n)} with a feasible design"
    )
    print("    slowest: " + ", ".join(f"{n} {t:.1f} s" for t, _, n, _ in sorted(timed, reverse=True)[:5]))
    whole = sum(seconds) * len(found) / len(timed) / args.jobs
    print(
        f"  the whole search of {len(found)} trains of {args.links} links: "
        f"about {whole / 60:.0f} min with {args.jobs} workers (a sample misses the few trains whose directions "
        "run to the work budget, most of the whole: time the command itself for that)"
    )


if __name__ == "__main__":
    main()
