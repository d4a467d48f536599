"""Absolute motions, carriers, virtual power flow and ordinary efficiencies (Laus
sections 3.1.1, 3.3.5, 3.4.1.4-3.4.1.5)."""

from __future__ import annotations

import sympy

import davies_sym
from davies_sym.efficiency.absolute_motion import (
    absolute_motions,
    reduced_incidence_pseudoinverse,
    relative_motions,
    twists_equal,
)
from davies_sym.efficiency.virtual_power import mesh_power_flow
from davies_sym.topology.gear_mesh import GearMesh

from conftest import S, catalog_path, catalog_trains, equal

r1, r2, r3, r4 = (S(f"r{i}") for i in range(1, 5))
eta = S("eta_C", "efficiency")  # the default efficiency symbol of mesh C
etaD = S("eta_D", "efficiency")
tA = S("t_A", "magnitude")
PLANAR = {r4: r2 - r1 + r3}


def tuplin(mode: str = "mesh-linear") -> davies_sym.Analysis:
    return davies_sym.analyse(davies_sym.load(catalog_path("tuplin")), coulomb_signs=mode)


def flows(analysis: davies_sym.Analysis) -> dict:
    return {c.name: mesh_power_flow(analysis, c) for c in analysis.train.couplings if isinstance(c, GearMesh)}


def test_pseudoinverse_of_reduced_incidence_eq67():
    """Laus eq. (67): A_5^+ = [[5,4,3],[1,-4,-1],[2,0,-2],[1,4,-1],[3,4,5]] / 8 for eq. (66)."""
    a5 = tuplin().network.graph.reduced_incidence_matrix("5")
    assert a5 == sympy.Matrix([[1, 1, 1, 0, 0], [0, -1, 0, 1, 0], [0, 0, -1, -1, 1]])
    expected = sympy.Matrix([[5, 4, 3], [1, -4, -1], [2, 0, -2], [1, 4, -1], [3, 4, 5]]) / 8
    assert reduced_incidence_pseudoinverse(a5) == expected


def test_absolute_motions_eq68_and_path_walk_eq85_agree():
    """Laus eq. (6) and the walk of eq. (85) give the same ^5$ of every link.  Columns 2
    and 3 are those of eq. (68); column 1 is -t_A, not +t_A as printed: the walk 5 -> 1
    against edge A gives -$_A = (-t_A, 0), and only then does eq. (69) hold."""
    a = tuplin()
    by_pinv, by_walk = absolute_motions(a, "5"), relative_motions(a, "5")
    assert twists_equal(by_pinv, by_walk)
    m = {k: [x.to_expr() for x in v] for k, v in by_pinv.items()}
    assert m["1"] == [-tA, 0]
    assert equal(m["2"][0], -r1 * r4 / (r2 * r3) * tA, PLANAR) and m["2"][1] == 0
    assert equal(m["3/4"][0], -r1 / r3 * tA) and equal(m["3/4"][1], (r1 - r1**2 / r3) * tA)


def test_both_motion_routes_agree_on_every_catalog_train():
    """Eq. (6)-(7) against eq. (85) with every link as the reference."""
    for name, train in catalog_trains():
        a = davies_sym.analyse(train)
        for link in a.train.link_names:
            assert twists_equal(absolute_motions(a, link), relative_motions(a, link)), (name, link)


def test_carriers_and_virtual_power_flow_eqs69_70():
    """Carrier 5 for both meshes; P_13 / (T_A t_A) = r1 r4 / (r1 r4 - r2 r3) and
    P_24 = -P_13 (Laus eqs. (69)-(70))."""
    f = flows(tuplin())
    assert f["C"].carrier == f["D"].carrier == "5"
    assert equal(f["C"].flow_ratio.to_expr(), r1 * r4 / (r1 * r4 - r2 * r3), PLANAR)
    assert equal(f["D"].flow_ratio.to_expr(), -r1 * r4 / (r1 * r4 - r2 * r3), PLANAR)


def test_ordinary_efficiencies_and_friction_coefficients_eqs72_75():
    """eta_13 = r1 (zeta_C - r3) / (r3 (zeta_C - r1)) and eta_42 = r4 (zeta_D - r2) /
    (r2 (zeta_D - r4)) with T = zeta U (eqs. (63)-(64)); solved: eqs. (74)-(75)."""
    f = flows(tuplin())
    zC, zD = S("zeta_C", "friction"), S("zeta_D", "friction")
    assert equal(f["C"].ordinary_efficiency(True).to_expr(), r1 * (zC - r3) / (r3 * (zC - r1)))
    # Edge D runs 2 -> 3/4, so gear 4 driving gear 2 is the edge's second gear driving.
    assert equal(f["D"].ordinary_efficiency(False).to_expr(), r4 * (zD - r2) / (r2 * (zD - r4)), PLANAR)
    assert equal(f["C"].friction_for(eta, True).to_expr(), (r1 * r3 - eta * r1 * r3) / (r1 - eta * r3))
    assert equal(f["D"].friction_for(etaD, False).to_expr(), (r2 * r4 - etaD * r2 * r4) / (r4 - etaD * r2), PLANAR)


def test_simple_pair_ordinary_efficiency_eqs32_35():
    """Laus eqs. (32)-(35).  The engine's signed law is T = zeta U; the thesis writes the
    pair with T + a zeta U = 0, a = sign(T_A) sign(t_A), so its zeta is -a times ours."""
    a = davies_sym.analyse(davies_sym.load(catalog_path("simple_pair")), coulomb_signs="mesh-linear")
    (f,) = flows(a).values()
    p1, p2, z = S("r1"), S("r2"), S("zeta_C", "friction")
    assert f.carrier == "0" and f.flow_ratio.to_expr() == 1
    # a = +1 (gear 1 drives): zeta_thesis = -zeta.
    assert equal(f.ordinary_efficiency(True).to_expr().subs(z, -z), p1 * (p2 - z) / (p2 * (p1 + z)))
    assert equal(-f.friction_for(eta, True).to_expr(), p1 * p2 * (1 - eta) / (p1 + eta * p2))
    # a = -1 (gear 2 drives): zeta_thesis = +zeta.
    assert equal(f.ordinary_efficiency(False).to_expr(), p2 * (p1 - z) / (p1 * (p2 + z)))
    assert equal(f.friction_for(eta, False).to_expr(), p1 * p2 * (1 - eta) / (p2 + eta * p1))
