"""The only module of the oracle that calls the engine (``davies_sym``).

When the package is restructured, only the imports below need new paths.  Values are
passed by symbol name; the results come back as exact ``Fraction`` when the engine's
number is rational, else as a float.
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from functools import lru_cache
from typing import Any

import sympy

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.errors import DaviesError
from davies_sym.network.analysis import analyse
from davies_sym.topology.states import train_in_state

#: Exceptions by which the engine refuses a train (as opposed to a crash).
REFUSALS: tuple[type[BaseException], ...] = (DaviesError,)


@lru_cache(maxsize=32)
def _train(yaml_text: str, state: str | None) -> Any:
    train = davies_sym.loads(yaml_text, "oracle.yaml")
    if state is not None:
        train = train_in_state(train, train.state(state))
    return train


@lru_cache(maxsize=32)
def _variants(yaml_text: str, state: str | None) -> Any:
    return derive_variants(_train(yaml_text, state))


def engine_load(yaml_text: str) -> Any:
    """Load the train (raises on a refusal)."""
    return _train(yaml_text, None)


def engine_states(yaml_text: str) -> list[str]:
    """Names of the operating states the file declares."""
    return [s.name for s in _train(yaml_text, None).states]


def _values(train: Any, values: Mapping[str, Fraction]) -> dict[sympy.Symbol, sympy.Rational]:
    symbols = train.symbols
    return {symbols[name]: sympy.Rational(v.numerator, v.denominator) for name, v in values.items() if name in symbols}


def _number(expr: Any) -> Fraction | float:
    value = sympy.nsimplify(expr) if not isinstance(expr, sympy.Rational) else expr
    value = sympy.simplify(value) if not value.is_Rational else value
    if value.is_Rational:
        return Fraction(int(value.p), int(value.q))
    if not value.is_number:
        raise ValueError(f"the engine's value is not a number: {value}")
    return float(sympy.N(value, 30))


def engine_derive(yaml_text: str, state: str | None = None) -> int:
    """Derive the variants (raises on a refusal); returns the number of variants."""
    return len(_variants(yaml_text, state).variants)


def engine_efficiency(
    yaml_text: str, values: Mapping[str, Fraction], input_port: str, state: str | None = None
) -> Fraction | float:
    """The engine's efficiency -P_out / P_in with ``input_port`` as input."""
    vs = _variants(yaml_text, state)
    return _number(vs.evaluate(_values(vs.train, values), input_port))


def engine_speed_ratio(yaml_text: str, values: Mapping[str, Fraction], state: str | None = None) -> Fraction | float:
    """The engine's t_in / t_out for the declared ports (of ``state``): each t is the
    motion of the port coupling's second link relative to its first."""
    train = _train(yaml_text, state)
    rf = analyse(train).speed_ratio()
    return _number(rf.to_expr().subs(_values(train, values)))


def clear_cache() -> None:
    _train.cache_clear()
    _variants.cache_clear()
