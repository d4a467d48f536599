"""Displayed formulas broken into lines that fit the page of the LaTeX documents.

A formula whose LaTeX fits `LINE_WIDTH` stays one ``equation``; a longer one
becomes an ``align*`` whose continuation lines start ``&\\quad + ...`` (a sum broken
between its terms) or ``&\\quad \\cdot ...`` (a term too wide alone, broken between its
factors).  A parenthesised sum broken inside a product closes every line with
``\\right.`` and opens the next with ``\\left.``, so each line is a balanced cell.  An
efficiency N/D too wide for one line is written ``\\eta_{(n)} = N_{(n)} / D_{(n)}`` with
N and D below it (Laus prints his long formulas the same way).  Only ``amsmath`` is
needed (``align*`` with ``\\tag``).

The width of a line is estimated, not measured: `estimate_width` adds up the
typical width in points of each typeset glyph of 11 pt Computer Modern math (lower-case
letters 5.5 pt, capitals 8 pt, Greek letters 6.5 pt, digits 5.5 pt, binary operators
with their spacing 12.2 pt, relations 14 pt, ``\\cdot`` 7.2 pt), subscripts, superscripts
and the parts of a fraction inside a fraction at 75 %, a fraction as its wider part.
Measured against pdflatex it is within about 10 % of the typeset width; the line budget
leaves room for that, and tests/test_latex_compiles.py compiles every document.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import sympy

from davies_sym.topology.symbol_display import latex

#: Text width of the documents: A4 (597.5 pt) less two 2 cm margins (11pt article, geometry margin=2cm).
TEXT_WIDTH = 483.7
#: Budget of one line's formula after its left side and ``=`` or ``\quad +``: the text
#: width less the left column of the alignment (``N_{(12)} =``, about 40 pt) and the
#: estimate's uncertainty.
LINE_WIDTH = TEXT_WIDTH - 64.0
#: Width of one ``\quad`` of indentation (1 em at 11 pt).
QUAD = 11.0

# Estimated widths in points of the glyphs and spaces of display math at 11 pt.
_LOWER, _UPPER, _GREEK, _DIGIT, _BINARY, _RELATION, _DOT = 5.5, 8.0, 6.5, 5.5, 12.2, 14.0, 7.2
_SCRIPT = 0.75
_SPACES = {r"\quad": QUAD, r"\qquad": 2 * QUAD, r"\,": 1.8, r"\;": 3.1, r"\:": 2.4, r"\!": -1.8}
_BINARIES = {"+", "-", r"\pm", r"\times"}
_RELATIONS = {"=", "<", ">", r"\le", r"\ge", r"\leq", r"\geq", r"\neq"}
_OPERATORS = {r"\log", r"\sin", r"\cos", r"\tan", r"\exp", r"\ln", r"\sinh", r"\cosh", r"\tanh"}
_TOKEN = re.compile(r"\\[A-Za-z]+\*?|\\.|[{}^_]|\d|\S")

#: Functions of one argument whose parenthesis may be broken across lines.
_FUNCTIONS = {sympy.log: r"\log", sympy.sin: r"\sin", sympy.cos: r"\cos", sympy.tan: r"\tan", sympy.exp: r"\exp"}

#: A line of a broken formula: (indentation in quads, LaTeX of the line).
Line = tuple[int, str]


class _Widths:
    """Recursive reader of LaTeX tokens that adds up their estimated widths."""

    def __init__(self, tex: str) -> None:
        self.tokens = _TOKEN.findall(tex)
        self.pos = 0

    def run(self, scale: float, depth: int, stop: str | None = None) -> float:
        """Width of the tokens up to ``stop`` (a closing brace) or the end."""
        total = 0.0
        while self.pos < len(self.tokens):
            token = self.tokens[self.pos]
            if token == stop:
                self.pos += 1
                return total
            self.pos += 1
            total += self.item(token, scale, depth)
        return total

    def argument(self, scale: float, depth: int) -> float:
        """Width of one argument: a braced group or a single token."""
        if self.pos >= len(self.tokens):
            return 0.0
        token = self.tokens[self.pos]
        self.pos += 1
        return self.run(scale, depth, "}") if token == "{" else self.item(token, scale, depth)

    def item(self, token: str, scale: float, depth: int) -> float:
        """Width of one token (with the arguments it takes)."""
        # Script and fraction styles have no space around operators.
        spaced = scale == 1.0
        if token == "{":
            return self.run(scale, depth, "}")
        if token in ("^", "_"):
            return self.argument(scale * _SCRIPT, depth)
        if token in (r"\frac", r"\dfrac", r"\tfrac"):
            inner = scale if depth == 0 else scale * _SCRIPT
            return max(self.argument(inner, depth + 1), self.argument(inner, depth + 1)) + 2.0
        if token in (r"\left", r"\right", r"\bigl", r"\bigr", r"\Bigl", r"\Bigr", r"\big", r"\Big"):
            delimiter = self.tokens[self.pos] if self.pos < len(self.tokens) else "."
            self.pos += 1
            return 0.0 if delimiter == "." else 6.5 * scale
        if token in _SPACES:
            return _SPACES[token]
        if token in _BINARIES:
            return _BINARY if spaced else 7.8 * scale
        if token in _RELATIONS:
            return _RELATION if spaced else 7.8 * scale
        if token == r"\cdot":
            return _DOT if spaced else 2.8 * scale
        if token in _OPERATORS:
            return (5.0 * (len(token) - 1) + 1.8) * scale
        if token in ("&", r"\\", r"\tag", r"\notag", r"\nonumber"):
            return 0.0
        if token.isdigit():
            return _DIGIT * scale
        if token in ("(", ")", "[", "]", "|"):
            return 4.3 * scale
        if token in (",", ";", "."):
            return 3.0 * scale + (1.8 if spaced else 0.0)
        if token.isupper():
            return _UPPER * scale
        return (_GREEK if token.startswith("\\") else _LOWER) * scale


def estimate_width(tex: str) -> float:
    """Estimated typeset width in points of ``tex`` (display math, 11 pt)."""
    return _Widths(tex).run(1.0, 0)


def fits(tex: str, width: float = LINE_WIDTH) -> bool:
    """Whether ``tex`` is estimated to fit ``width`` points."""
    return estimate_width(tex) <= width


def _negative(expr: sympy.Expr) -> bool:
    """Whether the printer writes ``expr`` with a leading minus (negative coefficient)."""
    return bool(expr.as_coeff_Mul()[0].is_negative)


def _reciprocal(factor: sympy.Expr) -> bool:
    """Whether ``factor`` is a sum to a negative integer power (a denominator too wide
    for a fraction, written ``\\left(..\\right)^{-k}``)."""
    return bool(factor.is_Pow and factor.base.is_Add and factor.exp.is_Integer and factor.exp < 0)


def _factor_tex(factor: sympy.Expr) -> str:
    """A factor of a product as the printer writes it in one: sums in parentheses."""
    if _reciprocal(factor):
        return rf"\left({latex(factor.base)}\right)^{{{factor.exp}}}"
    text = latex(factor)
    return rf"\left({text}\right)" if factor.is_Add else text


def _wrapped(lines: list[Line], opening: str, closing: str) -> list[Line]:
    """``lines`` inside a delimiter pair, every line balanced (``\\right.`` / ``\\left.``)."""
    out = []
    for k, (level, text) in enumerate(lines):
        head = opening if k == 0 else r"\left. "
        tail = closing if k == len(lines) - 1 else r" \right."
        out.append((level, head + text + tail))
    return out


def _shifted(lines: list[Line], level: int) -> list[Line]:
    return [(lvl + level, text) for lvl, text in lines]


def _budget(width: float, level: int) -> float:
    return width - level * QUAD


def _sum_lines(expr: sympy.Expr, width: float, first: float) -> list[Line]:
    """A sum over lines, broken between its terms (the printer's order and signs); a
    term too wide for a line of its own is broken between its factors."""
    lines: list[Line] = []
    current = ""
    for k, term in enumerate(expr.as_ordered_terms()):
        negative = _negative(term)
        body = -term if negative else term
        op = "- " if negative else ("+ " if k else "")
        piece = op + latex(body)
        if current and fits(f"{current} {piece}", first if not lines else _budget(width, 1)):
            current = f"{current} {piece}"
            continue
        if current:
            lines.append((0 if not lines else 1, current))
            current = ""
        room = first if not lines else _budget(width, 1)
        if fits(piece, room):
            current = piece
            continue
        shift = estimate_width(op)
        broken = _product_lines(body, _budget(width, 1), room - shift)
        lines += _shifted([(broken[0][0], op + broken[0][1]), *broken[1:]], 0 if not lines else 1)
    if current:
        lines.append((0 if not lines else 1, current))
    return lines


def _pieces(expr: sympy.Expr, room: float) -> list[sympy.Expr | str]:
    """The factors of a positive product: its coefficient over the denominator
    (``\\frac{c}{den}``) as LaTeX, then the factors of the numerator.  A denominator too
    wide for ``room`` gives a piece per factor instead, ``\\frac{1}{f}`` or, when that is
    still too wide, the reciprocal power ``f^{-k}`` that breaks inside its parentheses."""
    numerator, denominator = sympy.fraction(expr, exact=True)
    coefficient, rest = numerator.as_coeff_Mul()
    pieces: list[sympy.Expr | str] = []
    whole = rf"\frac{{{latex(coefficient)}}}{{{latex(denominator)}}}"
    if denominator == 1:
        pieces += [latex(coefficient)] if coefficient != 1 else []
    elif fits(whole, room):
        pieces.append(whole)
    else:
        # The coefficient goes over the first factor (``\\frac{2}{3 f}``), or alone when that is too wide.
        number, factors = denominator.as_coeff_Mul()
        for k, factor in enumerate(factors.as_ordered_factors()):
            top, bottom = (coefficient, number * factor) if k == 0 else (sympy.Integer(1), factor)
            reciprocal = rf"\frac{{{latex(top)}}}{{{latex(bottom)}}}"
            if fits(reciprocal, room):
                pieces.append(reciprocal)
                continue
            if k == 0 and coefficient != number:
                pieces.append(latex(coefficient / number))
            base, exponent = factor.as_base_exp()
            pieces.append(sympy.Pow(base, -exponent, evaluate=False))
    return pieces + (list(rest.as_ordered_factors()) if rest != 1 else [])


def _product_lines(expr: sympy.Expr, width: float, first: float) -> list[Line]:
    """A product (or one factor) over lines, broken between its factors at ``\\cdot``;
    a factor too wide for the rest of its line is broken inside its parentheses."""
    sign = ""
    if _negative(expr):
        sign, expr = "- ", -expr
    lines: list[Line] = []
    current, filled = sign, False
    for piece in _pieces(expr, first):
        text = piece if isinstance(piece, str) else _factor_tex(piece)
        room = first if not lines else _budget(width, 1)
        candidate = f"{current} {text}" if filled else current + text
        if fits(candidate, room) or (isinstance(piece, str) and not filled):
            current, filled = candidate, True
            continue
        left = room - estimate_width(current)
        if filled and (isinstance(piece, str) or left < 0.4 * room):
            lines.append((0 if not lines else 1, current))
            current, filled = r"\cdot ", False
            room = _budget(width, 1)
            if fits(current + text, room) or isinstance(piece, str):
                current, filled = current + text, True
                continue
        assert not isinstance(piece, str)
        lead = f"{current} " if filled else current
        shift = estimate_width(lead)
        broken = _factor_lines(piece, _budget(width, 1), room - shift)
        lines += _shifted([(broken[0][0], lead + broken[0][1]), *broken[1:]], 0 if not lines else 1)
        current, filled = r"\cdot ", False
    if filled or not lines:
        lines.append((0 if not lines else 1, current))
    return lines


def _factor_lines(factor: sympy.Expr, width: float, first: float) -> list[Line]:
    """One factor over lines: a sum in parentheses, an integer power of one, or a
    function of one argument broken inside its parentheses; anything else whole."""
    paren = 2 * estimate_width(r"\left(")
    if factor.is_Add:
        return _wrapped(_sum_lines(factor, width - paren, first - paren), r"\left(", r"\right)")
    if factor.is_Pow and factor.base.is_Add and factor.exp.is_Integer and factor.exp not in (0, 1):
        closing = rf"\right)^{{{factor.exp}}}"
        return _wrapped(_sum_lines(factor.base, width - paren, first - paren - 8), r"\left(", closing)
    name = _FUNCTIONS.get(factor.func)
    if name is not None and len(factor.args) == 1:
        shift = estimate_width(name) + paren
        inner = expression_lines(factor.args[0], width - shift, first - shift)
        return _wrapped(inner, name + r"\left(", r"\right)")
    return [(0, latex(factor))]


def expression_lines(expr: sympy.Expr, width: float = LINE_WIDTH, first: float | None = None) -> list[Line]:
    """``expr`` over as few lines as fit ``width`` (``first``: the first line's budget):
    one line when it fits, else broken between terms, then between factors.  Lines past
    the first begin with their operator; a part that cannot break stays whole."""
    first = width if first is None else first
    text = latex(expr)
    if fits(text, first):
        return [(0, text)]
    if expr.is_Add:
        return _sum_lines(expr, width, first)
    return _product_lines(expr, width, first)


def _rows(lhs: str, lines: Sequence[Line], relation: str = "=") -> list[str]:
    """``align*`` rows of one broken right side: ``lhs &= first``, then ``&\\quad ...``."""
    head = f"{lhs} &{relation} " if lhs else "& "
    return [head + lines[0][1]] + ["&" + r"\quad" * max(level, 1) + " " + text for level, text in lines[1:]]


def _align(rows: list[str]) -> list[str]:
    """The ``align*`` environment of ``rows``."""
    return [r"\begin{align*}", *(row + r" \\" for row in rows[:-1]), rows[-1], r"\end{align*}"]


def display(lhs: str, expr: sympy.Expr, relation: str = "=", tail: str = "") -> list[str]:
    """``lhs relation expr tail`` displayed unnumbered (``lhs`` may be empty: an
    inequality ``expr > 0`` is ``display("", expr, tail=" > 0")``)."""
    text = latex(expr)
    line = f"{lhs} {relation} {text}{tail}" if lhs else text + tail
    if fits(line, LINE_WIDTH):
        return [r"\begin{equation*}", line, r"\end{equation*}"]
    lines = expression_lines(expr, LINE_WIDTH - estimate_width(tail))
    rows = _rows(lhs, lines, relation)
    return _align([*rows[:-1], rows[-1] + tail])


def aligned(rows: Sequence[tuple[str, sympy.Expr]]) -> list[str]:
    """Several equations ``lhs = expr`` in one ``align*``, each broken as it needs
    (nothing when there are none)."""
    if not rows:
        return []
    out: list[str] = []
    for lhs, expr in rows:
        out += _rows(lhs, expression_lines(expr))
    return _align(out)


def numbered(name: str, expr: sympy.Expr, tag: int) -> list[str]:
    """``name = expr`` tagged ``(tag)``: one ``equation`` when it fits (``\\eta = ...``
    then ``\\tag{n}`` on the next line), else ``name_{(n)} = N_{(n)}/D_{(n)}`` with the
    numerator and denominator broken below it."""
    text = latex(expr)
    if fits(f"{name} = {text}", LINE_WIDTH):
        return [r"\begin{equation}", f"{name} = {text}", rf"\tag{{{tag}}}", r"\end{equation}"]
    label = f"_{{({tag})}}"
    negative = _negative(expr)
    numerator, denominator = sympy.fraction(-expr if negative else expr, exact=True)
    if denominator == 1:
        rows = _rows(name + label, expression_lines(expr))
    else:
        rows = [rf"{name}{label} &= {'-' if negative else ''}\frac{{N{label}}}{{D{label}}}"]
        rows += _rows("N" + label, expression_lines(numerator))
        rows += _rows("D" + label, expression_lines(denominator))
    rows[0] += rf" \tag{{{tag}}}"
    return _align(rows)
