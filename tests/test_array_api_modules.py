"""The formula modules on arrays of other libraries (the array API standard): every
one-input catalog module gives on array-api-strict and on JAX arrays what it gives on
NumPy arrays (the NumPy path is checked against the exact variants elsewhere), NaN at the
same points and the same warning, an array of the same library back; the namespace of
the arguments is found with and without array-api-compat."""

from __future__ import annotations

import glob
import importlib.util
import os
import random
import subprocess
import sys
import warnings
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from conftest import ROOT

strict = pytest.importorskip("array_api_strict")

DERIVATIONS = os.path.join(ROOT, "derivations")


def _module(path: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"arrays_{os.path.basename(path)[:-3]}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: The modules of trains driven at one port (a train driven at several has `torques`).
ONE_INPUT = sorted(
    p for p in glob.glob(os.path.join(DERIVATIONS, "*.py")) if "def torques(" not in Path(p).read_text(encoding="utf-8")
)


def _points(module: ModuleType, count: int, seed: int) -> dict[str, np.ndarray]:
    """Designs drawn around the admissible ranges: mostly inside (efficiencies from 0.5,
    so some self-lock), some outside, so every NaN reason occurs."""
    rng = random.Random(seed)
    out = {}
    for p in module.PARAMETERS:
        low, high = p["low"], min(p["high"], p["low"] + 100.0)
        if p["name"].startswith("eta"):
            low = 0.5
        values = [rng.uniform(low, high) if rng.random() > 0.1 else rng.uniform(-high, 2 * high) for _ in range(count)]
        out[p["name"]] = np.array(values)
    return out


def _back(array: Any) -> np.ndarray:
    return np.asarray(np.from_dlpack(array)) if not isinstance(array, np.ndarray) else array


def _calls(module: ModuleType, kwargs: dict[str, Any], port: str) -> tuple[dict[str, Any], list[str]]:
    """Every entry point at ``kwargs`` with ``port`` as input, and the warnings said."""
    ratio_names = {n for n in kwargs if n in module.speed_ratio.__kwdefaults__ or n in _required(module.speed_ratio)}
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        out = {
            "efficiency": module.efficiency(input=port, **kwargs),
            "variant": module.variant(input=port, **kwargs),
            "speed_ratio": module.speed_ratio(input=port, **{n: kwargs[n] for n in ratio_names}),
            **{f"loss {k}": v for k, v in module.losses(input=port, **kwargs).items()},
            **{f"d/d {n}": module.sensitivity(wrt=n, input=port, **kwargs) for n in module.SENSITIVE[:2]},
        }
    return out, [str(w.message) for w in said]


def _required(function: Any) -> set[str]:
    code = function.__code__
    return set(code.co_varnames[: code.co_kwonlyargcount]) - set(function.__kwdefaults__ or {})


def _same(numpy_results: dict[str, Any], other: dict[str, Any], library: str) -> None:
    for name, want in numpy_results.items():
        got = _back(other[name])
        assert type(other[name]).__module__.startswith(library), (name, type(other[name]))
        want = np.broadcast_to(want, got.shape)
        assert np.array_equal(np.isnan(got), np.isnan(want)) if got.dtype.kind == "f" else True, name
        assert np.allclose(got, want, rtol=1e-12, atol=1e-15, equal_nan=True), name


@pytest.mark.parametrize("path", ONE_INPUT, ids=[os.path.basename(p)[:-3] for p in ONE_INPUT])
def test_module_on_array_api_strict_arrays_is_the_numpy_module(path: str) -> None:
    module = _module(path)
    points = _points(module, 400, seed=len(path))
    if not points:
        pytest.skip("no parameters: a constant efficiency, no arrays to give")
    for port in module.PORTS:
        want, said = _calls(module, points, port)
        got, said_too = _calls(module, {n: strict.asarray(v) for n, v in points.items()}, port)
        _same(want, got, "array_api_strict")
        assert said_too == said
        assert any("NaN there" in w for w in said) or not any(np.isnan(want["efficiency"]))


def test_numbers_beside_arrays_and_a_variant_function(tmp_path: Any) -> None:
    """A number stays a number beside the arrays; a variant's own function takes arrays
    too and gives one of their library."""
    module = _module(os.path.join(DERIVATIONS, "tuplin.py"))
    r1 = strict.asarray([30.0, 40.0, 90.0])
    with pytest.warns(module.DesignWarning, match="1 design point"):  # r1 = 90: r4 = r1 - r3 + r2 is no radius
        got = module.efficiency(r1=r1, r2=60, r3=15, eta_C=0.99, eta_D=0.99)
    want = module.efficiency(r1=np.array([30.0, 40.0, 90.0]), r2=60, r3=15, eta_C=0.99, eta_D=0.99, errors="ignore")
    assert np.allclose(_back(got), want, rtol=1e-12, equal_nan=True)
    first = module.VARIANTS[0]["name"]
    part = getattr(module, first)(r1=r1, r2=60.0, r3=15.0, eta_C=0.99, eta_D=0.99)
    assert type(part).__module__.startswith("array_api_strict")


def test_a_dependent_parameter_is_checked_on_any_arrays() -> None:
    """Tuplin's r4 is dependent (r4 = r1 - r3 + r2): a wrong value is refused as with NumPy."""
    module = _module(os.path.join(DERIVATIONS, "tuplin.py"))
    if "r4" not in module.DEPENDENT:
        pytest.skip("no dependent parameter")
    with pytest.raises(module.DesignError, match="breaks the relation"):
        module.efficiency(r1=strict.asarray([40.0]), r2=60, r3=15, r4=strict.asarray([36.0]), eta_C=0.9, eta_D=0.9)


def test_namespace_without_array_api_compat(monkeypatch: pytest.MonkeyPatch) -> None:
    """Arrays that name their namespace need nothing more; the fallback says what to
    install for arrays that do not."""
    module = _module(os.path.join(DERIVATIONS, "simple_pair.py"))
    monkeypatch.setitem(sys.modules, "array_api_compat", None)  # its import now fails
    assert module._namespace(strict.asarray([1.0]), 2.0) is strict

    class Tensor:  # an array that speaks DLPack but names no namespace (as a PyTorch tensor)
        def __dlpack__(self) -> None: ...

    with pytest.raises(TypeError, match="pip install array-api-compat"):
        module._namespace(Tensor())
    assert module._namespace(np.ones(2), 3, [1.0]) is np


#: The JAX check runs in a process of its own: JAX starts threads, and a test worker that
#: forks afterwards (subprocesses, process pools) could deadlock.
_JAX_CHECK = """
import sys, warnings
import numpy as np
import jax
jax.config.update("jax_enable_x64", True)
import jax.numpy as jnp
sys.path.insert(0, sys.argv[1])
import test_array_api_modules as t
module = t._module(sys.argv[2])
points = t._points(module, 200, seed=3)
for port in module.PORTS:
    want, said = t._calls(module, points, port)
    got, said_too = t._calls(module, {n: jnp.asarray(v) for n, v in points.items()}, port)
    t._same(want, got, "jax")
    assert said_too == said, (said, said_too)
print("agree")
"""


def test_module_on_jax_arrays() -> None:
    pytest.importorskip("jax")
    tests = os.path.dirname(os.path.abspath(__file__))
    result = subprocess.run(
        [sys.executable, "-c", _JAX_CHECK, tests, os.path.join(DERIVATIONS, "wolfrom.py")],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join([tests, os.environ.get("PYTHONPATH", "")])},
        check=False,
        timeout=600,
    )
    assert result.returncode == 0 and result.stdout.strip() == "agree", result.stderr[-3000:]


