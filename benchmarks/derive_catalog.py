"""Wall time and peak memory of deriving every catalog train (all variants, LaTeX and
Python module), one fresh process per train so the memory figure is the train's own.

    python benchmarks/derive_catalog.py            # every catalog/*.yaml
    python benchmarks/derive_catalog.py catalog/tuplin.yaml
"""

from __future__ import annotations

import glob
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def measure(path: str, out: str) -> tuple[float, float, int]:
    """(seconds, peak resident MiB, exit status) of `derive PATH --out OUT`."""
    start = time.perf_counter()
    child = subprocess.Popen(
        [sys.executable, "-m", "davies_sym.cli", path, "--out", out, "--quiet"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    _, status, usage = os.wait4(child.pid, 0)
    elapsed = time.perf_counter() - start
    return elapsed, usage.ru_maxrss / 1024, os.waitstatus_to_exitcode(status)


def main(paths: list[str]) -> None:
    print(f"{'train':<22} {'time':>8} {'peak memory':>12}")
    with tempfile.TemporaryDirectory() as out:
        for path in paths:
            seconds, mib, code = measure(path, out)
            name = os.path.splitext(os.path.basename(path))[0]
            flag = "" if code == 0 else f"  (exit {code})"
            print(f"{name:<22} {seconds:>7.2f}s {mib:>9.0f} MiB{flag}")


if __name__ == "__main__":
    main(sys.argv[1:] or sorted(glob.glob(os.path.join(ROOT, "catalog", "*.yaml"))))
