"""Counts and wall time of the atlas of 1-DOF planetary gear trains, 4 to 8 links (or the
link counts given), beside the published counts (Yang and Ding, J. Mech. Des. 141(4)
043301, 2019). Each count runs in a fresh process, so no cache is shared.

    python benchmarks/atlas_counts.py [LINKS ...]
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

#: Yang and Ding (2019): links -> (rotation graphs, displacement graphs).
PUBLISHED = {6: (27, 81), 7: (152, 647), 8: (1070, 6360), 9: (8654, 71837)}

CHILD = """
import json, sys
from davies_sym.atlas.enumeration import atlas
found = atlas(int(sys.argv[1]))
print(json.dumps([found.rotation_count, found.displacement_count, found.two_axis_gear_count,
                  found.main_axis_histogram]))
"""


def count(links: int) -> tuple[int, int, int, dict[int, int], float]:
    """The atlas's counts for ``links`` links (r-graphs, d-graphs, d-graphs with a link
    whose gears lie on two axes, number of candidate main axes -> d-graphs) and the wall
    time of the run, in seconds."""
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", CHILD, str(links)], check=True, capture_output=True, text=True)
    rotations, displacements, two_axis, histogram = json.loads(out.stdout)
    seconds = time.perf_counter() - start
    return rotations, displacements, two_axis, {int(k): v for k, v in histogram.items()}, seconds


def main(links: list[int]) -> None:
    print(f"{'links':>5} {'r-graphs':>9} {'d-graphs':>9} {'published':>12} {'two-axis':>9}  main axes  time")
    for n in links:
        rotations, displacements, two_axis, histogram, seconds = count(n)
        published = "/".join(map(str, PUBLISHED[n])) if n in PUBLISHED else "-"
        print(f"{n:>5} {rotations:>9} {displacements:>9} {published:>12} {two_axis:>9}  {histogram}  {seconds:.1f} s")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [4, 5, 6, 7, 8])