#: JAX as it comes (32-bit: no int64): the entry points ask for the library's own integer
#: type, so a call says no word about dtypes; the variants are NumPy's wherever the two
#: precisions agree on the conditions' signs (points inside the ranges, away from NaN).
_JAX_32_CHECK = """
import sys, warnings
import numpy as np
warnings.filterwarnings("error", message=".*dtype.*")
import jax.numpy as jnp
sys.path.insert(0, sys.argv[1])
import test_array_api_modules as t
for path in sys.argv[2:]:
    module = t._module(path)
    points = t._points(module, 200, seed=5)
    for port in module.PORTS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", module.DesignWarning)
            want = module.efficiency(input=port, **points)
            numbers = module.variant(input=port, **points)
            given = {n: jnp.asarray(v, dtype=jnp.float32) for n, v in points.items()}
            got = np.asarray(module.efficiency(input=port, **given))
            got_numbers = np.asarray(module.variant(input=port, **given))
        assert str(got_numbers.dtype) == "int32", got_numbers.dtype
        sure = ~np.isnan(want) & ~np.isnan(got)
        assert sure.sum() > 50, sure.sum()
        assert (got_numbers[sure] == numbers[sure]).mean() > 0.95
        assert np.allclose(got[sure], want[sure], rtol=1e-4)
print("agree")
"""


