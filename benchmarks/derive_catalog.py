"""Wall time and peak memory of deriving every catalog train (all variants, LaTeX and
Python module), one fresh process per train so the memory figure is the train's own;
with ``--in-process``, the derivation alone (every state, every variant) in one warm
process, the time a design study pays per train once the interpreter is up.

    python benchmarks/derive_catalog.py            # every catalog/*.yaml
    python benchmarks/derive_catalog.py catalog/tuplin.yaml
    python benchmarks/derive_catalog.py --in-process
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


def in_process(paths: list[str]) -> None:
    """Every state of every train derived with all its variants in this process."""
    import davies_sym

    davies_sym.derive(davies_sym.load(os.path.join(ROOT, "catalog", "simple_pair.yaml")))  # imports, warm-up
    print(f"{'train':<22} {'derivation':>10}")
    for path in paths:
        train = davies_sym.load(path)
        start = time.perf_counter()
        if train.states:
            for state in train.states:
                davies_sym.derive(davies_sym.train_in_state(train, state))
        elif (train.degrees_of_freedom or 1) == 1:
            davies_sym.derive(train)
        name = os.path.splitext(os.path.basename(path))[0]
        print(f"{name:<22} {time.perf_counter() - start:>9.2f}s")


def main(paths: list[str]) -> None:
    print(f"{'train':<22} {'time':>8} {'peak memory':>12}")
    with tempfile.TemporaryDirectory() as out:
        for path in paths:
            seconds, mib, code = measure(path, out)
            name = os.path.splitext(os.path.basename(path))[0]
            flag = "" if code == 0 else f"  (exit {code})"
            print(f"{name:<22} {seconds:>7.2f}s {mib:>9.0f} MiB{flag}")


def _machine(path: str) -> bool:
    with open(path, encoding="utf-8") as handle:
        return any(line.startswith("machine:") for line in handle)


if __name__ == "__main__":
    arguments = [a for a in sys.argv[1:] if a != "--in-process"]
    # Gear trains only: the machines (a `machine:` entry) have their own benchmark, three_upu_task.py.
    files = arguments or [p for p in sorted(glob.glob(os.path.join(ROOT, "catalog", "*.yaml"))) if not _machine(p)]
    (in_process if "--in-process" in sys.argv[1:] else main)(files)
