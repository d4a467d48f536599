"""Time the generated formula modules on a million design points each.

    python3 benchmarks/formula_modules.py [POINTS]

For every module in derivations/: admissible designs sampled exactly from the train's
parameter domain are tiled to POINTS rows (default 1,000,000), each mesh efficiency drawn
uniformly in [0.9, 1), and ``efficiency`` (the variant chosen element by element,
screened for self-locking) is timed, best of three; also ``losses``.  The SR20
differential's module (two input shafts) last, on drawn speeds and loads.
"""

from __future__ import annotations

import glob
import importlib.util
import os
import sys
import time
import warnings

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from davies_sym.efficiency.parameter_domain import ParameterDomain  # noqa: E402
from davies_sym.efficiency.parameters import formula_symbols  # noqa: E402
from davies_sym.efficiency.variants import derive_variants  # noqa: E402
from davies_sym.topology.loader import load  # noqa: E402
from davies_sym.topology.states import train_in_state  # noqa: E402


def _trains():
    for path in sorted(glob.glob(os.path.join(ROOT, "catalog", "*.yaml"))):
        with open(path, encoding="utf-8") as handle:
            if any(line.startswith("machine:") for line in handle):
                continue  # a machine: no formula module
        train = load(path)
        stem = os.path.splitext(os.path.basename(path))[0]
        if (train.degrees_of_freedom or 1) > 1:
            continue
        if train.states:
            for st in train.states:
                yield f"{stem}_{st.name}", train_in_state(train, st)
        else:
            yield stem, train


def _module(stem: str):
    spec = importlib.util.spec_from_file_location(stem, os.path.join(ROOT, "derivations", f"{stem}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _best(function, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def main(points: int) -> None:
    rng = np.random.default_rng(0)
    print(f"| module | variants | efficiency, {points:,} points | losses | design points per second |")
    print("| --- | --- | --- | --- | --- |")
    for stem, train in _trains():
        vs = derive_variants(train)
        module = _module(stem)
        domain = ParameterDomain.of(train, vs.analysis.network.layout)
        samples = list(domain.samples(500, seed=1))
        sampled = {str(s): s for s in samples[0]} if samples else {}
        kwargs = {}
        for s in formula_symbols(vs):
            name = str(s)
            if name.startswith("eta"):
                kwargs[name] = rng.uniform(0.9, 1.0, points)
            elif name.startswith("mu"):  # sliding friction coefficients (worm, crossed helical)
                kwargs[name] = rng.uniform(0.02, 0.1, points)
            elif name in sampled:
                kwargs[name] = np.resize(np.array([float(p[sampled[name]]) for p in samples]), points)
            elif f"cos_{name}" in sampled:  # an angle, sampled by its cosine and sine
                cos, sin = sampled[f"cos_{name}"], sampled[f"sin_{name}"]
                angles = [np.arctan2(float(p[sin]), float(p[cos])) for p in samples]
                kwargs[name] = np.resize(np.array(angles), points)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t_eff = _best(lambda: module.efficiency(errors="ignore", **kwargs))  # noqa: B023
            t_loss = _best(lambda: module.losses(errors="ignore", **kwargs))  # noqa: B023
        rate = points / t_eff
        print(f"| {stem} | {len(vs.variants)} | {t_eff:.3f} s | {t_loss:.3f} s | {rate:.2e} |", flush=True)
    several_inputs(points, rng)


def several_inputs(points: int, rng: np.random.Generator) -> None:
    """The SR20 differential's module (two input shafts): shaft speeds drawn in [-100, 100]
    rad/s, the output torque in [10, 100], the planets' drag in [0, 0.5], the mesh
    efficiency in [0.9, 1); ``torques`` in the losses' column."""
    module = _module("sr20_differential")
    kwargs = {
        "D_P": rng.uniform(0.0, 0.5, points),
        "eta_M": rng.uniform(0.9, 1.0, points),
        "omega_A": rng.uniform(-100.0, 100.0, points),
        "omega_K": rng.uniform(-100.0, 100.0, points),
        "tau_out": rng.uniform(10.0, 100.0, points),
    }
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_eff = _best(lambda: module.efficiency(errors="ignore", **kwargs))
        t_torques = _best(lambda: module.torques(errors="ignore", **kwargs))
    rate = points / t_eff
    print(
        f"| sr20_differential (regions; torques) | {len(module.REGIONS)} | {t_eff:.3f} s | {t_torques:.3f} s | "
        f"{rate:.2e} |",
        flush=True,
    )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
