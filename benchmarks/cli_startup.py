"""Start-up of the ``derive`` command: wall time of ``derive --help`` and ``derive
--version`` in a fresh interpreter (median of several runs), beside a bare interpreter
and the import of the whole engine, which those two calls no longer pay.

    python benchmarks/cli_startup.py [RUNS]
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time

CASES = {
    "python -c pass (the interpreter alone)": ["-c", "pass"],
    "derive --help": ["-m", "davies_sym.cli", "--help"],
    "derive --version": ["-m", "davies_sym.cli", "--version"],
    "import of the engine (load, analyse, derive)": ["-c", "import davies_sym; davies_sym.derive; davies_sym.load"],
}


def wall_time(args: list[str], runs: int) -> float:
    """Median wall time of ``python ARGS`` over ``runs`` runs, in seconds."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run([sys.executable, *args], check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main(runs: int) -> None:
    for name, args in CASES.items():
        print(f"{name:<46} {wall_time(args, runs):7.3f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
