"""The condensed matrices and null-space vectors of an analysis as sympy matrices, for
reading and comparing with the printed equations (Laus eqs. (23), (26), (58), (59),
(65)); the pipeline itself works on the exact rational functions."""

from __future__ import annotations

import sympy

from davies_sym.errors import DerivationError
from davies_sym.network.analysis import Analysis


def action_null_space(analysis: Analysis) -> sympy.Matrix:
    """The vector spanning Null(D_A), scaled so the input torque entry is 1 (eq. (23))."""
    if analysis.dependent_sources.rows:
        raise DerivationError("with dependent sources D_A Psi = [0; nu] has no plain null space")
    return sympy.Matrix([a.to_expr() for a, _ in analysis.action_solution.values()])


def motion_null_space(analysis: Analysis) -> sympy.Matrix:
    """The vector spanning Null(M_N), scaled so the input speed entry is 1 (eq. (58))."""
    return sympy.Matrix([c.to_expr() for c in analysis.motion_coefficients.values()])


def motion_matrix(analysis: Analysis) -> sympy.Matrix:
    """M (d x e), condensed per coupling, in terms of the input speed (eq. (59))."""
    cols = [[c.to_expr() for c in analysis.coupling_twist(e)] for e in analysis.network.graph.edges]
    return sympy.Matrix(cols).T


def action_matrix(analysis: Analysis) -> sympy.Matrix:
    """A (d x e), condensed per coupling, in terms of the input torque (eqs. (26), (65))."""
    cols = [[c.to_expr() for c in analysis.coupling_wrench(e)] for e in analysis.network.graph.edges]
    return sympy.Matrix(cols).T
