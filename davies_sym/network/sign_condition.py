"""A Coulomb friction sign that the declared ports leave open (Laus sec. 3.3: the sign
of the transmitted force times the relative motion)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy


@dataclass(frozen=True)
class SignCondition:
    """A Coulomb friction sign the declared ports do not decide.

    ``symbol`` (+1 or -1) stands for ``sign(expression)`` in the friction form.
    """

    coupling: str
    symbol: sympy.Symbol
    expression: sympy.Expr
