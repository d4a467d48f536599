"""A symbol of the formulas defined by a loss model in other parameters.

The derivation works on exact polynomials, so a coefficient that a loss model gives as
a transcendental expression (the logarithms of Laus eq. (136), the pi of a journal's
contact law) stays a symbol there; the outputs state the definition and every
evaluation substitutes it."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import sympy


@dataclass(frozen=True)
class Definition:
    """``symbol = expression``, with what it is and where the model comes from."""

    symbol: sympy.Symbol
    expression: sympy.Expr
    meaning: str
    source: str
    #: Unit of each parameter the definition takes: (symbol name, unit).
    units: tuple[tuple[str, str], ...] = ()

    def unit_of(self, symbol: sympy.Symbol) -> str:
        return dict(self.units).get(str(symbol), "")

    def __str__(self) -> str:
        return f"{self.symbol} = {sympy.sstr(self.expression)}"


def substituted(expr: sympy.Expr, definitions: Iterable[Definition]) -> sympy.Expr:
    """``expr`` with every defined symbol replaced by its definition."""
    table = {d.symbol: d.expression for d in definitions}
    return sympy.sympify(expr).xreplace(table) if table else expr


def completed(
    values: Mapping[sympy.Symbol, sympy.Expr], definitions: Iterable[Definition]
) -> dict[sympy.Symbol, sympy.Expr]:
    """``values`` with the value of every defined symbol whose parameters are given."""
    out = dict(values)
    for d in definitions:
        value = d.expression.xreplace(out)
        if not value.free_symbols:
            out[d.symbol] = value
    return out


def parameters_of(symbols: Iterable[sympy.Symbol], definitions: Iterable[Definition]) -> set[sympy.Symbol]:
    """``symbols`` with every defined symbol replaced by the parameters of its definition."""
    table = {d.symbol: d.expression for d in definitions}
    out: set[sympy.Symbol] = set()
    for s in symbols:
        out |= table[s].free_symbols if s in table else {s}
    return out
