"""Epicyclic train with two annuli (Tuplin), Laus 2011 section 3.4.1 (Fig. 7): eqs. (54)-(71)."""

from __future__ import annotations

import sympy

import davies_sym
from davies_sym.network.matrix_views import action_matrix, motion_matrix, motion_null_space

from conftest import S, catalog_path, equal, variant

r1, r2, r3, r4 = (S(f"r{i}") for i in range(1, 5))
zC, zD = S("zeta_C", "friction"), S("zeta_D", "friction")
TA, tA = S("T_A", "magnitude"), S("t_A", "magnitude")
PLANAR = {r4: r2 - r1 + r3}  # the geometric identity r1 - r3 = r2 - r4


def train():
    return davies_sym.load(catalog_path("tuplin"))


def linear_law():
    """Laus eqs. (63)-(64): T_C = zeta_C U_C, T_D = zeta_D U_D with real coefficients."""
    return variant("tuplin", {"coulomb: zeta_C": "linear: zeta_C", "coulomb: zeta_D": "linear: zeta_D"})


def test_geometry_derived_from_meshes():
    """Table 12: pitch points at r1 and r2, planet bearing E at r1 - r3; the constraint
    r1 - r3 = r2 - r4 (Laus section 3.4.1.6) gives r4, which the gears then use."""
    analysis = davies_sym.analyse(train())
    net = analysis.network
    ys = {k: net.layout.coupling_points[k][1] for k in "ABCDE"}
    assert ys == {"A": 0, "B": 0, "C": r1, "D": r2, "E": r1 - r3}
    (relation,) = analysis.train.dependent or ()
    assert relation.constraint == "r1 - r3 = r2 - r4" and str(relation) == "r4 = -r1 + r2 + r3"
    assert net.layout.constraints == ()
    assert net.order == 2 and net.system.twist_names == ("t", "u")


def test_unit_motion_matrix_circuits_and_network_matrix_eqs54_57():
    """Laus eqs. (54), (55), (57) with chords D and E."""
    net = davies_sym.analyse(train()).network
    assert net.unit_motion_matrix() == sympy.Matrix([[1, 1, 1, 1, 1], [0, 0, r1, r2, r1 - r3]])
    assert net.circuit_matrix() == sympy.Matrix([[0, 1, -1, 1, 0], [-1, 0, 1, 0, 1]])
    assert net.network_motion_matrix() == sympy.Matrix(
        [[0, 1, -1, 1, 0], [0, 0, -r1, r2, 0], [-1, 0, 1, 0, 1], [0, 0, r1, 0, r1 - r3]]
    )


def test_motion_null_space_eq58_and_motion_matrix_eq59():
    a = davies_sym.analyse(train())
    expected = [1, (r1 - r2) * (r1 - r3) / (r2 * r3), 1 - r1 / r3, -r1 * (r1 - r3) / (r2 * r3), r1 / r3]
    assert all(equal(x, y) for x, y in zip(motion_null_space(a), expected, strict=True))
    M59 = (
        sympy.Matrix(
            [
                [r2 * r3, (r1 - r2) * (r1 - r3), -r2 * (r1 - r3), -r1 * (r1 - r3), r1 * r2],
                [0, 0, -r1 * r2 * (r1 - r3), -r1 * r2 * (r1 - r3), r1 * r2 * (r1 - r3)],
            ]
        )
        * tA
        / (r2 * r3)
    )
    assert all(equal(x, y) for x, y in zip(motion_matrix(a), M59, strict=True))


def test_lossless_actions_eqs60_62():
    """Laus eqs. (60)-(61) and (62) (the latter uses r1 - r3 = r2 - r4)."""
    a = davies_sym.analyse(
        variant(
            "tuplin", {"friction: {coulomb: zeta_C}": "friction: none", "friction: {coulomb: zeta_D}": "friction: none"}
        )
    )
    net = a.network
    assert net.unit_action_matrix() == sympy.Matrix([[1, 0, 1, 0, -r1, -r2, r3 - r1], [0, 1, 0, 1, 1, 1, 1]])
    assert net.action_cutset_matrix() == sympy.Matrix(
        [[1, 1, 0, 0, 0, 0, 1], [0, 0, 1, 1, 0, -1, 0], [0, 0, 0, 0, 1, 1, -1]]
    )
    k = r2 * r3 - r1 * r4
    A62 = sympy.Matrix([[k, -r2 * r3, r1 * r4, -r2 * r3, r1 * r4 - r2 * r3], [r2 - r1, r3, -r4, r3, r1 - r2]]) * TA / k
    assert all(equal(x, y, PLANAR) for x, y in zip(action_matrix(a), A62, strict=True))


def test_lossy_actions_eq65_and_efficiency_eq71():
    """Laus eq. (65) (moment row) and eq. (71) with the signed linear law (63)-(64).

    The transcribed third entry of (65) reads (zeta_D + r4); its zeta -> 0 limit would then
    contradict eq. (62), so the text has lost a sign: the entry is (zeta_D - r4), which is
    what the network gives and what reduces to (62).
    """
    a = davies_sym.analyse(linear_law())
    den = zC - zD - r1 + r2
    row = [r1 - r3, (zD - r2) * (zC - r3) / den, -(zC - r1) * (zD - r4) / den, (zD - r2) * (zC - r3) / den, r3 - r1]
    A = action_matrix(a)
    assert all(equal(A[0, j], row[j] * TA / (r1 - r3), PLANAR) for j in range(5))
    eta71 = (r2 - r1) * (zD - r2) * (zC - r3) / (r2 * r3 * (zC - zD - r1 + r2))
    assert equal(a.efficiency, eta71)
    assert a.sign_conditions == []


def test_coulomb_signs_reported_not_guessed():
    """With Coulomb friction the sign of the friction on C and D depends on r1 < r2 (the
    turning condition of Table 5); the engine keeps sigma_C, sigma_D and says so."""
    a = davies_sym.analyse(train())
    conditions = {c.coupling: c.expression for c in a.sign_conditions}
    assert set(conditions) == {"C", "D"}
    assert equal(conditions["C"], r1 - r2) and equal(conditions["D"], r2 - r1)
    sC, sD = S("sigma_C", "sign"), S("sigma_D", "sign")
    eta71 = (r2 - r1) * (zD - r2) * (zC - r3) / (r2 * r3 * (zC - zD - r1 + r2))
    # The linear law T = zeta U of eqs. (63)-(64) is the Coulomb row T + sigma zeta U = 0 at sigma = -1.
    assert equal(a.efficiency.subs({sC: -1, sD: -1}), eta71)
    assert equal(a.efficiency.subs({zC: 0, zD: 0}), 1)


def test_result_independent_of_spanning_tree():
    """Every spanning tree of G_C (there are 8) gives the same efficiency, for the motion
    tree and the action tree chosen independently."""
    base = davies_sym.analyse(train())
    trees = list(base.network.graph.spanning_trees())
    assert len(trees) == 8
    reference = base.efficiency
    for tree in trees:
        for action_tree in trees:
            a = davies_sym.analyse(train(), tree=tree, action_tree=action_tree)
            assert equal(a.efficiency, reference), (tree, action_tree)
            B, Q = a.network.circuit_matrix(), a.network.cutset_matrix()
            assert sympy.zeros(B.rows, len(tree)) == B * a.network.graph.cutset_matrix(tree).T
            assert Q.rows == 3
