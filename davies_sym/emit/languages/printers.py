"""sympy's code printers, set up for the generated files, and the names they write.

Every printer prints calls of the program's own routines (undefined sympy functions) as
``name(arguments)`` and numbers to 17 significant digits, so a double survives the trip
through the text.  A file needs nothing it does not declare: pi is the language's own
(C's ``M_PI``, which the C file defines where strict C99's math.h leaves it out, and no
other math.h macro: sqrt(2), pi/2 or log(2) are written as such, not as ``M_SQRT2``,
``M_PI_2`` or ``M_LN2``; Rust's ``std::f64::consts::PI`` by its path, as no ``use`` is
written; Julia's and Octave's ``pi``), and every other number symbol (e, Euler's gamma,
the golden ratio) a decimal, never a ``const`` declaration in front of the statement
(Julia refuses one inside a function).  Octave's printer writes ``~=`` for ``!=``, which
MATLAB does not read.

sympy's Rust printer needs six repairs: it writes integers as integers (``2/x`` does not
compile in Rust, where every number here is an ``f64``); the casts it wraps around the
factors of a product with a fraction lose the parentheses of a sum (``(1/2)*(a - b)``
came out as ``(1_f64/2.0)*a - b``); it writes ``NAN``, ``INFINITY`` and ``PI`` without
their type or path; it refuses calls of undefined functions; a number whose method it
calls must be typed (``2.0.ln()`` does not compile: ``2_f64.ln()``); and it rounds an
integer's root to 15 digits (sqrt(2) came out as ``1.4142135623731``: ``2_f64.sqrt()``).
Every number being printed as an ``f64`` already, the repaired printer prints sums,
products and relations as the generic code printer does, without casts.
"""

from __future__ import annotations

from typing import Any

import sympy
from sympy.core.function import AppliedUndef
from sympy.printing.c import C99CodePrinter
from sympy.printing.codeprinter import CodePrinter
from sympy.printing.julia import JuliaCodePrinter
from sympy.printing.octave import OctaveCodePrinter
from sympy.printing.rust import RustCodePrinter

_SETTINGS: dict[str, Any] = {"allow_unknown_functions": True, "precision": 17}


class _Decimals:
    """Every number symbol but pi (e, Euler's gamma, the golden ratio ...) as a decimal."""

    def _print_NumberSymbol(self, expr: sympy.NumberSymbol, **kwargs: Any) -> str:
        digits = _SETTINGS["precision"]
        return str(self._print(sympy.Float(expr.evalf(digits), digits), **kwargs))  # type: ignore[attr-defined]

    _print_Exp1 = _print_EulerGamma = _print_Catalan = _print_GoldenRatio = _print_NumberSymbol
    _print_TribonacciConstant = _print_NumberSymbol


class RustPrinter(_Decimals, RustCodePrinter):  # type: ignore[misc]  # sympy has no type information
    """Rust with every number an ``f64`` but integer exponents (``powi(2)``) and the port
    (an ``i32``, compared with integers)."""

    def _print_Integer(self, expr: sympy.Integer, _type: bool = False) -> str:
        return f"{int(expr)}.0"

    def _print_Mul(self, expr: sympy.Mul) -> str:
        return str(CodePrinter._print_Mul(self, expr))

    def _print_Add(self, expr: sympy.Add, order: str | None = None) -> str:
        return str(CodePrinter._print_Add(self, expr, order))

    def _print_Pow(self, expr: sympy.Pow) -> str:
        if expr.exp.is_Integer and expr.exp != -1:
            return f"{self._print_caller_var(expr.base)}.powi({int(expr.exp)})"
        # sympy's own turns an integer base into a 15-digit Float first (sqrt(2) came
        # out as 1.4142135623731); the method call on the typed number is exact.
        return str(self._print_Function(expr))

    def _print_caller_var(self, expr: sympy.Basic) -> str:
        """The receiver of a method call: a number typed, as ``2.0.sqrt()`` does not
        compile, and in parentheses where it has a sign or an operator."""
        if expr.is_Number or (isinstance(expr, sympy.NumberSymbol) and expr is not sympy.pi):
            digits = _SETTINGS["precision"]
            value = sympy.Rational(expr) if expr.is_Rational else sympy.Float(expr.evalf(digits), digits)
            if value.is_Integer:
                text = f"{int(value)}_f64"
            elif value.is_Rational:
                text = f"{value.p}_f64/{value.q}.0"
            else:
                text = f"{RustCodePrinter._print_Float(self, value)}_f64"
            return text if value.is_Integer and value >= 0 else f"({text})"
        return str(super()._print_caller_var(expr))

    def _print_Relational(self, expr: sympy.core.relational.Relational) -> str:
        if expr.lhs.is_Symbol and expr.lhs.is_integer and expr.rhs.is_Integer:
            return f"{self._print(expr.lhs)} {expr.rel_op} {int(expr.rhs)}"
        return f"{self._print(expr.lhs)} {expr.rel_op} {self._print(expr.rhs)}"

    def _print_Function(self, expr: sympy.Function) -> str:
        if isinstance(expr, AppliedUndef):
            return f"{expr.func.__name__}({', '.join(self._print(a) for a in expr.args)})"
        return str(super()._print_Function(expr))

    def _print_Pi(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "std::f64::consts::PI"

    def _print_NaN(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::NAN"

    def _print_Infinity(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::INFINITY"

    def _print_NegativeInfinity(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::NEG_INFINITY"


class CPrinter(_Decimals, C99CodePrinter):  # type: ignore[misc]
    """C99 with pi the only math.h macro (``M_PI``: the C file defines it where math.h does not)."""

    def _print_Pi(self, expr: sympy.Basic) -> str:
        return "M_PI"


class JuliaPrinter(_Decimals, JuliaCodePrinter):  # type: ignore[misc]
    """Julia with pi as Base's ``pi``, also where the printer is not inline (it writes
    ``if`` statements for choices)."""

    def _print_Pi(self, expr: sympy.Basic) -> str:
        return "pi"


class OctavePrinter(_Decimals, OctaveCodePrinter):  # type: ignore[misc]
    """Octave in the syntax MATLAB shares: ``~=`` for ``!=``."""

    def _print_Relational(self, expr: sympy.core.relational.Relational) -> str:
        op = "~=" if expr.rel_op == "!=" else expr.rel_op
        return f"{self._print(expr.lhs)} {op} {self._print(expr.rhs)}"


def c_printer() -> CodePrinter:
    return CPrinter({**_SETTINGS, "math_macros": {}})


def julia_printer() -> CodePrinter:
    return JuliaPrinter({**_SETTINGS, "inline": False})


def octave_printer() -> CodePrinter:
    return OctavePrinter({**_SETTINGS, "inline": False})


def rust_printer() -> CodePrinter:
    return RustPrinter({"precision": 17, "inline": True})


def printed_names(printer: CodePrinter) -> frozenset[str]:
    """The function names the printer may write (``sqrt``, ``fabs``, ``pow`` ...): a
    parameter of that name would hide them."""
    names: set[str] = set()
    for value in getattr(printer, "known_functions", {}).values():
        for item in [value] if isinstance(value, str) else value:
            name = item if isinstance(item, str) else item[1]
            names.add(name.split("(")[0].split(".")[0])
    return frozenset(n for n in names if n.isidentifier())
