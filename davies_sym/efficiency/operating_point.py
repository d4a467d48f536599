"""The operating point of the one-input formulas and the substitution of each mesh's
friction coefficient.

Where dependent sources (viscous, drag) make the efficiency depend on the operating
point, the formulas take the input torque and speed as magnitudes (input power
tau_in omega_in).  Every mesh's signed law T = zeta U (Laus eqs. (63)-(64)) is then
given the zeta of its driving direction in ordinary efficiencies (eqs. (74)-(75)).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.turning_conditions import MeshRole
from davies_sym.efficiency.virtual_power import MeshPowerFlow
from davies_sym.network.analysis import Analysis

#: No coupling's magnitude is named so (those are T_<coupling>, t_<coupling>, ...).
INPUT_TORQUE = sympy.Symbol("tau_in", positive=True)
INPUT_SPEED = sympy.Symbol("omega_in", positive=True)
OPERATING_SYMBOLS = (INPUT_TORQUE, INPUT_SPEED)


def at_operating_point(form: RationalFunction, analysis: Analysis) -> RationalFunction:
    """``form`` with the input port's torque and speed magnitudes written as tau_in and
    omega_in (the input turning forwards and putting power in: Laus's primary variables,
    eq. (53) and the efficiency after it)."""
    torque = form.ring.rational(analysis.input_power_sign * INPUT_TORQUE)
    return form.substitute(
        {analysis.input_action.symbol: torque, analysis.input_motion.symbol: form.ring.rational(INPUT_SPEED)}
    )


def zeta_forms(
    flows: Mapping[str, MeshPowerFlow], roles: Sequence[MeshRole]
) -> dict[tuple[str, bool], RationalFunction]:
    """zeta of every mesh for both directions (Laus eqs. (74)-(75)), in the ring of ``flows``."""
    out = {}
    for role in roles:
        flow = flows[role.coupling]
        for first in (True, False):
            eta = role.efficiencies[0] if first else role.efficiencies[1]
            out[(role.coupling, first)] = flow.friction_for(eta, first)
    return out


def substituted(
    form: RationalFunction,
    roles: Sequence[MeshRole],
    zetas: Mapping[tuple[str, bool], RationalFunction],
    first: Mapping[str, bool],
) -> RationalFunction:
    """``form`` with each mesh's zeta of the direction ``first`` gives it (first gear drives
    or not), every mesh at once: each factor of ``form`` is factored once."""
    return form.substitute({r.flow.friction_symbol: zetas[(r.coupling, first[r.coupling])] for r in roles})
