"""The generated formula module of every random train (tests/oracle/) against the
independent oracle: the module text is laid out within 120 columns, compiles, imports,
and its ``efficiency`` and ``speed_ratio`` give the oracle's numbers (every state, both
input ports; NaN where the oracle finds the train self-locking).  The modules of the
states of one file share one signature."""

from __future__ import annotations

import inspect
import math
import types
import warnings
from fractions import Fraction

import pytest
from oracle.balance import SelfLocking, solve
from oracle.compare import close
from oracle.random_trains import FAMILIES, generate, spelling

import davies_sym
from davies_sym.efficiency.parameters import file_parameters
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.python_module import python_module
from davies_sym.topology.states import train_in_state

SPELLINGS = ("catalog", "renamed", "reversed")


def _module(source: str, name: str) -> types.ModuleType:
    assert max(len(line) for line in source.splitlines()) <= 120
    module = types.ModuleType(name)
    exec(compile(source, f"<{name}>", "exec"), module.__dict__)
    return module


def _families() -> list[str]:
    # The Ravigneaux set takes seconds per state: it is covered by the catalog's modules.
    return [f for f in FAMILIES if f != "ravigneaux"]


@pytest.mark.parametrize("spelling_name", SPELLINGS)
@pytest.mark.parametrize("family", _families())
def test_module_of_a_random_train_agrees_with_the_oracle(family: str, spelling_name: str) -> None:
    train = generate(family, 0)
    sp = spelling(train, spelling_name)
    spec = train.oracle()
    loaded = davies_sym.loads(sp.yaml, "random.yaml")
    accepted = file_parameters(loaded)
    signatures = set()
    for state in train.oracle_states():
        estate = sp.engine_state(state.name)
        in_state = loaded if estate is None else train_in_state(loaded, loaded.state(estate))
        module = _module(python_module(derive_variants(in_state), accepted), f"random_{family}_{state.name}")
        parameters = inspect.signature(module.efficiency).parameters
        signatures.add(frozenset(parameters))
        values = {n: float(v) for n, v in sp.values.items() if n in parameters}
        ratio = solve(spec, state.input, state, lossless=True).speed_ratio
        ratio *= sp.orientation[state.input] * sp.orientation[state.output]
        geometry = {n: v for n, v in values.items() if n in inspect.signature(module.speed_ratio).parameters}
        assert close(float(module.speed_ratio(**geometry)), ratio), (state.name, module.speed_ratio(**geometry), ratio)
        for port in (state.input, state.output):
            try:
                expected: Fraction | None = Fraction(solve(spec, port, state).efficiency)
            except SelfLocking:
                expected = None
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", module.DesignWarning)
                got = float(module.efficiency(input=sp.ports[port], **values))
            if expected is None:
                assert math.isnan(got), (state.name, port, got)
            else:
                assert close(got, expected), (state.name, port, got, float(expected))
    assert len(signatures) == 1, "the states' modules take different parameters"
