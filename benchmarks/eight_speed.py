"""Wall time and memory of deriving every gear of the ZF 8HP70 eight-speed transmission.

Derives every state of benchmarks/eight_speed.yaml (four planetary sets, eight meshes,
nine gears) in this process with every variant (`davies_sym.derive` on each state's
train), then runs ``derive benchmarks/eight_speed.yaml --out <tmpdir>`` (every variant,
LaTeX and Python module of every state) as a separate process.  Prints, per state, the
size of D_A, the number of variants and the time; the total and the peak resident size of
this process; the peak of the Python memory traced by tracemalloc in a second pass, run in
a fresh process because tracing slows the derivation about 2.5 times (its own times are
not the ones printed); and the time of the whole ``derive`` process.

    python benchmarks/eight_speed.py
"""

from __future__ import annotations

import multiprocessing
import os
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc

import davies_sym

HERE = os.path.dirname(os.path.abspath(__file__))
YAML = os.path.join(HERE, "eight_speed.yaml")


def in_process() -> None:
    train = davies_sym.load(YAML)
    print(f"{'state':<9} {'D_A':>9} {'variants':>8} {'time':>8}")
    total = 0.0
    for state in train.states:
        start = time.perf_counter()
        variants = davies_sym.derive(davies_sym.train_in_state(train, state))
        elapsed = time.perf_counter() - start
        total += elapsed
        D = variants.analysis.augmented_action_matrix
        print(f"{state.name:<9} {D.rows:>4}x{D.cols:<4} {len(variants.variants):>8} {elapsed:>7.2f}s", flush=True)
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux
    print(f"{'total':<9} {'':>9} {'':>8} {total:>7.2f}s")
    print(f"peak resident size of this process: {maxrss:.0f} MiB")


def traced_peak() -> float:
    """Peak of the traced Python memory in MiB while every state is derived (fresh process)."""
    train = davies_sym.load(YAML)
    tracemalloc.start()
    for state in train.states:
        davies_sym.derive(davies_sym.train_in_state(train, state))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak / 2**20


def traced() -> None:
    with multiprocessing.get_context("spawn").Pool(1) as pool:
        peak = pool.apply(traced_peak)
    print(f"peak traced Python memory (tracemalloc, all states, fresh process): {peak:.1f} MiB")


def whole_process() -> None:
    with tempfile.TemporaryDirectory() as out:
        command = [sys.executable, "-m", "davies_sym.cli", YAML, "--quiet", "--out", out]
        start = time.perf_counter()
        child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        stderr = child.stderr.read() if child.stderr else ""
        _, status, usage = os.wait4(child.pid, 0)
        elapsed = time.perf_counter() - start
        child.returncode = os.waitstatus_to_exitcode(status)
        if child.returncode != 0:
            sys.exit(f"derive failed (exit {child.returncode}):\n{stderr}")
        written = len(os.listdir(out))
    print(
        f"derive {os.path.relpath(YAML)} --out <tmpdir>: {elapsed:.2f}s "
        f"({written} files, peak resident size {usage.ru_maxrss / 1024:.0f} MiB)"
    )


if __name__ == "__main__":
    in_process()
    traced()
    whole_process()
