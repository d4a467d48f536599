"""The LaTeX of an emitted formula, read back and compared with the formula it should be.

The text is read, not printed from the expression, so a wrong, truncated or garbled
formula fails.  :func:`read_latex` is a strict recursive-descent reader of the LaTeX
that formulas in the train's symbols are written in: sums and differences, products by
juxtaposition or ``\\cdot``, ``\\frac{..}{..}``, ``\\left( .. \\right)``,
``\\bigl( .. \\bigr)``, ``( .. )``, ``{ .. }``, powers ``^{..}`` (``^{-1}`` too) or
``^2``, decimal numbers, ``\\pi``, the functions ``\\log``, ``\\sin``, ``\\cos``,
``\\tan``, ``\\exp`` of a parenthesis, and the symbols.

Symbols are read under their display names, by this reader's own rule (not the
package's): the quantity is a leading Greek word (``eta``, ``zeta``, ``mu``, ``tau``,
``omega``, ...) not followed by a lower-case letter, or else the first letter; the rest
of the name, its leading underscore dropped, is the subscript, further underscores
written as commas (one subscript of several indices): ``rp1`` is ``r_{p1}``, ``eta_12``
``\\eta_{12}``, ``eta_C_1_2`` ``\\eta_{C,1,2}``; a letter or a Greek word alone stays
(``r``, ``\\mu``).  sympy's own spelling (``rp_{1}``) is read too, for the outputs
that still print with plain :func:`sympy.latex` (JSON ``latex`` fields, formula
modules), unless it is another symbol's display name.

A formula broken across the lines of an ``align*`` is read as one: ``&``, ``\\\\``,
``\\quad`` and ``\\qquad`` between tokens are layout, and a ``\\right.`` at the end
of a line must be followed by ``\\left.`` at the start of the next (the parenthesis
continues).  :func:`document_equations`, :func:`force_conditions` and
:func:`align_rows` take the numbered formulas, the loaded-force conditions and the
rows of an ``align*`` out of an emitted document.

Anything else (an unknown name or command, an unbalanced brace, text left over) raises
:class:`LatexError`.  (sympy's own LaTeX parser, lark backend, reads ``\\left(`` also as
``\\le ft(``, a symbol before a parenthesis also as a function call, and no
multi-character subscript, so it cannot read these formulas in general.)
"""

from __future__ import annotations

import random
import re
from collections.abc import Iterable

import sympy


class LatexError(ValueError):
    """The text is not a formula in the given symbols."""


_NUMBER = re.compile(r"\d+(?:\.\d+)?")
_DIGIT = re.compile(r"\d")

#: Greek words a symbol's name may start with (its quantity).
GREEK = (
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "zeta",
    "eta",
    "theta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "omicron",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "chi",
    "psi",
    "omega",
)
_QUANTITY = re.compile(r"(%s)(?![a-z])(.*)\Z" % "|".join(sorted(GREEK, key=len, reverse=True)), re.DOTALL)
#: Layout between the tokens of a formula broken over lines.
_LAYOUT = re.compile(r"\s+|&|\\\\|\\qquad(?![A-Za-z])|\\quad(?![A-Za-z])")
_FUNCTIONS = {"\\log": sympy.log, "\\sin": sympy.sin, "\\cos": sympy.cos, "\\tan": sympy.tan, "\\exp": sympy.exp}
#: Opening and closing delimiters of a parenthesis.
_PARENTHESES = (("\\left(", "\\right)"), ("\\bigl(", "\\bigr)"), ("\\Bigl(", "\\Bigr)"), ("(", ")"))


def display_latex(name: str) -> str:
    """The LaTeX of a symbol under its display name: ``rp1`` -> ``r_{p1}``, ``eta_C`` ->
    ``\\eta_{C}``, ``eta_C_1_2`` -> ``\\eta_{C,1,2}``, ``mu`` -> ``\\mu``, ``r`` -> ``r``."""
    function, _, argument = name.partition("_")
    if function in ("cos", "sin") and argument:  # a skew mesh's cos_gamma is cos(gamma)
        return f"\\{function}{{{display_latex(argument)}}}"
    match = _QUANTITY.match(name)
    quantity, rest = (f"\\{match.group(1)}", match.group(2)) if match else (name[:1], name[1:])
    rest = rest[1:] if rest.startswith("_") else rest
    return f"{quantity}_{{{rest.replace('_', ',')}}}" if rest else quantity


def _names(symbols: Iterable[sympy.Symbol]) -> list[tuple[str, sympy.Symbol]]:
    """(LaTeX, symbol) of every symbol, display names and sympy's spellings that are no
    other symbol's display name, longest first (``r_{p1}`` before ``r_{p}``)."""
    symbols = set(symbols)
    shown = {display_latex(s.name): s for s in symbols}
    if len(shown) != len(symbols):
        raise LatexError(f"two symbols share a display name: {sorted(map(str, symbols))}")
    names = dict(shown)
    for s in symbols:
        names.setdefault(sympy.latex(s), s)
    return sorted(names.items(), key=lambda p: -len(p[0]))


