"""The Python API refuses what the command line refuses, with the same reason: Chen's
virtual-power balance on a design ``derive --eval`` refuses or does not cover, an
efficiency outside its scope, design values of other number types (numpy, Decimal, a
truth value, a foreign sympy symbol), unknown ports and states.
"""

from __future__ import annotations

import pytest
from harness.helpers import (
    CATALOG,
    DATA,
    run_main,
)

import davies_sym

TUPLIN_DESIGN = {"r1": 40, "r2": 60, "r3": 15, "eta_C": 0.99, "eta_D": 0.99}


def _refusal(call):  # type: ignore[no-untyped-def]
    with pytest.raises(davies_sym.DaviesError) as caught:
        call()
    return caught.value


@pytest.mark.parametrize(
    ("values", "port", "cli", "kind", "words"),
    [
        (
            {**TUPLIN_DESIGN, "r1": 60},
            None,
            ["r1=60", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"],
            davies_sym.NotCoveredError,
            "port B does not turn at these values",
        ),
        (
            TUPLIN_DESIGN,
            "C",
            [*(f"{k}={v}" for k, v in TUPLIN_DESIGN.items()), "--input", "C"],
            davies_sym.InputError,
            "'C' is not a port (ports: A, B)",
        ),
        (
            {k: v for k, v in TUPLIN_DESIGN.items() if k != "r3"},
            None,
            ["r1=40", "r2=60", "eta_C=0.99", "eta_D=0.99"],
            davies_sym.InputError,
            "missing values for r3",
        ),
    ],
    ids=["port-still", "mesh-as-input", "missing-value"],
)
def test_the_balance_refuses_a_design_as_the_command_line_does(values, port, cli, kind, words):
    """Chen's virtual-power balance (a route sharing no code with Davies') raised
    DerivationError, KeyError or a sympy TypeError where `derive --eval` gives a reason."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = davies_sym.load(CATALOG / "tuplin.yaml")
    error = _refusal(lambda: virtual_power_balance(train, values, port))
    assert isinstance(error, kind) and words in str(error), error
    result = run_main([CATALOG / "tuplin.yaml", "--quiet", "--eval", *cli])
    assert words in result.stdout + result.stderr, result.describe()


def test_the_balance_says_a_transcendental_efficiency_is_outside_its_scope():
    """Buckingham's mesh efficiency holds logarithms (Laus App. A): the exact balance cannot
    take it; it says so instead of a sympy TypeError."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = davies_sym.load(CATALOG / "buckingham_pair.yaml")
    error = _refusal(lambda: virtual_power_balance(train, {"mu": 0.0272}))
    assert isinstance(error, davies_sym.DerivationError) and "not an algebraic number" in str(error)


def test_design_values_of_numpy_decimal_and_foreign_symbols_are_read_exactly():
    """numpy scalars raised a sympy TypeError, a Decimal was 'not a number', True was 1 and
    sympy.Symbol("r1") (without the train's assumptions) was an unknown symbol r1."""
    from decimal import Decimal

    import numpy as np
    import sympy

    variants = davies_sym.derive(davies_sym.load(CATALOG / "simple_pair.yaml"))
    assert variants.evaluate({"r1": np.float64(20), "r2": np.int64(50), "eta_C": np.float32(0.5)}) == sympy.Rational(
        1, 2
    )
    assert variants.evaluate({"r1": Decimal("20"), "r2": 50, "eta_C": Decimal("0.98")}) == sympy.Rational(49, 50)
    assert variants.evaluate({sympy.Symbol("r1"): 20, "r2": 50, "eta_C": 0.9}) == sympy.Rational(9, 10)
    for bad, words in ((True, "a truth value is not a number"), (float("nan"), "not a finite number")):
        error = _refusal(lambda bad=bad: variants.evaluate({"r1": 20, "r2": 50, "eta_C": bad}))
        assert isinstance(error, davies_sym.InputError) and words in str(error)


def test_derive_and_a_state_lookup_refuse_unknown_names_as_the_options_do():
    train = davies_sym.load(CATALOG / "simple_pair.yaml")
    for port in ("Z", "C"):
        error = _refusal(lambda port=port: davies_sym.derive(train, inputs=[port]))
        assert isinstance(error, davies_sym.InputError) and f"'{port}' is not a port (ports: A, B)" in str(error)
    states = davies_sym.load(DATA / "two_states.yaml")
    error = _refusal(lambda: states.state("nope"))
    assert isinstance(error, davies_sym.InputError) and "unknown state 'nope'" in str(error)
