"""Kinematic ratios of catalog trains against their textbook formulas (issue: catalog);
the efficiencies are cross-checked by the virtual-power balance in test_variants."""

from __future__ import annotations

import sympy

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.efficiency.virtual_power_balance import virtual_power_balance
from davies_sym.topology.states import train_in_state

from conftest import S, catalog_path, equal


def test_wolfrom_ratio_is_the_textbook_formula():
    """i = (1 + z_R1/z_S) / (1 - z_R1 z_P2 / (z_P1 z_R2)) on the constraints
    rr1 = rs + 2 rp1, rr2 = rs + rp1 + rp2; 45 for z = 12, 18, 48, 15, 45 (module 1)."""
    a = davies_sym.analyse(davies_sym.load(catalog_path("wolfrom")))
    rs, rp1, rr1, rp2, rr2 = (S(n) for n in ("rs", "rp1", "rr1", "rp2", "rr2"))
    on_constraints = {rr1: rs + 2 * rp1, rr2: rs + rp1 + rp2}
    textbook = (1 + rr1 / rs) / (1 - rr1 * rp2 / (rp1 * rr2))
    assert equal(a.speed_ratio().to_expr(), textbook, on_constraints)
    values = {rs: 6, rp1: 9, rr1: 24, rp2: sympy.Rational(15, 2), rr2: sympy.Rational(45, 2)}
    assert a.speed_ratio().to_expr().subs(values) == 45


def test_planetary_simple_ratio_chen_eq_4_7():
    """Chen eq. (4.7): w_2 = (gamma + 1) w_3, gamma = N_A / N_B (arm input, planet output)."""
    a = davies_sym.analyse(davies_sym.load(catalog_path("planetary_simple")))
    rA, rB = S("rA"), S("rB")
    assert equal(a.speed_ratio().to_expr(), 1 / (rA / rB + 1))


def test_tuplin_ratio_chen_k():
    """Chen eq. (4.13): w_4 = w_2 / k, k = N_A N_D / (N_A N_D - N_B N_C) (carrier input)."""
    a = davies_sym.analyse(davies_sym.load(catalog_path("tuplin")))
    r1, r2, r3, r4 = (S(f"r{i}") for i in range(1, 5))
    k = r3 * r2 / (r3 * r2 - r1 * r4)
    assert equal(a.speed_ratio().to_expr(), k, {r4: r2 - r1 + r3})


def test_simpson_ratios_in_every_state():
    """Simpson set, textbook ratios with S the sun and R1, R2 the rings:
    1st (R1 + R2 + S)/R1, 2nd 1 + S/R1, 3rd 1, reverse -R2/S."""
    train = davies_sym.load(catalog_path("simpson"))
    rs, rr1, rr2 = S("rs"), S("rr1"), S("rr2")
    rp1, rp2 = S("rp1"), S("rp2")
    on_constraints = {rr1: rs + 2 * rp1, rr2: rs + 2 * rp2}
    textbook = {
        "first": (rr1 + rr2 + rs) / rr1,
        "second": 1 + rs / rr1,
        "third": sympy.Integer(1),
        "reverse": -rr2 / rs,
    }
    for state in train.states:
        a = davies_sym.analyse(train_in_state(train, state))
        assert equal(a.speed_ratio().to_expr(), textbook[state.name], on_constraints), state.name


def test_third_gear_is_direct_with_no_loss():
    """A clutch locks the front set: no mesh turns in its carrier, the efficiency is 1."""
    train = train_in_state(
        davies_sym.load(catalog_path("simpson")), davies_sym.load(catalog_path("simpson")).state("third")
    )
    vs = derive_variants(train)
    assert all(v.efficiency == 1 for v in vs.variants)


