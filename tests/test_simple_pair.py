"""Simple gear pair, Laus 2011 section 3.3 (Fig. 5): eqs. (16)-(53)."""

from __future__ import annotations

import sympy

import davies_sym
from davies_sym.network.matrix_views import action_matrix, action_null_space, motion_matrix

from conftest import S, catalog_path, equal, variant

r1, r2 = S("r1"), S("r2")
zC, zA, zB = S("zeta_C", "friction"), S("zeta_A", "friction"), S("zeta_B", "friction")
TA, tA = S("T_A", "magnitude"), S("t_A", "magnitude")
c = S("sigma_C", "sign")


def analysis(**options):
    return davies_sym.analyse(davies_sym.load(catalog_path("simple_pair")), **options)


def test_motion_matrix_eq16():
    """Laus eq. (16): M = [[r2, -r1, -r1-r2], [0, -r1(r1+r2), -r1(r1+r2)]] t_A / r2."""
    M = motion_matrix(analysis())
    expected = sympy.Matrix([[r2, -r1, -r1 - r2], [0, -r1 * (r1 + r2), -r1 * (r1 + r2)]]) * tA / r2
    assert all(equal(a, b) for a, b in zip(M, expected, strict=True))


def test_unit_and_network_action_matrices_eqs17_20():
    """Laus eqs. (17), (18), (20): A_D, Q_A and A_N of the pair."""
    net = analysis().network
    assert net.unit_action_matrix() == sympy.Matrix([[1, 0, 1, -r1 - r2, 1, -r1], [0, 1, 0, 1, 0, 1]])
    assert net.action_cutset_matrix() == sympy.Matrix([[1, 1, 0, 0, -1, -1], [0, 0, 1, 1, 1, 1]])
    assert net.network_action_matrix() == sympy.Matrix(
        [[1, 0, 0, 0, -1, r1], [0, 1, 0, 0, 0, -1], [0, 0, 1, -r1 - r2, 1, -r1], [0, 0, 0, 1, 0, 1]]
    )


def test_augmented_matrix_and_null_space_eqs22_23():
    """Laus eqs. (22)-(23) with c = sign(U_C) sign(t_C) kept as a symbol."""
    a = analysis(coulomb_signs="symbolic")
    assert a.augmented_action_matrix.row(4) == sympy.Matrix([[0, 0, 0, 0, 1, c * zC]])
    den = r1 + c * zC
    expected = [1, -1 / den, (r2 - c * zC) / den, 1 / den, c * zC / den, -1 / den]
    assert all(equal(x, y) for x, y in zip(action_null_space(a), expected, strict=True))


def test_condensed_action_matrix_eq26():
    """Laus eq. (26): A = [[1, -1, 1], [-1, 1, -1]/(r1 + a zeta_C)] T_A, a = sign(T_A) sign(t_A).

    With the ports of the file (A input) the engine decides a = +1; with symbolic signs
    sigma_C = sign(U_C) sign(t_C) equals a (eq. (24): sign(U_C) = -sign(T_A), sign(t_C) = -sign(t_A)).
    """
    for a_value, options in ((1, {}), (c, {"coulomb_signs": "symbolic"})):
        A = action_matrix(analysis(**options))
        den = r1 + a_value * zC
        expected = sympy.Matrix([[1, -1, 1], [-1 / den, 1 / den, -1 / den]]) * TA
        assert all(equal(x, y) for x, y in zip(A, expected, strict=True))


def test_powers_eqs27_29_sum_to_zero():
    """Laus eqs. (27)-(29); P_A + P_B + P_C = 0 identically (Tellegen).

    The transcription of eq. (29) carries sign(T_A) sign(t_A) twice; the form
    -T_A t_A zeta_C (r1 + r2) / (r2 (r1 a + zeta_C)) is the one that keeps P_C < 0 for
    both signs of a (as the text states) and that makes the three powers sum to zero.
    """
    a = analysis(coulomb_signs="symbolic")
    PA, PB, PC = (a.power(k) for k in "ABC")
    assert equal(PA, TA * tA)
    assert equal(PB, -TA * tA * r1 * (r2 - zC * c) / (r2 * (r1 + zC * c)))
    for sign in (1, -1):
        assert equal(PC, -TA * tA * zC * (r1 + r2) / (r2 * (r1 * c + zC)), {c: sign})
    assert equal(PA + PB + PC, 0)


def test_ordinary_efficiency_eq32_and_zeta_eq33():
    """Laus eq. (32) eta_12 = r1 (r2 - zeta) / (r2 (r1 + zeta)); eq. (33) inverts it."""
    eta = analysis().efficiency
    assert equal(eta, r1 * (r2 - zC) / (r2 * (r1 + zC)))
    e12 = S("eta_12", "efficiency")
    assert equal(eta.subs(zC, r1 * r2 * (1 - e12) / (r1 + e12 * r2)), e12)


def test_reverse_efficiency_eq34_and_zeta_eq35():
    """Laus eq. (34): with B as input, eta_21 = r2 (r1 - zeta) / (r1 (r2 + zeta)); eq. (35)."""
    train = davies_sym.load(catalog_path("simple_pair"))
    eta = davies_sym.analyse(train.with_ports(train.ports.swapped())).efficiency
    assert equal(eta, r2 * (r1 - zC) / (r1 * (r2 + zC)))
    e21 = S("eta_21", "efficiency")
    assert equal(eta.subs(zC, r1 * r2 * (1 - e21) / (r2 + e21 * r1)), e21)


