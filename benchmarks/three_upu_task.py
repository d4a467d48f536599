"""Wall time of the 3-UPU's tasks (Laus sec. 4.3.4): every time step's motions and
actions with the 30 friction signs resolved, powers and energies.

Laus reports about 2 minutes for 200 time steps in C++ with homotopy continuation; the
target here is 200 steps in under 10 s.  Prints, per task, the steps, the time (the
first includes compiling the geometry), the friction rounds per step and the task
efficiency; then the peak resident size of this process.

    python benchmarks/three_upu_task.py
"""

from __future__ import annotations

import os
import resource
import time

from davies_sym.machines.machine_loader import build_machine
from davies_sym.machines.task import run_task
from davies_sym.topology.documents import read_document

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main() -> None:
    machine = build_machine(read_document(os.path.join(ROOT, "catalog", "three_upu.yaml")))
    print(f"{'task':<10} {'steps':>5} {'time':>8} {'per step':>9} {'efficiency':>10}")
    for task in ("lift", "lift_half", "ellipse"):
        start = time.perf_counter()
        result = run_task(machine, task)
        elapsed = time.perf_counter() - start
        steps = len(result.steps)
        print(f"{task:<10} {steps:>5} {elapsed:>7.2f}s {1000 * elapsed / steps:>7.1f}ms {result.efficiency:>10.4f}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak resident size: {peak:.0f} MiB")


if __name__ == "__main__":
    main()