def test_sr20_two_degree_of_freedom_kinematics():
    """Mantriota & Pennestri 2003, section 6: w_o = (w_d1 + w_d2)/2 for z = 36, 32, 20, 45,
    e.g. 180 = (309 + 51)/2 of their tables; the engine finds it from M_N (two primaries)."""
    a = davies_sym.analyse(davies_sym.load(catalog_path("sr20_differential")))
    assert a.degrees_of_freedom == 2
    basis = {k: {f: c.to_expr() for f, c in v.items()} for k, v in a.motion_basis.items()}
    tA, tK, tO = S("t_A", "magnitude"), S("t_K", "magnitude"), S("t_O", "magnitude")
    speed = {name: sum(c * S(f, "magnitude") for f, c in combo.items()) for name, combo in basis.items()}
    # t_A = w_d1, t_K = w_d2 (carrier), t_O = w_o, all relative to the housing.
    assert sympy.expand(speed["t_O"] - (speed["t_A"] + speed["t_K"]) / 2) == 0
    free = {tA, tK, tO} & set().union(*(e.free_symbols for e in speed.values()))
    assert len(free) == 2


def test_sr20_cli_prints_the_kinematics_and_regions():
    import subprocess
    import sys

    result = subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", catalog_path("sr20_differential")],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "speed of O: omega_O = omega_A/2 + omega_K/2" in result.stdout and "inputs A, K" in result.stdout


def test_litvin_face_gear_drive_chen_eqs_4_17_and_4_24():
    """Chen 2006 section 4.9: w_c / w_1 = N1 N3 / (N1 N3 - N2 N4) (eq. 4.17) and, carrier
    input with N1 N3 > N2 N4, eta = (N1 N3 - N2 N4) / (N1 N3 - eta1 eta2 N2 N4) (eq. 4.24);
    the turning condition is the sign of N1 N3 - N2 N4 (no planar constraint here)."""
    train = davies_sym.load(catalog_path("litvin_face_drive"))
    n1, n2, n3, n4 = (S(f"N{i}") for i in range(1, 5))
    e1, e2 = S("eta_1", "efficiency"), S("eta_2", "efficiency")
    a = davies_sym.analyse(train)
    assert a.network.order == 2 and a.network.system.twist_names == ("s", "t")
    assert equal(a.speed_ratio().to_expr(), n1 * n3 / (n1 * n3 - n2 * n4))
    vs = derive_variants(train)
    (c1,) = vs.conditions
    assert equal(c1.expression, n1 * n3 - n2 * n4)
    forward = next(v for v in vs.variants if v.input == "A" and v.signs["c1"] == 1)
    assert equal(forward.efficiency, (n1 * n3 - n2 * n4) / (n1 * n3 - e1 * e2 * n2 * n4))
    value = vs.evaluate({n1: 100, n2: 17, n3: 17, n4: 88, e1: sympy.Rational(98, 100), e2: sympy.Rational(98, 100)})
    assert round(float(value), 3) == 0.775


def test_litvin_pitch_points_on_both_pitch_cones():
    """Conical layout: each pitch point lies at the face-gear radius from the main axis and
    at the pinion radius from the planet axis (all axes through the origin)."""
    layout = davies_sym.analyse(davies_sym.load(catalog_path("litvin_face_drive"))).network.layout
    n1, n2, n3, n4 = (S(f"N{i}") for i in range(1, 5))
    assert tuple(layout.coupling_points["G1"]) == (0, n1, n2)
    assert tuple(layout.coupling_points["G2"]) == (0, n4, n3)


def test_balance_route_on_litvin_face_drive():
    """Chen 2006, eq. (4.24) and the example after it: 77.5 % by the virtual-power balance
    (carrier-frame Willis equation of each face-gear mesh), exactly Chen's formula."""
    train = davies_sym.load(catalog_path("litvin_face_drive"))
    N1, N2, N3, N4, e1, e2 = (train.symbols[n] for n in ("N1", "N2", "N3", "N4", "eta_1", "eta_2"))
    values = {N1: 100, N2: 17, N3: 17, N4: 88, e1: sympy.Rational(98, 100), e2: sympy.Rational(98, 100)}
    result = virtual_power_balance(train, values)
    chen = (N1 * N3 - N2 * N4) / (N1 * N3 - e1 * e2 * N2 * N4)
    assert result.efficiency == chen.subs(values)
    assert abs(float(result.efficiency) - 0.775) < 5e-4
