"""Expressions written by users, read by a small grammar and never evaluated as Python.

The grammar: numbers (integers, decimals, exponents), names, ``+ - * / **``,
parentheses, the functions ``sqrt``, ``sin``, ``cos``, ``tan`` and the constant ``pi``::

    expr    := expr ('+' | '-') term | term
    term    := term ('*' | '/') factor | factor
    factor  := ('+' | '-') factor | power
    power   := atom ['**' factor]          (the exponent a small rational constant)
    atom    := number | name | 'pi' | function '(' expr ')' | '(' expr ')'

Python's own tokenizer and parser (`ast.parse`) split the text; only the node
kinds of this grammar are accepted and each is turned into a sympy object directly,
so no attribute, subscript, call of anything else, lambda, string or comprehension can
reach the interpreter.  Sizes are bounded before anything is computed: the text's
length, the nesting depth, the exponents and the digits of every number, so an
expression bomb (``9**9**9``, ``r**100000``) is refused at once.
"""

from __future__ import annotations

import ast
import builtins
import keyword
import re
from collections.abc import Callable, Sequence
from fractions import Fraction

import sympy

from davies_sym.errors import InputError, Problem, shortened

#: Longest expression accepted (characters).
MAX_LENGTH = 500
#: Deepest nesting of parentheses and operators accepted.
MAX_DEPTH = 40
#: Largest exponent accepted in ``a ** n`` (absolute value of its numerator).
MAX_EXPONENT = 64
#: Largest number accepted (bits of a numerator or denominator).
MAX_BITS = 1024

_FUNCTIONS: dict[str, Callable[[sympy.Expr], sympy.Expr]] = {
    "sqrt": sympy.sqrt,
    "sin": sympy.sin,
    "cos": sympy.cos,
    "tan": sympy.tan,
}
_CONSTANTS: dict[str, sympy.Expr] = {"pi": sympy.pi}
#: A decimal literal with an exponent small enough to expand (Fraction would expand any).
_DECIMAL = re.compile(r"(\d+(\.\d*)?|\.\d+)([eE][-+]?\d{1,3})?")
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
#: Names that read as infinities or not-a-number (sympy's ``oo``, ``zoo``, ``nan``; numpy's ``inf``).
NON_FINITE_NAMES = frozenset({"oo", "zoo", "nan", "inf"})
#: The public names a generated formula module binds at module level and in its entry
#: points (tests/test_reserved_names.py keeps this equal to what the generator writes):
#: a symbol of one of these names would shadow or be shadowed by the module's own.
FORMULA_MODULE_NAMES = frozenset(
    {
        *("Any", "Array", "ArrayLike", "Callable", "Final", "NDArray", "TypedDict", "annotations", "cast"),
        *("CONDITIONS", "DEPENDENT", "EXCLUDED", "IGNORED", "INPUTS", "LOSSY", "OUTPUT", "PARAMETERS", "SENSITIVE"),
        *("PORTS", "REGIONS", "RELATIONS", "SPEEDS", "VARIANTS"),
        *("DesignError", "DesignWarning", "Parameter", "Region", "Variant"),
        *("efficiency", "losses", "region", "sensitivity", "speed_ratio", "speeds", "torques", "values", "variant"),
        *("wrt", "xp"),
    }
)
#: The operating point of the formulas: input torque and speed, and the load of a train
#: driven on several shafts.
OPERATING_NAMES = {"tau_in": "input torque", "omega_in": "input speed", "tau_out": "load torque"}
#: Names a symbol may not take: Python keywords and built-ins (a generated formula
#: module uses them), the grammar's functions and constants, the non-finite names and
#: the names the generated modules define for themselves.
RESERVED_NAMES = frozenset(
    [
        *keyword.kwlist,
        *keyword.softkwlist,
        *dir(builtins),
        *_FUNCTIONS,
        *_CONSTANTS,
        *NON_FINITE_NAMES,
        "np",
        "numpy",
        "math",
        "warnings",
        "input",
        "errors",
        "state",
        *OPERATING_NAMES,
        *FORMULA_MODULE_NAMES,
    ]
)


class ExpressionError(ValueError):
    """Text that is not an expression of the grammar (the message says why)."""


