"""The generated formula modules on the arrays of other libraries, on a GPU where one is.

    python3 benchmarks/array_libraries.py [POINTS]

For every module in derivations/ (a train driven at several ports too): POINTS designs drawn
around the admissible ranges (some outside, some self-locking), ``efficiency`` and
``losses`` on NumPy arrays, then on the arrays of each library installed here (CuPy;
JAX and PyTorch on their default device, JAX in float64; PyTorch needs array-api-compat).
Each library's result must be an array of that library with NaN where NumPy's is and the
same values to 1e-12 relative; the table gives the best of three times of ``efficiency``
(the device synchronised).  Exit status 1 when a library disagrees.
"""

from __future__ import annotations

import glob
import importlib
import importlib.util
import os
import random
import sys
import time
import warnings
from collections.abc import Callable
from types import ModuleType
from typing import Any

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _module(path: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"bench_{os.path.basename(path)[:-3]}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _points(module: ModuleType, count: int, seed: int) -> dict[str, np.ndarray]:
    rng = random.Random(seed)
    out = {}
    for p in module.PARAMETERS:
        low = max(p["low"], -100.0)
        high = min(p["high"], low + 100.0 if p["low"] > -np.inf else 100.0)
        if p["name"].startswith("eta"):
            low = 0.5
        inside = np.array([rng.uniform(low, high) for _ in range(min(count, 4096))])
        values = np.resize(inside, count)
        outside = np.arange(count) % 10 == 3
        values[outside] = -values[outside]
        out[p["name"]] = values
    return out


def _libraries() -> dict[str, tuple[Callable[[np.ndarray], Any], Callable[[Any], np.ndarray], Callable[[], None]]]:
    """name: (to the library's array, back to numpy, synchronise) of each library here."""
    found: dict[str, tuple[Callable[[np.ndarray], Any], Callable[[Any], np.ndarray], Callable[[], None]]] = {}
    try:
        cupy = importlib.import_module("cupy")
        found["cupy"] = (cupy.asarray, cupy.asnumpy, lambda: cupy.cuda.Device().synchronize())
    except ImportError:
        pass
    try:
        jax = importlib.import_module("jax")
        jax.config.update("jax_enable_x64", True)
        jnp = importlib.import_module("jax.numpy")
        found["jax"] = (jnp.asarray, lambda a: np.asarray(a), lambda: None)
    except ImportError:
        pass
    try:
        torch = importlib.import_module("torch")
        importlib.import_module("array_api_compat")
        device = "cuda" if torch.cuda.is_available() else "cpu"
        synchronise = torch.cuda.synchronize if device == "cuda" else (lambda: None)
        found["torch"] = (
            lambda a: torch.asarray(a, device=device),
            lambda a: a.cpu().numpy(),
            synchronise,
        )
    except ImportError:
        pass
    return found


def _best(function: Callable[[], Any], synchronise: Callable[[], None]) -> float:
    times = []
    for _ in range(3):
        start = time.perf_counter()
        result = function()
        synchronise()
        times.append(time.perf_counter() - start)
        del result
    return min(times)


def main(count: int) -> int:
    libraries = _libraries()
    print(f"libraries: {', '.join(libraries) or 'none besides numpy'}; {count:,} points")
    paths = sorted(glob.glob(os.path.join(ROOT, "derivations", "*.py")))
    print("| module | numpy | " + " | ".join(libraries) + " |")
    print("| --- | --- | " + " | ".join("---" for _ in libraries) + " |")
    failures = 0
    warnings.simplefilter("ignore")
    for path in paths:
        module = _module(path)
        points = _points(module, count, seed=len(path))
        if not points:
            continue
        want = module.efficiency(errors="ignore", **points)
        # A train driven at several ports gives its port torques where one port gives losses.
        parts = getattr(module, "losses", None) or module.torques
        lost = parts(errors="ignore", **points)
        on_numpy = _best(lambda: module.efficiency(errors="ignore", **points), lambda: None)  # noqa: B023
        row = [os.path.basename(path)[:-3], f"{on_numpy:.4f} s"]
        for to, back, synchronise in libraries.values():
            given = {n: to(v) for n, v in points.items()}
            got = module.efficiency(errors="ignore", **given)
            same = type(got).__module__.split(".")[0] == type(given[next(iter(given))]).__module__.split(".")[0]
            same = same and np.allclose(back(got), want, rtol=1e-12, atol=1e-15, equal_nan=True)
            for key, part in parts(errors="ignore", **given).items():
                same = same and np.allclose(back(part), lost[key], rtol=1e-12, atol=1e-15, equal_nan=True)
            took = _best(lambda: module.efficiency(errors="ignore", **given), synchronise)  # noqa: B023
            row.append(f"{took:.4f} s" + ("" if same else " DISAGREES"))
            failures += not same
        print("| " + " | ".join(row) + " |", flush=True)
    print("every library agrees with numpy" if not failures else f"{failures} disagreements")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000))
