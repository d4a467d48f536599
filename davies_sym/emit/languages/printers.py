"""sympy's code printers, set up for the generated files, and the names they write.

Every printer prints calls of the program's own routines (undefined sympy functions) as
``name(arguments)`` and numbers to 17 significant digits, so a double survives the trip
through the text.  sympy's Rust printer needs four repairs: it writes integers as
integers (``2/x`` does not compile in Rust, where every number here is an ``f64``); the
casts it wraps around the factors of a product with a fraction lose the parentheses of a
sum (``(1/2)*(a - b)`` came out as ``(1_f64/2.0)*a - b``); it writes ``NAN`` and
``INFINITY`` without their type; and it refuses calls of undefined functions.  Every
number being printed as an ``f64`` already, the repaired printer prints sums, products
and relations as the generic code printer does, without casts.
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


class RustPrinter(RustCodePrinter):  # type: ignore[misc]  # sympy has no type information
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
        return str(super()._print_Pow(expr))

    def _print_Relational(self, expr: sympy.core.relational.Relational) -> str:
        if expr.lhs.is_Symbol and expr.lhs.is_integer and expr.rhs.is_Integer:
            return f"{self._print(expr.lhs)} {expr.rel_op} {int(expr.rhs)}"
        return f"{self._print(expr.lhs)} {expr.rel_op} {self._print(expr.rhs)}"

    def _print_Function(self, expr: sympy.Function) -> str:
        if isinstance(expr, AppliedUndef):
            return f"{expr.func.__name__}({', '.join(self._print(a) for a in expr.args)})"
        return str(super()._print_Function(expr))

    def _print_NaN(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::NAN"

    def _print_Infinity(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::INFINITY"

    def _print_NegativeInfinity(self, expr: sympy.Basic, _type: bool = False) -> str:
        return "f64::NEG_INFINITY"


def c_printer() -> CodePrinter:
    return C99CodePrinter(dict(_SETTINGS))


def julia_printer() -> CodePrinter:
    return JuliaCodePrinter({**_SETTINGS, "inline": False})


def octave_printer() -> CodePrinter:
    return OctaveCodePrinter({**_SETTINGS, "inline": False})


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