class _Reader:
    def __init__(self, text: str, symbols: Iterable[sympy.Symbol]):
        self.text, self.pos = text, 0
        self.names = _names(symbols)

    def fail(self, what: str) -> LatexError:
        return LatexError(f"{what} at {self.pos}: ...{self.text[self.pos : self.pos + 30]!r} in {self.text!r}")

    def _layout(self, pos: int) -> int:
        while True:
            match = _LAYOUT.match(self.text, pos)
            if match is None or match.end() == pos:
                return pos
            pos = match.end()

    def skip_space(self) -> None:
        """Skip white space and line-break layout; ``\\right.`` only with the ``\\left.``
        that reopens its parenthesis on the next line."""
        while True:
            self.pos = self._layout(self.pos)
            if not self.text.startswith("\\right.", self.pos):
                return
            after = self._layout(self.pos + len("\\right."))
            if not self.text.startswith("\\left.", after):
                return
            self.pos = after + len("\\left.")

    def at(self, literal: str) -> bool:
        self.skip_space()
        if not self.text.startswith(literal, self.pos):
            return False
        if literal[-1].isalpha():  # a command or name: not the start of a longer word
            end = self.pos + len(literal)
            if end < len(self.text) and (self.text[end].isalpha() or self.text[end] == "_"):
                return False
        return True

    def take(self, literal: str) -> None:
        if not self.at(literal):
            raise self.fail(f"expected {literal!r}")
        self.pos += len(literal)

    def done(self) -> bool:
        self.skip_space()
        return self.pos == len(self.text)

    def sum(self) -> sympy.Expr:
        if self.at("-"):
            self.take("-")
            value = -self.product()
        else:
            value = self.product()
        while True:
            if self.at("+"):
                self.take("+")
                value = value + self.product()
            elif self.at("-"):
                self.take("-")
                value = value - self.product()
            else:
                return value

    def product(self) -> sympy.Expr:
        value = self.power()
        while True:
            if self.at("\\cdot"):
                self.take("\\cdot")
                value = value * self.power()
            elif self.done() or any(self.at(stop) for stop in ("+", "-", "}", ")", "\\right", "\\bigr", "\\Bigr")):
                return value
            else:
                value = value * self.power()

    def power(self) -> sympy.Expr:
        base = self.atom()
        if self.at("^"):
            self.take("^")
            if self.at("{"):
                return base ** self.group()
            match = _DIGIT.match(self.text, self.pos)
            if match is None:
                raise self.fail("expected an exponent")
            self.pos = match.end()
            return base ** sympy.Integer(match.group())
        return base

    def group(self) -> sympy.Expr:
        self.take("{")
        value = self.sum()
        self.take("}")
        return value

    def parenthesis(self) -> sympy.Expr | None:
        """A parenthesised sum, if one starts here."""
        for opening, closing in _PARENTHESES:
            if self.at(opening):
                self.take(opening)
                value = self.sum()
                self.take(closing)
                return value
        return None

    def atom(self) -> sympy.Expr:
        if self.at("\\frac"):
            self.take("\\frac")
            numerator = self.group()
            return numerator / self.group()
        for command, function in _FUNCTIONS.items():
            if self.at(command):
                # \log{\left(x \right)} (sympy) or \log\left(x\right) (a broken line).
                self.take(command)
                argument = self.group() if self.at("{") else self.parenthesis()
                if argument is None:
                    raise self.fail(f"expected the argument of {command}")
                return function(argument)
        if self.at("\\pi"):
            self.take("\\pi")
            return sympy.pi
        value = self.parenthesis()
        if value is not None:
            return value
        if self.at("{"):
            return self.group()
        match = _NUMBER.match(self.text, self.pos)
        if match:
            self.pos = match.end()
            return sympy.Rational(match.group())
        for name, symbol in self.names:
            if self.at(name):
                self.pos += len(name)
                return symbol
        raise self.fail("expected a number, a symbol, \\frac or a parenthesis")


def read_latex(text: str, symbols: Iterable[sympy.Symbol]) -> sympy.Expr:
    """The formula ``text`` (LaTeX, on one line or broken over the lines of an
    ``align*``) in ``symbols``, read back into a sympy expression."""
    reader = _Reader(text, symbols)
    value = reader.sum()
    if not reader.done():
        raise reader.fail("unexpected text")
    return value


_ALIGN = re.compile(r"\\begin\{align\*\}\n(.*?)\n\\end\{align\*\}", re.DOTALL)


