"""Ordinary efficiency of an involute spur mesh from its tooth geometry (Laus App. A).

Along the path of contact the friction force ``mu Q_N`` acts at distance rho from the
pitch point; averaging the instantaneous efficiency over the contact interval gives
Laus eq. (136) in closed form.  The approach and recess lengths are where the pressure
line leaves the addendum circles (eqs. (134)-(135)).  Gear 1 is the driver; the other
direction exchanges the gears.
"""

from __future__ import annotations

import sympy


def contact_lengths(
    r_driver: sympy.Expr, r_driven: sympy.Expr, addendum: sympy.Expr, pressure_angle: sympy.Expr
) -> tuple[sympy.Expr, sympy.Expr]:
    """(approach, recess) = (DP, EP) of Laus eqs. (135) and (134): the driven gear's
    addendum circle bounds the approach, the driver's the recess."""
    s, c = sympy.sin(pressure_angle), sympy.cos(pressure_angle)

    def length(r: sympy.Expr) -> sympy.Expr:
        return -r * s + sympy.sqrt((r + addendum) ** 2 - r**2 * c**2)

    return length(r_driven), length(r_driver)


def spur_mesh_efficiency(
    r_driver: sympy.Expr,
    r_driven: sympy.Expr,
    pressure_angle: sympy.Expr,
    mu: sympy.Expr,
    approach: sympy.Expr,
    recess: sympy.Expr,
) -> sympy.Expr:
    """eta_12 of Laus eq. (136): the mean over the contact interval of the instantaneous
    efficiency, with kappa_1, kappa_2 the constants of App. A.3."""
    s, c = sympy.sin(pressure_angle), sympy.cos(pressure_angle)
    kappa1 = -r_driver * (s + c / mu)
    kappa2 = -r_driver * (s - c / mu)
    ratio = r_driver / r_driven
    mean = kappa2 * sympy.log(1 + approach / kappa2) - kappa1 * sympy.log(1 - recess / kappa1)
    return (ratio + 1) * mean / (approach + recess) - ratio