def bearing_analysis():
    return davies_sym.analyse(
        variant(
            "simple_pair",
            {
                "A: {type: revolute, links: [0, 1]}": "A: {type: revolute, links: [0, 1], friction: {coulomb: zeta_A}}",
                "B: {type: revolute, links: [0, 2]}": "B: {type: revolute, links: [0, 2], friction: {coulomb: zeta_B}}",
            },
        )
    )


def test_bearing_losses_eqs40_42():
    """Laus eqs. (40)-(42): with a = +1 (A input), Null(D_A) and the action matrix.

    The first row of eq. (42) as transcribed reads (1, 0); it is T_A itself, i.e.
    (r1 + a(zeta_A + zeta_C), 0) once the common factor is taken out.
    """
    a = bearing_analysis()
    assert [v.name for v in a.network.actions] == ["T_A", "Tstar_A", "U_A", "T_B", "Tstar_B", "U_B", "T_C", "U_C"]
    D = a.augmented_action_matrix
    assert D[4:, :] == sympy.Matrix([[0, 1, -zA, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1, -zB, 0, 0], [0, 0, 0, 0, 0, 0, 1, zC]])
    den = r1 + zA + zC
    expected = [1, -zA / den, -1 / den, (r2 - zB - zC) / den, zB / den, 1 / den, zC / den, -1 / den]
    assert all(equal(x, y) for x, y in zip(action_null_space(a), expected, strict=True))
    rows = {
        "Tstar_A": (-zA, 0),
        "U_A": (0, -1),
        "T_B": (r2 - zB - zC, 0),
        "Tstar_B": (zB, 0),
        "U_B": (-r1 - r2, 1),
        "T_C": (zC, 0),
        "U_C": (r1, -1),
    }
    for name, (T, U) in rows.items():
        wrench = a.action_wrench([name])
        assert equal(wrench[0].to_expr(), T * TA / den) and equal(wrench[1].to_expr(), U * TA / den), name


def test_bearing_efficiencies_eqs45_49():
    """Laus eqs. (45), (47) and (49): eta_A, eta_B and eta = eta_A eta_B eta_12."""
    a = bearing_analysis()
    eta_A = (a.power_rf("A") / a.port_power_rf("A")).to_expr()
    eta_B = (a.port_power_rf("B") / a.power_rf("B")).to_expr()
    assert equal(eta_A, (r1 + zC) / (r1 + zA + zC))
    assert equal(eta_B, (r2 - zB - zC) / (r2 - zC))
    e12, eA, eB = S("eta_12", "efficiency"), S("eta_A", "efficiency"), S("eta_B", "efficiency")
    zeta_C = r1 * r2 * (1 - e12) / (r1 + e12 * r2)  # eq. (33)
    zeta_A = (1 - eA) * (r1 + zeta_C) / eA  # eq. (46)
    zeta_B = (1 - eB) * (r2 - zeta_C)  # eq. (48)
    eta = a.efficiency.subs({zA: zeta_A, zB: zeta_B}).subs(zC, zeta_C)
    assert equal(eta, eA * eB * e12)


def test_viscous_losses_after_eq53():
    """Laus eqs. (50)-(53) and the efficiency printed after eq. (53).

    The engine's viscous law is T = -b t (the torque opposes the relative motion).  The
    thesis writes T = -b t sign(t) = -b |t| (eq. (50)), which on B and C, whose speeds
    are negative when t_A > 0, points along the motion: its printed formula has
    -b_B and -b_C where the physical law has +b_B and +b_C.  The test reproduces the
    printed formula exactly from the thesis's own sources and checks the physical
    one by the power balance (each viscous element dissipates b t^2).
    """
    bA, bB, bC = (S(n, "viscous") for n in ("b_A", "b_B", "b_C"))
    a = davies_sym.analyse(
        variant(
            "simple_pair",
            {
                "A: {type: revolute, links: [0, 1]}": "A: {type: revolute, links: [0, 1], friction: {viscous: b_A}}",
                "B: {type: revolute, links: [0, 2]}": "B: {type: revolute, links: [0, 2], friction: {viscous: b_B}}",
                "friction: {coulomb: zeta_C}": "friction: {coulomb: zeta_C, viscous: b_C}",
            },
        )
    )
    assert [v.name for v in a.network.actions] == [
        "T_A",
        "Tddag_A",
        "U_A",
        "T_B",
        "Tddag_B",
        "U_B",
        "T_C",
        "Tddag_C",
        "U_C",
    ]
    assert all(
        equal(x, y)
        for x, y in zip(a.dependent_sources, [-bA * tA, bB * r1 / r2 * tA, bC * (r1 + r2) / r2 * tA], strict=True)
    )
    printed_a = bA * (r2 - zC) * r1 * r2 - bB * (r1 + zC) * r1**2 - bC * r1 * (r1 + r2) ** 2
    printed = (TA * ((r2 - zC) * r1 * r2) - printed_a * tA) / (TA * r2**2 * (r1 + zC))
    assert equal(a.efficiency.subs({bB: -bB, bC: -bC}), printed)
    # Power balance: input = output + mesh friction + b t^2 of every viscous element.
    speeds = {k: a.motion_magnitudes[f"t_{k}"].to_expr() for k in "ABC"}
    losses = sum(b * speeds[k] ** 2 for b, k in ((bA, "A"), (bB, "B"), (bC, "C")))
    coulomb = -a.power("C", ["T_C"])
    P_in, P_out = a.port_power_rf("A").to_expr(), a.port_power_rf("B").to_expr()
    assert equal(P_in + P_out - coulomb - losses, 0)
