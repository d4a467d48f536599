"""Where the motions of a train do not hold: the factors of the denominators of every
member's speed over the input's (psi_alpha / t_in, Laus eq. (56)) whose sign the
admissible domain does not decide.

Where such a factor vanishes the train does not move as one degree of freedom from its
input (it locks, or a member turns freely), whatever finite value the reduced speed
ratio keeps: a compound planet whose steps copy the suns it meshes (equal tooth numbers)
locks a train whose input to output ratio stays finite.  Every entry point refuses such
a design with the same reason (`davies_sym.efficiency.design_point`, the formula
modules, the searches' exact rules).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import sympy

if TYPE_CHECKING:
    from davies_sym.network.analysis import Analysis


def vanishing_denominators(analysis: Analysis) -> tuple[sympy.Expr, ...]:
    """The distinct irreducible factors of the denominators of the motions that can vanish
    in the domain: a factor the sign oracle decides (a planet's own teeth, a sum of
    products of positive parameters, a positive geometric fact) never does."""
    out: list[sympy.Expr] = []
    for coefficient in analysis.motion_coefficients.values():
        _, factors = coefficient.factorisation[1]
        for polynomial, _ in factors:
            factor = coefficient.ring.to_expr(polynomial)
            if factor not in out and analysis.oracle.factor_sign(factor) is None:
                out.append(factor)
    return tuple(out)
