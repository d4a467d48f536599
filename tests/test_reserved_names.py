"""The symbol names the loader refuses are exactly those a generated formula module
cannot take, so the CLI, the API and the module accept and refuse the same files:
``FORMULA_MODULE_NAMES`` is checked against what the generator writes, and names that
only the runtime's functions use inside themselves (``ok``, ``shape``, ``result``, ``k``)
are ordinary symbols that derive and generate a working module."""

from __future__ import annotations

import ast
import importlib.util
import inspect
from fractions import Fraction
from pathlib import Path

import pytest
from harness.helpers import CATALOG, run_main

from davies_sym.emit import array_api_runtime, formula_runtime, several_inputs_runtime, shared_runtime
from davies_sym.emit.formula_code import module_level_names
from davies_sym.emit.python_module import _ENTRY_NAMES as ONE_INPUT_ENTRY_NAMES
from davies_sym.emit.several_inputs_module import _ENTRY_NAMES as SEVERAL_INPUTS_ENTRY_NAMES
from davies_sym.topology.expressions import FORMULA_MODULE_NAMES, RESERVED_NAMES

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")


def test_the_loader_reserves_every_public_name_a_generated_module_binds():
    bound: set[str] = set(ONE_INPUT_ENTRY_NAMES | SEVERAL_INPUTS_ENTRY_NAMES)
    for runtime in (formula_runtime, several_inputs_runtime, shared_runtime, array_api_runtime):
        bound |= module_level_names(ast.parse(inspect.getsource(runtime)))
    public = {n for n in bound if not n.startswith("_") and n != "davies_sym"}
    assert public <= RESERVED_NAMES, sorted(public - RESERVED_NAMES)
    # and nothing more than that: every reserved module name is bound by the generator
    assert public >= FORMULA_MODULE_NAMES, sorted(FORMULA_MODULE_NAMES - public)


@pytest.mark.parametrize(("first", "second"), [("ok", "shape"), ("result", "k"), ("ratio", "n")])
def test_names_the_runtime_uses_only_inside_its_functions_are_ordinary_symbols(tmp_path: Path, first, second):
    """A pair whose radii are called ``ok`` and ``shape`` derives, and its module gives
    -r2/r1 for the speed ratio and the mesh efficiency for the efficiency (Laus eq. (36))."""
    text = PAIR.replace("radius: r1", f"radius: {first}").replace("radius: r2", f"radius: {second}")
    train = tmp_path / "pair.yaml"
    train.write_text(text, encoding="utf-8")
    module_path = tmp_path / "pair_module.py"
    result = run_main([train, "--quiet", "--python", module_path])
    assert result.returncode == 0, result.describe()
    spec = importlib.util.spec_from_file_location("pair_module", module_path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    ratio = module.speed_ratio(**{first: 20.0, second: 50.0})
    assert float(ratio) == float(-Fraction(50, 20))
    assert float(module.efficiency(eta_C=0.97, **{first: 20.0, second: 50.0})) == pytest.approx(0.97, abs=1e-15)
    evaluated = run_main([train, "--quiet", "--eval", f"{first}=20", f"{second}=50", "eta_C=0.97"])
    assert evaluated.returncode == 0 and evaluated.stdout.strip().endswith("0.97"), evaluated.describe()
