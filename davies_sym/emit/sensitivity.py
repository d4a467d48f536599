"""``derive FILE --sensitivity NAME``: the partial derivative of every variant's efficiency
in one parameter, from the exact closed form (the formula modules' ``sensitivity`` gives
the same derivative of the variant that holds, element by element)."""

from __future__ import annotations

import sympy

from davies_sym.efficiency.parameters import given_form, given_parameters
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.latex import PREAMBLE, escape
from davies_sym.emit.latex_lines import display
from davies_sym.errors import InputError, Problem
from davies_sym.topology.symbol_display import latex


def sensitivity_forms(variants: VariantSet, name: str) -> list[tuple[int, str, str, sympy.Expr]]:
    """(number, ports and where it holds, d eta / d name) of every variant, the efficiency written in
    the parameters the user gives (square roots and defined symbols replaced, so a
    derivative in an angle reaches its cosine and sine)."""
    train = variants.train
    parameters = given_parameters(variants)
    if name not in parameters:
        known = ", ".join(sorted(parameters))
        why = f"{name!r} is not a parameter of the formulas (they take: {known})"
        raise InputError([Problem("--sensitivity", why)], train.path)
    radicals = variants.analysis.network.layout.radicals
    out = []
    for v in variants.variants:
        eta = given_form(v.efficiency, train, radicals)
        where = ", ".join(f"{c} {'>' if sign > 0 else '<'} 0" for c, sign in v.signs.items())
        ports = f"input {v.input}, output {v.output}" + (f", where {where}" if where else "")
        out.append((v.number, ports, where, partial_derivative(eta, parameters[name])))
    return out


def partial_derivative(eta: sympy.Expr, symbol: sympy.Symbol) -> sympy.Expr:
    """d eta / d symbol of a quotient eta = N / D by the quotient rule, (N' D - N D') / D**2,
    the numerator expanded so that terms that cancel are gone and its common factors
    taken out (a derivative written as sympy differentiates keeps them)."""
    numerator, denominator = sympy.fraction(sympy.together(eta))
    top = sympy.factor_terms(
        sympy.expand(sympy.diff(numerator, symbol) * denominator - numerator * sympy.diff(denominator, symbol))
    )
    return top / denominator**2


def sensitivity_text(variants: VariantSet, name: str) -> str:
    """One line per variant: ``(1) input A, output B: d eta / d r1 = ...``."""
    lines = [f"{variants.train.name}: partial derivatives of the efficiency in {name}"]
    for number, ports, _, form in sensitivity_forms(variants, name):
        lines.append(f"  ({number}) {ports}: d eta / d {name} = {sympy.sstr(form)}")
    return "\n".join(lines) + "\n"


def sensitivity_latex(variants: VariantSet, name: str) -> str:
    """A standalone LaTeX document: each variant's derivative, broken into lines that fit."""
    symbol = latex(sympy.Symbol(name))
    body = [rf"\section*{{{escape(variants.train.name)}: $\partial\eta / \partial {symbol}$}}"]
    for number, ports, _, form in sensitivity_forms(variants, name):
        body.append(rf"\noindent Variant ({number}), {escape(ports)}:")
        body += display(rf"\frac{{\partial \eta_{{({number})}}}}{{\partial {symbol}}}", form)
    return "\n".join([*PREAMBLE, *body, r"\end{document}", ""])
