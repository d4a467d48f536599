"""A deterministic order of sympy symbols: by name, then by assumptions.

Sets of symbols (``free_symbols``) iterate in hash order, which changes from run to run;
every sequence of symbols whose order can reach a result is sorted by `symbol_key`.
Two symbols with one name and different assumptions are different symbols to sympy;
the key keeps them apart (and in a fixed order) where sorting by name alone would not.
"""

from __future__ import annotations

from collections.abc import Iterable

import sympy

Assumptions = tuple[tuple[str, bool], ...]


def assumptions(symbol: sympy.Symbol) -> Assumptions:
    """Every fact sympy knows about ``symbol`` (the given assumptions and what they
    imply), sorted by name."""
    return tuple(sorted((str(k), bool(v)) for k, v in symbol.assumptions0.items()))


def describe_assumptions(symbol: sympy.Symbol) -> str:
    """The facts that hold for ``symbol``, e.g. ``commutative, complex, ..., real``."""
    return ", ".join(k for k, v in assumptions(symbol) if v) or "none"


def symbol_key(symbol: sympy.Symbol) -> tuple[str, Assumptions]:
    """Sort key: the name, then the assumptions."""
    return (symbol.name, assumptions(symbol))


def sorted_symbols(symbols: Iterable[sympy.Symbol]) -> list[sympy.Symbol]:
    """``symbols`` sorted by `symbol_key`."""
    return sorted(symbols, key=symbol_key)
