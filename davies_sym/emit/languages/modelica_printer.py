"""A Modelica expression printer on sympy's ``StrPrinter`` (sympy has none).

Modelica writes powers with ``^``, square roots and absolute values as ``sqrt`` and
``abs``, choices as ``if .. then .. elseif .. else ..`` expressions, ``and``, ``or``,
``not`` and ``<>``; integer division ``1/2`` is a Real there, as in the formulas.
Modelica has no NaN: where the other languages return NaN the generated functions
return the ``not_covered`` value (0, which no efficiency in (0, 1] takes).  Nor has it a
built-in pi (``Modelica.Constants.pi`` is the Standard Library's, which the package does
not load), so pi, e and the other number symbols are written as decimals.  Unary minus
may only open an expression in Modelica, so a negative factor or exponent is
parenthesised, and every boolean operand is parenthesised, since ``not`` binds less
tightly than a relation there.
"""

from __future__ import annotations

from typing import Any, ClassVar

import sympy
from sympy.core.function import AppliedUndef
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.str import StrPrinter


class ModelicaPrinter(StrPrinter):  # type: ignore[misc]  # sympy has no type information
    """``doprint(expr)``: the Modelica text of a real or boolean expression."""

    _default_settings: ClassVar[dict[str, Any]] = {**StrPrinter._default_settings, "not_covered": "0.0"}

    #: sympy's functions by their Modelica names (``Abs`` is ``abs``, the others keep theirs).
    _functions: ClassVar[dict[str, str]] = {
        "Abs": "abs",
        **{f: f for f in ("sqrt", "exp", "log", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh")},
    }

    def _print_Pow(self, expr: sympy.Pow, rational: bool = False) -> str:
        base, exp = expr.base, expr.exp
        if exp == sympy.S.Half:
            return f"sqrt({self._print(base)})"
        if exp.is_number and exp.is_negative:
            if exp == -1:
                return f"1/{self.parenthesize(base, PRECEDENCE['Mul'], strict=False)}"
            if exp == -sympy.S.Half:
                return f"1/sqrt({self._print(base)})"
            return f"1/{self.parenthesize(base, PRECEDENCE['Pow'], strict=True)}^{self._exponent(-exp)}"
        return f"{self.parenthesize(base, PRECEDENCE['Pow'], strict=True)}^{self._exponent(exp)}"

    def _exponent(self, exp: sympy.Expr) -> str:
        text = str(self._print(exp))
        return text if (exp.is_Integer and exp >= 0) or exp.is_Symbol else f"({text})"

    def parenthesize(self, item: sympy.Basic, level: int, strict: bool = False) -> str:
        """As StrPrinter does, and a factor or base that prints with a leading minus too."""
        text = str(super().parenthesize(item, level, strict))
        if text.startswith("-") and level >= PRECEDENCE["Mul"]:
            return f"({text})"
        return text

    def _print_Rational(self, expr: sympy.Rational) -> str:
        return f"{expr.p}/{expr.q}"

    def _print_Float(self, expr: sympy.Float) -> str:
        return repr(float(expr))

    def _print_NumberSymbol(self, expr: sympy.NumberSymbol) -> str:
        return repr(float(expr))

    _print_Pi = _print_Exp1 = _print_EulerGamma = _print_Catalan = _print_GoldenRatio = _print_NumberSymbol
    _print_TribonacciConstant = _print_NumberSymbol

    def _print_NaN(self, expr: sympy.Basic) -> str:
        return str(self._settings["not_covered"])

    def _print_Infinity(self, expr: sympy.Basic) -> str:
        raise ValueError("Modelica has no infinity: an infinite bound must be left out")

    _print_NegativeInfinity = _print_Infinity

    def _print_Function(self, expr: sympy.Function) -> str:
        if isinstance(expr, AppliedUndef):
            name = expr.func.__name__
        elif expr.func.__name__ in self._functions:
            name = self._functions[expr.func.__name__]
        else:
            raise ValueError(f"no Modelica function for {expr.func.__name__}")
        return f"{name}({', '.join(self._print(a) for a in expr.args)})"

    def _print_Relational(self, expr: sympy.core.relational.Relational) -> str:
        op = {"==": "==", "!=": "<>", "<": "<", "<=": "<=", ">": ">", ">=": ">="}[expr.rel_op]
        return f"{self._print(expr.lhs)} {op} {self._print(expr.rhs)}"

    def _operand(self, item: sympy.Basic) -> str:
        text = str(self._print(item))
        return (
            text if item.is_Symbol or isinstance(item, (AppliedUndef, sympy.logic.boolalg.BooleanAtom)) else f"({text})"
        )

    def _print_And(self, expr: sympy.And) -> str:
        return " and ".join(self._operand(a) for a in expr.args)

    def _print_Or(self, expr: sympy.Or) -> str:
        return " or ".join(self._operand(a) for a in expr.args)

    def _print_Not(self, expr: sympy.Not) -> str:
        return f"not {self._operand(expr.args[0])}"

    def _print_BooleanTrue(self, expr: sympy.Basic) -> str:
        return "true"

    def _print_BooleanFalse(self, expr: sympy.Basic) -> str:
        return "false"

    def _print_Piecewise(self, expr: sympy.Piecewise) -> str:
        if expr.args[-1].cond != sympy.true:
            raise ValueError("a choice needs a last branch that always holds")
        parts = []
        for k, (value, cond) in enumerate(expr.args[:-1]):
            parts.append(f"{'if' if k == 0 else 'elseif'} {self._print(cond)} then {self._print(value)}")
        last = self._print(expr.args[-1].expr)
        return f"({' '.join(parts)} else {last})" if parts else str(last)


def modelica_code(expr: sympy.Basic, **settings: Any) -> str:
    """The Modelica text of ``expr``."""
    return str(ModelicaPrinter(settings).doprint(expr))
