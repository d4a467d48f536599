"""Wall time of ``derive shifts`` on the examples of its specification, each in a fresh
process (the gears' derivation included):

- level 1, the four sets and four connections of the ZF 8HP70
  (tests/data/shifts_eight_speed.yaml: benchmarks/search_eight_speed.yaml with the
  published teeth as numbers and no states), its nine published ratios within 0.5 %,
  five elements; wanted under 60 s on a 2-core machine;
- level 2, two simple sets of sun 30, planet 20, ring 70 and two shafts, nothing
  connected (tests/data/shifts_two_sets.yaml), the Simpson ratios, three connections
  and four elements; wanted under 60 s;
- teeth searched with the scheme, the Simpson sets with their teeth as symbols
  (tests/data/shifts_simpson_teeth.yaml), sun 17 to 60, planets 17 to 40, three planets
  per set.

    python benchmarks/shifts.py [--jobs N]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
EIGHT = ["R=-3.2968", "1=4.6957", "2=3.1304", "3=2.1039", "4=1.6667", "5=1.2845", "6=1", "7=0.8392", "8=0.6667"]
SIMPSON = ["1=2.4286", "2=1.4286", "3=1", "R=-2.3333"]
CASES = {
    "level 1, ZF 8HP70 sets and connections, 5 elements": [
        os.path.join(DATA, "shifts_eight_speed.yaml"),
        *("--target", *EIGHT, "--tolerance", "0.005", "--elements", "5"),
    ],
    "level 2, two simple sets, 3 connections, 4 elements": [
        os.path.join(DATA, "shifts_two_sets.yaml"),
        *("--target", *SIMPSON, "--tolerance", "0.005", "--connections", "3", "--elements", "4"),
    ],
    "teeth, Simpson sets, sun 17-60, planets 17-40, 3 planets": [
        os.path.join(DATA, "shifts_simpson_teeth.yaml"),
        *("--target", *SIMPSON, "--tolerance", "0.005", "--teeth", "zs=17:60", "zp1=17:40", "zp2=17:40"),
        *("--planets", "3"),
    ],
}


def main(extra: list[str]) -> None:
    for name, args in CASES.items():
        start = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-m", "davies_sym.cli", "shifts", *args, "--json", "--quiet", "--top", "3", *extra],
            check=True,
            capture_output=True,
            text=True,
        )
        seconds = time.perf_counter() - start
        document = json.loads(done.stdout)
        print(
            f"{name}: {seconds:.1f} s wall ({document['seconds']:.1f} s searching), "
            f"{document['feasible']} design(s), {document['searched']} combinations evaluated"
            + (f", {document['tooth_designs']} tooth designs" if "tooth_designs" in document else "")
        )


if __name__ == "__main__":
    main(sys.argv[1:])