def check_name(name: str) -> str | None:
    """Why ``name`` cannot be a symbol, or None when it can."""
    if not _NAME.fullmatch(name):
        return (
            f"{shortened(name)} is not a symbol name: use ASCII letters, digits and underscores, starting with a letter"
        )
    if name in NON_FINITE_NAMES or name.lower() in {"nan", "inf", "infinity"}:
        return f"{name!r} reads as a value that is not finite; write a finite number, or name the symbol {name}_1"
    if name in OPERATING_NAMES:
        return f"{name!r} is the {OPERATING_NAMES[name]} of the formulas; choose another name, e.g. {name}_1"
    if name in RESERVED_NAMES:
        return f"{name!r} is a reserved name (a Python or formula-module name); choose another, e.g. {name}_1"
    return None


def parse_expression(text: str, symbol: Callable[[str], sympy.Symbol] | None = None) -> sympy.Expr:
    """``text`` as an exact sympy expression; ``symbol(name)`` gives the symbol of a name.

    Without ``symbol``, names other than ``pi`` are refused (a plain number is wanted).
    Decimals are exact (``0.99`` is 99/100).  Raises `ExpressionError`.
    """
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"{shortened(text)} is too long for an expression (at most {MAX_LENGTH} characters)")
    if not text.strip():
        raise ExpressionError("expected a number or an expression, got an empty text")
    if _nesting(text) > MAX_DEPTH:
        raise ExpressionError(f"{shortened(text)} is nested too deeply (at most {MAX_DEPTH} levels)")
    if "#" in text:
        # Python's parser would drop the rest as a comment; in YAML a comment needs a space before '#'.
        raise ExpressionError(
            f"{shortened(text)}: '#' is not part of an expression (a YAML comment needs a space before it)"
        )
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        words = [w for w in _NAME.findall(text) if keyword.iskeyword(w)]
        hint = f" ({words[0]!r} is a Python keyword, not a name)" if words else ""
        raise ExpressionError(
            f"cannot read {shortened(text)} as an expression{hint}: write numbers, names, "
            "+ - * / **, parentheses, sqrt, sin, cos, tan and pi"
        ) from None
    try:
        expr = _Builder(text, symbol).build(tree.body, 0)
    except RecursionError:  # pragma: no cover - the depth bound comes first
        raise ExpressionError(f"{shortened(text)} is nested too deeply") from None
    if expr.has(sympy.zoo, sympy.oo, -sympy.oo, sympy.nan):
        raise ExpressionError(f"{shortened(text)} is not finite (a division by zero?)")
    if expr.is_number and expr.is_real is False:
        raise ExpressionError(f"{shortened(text)} is not a real number")
    return expr


def _nesting(text: str) -> int:
    """Deepest bracket nesting, counted on the characters (before any parsing)."""
    depth = deepest = 0
    for ch in text:
        if ch in "([{":
            depth += 1
            deepest = max(deepest, depth)
        elif ch in ")]}":
            depth -= 1
    return deepest


