"""Coulomb friction of a cylindrical journal bearing (Laus App. D).

The friction torque is the bearing load times the radius of the friction circle,
``T = zeta |F|`` (Laus eqs. (38)-(39)); for a journal of radius ``a`` and a planar
friction coefficient ``mu`` the radius is ``zeta = k mu a``, where ``k`` depends on how
the normal pressure spreads over the contact (Laus Table 16, contact angle 2 beta =
pi): a new, uniformly loaded journal has k = pi/2, a worn-in one with a cosine
distribution k = 4/pi; ``k = 1`` takes ``mu`` as the bearing's own coefficient (as
bearing catalogues quote it).
"""

from __future__ import annotations

import sympy

#: Multiplier of the friction coefficient per contact law (Laus Table 16, beta = pi/2).
CONTACT_LAWS: dict[str, sympy.Expr] = {
    "new": sympy.pi / 2,
    "worn": 4 / sympy.pi,
    "catalogue": sympy.Integer(1),
}


def friction_circle_radius(mu: sympy.Expr, radius: sympy.Expr, contact: str = "catalogue") -> sympy.Expr:
    """zeta = k mu a: the lever of the friction torque per unit bearing load (Laus Table 16)."""
    return CONTACT_LAWS[contact] * mu * radius
