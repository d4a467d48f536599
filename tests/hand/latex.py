"""The LaTeX of an emitted formula, read back and compared with the formula it should be.

The text is read, not printed from the expression, so a wrong, truncated or garbled
formula fails.  :func:`read_latex` is a strict recursive-descent reader of the LaTeX
that formulas in the train's symbols are written in: sums and differences, products by
juxtaposition or ``\\cdot``, ``\\frac{..}{..}``, ``\\left( .. \\right)``, ``( .. )``,
``{ .. }``, powers ``^{..}`` or ``^2``, decimal numbers, and the symbols under their
LaTeX names (``\\eta_{12}``, ``r_{1}``, ``rs_{1}``, ``rpl``).  Anything else (an
unknown name or command, an unbalanced brace, text left over) raises
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


class _Reader:
    def __init__(self, text: str, symbols: Iterable[sympy.Symbol]):
        self.text, self.pos = text, 0
        # Longest names first: rr_{1} before rr, \eta_{12} is not a prefix of \eta_{1}x.
        self.names = sorted(((sympy.latex(s), s) for s in set(symbols)), key=lambda p: -len(p[0]))

    def fail(self, what: str) -> LatexError:
        return LatexError(f"{what} at {self.pos}: ...{self.text[self.pos:self.pos + 30]!r} in {self.text!r}")

    def skip_space(self) -> None:
        while self.pos < len(self.text) and self.text[self.pos].isspace():
            self.pos += 1

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
            elif self.done() or any(self.at(stop) for stop in ("+", "-", "}", ")", "\\right")):
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

    def atom(self) -> sympy.Expr:
        if self.at("\\frac"):
            self.take("\\frac")
            numerator = self.group()
            return numerator / self.group()
        if self.at("\\left("):
            self.take("\\left(")
            value = self.sum()
            self.take("\\right)")
            return value
        if self.at("("):
            self.take("(")
            value = self.sum()
            self.take(")")
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
    """The formula ``text`` (LaTeX) in ``symbols``, read back into a sympy expression."""
    reader = _Reader(text, symbols)
    value = reader.sum()
    if not reader.done():
        raise reader.fail("unexpected text")
    return value


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
