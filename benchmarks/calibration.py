"""Time of calibrating the SR20 model on Table I of Mantriota and Pennestri (2003): the
derivation of its regions, the least-squares fit, and the prediction of Tables II-V, each
measured in one process (best of a few runs), plus the whole command as a fresh process.

    python benchmarks/calibration.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

from davies_sym.calibration.measurements import read_measurements
from davies_sym.calibration.train_fit import calibrate, derived_model
from davies_sym.topology.loader import load

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TRAIN = os.path.join(ROOT, "catalog", "sr20_differential.yaml")
TABLES = [os.path.join(ROOT, "catalog", "data", f"sr20_table{k}.csv") for k in range(1, 6)]
COLUMNS = ["w_A", "w_K", "T_O"]


def best(function, runs: int = 3) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    train = load(TRAIN)
    data = read_measurements(TABLES[0], [*COLUMNS, "eta"])
    others = [read_measurements(path, COLUMNS, ["eta"]) for path in TABLES[1:]]
    model, result = calibrate(derived_model(train), data)
    print(
        f"fit: {', '.join(f'{n} = {v:.6g}' for n, v in result.parameters.items())} "
        f"({result.evaluations} model evaluations)"
    )
    print(f"derive the regions and fit Table I: {best(lambda: calibrate(derived_model(train), data)):.3f} s")
    print(
        f"predict Tables II-V ({sum(len(o) for o in others)} rows): "
        f"{best(lambda: [model.predict(o, result.parameters) for o in others]):.4f} s"
    )
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", "calibrate", TRAIN, TABLES[0], "--predict", *TABLES[1:], "--json"],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    print(f"derive calibrate ... --predict (fresh process): {time.perf_counter() - start:.2f} s")


if __name__ == "__main__":
    main()