class _Builder:
    """Turns the accepted node kinds of one parsed text into sympy objects."""

    def __init__(self, text: str, symbol: Callable[[str], sympy.Symbol] | None):
        self.text = text
        self.source = text.strip()
        self.symbol = symbol

    def refuse(self, what: str) -> ExpressionError:
        return ExpressionError(
            f"{shortened(self.text)}: {what} is not allowed in an expression (write numbers, "
            "names, + - * / **, parentheses, sqrt, sin, cos, tan and pi)"
        )

    def build(self, node: ast.expr, depth: int) -> sympy.Expr:
        if depth > MAX_DEPTH:
            raise ExpressionError(f"{shortened(self.text)} is nested too deeply (at most {MAX_DEPTH} levels)")
        if isinstance(node, ast.Constant):
            return self.number(node.value, ast.get_source_segment(self.source, node) or "")
        if isinstance(node, ast.Name):
            return self.name(node.id)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            operand = self.build(node.operand, depth + 1)
            return -operand if isinstance(node.op, ast.USub) else operand
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
            return self.power(self.build(node.left, depth + 1), self.build(node.right, depth + 1))
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
            left, right = self.build(node.left, depth + 1), self.build(node.right, depth + 1)
            if isinstance(node.op, ast.Add):
                return self.bounded(left + right)
            if isinstance(node.op, ast.Sub):
                return self.bounded(left - right)
            if isinstance(node.op, ast.Mult):
                return self.bounded(left * right)
            if right == 0:
                raise ExpressionError(f"{shortened(self.text)} divides by zero")
            return self.bounded(left / right)
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in _FUNCTIONS
            and len(node.args) == 1
            and not node.keywords
            and not isinstance(node.args[0], ast.Starred)
        ):
            return self.bounded(_FUNCTIONS[node.func.id](self.build(node.args[0], depth + 1)))
        raise self.refuse(_describe(node))

    def number(self, value: object, written: str) -> sympy.Expr:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.refuse(f"the constant {shortened(repr(value), 30)}")
        if isinstance(value, float):
            # The decimal as written, exactly (0.99 is 99/100, 1e-400 is not 0).
            digits = written.replace("_", "")
            if not _DECIMAL.fullmatch(digits):
                raise ExpressionError(f"{shortened(self.text)}: cannot read the number {shortened(written, 30)}")
            frac = Fraction(digits)
            return self.bounded(sympy.Rational(frac.numerator, frac.denominator))
        if value.bit_length() > MAX_BITS:
            raise ExpressionError(f"{shortened(self.text)}: a number has more than {MAX_BITS} bits")
        return sympy.Integer(value)

    def name(self, name: str) -> sympy.Expr:
        if name in _CONSTANTS:
            return _CONSTANTS[name]
        if name in _FUNCTIONS:
            raise self.refuse(f"the function name {name!r} without an argument")
        if self.symbol is None:
            raise ExpressionError(f"{shortened(self.text)} is not a number (it names {name!r})")
        why = check_name(name)
        if why is not None:
            raise ExpressionError(why)
        return self.symbol(name)

    def power(self, base: sympy.Expr, exponent: sympy.Expr) -> sympy.Expr:
        if not exponent.is_Rational:
            raise ExpressionError(
                f"{shortened(self.text)}: an exponent must be a rational number, not {shortened(str(exponent), 30)}"
            )
        if abs(exponent.p) > MAX_EXPONENT or exponent.q > MAX_EXPONENT:
            raise ExpressionError(
                f"{shortened(self.text)}: the exponent {exponent} is too large (at most {MAX_EXPONENT})"
            )
        if base == 0 and exponent < 0:
            raise ExpressionError(f"{shortened(self.text)} divides by zero")
        return self.bounded(base**exponent)

    def bounded(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` unless a number in it or a power of it outgrew the bounds (nested powers)."""
        for atom in expr.atoms(sympy.Rational):
            if max(abs(atom.p).bit_length(), atom.q.bit_length()) > MAX_BITS:
                raise ExpressionError(f"{shortened(self.text)}: a number has more than {MAX_BITS} bits")
        for pw in expr.atoms(sympy.Pow):
            e = pw.exp
            if e.is_Rational and (abs(e.p) > MAX_EXPONENT or e.q > MAX_EXPONENT):
                raise ExpressionError(f"{shortened(self.text)}: the exponent {e} is too large (at most {MAX_EXPONENT})")
        return expr


def _describe(node: ast.AST) -> str:
    if isinstance(node, ast.BinOp):
        if isinstance(node.op, ast.BitXor):
            return "^ (write ** for a power)"
        return f"the operator {type(node.op).__name__}"
    kinds = {
        ast.Attribute: "an attribute (.)",
        ast.Subscript: "a subscript ([])",
        ast.Lambda: "a lambda",
        ast.IfExp: "a conditional (if/else)",
        ast.Call: "a call of anything but sqrt, sin, cos, tan",
        ast.Compare: "a comparison",
        ast.BoolOp: "and/or",
        ast.JoinedStr: "a string",
    }
    for kind, text in kinds.items():
        if isinstance(node, kind):
            return text
    return f"a {type(node).__name__.lower()}"


def assignments(pairs: Sequence[str], option: str, source: str | None) -> dict[str, sympy.Expr]:
    """``NAME=VALUE`` pairs of the command line as exact numbers by name; every malformed
    pair is reported at once (an `InputError` naming ``option``)."""
    out: dict[str, sympy.Expr] = {}
    problems = []
    for pair in pairs:
        name, sep, text = pair.partition("=")
        name = name.strip()
        if not sep or not name:
            problems.append(Problem(option, f"expected NAME=VALUE, got {shortened(pair)}"))
            continue
        try:
            out[name] = parse_expression(text)
        except ExpressionError as exc:
            problems.append(Problem(option, f"{name}: {exc}"))
    if problems:
        raise InputError(problems, source)
    return out
