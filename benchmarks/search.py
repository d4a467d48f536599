"""Wall time of ``derive search`` on the two designs of its specification, each in a fresh
process (the states' derivation included), and the designs examined per second:

- the simple planetary of tests/data/search_planetary.yaml: target 4.6 within 1 %, sun
  17..60, ring 50..150, 3 planets (4,444 designs in the bounds); wanted under 2 s;
- the four-set eight-speed of benchmarks/search_eight_speed.yaml: its nine published
  ratios (ZF 8HP70) within 0.5 %, eight free tooth numbers in 17..120 (1.4e16 designs in
  the bounds), 3 planets per set; wanted under 60 s on a 2-core machine.

    python benchmarks/search.py [--jobs N]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EIGHT_SPEED = {
    "first": "4.696",
    "second": "3.130",
    "third": "2.104",
    "fourth": "1.667",
    "fifth": "1.285",
    "sixth": "1.000",
    "seventh": "0.839",
    "eighth": "0.667",
    "reverse": "-3.297",
}
CASES = {
    "simple planetary (4,444 designs)": [
        os.path.join(ROOT, "tests", "data", "search_planetary.yaml"),
        *("--target", "4.6", "--tolerance", "0.01", "--teeth", "zs=17:60", "zr=50:150", "--planets", "3"),
    ],
    "eight-speed, 8 free tooth numbers in 17..120": [
        os.path.join(ROOT, "benchmarks", "search_eight_speed.yaml"),
        "--target",
        *(f"{state}={ratio}" for state, ratio in EIGHT_SPEED.items()),
        *("--tolerance", "0.005", "--planets", "3", "--teeth"),
        *(f"{name}=17:120" for name in ("zs1", "zr1", "zs2", "zr2", "zs3", "zr3", "zs4", "zr4")),
    ],
}


def main(extra: list[str]) -> None:
    for name, args in CASES.items():
        start = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-m", "davies_sym.cli", "search", *args, "--json", "--quiet", "--top", "3", *extra],
            check=True,
            capture_output=True,
            text=True,
        )
        seconds = time.perf_counter() - start
        document = json.loads(done.stdout)
        rate = document["examined"] / document["seconds"] if document["seconds"] else float("inf")
        print(
            f"{name}: {seconds:.2f} s in all ({document['seconds']:.2f} s searching, the rest starting Python); "
            f"{document['searched']:.3g} designs in the bounds, {document['examined']} rows evaluated "
            f"({rate:,.0f} per second), {document['feasible']} feasible"
        )


if __name__ == "__main__":
    main(sys.argv[1:])
