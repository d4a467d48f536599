"""Kinematic ratios of catalog trains against their textbook formulas (issue: catalog);
the efficiencies are cross-checked by the virtual-power balance in test_variants."""

from __future__ import annotations

import sympy

import davies_sym

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
