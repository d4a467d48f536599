"""Wall time of writing the atlas of N links and deriving every train file it writes
(every state, both directions: ``derive FILES --out DIR --json``), the trains drawn on a
line apart from those drawn in 2-D (``placement:``, whose planet triangles bring square
roots into the elimination). Each step is one ``derive`` process, as a user runs it.

    python benchmarks/atlas_derive.py [LINKS] [--jobs N] [--line-only]

The time of each operating state (its distribution and the ten slowest), a sample of an
atlas too big for one machine with the whole extrapolated, and a run on a Dask cluster
are measured by ``benchmarks/atlas_states.py``.
"""

from __future__ import annotations

import argparse
import glob
import os
import subprocess
import sys
import tempfile
import time

import yaml


def _run(args: list[str]) -> float:
    """Seconds of ``derive ARGS`` (which must succeed)."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "davies_sym.cli", *args, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def _states(path: str) -> int:
    with open(path, encoding="utf-8") as handle:
        return len(yaml.safe_load(handle).get("states") or {}) or 1


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("links", type=int, nargs="?", default=6)
    p.add_argument("--jobs", default="2")
    p.add_argument("--line-only", action="store_true", help="leave out the trains drawn in 2-D")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        atlas = os.path.join(folder, "atlas")
        seconds = _run(["atlas", "--links", str(args.links), "--out", atlas, "--jobs", args.jobs])
        files = sorted(glob.glob(os.path.join(atlas, "*.yaml")))
        print(f"{args.links} links: {len(files)} train files written in {seconds:.0f} s (--jobs {args.jobs})")
        groups: dict[str, list[str]] = {"on a line": [], "in 2-D": []}
        for path in files:
            with open(path, encoding="utf-8") as handle:
                groups["in 2-D" if "\nplacement:" in handle.read() else "on a line"].append(path)
        for kind, paths in groups.items():
            if not paths or (kind == "in 2-D" and args.line_only):
                continue
            out = os.path.join(folder, "derived_" + kind.split()[-1].replace("-", ""))
            seconds = _run([*paths, "--out", out, "--json", "--jobs", args.jobs])
            states = sum(_states(path) for path in paths)
            print(
                f"  drawn {kind}: {len(paths)} files, {states} states derived in {seconds:.0f} s "
                f"({seconds / states:.3f} s per state)"
            )


if __name__ == "__main__":
    main()
