"""How an analysis shows itself in a notebook (``Analysis._repr_latex_``, ``_repr_html_``):
the mobility, the speed ratio and the efficiency in the friction coefficients (Laus eq. (71))."""

from __future__ import annotations

import html

import sympy

from davies_sym.topology.symbol_display import latex


def analysis_latex(
    mobility: int, ports: tuple[str, str], ratio: sympy.Expr | None, efficiency: sympy.Expr | None
) -> str:
    """``$$F_N = 1,\\ \\omega_A / \\omega_B = ...,\\ \\eta = ...$$`` (``ports``: input and
    output); a train of several degrees of freedom shows its mobility alone, its
    efficiency needs the input speeds (``derive_several_inputs``)."""
    parts = [f"F_N = {mobility}"]
    if ratio is not None:
        parts.append(rf"\frac{{\omega_{{\mathrm{{{ports[0]}}}}}}}{{\omega_{{\mathrm{{{ports[1]}}}}}}} = {latex(ratio)}")
    if efficiency is not None:
        parts.append(rf"\eta = {latex(efficiency)}")
    return "$$" + r",\qquad ".join(parts) + "$$"


def analysis_html(
    mobility: int, ports: tuple[str, str], ratio: sympy.Expr | None, efficiency: sympy.Expr | None
) -> str:
    """`analysis_latex` as a table, one row each (math for the notebook's renderer)."""
    rows = [("degrees of freedom", str(mobility))]
    if ratio is not None:
        rows.append((f"speed ratio {ports[0]} over {ports[1]}", rf"\({latex(ratio)}\)"))
    if efficiency is not None:
        rows.append((f"efficiency {ports[0]} \u2192 {ports[1]}", rf"\(\eta = {latex(efficiency)}\)"))
    cells = "".join(f"<tr><td>{html.escape(k)}</td><td>{html.escape(v)}</td></tr>" for k, v in rows)
    return f"<table>{cells}</table>"
