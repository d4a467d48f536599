"""Whether a one-input variant holds at an operating point with drag: its tooth forces
keep their lossless directions.

A variant fixes which gear drives in each mesh from the lossless power flow (Laus eqs.
(69)-(75)).  A constant drag, viscous or bearing friction does not scale with the tooth
forces, and at light load it can reverse one (the planet's drag of a planetary larger
than the ring's share of the load): the mesh's driving gear then swaps and the
variant's formula gives a wrong number.  This check solves the variant's tooth forces
(the action null space of D_A, ``Analysis.action_solution``, with each mesh's zeta of
the variant's direction) and names the meshes whose force the losses reverse.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.efficiency.mesh_friction import is_mesh_law
from davies_sym.efficiency.variants import Variant, VariantSet, at_operating_point, substituted


def reversed_meshes(variants: VariantSet, variant: Variant, values: Mapping[sympy.Symbol, sympy.Expr]) -> list[str]:
    """The meshes whose tooth force at ``values`` (input torque and speed included) has
    the opposite sign of its lossless one in ``variant``; empty when no law but the
    meshes' own friction is present (every force then scales with the load)."""
    if variants.swapped is None:
        return []
    declared = variant.input == variants.train.ports.input
    analysis, zetas = (variants.analysis, variants.zetas) if declared else (variants.swapped, variants.swapped_zetas)
    roles = variants.roles
    torque = analysis.input_action.symbol
    solution = analysis.action_solution
    lossless = analysis.lossless_action_coefficients
    out = []
    for role in (r for r in roles if not r.idle):
        law = next(law for law in analysis.network.laws if is_mesh_law(law, (role.coupling,)))
        a, b = solution[law.transmitted or ""]
        force = a * analysis.ring.rational(torque) + b
        force = at_operating_point(substituted(force, roles, zetas, variant.first_drives), analysis)
        ideal = at_operating_point(lossless[law.transmitted or ""] * analysis.ring.rational(torque), analysis)
        actual, expected = (sympy.sympify(f.to_expr().subs(values)) for f in (force, ideal))
        if actual.is_number and expected.is_number and actual * expected < 0:
            out.append(role.coupling)
    return out