def test_module_on_jax_32_bit_arrays_says_nothing_of_dtypes() -> None:
    pytest.importorskip("jax")
    tests = os.path.dirname(os.path.abspath(__file__))
    env = {k: v for k, v in os.environ.items() if k != "JAX_ENABLE_X64"}
    modules = [os.path.join(DERIVATIONS, f"{name}.py") for name in ("wolfrom", "planetary_simple")]
    result = subprocess.run(
        [sys.executable, "-c", _JAX_32_CHECK, tests, *modules],
        capture_output=True,
        text=True,
        env={**env, "PYTHONPATH": os.pathsep.join([tests, os.environ.get("PYTHONPATH", "")])},
        check=False,
        timeout=600,
    )
    assert result.returncode == 0 and result.stdout.strip() == "agree", result.stderr[-3000:]


def test_a_train_driven_at_several_ports_on_array_api_strict_arrays() -> None:
    """The SR20 differential's module (two input shafts, Mantriota and Pennestri): its
    efficiency, port torques, speeds and region numbers on array-api-strict arrays are
    those on NumPy arrays, NaN and warning included."""
    module = _module(os.path.join(DERIVATIONS, "sr20_differential.py"))
    rng = np.random.default_rng(7)
    points = {
        "omega_A": rng.uniform(-100, 100, 600),
        "omega_K": rng.uniform(-100, 100, 600),
        "tau_out": rng.uniform(-10, 100, 600),
        "eta_M": rng.uniform(0.5, 1.0, 600),
        "D_P": rng.uniform(0.0, 3.0, 600),
    }
    speeds = {n: points[n] for n in ("omega_A", "omega_K")}

    def every(given: dict[str, Any]) -> tuple[dict[str, Any], list[str]]:
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            out = {
                "efficiency": module.efficiency(**given),
                "region": module.region(**given),
                **{f"torque {k}": v for k, v in module.torques(**given).items()},
                **{f"speed {k}": v for k, v in module.speeds(**{n: given[n] for n in speeds}).items()},
            }
        return out, [str(w.message) for w in said]

    want, said = every(points)
    got, said_too = every({n: strict.asarray(v) for n, v in points.items()})
    _same(want, got, "array_api_strict")
    assert said_too == said and said


def test_formulas_are_printed_with_the_array_api_names() -> None:
    """numpy's arccos and arctan2 are acos and atan2 in the standard (and in NumPy 2): the
    generated formula calls them on xp, the arguments' namespace (abs is Python's, which
    every array takes)."""
    import ast

    import sympy

    from davies_sym.emit.formula_code import formula_function

    x, y = sympy.symbols("x y")
    function, args = formula_function("f", "A test formula.", [sympy.acos(x) + sympy.atan2(y, x) + sympy.Abs(y)])
    code = ast.unparse(ast.fix_missing_locations(ast.Module([function], type_ignores=[])))
    assert args == ("x", "y") and "xp.acos(" in code and "xp.atan2(" in code and "abs(y)" in code
    scope: dict[str, Any] = {}
    module = _module(os.path.join(DERIVATIONS, "simple_pair.py"))
    exec(code, {**vars(module), "__name__": "formula"}, scope)
    for library, to in ((np, np.asarray), (strict, strict.asarray)):
        got = scope["f"](x=to([0.5]), y=to([-0.25]))
        want = np.arccos(0.5) + np.arctan2(-0.25, 0.5) + 0.25
        assert np.allclose(_back(got), want), library
