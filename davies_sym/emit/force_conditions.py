"""Where a variant or region holds beyond its turning or speed conditions: each loaded
force (a mesh's tooth force, a bearing's Coulomb reaction) with the sign it assumes, as
text and as LaTeX.  At light load the losses reverse some of them, and the variant
that holds is the one whose forces all have their signs."""

from __future__ import annotations

from collections.abc import Collection, Mapping

import sympy

from davies_sym.algebra.polynomials import RationalFunction


def force_conditions(
    loaded: Mapping[str, tuple[RationalFunction, int]], meshes: Collection[str], reversed_forces: Collection[str]
) -> list[tuple[str, sympy.Expr, int]]:
    """(what the force is, the force, the sign it needs) for each loaded force."""
    out = []
    for coupling, (force, sign) in loaded.items():
        what = "tooth force of" if coupling in meshes else "reaction in"
        flipped = " (reversed by the losses)" if coupling in reversed_forces else ""
        out.append((f"{what} {coupling}{flipped}", force.to_expr(), sign))
    return out


def force_text(conditions: list[tuple[str, sympy.Expr, int]]) -> list[str]:
    """Each condition as ``tooth force of M1: ... > 0``."""
    return [f"{what}: {sympy.sstr(force)} {'>' if sign > 0 else '<'} 0" for what, force, sign in conditions]
