"""How an analysis shows itself in a notebook (``Analysis._repr_latex_``): the mobility,
the speed ratio and the efficiency in the friction coefficients (Laus eq. (71))."""

from __future__ import annotations

from typing import TYPE_CHECKING

from davies_sym.topology.symbol_display import latex

if TYPE_CHECKING:  # the analysis imports this module; the type only for the checker
    from davies_sym.network.analysis import Analysis


def analysis_latex(analysis: Analysis) -> str:
    """``$$F_N = 1,\\ \\omega_A / \\omega_B = ...,\\ \\eta = ...$$``; for a train of
    several degrees of freedom the mobility alone (its efficiency needs the input speeds:
    ``derive_several_inputs``)."""
    ports = analysis.train.ports
    mobility = analysis.degrees_of_freedom
    parts = [f"F_N = {mobility}"]
    if mobility == 1:
        ratio = latex(analysis.speed_ratio().to_expr())
        parts += [rf"\frac{{\omega_{{\mathrm{{{ports.input}}}}}}}{{\omega_{{\mathrm{{{ports.output}}}}}}} = {ratio}",
                  rf"\eta = {latex(analysis.efficiency)}"]
    return "$$" + r",\qquad ".join(parts) + "$$"
