"""Level 2 of ``derive shifts`` on four sets: the four simple sets of the ZF 8HP70 and two
shafts, nothing connected (tests/data/shifts_four_sets.yaml), the 8HP70's nine ratios.
The 8HP70 itself has six permanent joins (input = carrier 2, output = carrier 4, sun 1 =
sun 2, carrier 1 = ring 4, ring 2 = sun 3, ring 3 = sun 4), so the search it needs is
``--connections 6``; this script measures it instead of running it:

- the number of join choices for 1 to 6 joins (groupings of the 14 main-axis members
  in which no group holds two members of one set), counted without the relabelling of
  the two identical sets (which halves them, nearly);
- the seconds per choice of the scheme search (screen, exact ratios, schedules), over a
  seeded random sample of six-join choices, and over the 8HP70's own joins (which must
  give the published scheme);
- the whole extrapolated, per core.

    python benchmarks/shifts_four_sets.py [SAMPLE]
"""

from __future__ import annotations

import random
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

from davies_sym.synthesis.shift_connections import joined_speeds, planetary_sets
from davies_sym.synthesis.shift_kinematics import member_speeds
from davies_sym.synthesis.shift_schedules import GearTarget, ShiftQuestion, shift_schemes
from davies_sym.topology.loader import load

FILE = Path(__file__).resolve().parent.parent / "tests" / "data" / "shifts_four_sets.yaml"
EIGHT = ["R=-3.2968", "1=4.6957", "2=3.1304", "3=2.1039", "4=1.6667", "5=1.2845", "6=1", "7=0.8392", "8=0.6667"]
PUBLISHED = [("in", "c2"), ("out", "c4"), ("s1", "s2"), ("c1", "r4"), ("r2", "s3"), ("r3", "s4")]


def groupings(home: dict[str, int], joins: int) -> int:
    """How many groupings of the members make ``joins`` joins, no group holding two
    members of one set and no group holding both shafts."""
    members = list(home)
    count = 0
    groups: list[list[str]] = []

    def extend(i: int) -> None:
        nonlocal count
        made = i - len(groups)
        if made > joins or len(members) - i < joins - made:
            return
        if i == len(members):
            count += made == joins
            return
        m = members[i]
        for g in groups:
            if all(home[x] != home[m] for x in g) and not {"in", "out"} <= {m, *g}:
                g.append(m)
                extend(i + 1)
                g.pop()
        groups.append([m])
        extend(i + 1)
        groups.pop()

    extend(0)
    return count


def random_grouping(home: dict[str, int], joins: int, rng: random.Random) -> frozenset[frozenset[str]]:
    """A grouping of ``joins`` joins, built by merging random admissible pairs of groups."""
    while True:
        groups = [[m] for m in home]
        for _ in range(1000):
            if len(home) - len(groups) == joins:
                return frozenset(frozenset(g) for g in groups if len(g) > 1)
            a, b = rng.sample(range(len(groups)), 2)
            merged = groups[a] + groups[b]
            if len({home[m] for m in merged}) == len(merged) and not {"in", "out"} <= set(merged):
                groups[a] = merged
                groups.pop(b)


def main(sample: int) -> None:
    train = load(FILE)
    speeds = member_speeds(train)
    sets = planetary_sets(train, speeds.members())
    home = {m: k for k, s in enumerate(sets) for m in s.members}
    targets = tuple(GearTarget(g, Fraction(r)) for g, r in (t.split("=") for t in EIGHT))
    question = ShiftQuestion(targets, Fraction(5, 1000), 5, None, True, 6)
    counts = {}
    for joins in range(1, 7):
        start = time.perf_counter()
        counts[joins] = groupings(home, joins)
        print(f"{joins} joins: {counts[joins]:,} groupings (counted in {time.perf_counter() - start:.1f} s)")
    start = time.perf_counter()
    published = frozenset(frozenset(p) for p in PUBLISHED)
    found = shift_schemes(joined_speeds(speeds, published), ("in", "out"), question)
    print(f"the 8HP70's joins: {len(found)} scheme(s) of five elements, {time.perf_counter() - start:.2f} s")
    rng = random.Random(0)
    seconds = []
    for _ in range(sample):
        blocks = random_grouping(home, 6, rng)
        start = time.perf_counter()
        joined = joined_speeds(speeds, blocks)
        if joined is not None:
            shift_schemes(joined, ("in", "out"), question)
        seconds.append(time.perf_counter() - start)
    per = statistics.mean(seconds)
    print(
        f"six joins, {sample} random choices: {per * 1000:.1f} ms mean, {statistics.median(seconds) * 1000:.1f} ms "
        f"median, {max(seconds) * 1000:.1f} ms slowest per choice"
    )
    whole = counts[6] / 2 * per
    choices = counts[6] / 2
    print(f"whole search extrapolated: about {whole / 3600:.1f} core-hours ({choices:,.0f} choices after relabelling)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 200)