def align_rows(body: str) -> list[tuple[str, str]]:
    """(left side, right side) of each equation of an ``align*`` body; a right side
    broken over lines is one text with its layout (``\\\\``, ``&\\quad``) kept.  A row
    without a left side (``& ...``) continues the equation before it, or starts one with
    an empty left side."""
    rows: list[tuple[str, str]] = []
    for line in (row.strip() for row in body.split("\\\\\n")):
        if line.startswith("&"):
            if rows:
                rows[-1] = (rows[-1][0], f"{rows[-1][1]} \\\\ {line}")
            else:
                rows.append(("", line[1:]))
            continue
        lhs, sep, rhs = line.partition(" &= ")
        if not sep:
            raise LatexError(f"not an equation row: {line!r}")
        rows.append((lhs, rhs))
    return rows


def document_equations(text: str, name: str = "\\eta") -> dict[int, str]:
    """Each numbered formula ``name = ...`` of an emitted document by its tag, as one text
    :func:`read_latex` reads: a one-line ``equation`` as written; a broken ``align*``
    (``name_{(n)} = N_{(n)} / D_{(n)}``, then the rows of N and D) with N and D put back
    into the fraction, their line breaks kept."""
    out: dict[int, str] = {}
    one_line = re.escape(f"\\begin{{equation}}\n{name} = ") + r"(.*)\n\\tag\{(\d+)\}\n\\end\{equation\}"
    for body, number in re.findall(one_line, text):
        if int(number) in out:
            raise LatexError(f"equation ({number}) written twice")
        out[int(number)] = body
    for block in _ALIGN.findall(text):
        rows = align_rows(block)
        match = re.fullmatch(re.escape(f"{name}_{{(") + r"(\d+)\)\}", rows[0][0])
        if match is None:
            continue
        number = int(match.group(1))
        formula, tags = re.subn(r" \\tag\{(\d+)\}", "", rows[0][1])
        if tags != 1 or f"\\tag{{{number}}}" not in rows[0][1] or number in out:
            raise LatexError(f"equation ({number}) not tagged ({number}) once, or written twice")
        label = f"_{{({number})}}"
        parts = {lhs: rhs for lhs, rhs in rows[1:]}
        if set(parts) - {f"N{label}", f"D{label}"}:
            raise LatexError(f"unexpected rows in equation ({number}): {sorted(parts)}")
        for part, rhs in parts.items():
            formula = formula.replace(part, f"{{{rhs}}}")
        out[number] = formula
    return out


def force_conditions(section: str) -> list[tuple[str, str]]:
    """(force, ``<`` or ``>``) of every "Holds where ...:" inequality ``force > 0`` in a
    section of an emitted document, on one line or broken over an ``align*``."""
    pattern = (
        r"Holds where [^\n]*:\n(?:\\begin\{equation\*\}\n(.*?) ([<>]) 0\n\\end\{equation\*\}"
        r"|\\begin\{align\*\}\n(.*?) ([<>]) 0\n\\end\{align\*\})"
    )
    out = []
    for line, relation, broken, broken_relation in re.findall(pattern, section, flags=re.DOTALL):
        if line:
            out.append((line, relation))
        else:
            rows = align_rows(broken)
            if len(rows) != 1 or rows[0][0]:
                raise LatexError(f"not one inequality: {broken!r}")
            out.append((rows[0][1], broken_relation))
    return out


def same_rational_function(a: sympy.Expr, b: sympy.Expr) -> bool:
    """a = b as rational functions: numer(a) denom(b) - numer(b) denom(a) expands to 0."""
    na, da = sympy.fraction(sympy.together(a))
    nb, db = sympy.fraction(sympy.together(b))
    return bool(sympy.expand(na * db - nb * da) == 0)


def equal_at_random_points(a: sympy.Expr, b: sympy.Expr, points: int = 3, seed: int = 0) -> bool:
    """a = b exactly at ``points`` random rational points where b is defined."""
    free = sorted(sympy.sympify(a).free_symbols | sympy.sympify(b).free_symbols, key=str)
    rng = random.Random(seed)
    checked = 0
    for _ in range(20 * points):
        point = {s: sympy.Rational(rng.randint(1, 997), rng.randint(1, 97)) for s in free}
        want = sympy.sympify(b).xreplace(point)
        if not want.is_finite:
            continue
        if sympy.sympify(a).xreplace(point) != want:
            return False
        checked += 1
        if checked == points:
            return True
    raise ValueError("no random point where the expected formula is defined")


def with_angle_symbols(expr: sympy.Expr, train: object) -> sympy.Expr:
    """``expr`` with cos(gamma) and sin(gamma) written as the symbols a skew mesh defines
    for them (``cos_gamma``), so that a formula read back compares with the derived one."""
    table = {
        d.expression: d.symbol
        for d in getattr(train, "definitions", ())
        if isinstance(d.expression, (sympy.cos, sympy.sin)) and d.expression.free_symbols
    }
    return sympy.sympify(expr).xreplace(table) if table else expr
