"""Where a variant or region holds beyond its turning or speed conditions: each loaded
force (the power through a mesh or its tooth force, a bearing's Coulomb reaction) with
the sign it assumes, as text and as LaTeX.  The losses can reverse some of them (a small
mesh power near a turning condition, any force at light load), and the variant that
holds is the one whose forces all have their signs."""

from __future__ import annotations

from collections.abc import Collection, Mapping

import sympy

from davies_sym.algebra.polynomials import RationalFunction


def force_conditions(
    loaded: Mapping[str, tuple[RationalFunction, int]], meshes: Collection[str], reversed_forces: Collection[str]
) -> list[tuple[str, sympy.Expr, int]]:
    """(what the force is, the force, the sign it needs) for each loaded force: for a mesh
    the power per unit input power crossing it from the first gear to the second, seen
    from its carrier (its sign says which gear drives); for a bearing its reaction."""
    out = []
    for coupling, (force, sign) in loaded.items():
        what = "power through" if coupling in meshes else "reaction in"
        flipped = " (reversed by the losses)" if coupling in reversed_forces else ""
        out.append((f"{what} {coupling}{flipped}", force.to_expr(), sign))
    return out


def force_text(conditions: list[tuple[str, sympy.Expr, int]]) -> list[str]:
    """Each condition as ``tooth force of M1: ... > 0``."""
    return [f"{what}: {sympy.sstr(force)} {'>' if sign > 0 else '<'} 0" for what, force, sign in conditions]
