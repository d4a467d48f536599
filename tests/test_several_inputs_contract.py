"""One contract for a train driven on several shafts (the SR20 differential, Mantriota and
Pennestri 2003): ``derive --eval``, `SeveralInputs.design_point` with names and with
symbols as keys, and the generated module (``derivations/sr20_differential.py``) accept
the same designs with one efficiency and refuse the same designs with one reason.

The accepted designs are checked against Mantriota and Pennestri's eq. (6) computed by the
independent free-body oracle of tests/oracles (`sr20_at_row`), which shares no code with
the engine."""

from __future__ import annotations

import importlib.util
import json
import warnings
from fractions import Fraction as F
from pathlib import Path
from types import ModuleType

import pytest
import sympy
from harness.helpers import run_main
from oracle.lossy_balance import sr20, sr20_at_row

import davies_sym
from davies_sym.errors import DaviesError, InputError, NotCoveredError

from conftest import CATALOG, ROOT

PATH = str(Path(CATALOG) / "sr20_differential.yaml")

#: (label, values, the module's words for the refusal or None where accepted).
DESIGNS = [
    (
        "Table I conditions without drag",
        {"omega_A": 309, "omega_K": 51, "tau_out": "5.08", "eta_M": "0.95", "D_P": 0},
        None,
    ),
    (
        "drag dominates (the carrier takes power)",
        {"omega_A": 309, "omega_K": 51, "tau_out": "0.01", "eta_M": "0.95", "D_P": 5},
        None,
    ),
    ("both shafts backwards", {"omega_A": -120, "omega_K": -80, "tau_out": 2, "eta_M": "0.9", "D_P": "0.3"}, None),
    ("inputs against each other", {"omega_A": 300, "omega_K": -100, "tau_out": 2, "eta_M": "0.9", "D_P": "0.3"}, None),
    (
        "equal speeds: on a speed condition",
        {"omega_A": 51, "omega_K": 51, "tau_out": 1, "eta_M": "0.95", "D_P": 5},
        "1 on a speed-condition line",
    ),
    (
        "output still: on a speed condition",
        {"omega_A": 309, "omega_K": -309, "tau_out": 1, "eta_M": "0.9", "D_P": 5},
        "1 on a speed-condition line",
    ),
    (
        "no load",
        {"omega_A": 309, "omega_K": 51, "tau_out": 0, "eta_M": "0.95", "D_P": 5},
        "1 point(s) outside the parameters' ranges",
    ),
    (
        "efficiency above one",
        {"omega_A": 309, "omega_K": 51, "tau_out": 1, "eta_M": "3/2", "D_P": 5},
        "1 point(s) outside the parameters' ranges",
    ),
    (
        "efficiency zero",
        {"omega_A": 309, "omega_K": 51, "tau_out": 1, "eta_M": 0, "D_P": 5},
        "1 point(s) outside the parameters' ranges",
    ),
    (
        "negative drag",
        {"omega_A": 309, "omega_K": 51, "tau_out": 1, "eta_M": "0.9", "D_P": -1},
        "1 point(s) outside the parameters' ranges",
    ),
]


@pytest.fixture(scope="module")
def several() -> davies_sym.SeveralInputs:
    return davies_sym.derive_several_inputs(davies_sym.load(PATH))


@pytest.fixture(scope="module")
def module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("contract_sr20", Path(ROOT) / "derivations" / "sr20_differential.py")
    assert spec is not None and spec.loader is not None
    loaded = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(loaded)
    return loaded


def _exact(value: object) -> F:
    return F(str(value))


@pytest.mark.slow
@pytest.mark.parametrize(("label", "values", "module_words"), DESIGNS, ids=[d[0] for d in DESIGNS])
def test_every_entry_point_accepts_and_refuses_the_same_designs(several, module, label, values, module_words):
    pairs = [f"{k}={v}" for k, v in values.items()]
    result = run_main([PATH, "--quiet", "--json", "--eval", *pairs], timeout=300)
    assert "Traceback" not in result.stderr, result.describe()
    document = json.loads(result.stdout) if result.stdout.strip() else {}
    try:
        point = several.design_point(values)
    except DaviesError as exc:
        refusal: DaviesError | None = exc
    else:
        refusal = None
    symbols = {
        **several.train.symbols,
        **{str(s): s for s in several.speeds},
        "tau_out": sympy.Symbol("tau_out", positive=True),
    }
    keyed = {symbols[k]: v for k, v in values.items()}
    floats = {k: float(_exact(v)) for k, v in values.items()}
    try:
        by_symbol = several.evaluate(keyed)
    except DaviesError as exc:
        assert refusal is not None and str(exc) == str(refusal), label
    else:
        assert refusal is None and by_symbol == point.efficiency, label
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        quiet = float(module.efficiency(errors="ignore", **floats))
    if refusal is None:
        assert module_words is None, f"{label}: the API accepts what the test expects refused"
        assert result.returncode == 0, result.describe()
        assert sympy.sympify(document["efficiency_exact"]) == point.efficiency, label
        # Mantriota and Pennestri eq. (6) by the free-body oracle.
        eta = _exact(values["eta_M"])
        w_a, w_k = _exact(values["omega_A"]), _exact(values["omega_K"])
        # The load resists the output's motion: its torque opposes w_O = (w_A + w_K)/2.
        load = -_exact(values["tau_out"]) * (1 if w_a + w_k > 0 else -1)
        truth = sr20_at_row(
            {"w_A": w_a, "w_K": w_k, "T_O": load},
            train=sr20(eta_1=eta, eta_2=eta, drag={"p": _exact(values["D_P"])}),
        )
        assert point.efficiency == sympy.Rational(truth.eta.numerator, truth.eta.denominator), label
        assert quiet == pytest.approx(float(point.efficiency), rel=1e-12), label
        return
    assert module_words is not None, f"{label}: the API refuses: {refusal}"
    assert result.returncode == (2 if isinstance(refusal, InputError) else 3), result.describe()
    assert not isinstance(refusal, NotCoveredError) or result.returncode == 3
    said = result.stderr + str(document.get("reason", ""))
    assert str(refusal).split(": ")[-1] in said, f"{label}: CLI says {said!r}, API {refusal}"
    assert quiet != quiet, f"{label}: the module gives {quiet} where the API refuses: {refusal}"
    with pytest.raises(module.DesignError) as raised:
        module.efficiency(errors="raise", **floats)
    assert module_words in str(raised.value), f"{label}: module says {raised.value}, API {refusal}"


def test_derive_variants_points_a_train_with_several_inputs_to_its_own_derivation():
    """One efficiency per input port is not the answer for two driven shafts: the API says
    which function derives the regions, at the ports' line, instead of a mobility error."""
    with pytest.raises(InputError) as raised:
        davies_sym.derive(davies_sym.load(PATH))
    text = str(raised.value)
    assert "sr20_differential.yaml:" in text and "ports:" in text and "derive_several_inputs" in text
