"""A square root of the geometry as a symbol: ``symbol = sqrt(radicand)`` (the table
that collects them is `davies_sym.algebra.radicals`; the polynomial ring reduces by
their relations ``symbol^2 = radicand``)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy


@dataclass(frozen=True)
class Radical:
    """``symbol = sqrt(radicand)``; the radicand is positive where the design exists."""

    symbol: sympy.Symbol
    radicand: sympy.Expr

    @property
    def expression(self) -> sympy.Expr:
        return sympy.sqrt(self.radicand)
