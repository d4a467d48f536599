"""Loss models beyond one constant mesh coefficient: the mesh efficiency from the tooth
geometry (Laus App. A), journal bearings (App. D), viscous and constant drag torques as
dependent sources (Laus section 3.3.7), every variant in the input torque and speed.

Expected values are published (Laus App. A.4, Buckingham) or derived by hand in the
docstrings (a torque balance of each gear); identities are checked at random exact
points, never against the formula under test.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import pytest
import sympy
from harness.helpers import run_main

import davies_sym
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.variants import derive_variants

from conftest import catalog_path

PAIR = """\
name: pair with losses
links: [0, 1, 2]
reference: 0
gears:
  "1": {{link: 1, radius: r1}}
  "2": {{link: 2, radius: r2}}
couplings:
  A: {{type: revolute, links: [0, 1]{a}}}
  B: {{type: revolute, links: [0, 2]{b}}}
  C: {{type: mesh, gears: ["1", "2"]}}
ports: {{input: A, output: B}}
"""


def _pair(a: str = "", b: str = "") -> davies_sym.Train:
    return davies_sym.loads(PAIR.format(a=a, b=b), "pair.yaml")


def _values(variants, **numbers: object) -> dict[sympy.Symbol, sympy.Expr]:
    symbols = dict(variants.train.symbols) | {str(s): s for s in (INPUT_TORQUE, INPUT_SPEED)}
    return {symbols[k]: sympy.nsimplify(v) for k, v in numbers.items()}


# -- tooth geometry (Laus App. A) --------------------------------------------------------


def test_buckingham_number_laus_app_a4_eq136() -> None:
    """Laus App. A.4: m = 1/3 in, z 18/48, 14.5 deg, mu = 0.0272 with the printed approach
    and recess lengths: eta_12 = 0.9936745104 (10 digits), printed by --eval."""
    result = run_main([catalog_path("buckingham_pair"), "--eval", "mu=0.0272", "--quiet"])
    assert result.returncode == 0, result.stderr
    assert abs(float(result.stdout.splitlines()[-1]) - 0.9936745104) < 5e-11


def _buckingham(beta_a: float, beta_r: float, mu: float, alpha: float, r1: float, r2: float) -> float:
    """Buckingham's 'more exact' formula (Laus App. A.4, the equation after (137)): a
    different route from eq. (136), in the approach and recess angles of the driver."""
    num = beta_a + beta_r - mu * math.tan(alpha) * (beta_a - beta_r) - mu * r1 / (2 * r2) * (beta_a**2 + beta_r**2)
    den = beta_a + beta_r - mu * math.tan(alpha) * (beta_a - beta_r) + mu / 2 * (beta_a**2 + beta_r**2)
    return num / den


def test_tooth_geometry_from_the_addenda_agrees_with_buckingham() -> None:
    """With the lengths computed from the addenda (m = 1/3 exactly, eqs. (134)-(135)) the
    efficiency is within 1e-6 of the printed 0.9936745104 and within 1e-5 of Buckingham's
    own formula 0.993668909 (Laus: they differ by a thousandth of a percent)."""
    text = Path(catalog_path("buckingham_pair")).read_text(encoding="utf-8")
    text = text.replace(", approach: 1.072029882, recess: 0.8844028695", "")
    variants = derive_variants(davies_sym.loads(text, "addenda.yaml"))
    eta = float(variants.evaluate(_values(variants, mu="0.0272")))
    assert abs(eta - 0.9936745104) < 1e-6
    alpha, r1 = math.radians(14.5), 3.0
    # Approach and recess angles of the driver from the lengths printed by Laus.
    beta_a, beta_r = 1.072029882 / (r1 * math.cos(alpha)), 0.8844028695 / (r1 * math.cos(alpha))
    assert abs(_buckingham(beta_a, beta_r, 0.0272, alpha, r1, 8.0) - 0.993668909) < 1e-8
    assert abs(eta - 0.993668909) < 1e-5


def test_tooth_efficiency_tends_to_one_and_falls_with_friction() -> None:
    variants = derive_variants(davies_sym.loads(Path(catalog_path("buckingham_pair")).read_text(), "b.yaml"))
    etas = [
        float(variants.evaluate(_values(variants, mu=mu), input=port))
        for port in ("A", "B")
        for mu in ("1e-9", "0.01", "0.05", "0.1")
    ]
    for side in (etas[:4], etas[4:]):
        assert abs(side[0] - 1) < 1e-8
        assert side == sorted(side, reverse=True)


def test_tooth_model_refuses_what_it_does_not_cover() -> None:
    base = Path(catalog_path("buckingham_pair")).read_text(encoding="utf-8")
    cases = {
        ", approach: 1.072029882, recess: 0.8844028695": (", approach: 1.07", "give both `approach` and `recess`"),
        "pressure_angle: 14.5": ("pressure_angle: 60", "between 0 and 45"),
        '"2": {link: 2, teeth: 48, module: 1/3}': ('"2": {link: 2, teeth: 48, module: 1/2}', None),
    }
    for old, (new, message) in cases.items():
        text = base.replace(old, new)
        if message is None:  # modules differ, but the lengths are given: accepted
            davies_sym.loads(text, "m.yaml")
            text = text.replace(", approach: 1.072029882, recess: 0.8844028695", "")
            message = "do not share one: give `addendum`"
        with pytest.raises(davies_sym.InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
            davies_sym.loads(text, "bad.yaml")


def test_tooth_model_on_an_internal_mesh_is_refused_with_its_line() -> None:
    text = """\
name: internal
links: [0, 1, 2]
reference: 0
gears:
  P: {link: 1, radius: 10, module: 1}
  R: {link: 2, radius: 30, module: 1, internal: true}
couplings:
  A: {type: revolute, links: [0, 1], at: 0}
  B: {type: revolute, links: [0, 2]}
  C: {type: mesh, gears: [P, R], efficiency: {mu: mu, pressure_angle: 20}}
ports: {input: A, output: B}
"""
    with pytest.raises(davies_sym.InputError) as caught:
        davies_sym.loads(text, "internal.yaml")
    assert "internal.yaml:10: couplings.C.efficiency: the tooth-contact model" in str(caught.value)


def test_a_defined_efficiency_is_not_an_eval_value(tmp_path: Path) -> None:
    result = run_main([catalog_path("buckingham_pair"), "--eval", "eta_C_1_2=0.9", "--quiet"])
    assert result.returncode == 2
    assert "eta_C_1_2 is the ordinary efficiency of mesh C" in result.stderr and "give mu instead" in result.stderr
    assert "Traceback" not in result.stderr


# -- journal bearing (Laus App. D) -------------------------------------------------------


def test_journal_bearing_contact_laws_laus_table16() -> None:
    """zeta = k mu a with k = pi/2 (new), 4/pi (worn), 1 (catalogue): Laus Table 16, beta = pi/2."""
    for contact, k in (("new", sympy.pi / 2), ("worn", 4 / sympy.pi), ("catalogue", 1)):
        train = _pair(a=f", friction: {{bearing: {{mu: mu_A, radius: a_A, contact: {contact}}}}}")
        (d,) = train.definitions
        mu, a = train.symbols["mu_A"], train.symbols["a_A"]
        assert str(d.symbol) == "zeta_A" and sympy.simplify(d.expression - k * mu * a) == 0


def test_journal_bearing_on_the_input_shaft_by_hand() -> None:
    """Gear 1 (input A) in a journal of friction-circle radius zeta = mu a; the tooth
    force F loads it.  The mesh friction couple zeta_C F acts against the driver (Laus
    eq. (42): the denominator r1 + zeta_A + zeta_C), so the torque balance of gear 1 is
    T_in = F (r1 + zeta_C) + zeta F; the teeth take F (r1 + zeta_C) w1 and eta_C of it
    reaches gear 2 (the carrier-held pair), zeta_C = r1 r2 (1 - eta)/(r1 + eta r2) (Laus
    eq. (33)).  So eta = eta_C (r1 + zeta_C) / (r1 + zeta_C + zeta)."""
    train = _pair(a=", friction: {bearing: {mu: mu_A, radius: a_A}}")
    variants = derive_variants(train)
    rng = random.Random(3)
    for _ in range(5):
        r1, r2 = sympy.Rational(rng.randint(10, 60)), sympy.Rational(rng.randint(10, 60))
        eta_c, mu, a = sympy.Rational(rng.randint(90, 99), 100), sympy.Rational(rng.randint(1, 9), 100), 2
        zeta_c = r1 * r2 * (1 - eta_c) / (r1 + eta_c * r2)
        expected = eta_c * (r1 + zeta_c) / (r1 + zeta_c + mu * a)
        got = variants.evaluate(_values(variants, r1=r1, r2=r2, eta_C=eta_c, mu_A=mu, a_A=a))
        assert sympy.simplify(got - expected) == 0


# -- dependent sources: viscous and constant drag ----------------------------------------


@pytest.mark.parametrize("law", ["viscous: b", "drag: D", "bearing: {mu: b, radius: 1}"])
@pytest.mark.parametrize("side", ["a", "b"])
def test_every_variant_falls_as_the_loss_grows(law: str, side: str) -> None:
    """The defect of the reversed variants: with a loss on either shaft, both directions
    lose efficiency as the loss coefficient grows, and reach eta_C as it vanishes."""
    entry = f", friction: {{{law}}}"
    train = _pair(**{side: entry})
    variants = derive_variants(train)
    assert {v.input for v in variants.variants} == {"A", "B"}
    for port in ("A", "B"):
        etas = []
        for b in ("1e-12", "0.01", "0.1", "0.5"):
            values = (
                _values(variants, r1=20, r2=50, eta_C="0.98", b=b)
                if "b" in law
                else _values(variants, r1=20, r2=50, eta_C="0.98", D=b)
            )
            values |= {INPUT_TORQUE: sympy.Integer(40), INPUT_SPEED: sympy.Integer(3)}
            etas.append(float(variants.evaluate(values, input=port)))
        assert abs(etas[0] - 0.98) < 1e-9
        assert etas == sorted(etas, reverse=True) and etas[-1] < etas[0]


def test_drag_on_the_output_by_hand_efficiency_rises_with_load() -> None:
    """Constant drag D on the output shaft B: P_out = eta_C P_in - D w_B with
    w_B = omega_in r1/r2, so eta = eta_C - D r1 / (r2 tau_in); rising with the input torque."""
    variants = derive_variants(_pair(b=", friction: {drag: D}"))
    for torque in (5, 10, 40):
        values = _values(variants, r1=20, r2=50, eta_C="0.98", D="0.5")
        values |= {INPUT_TORQUE: sympy.Integer(torque), INPUT_SPEED: sympy.Integer(7)}
        expected = sympy.Rational(98, 100) - sympy.Rational(1, 2) * 20 / (50 * torque)
        assert variants.evaluate(values) == expected


def test_viscous_on_the_output_by_hand_when_it_is_the_input() -> None:
    """Viscous b on shaft A with B the input (speed omega_in, torque tau_in): gear 1 turns at
    omega_in r2/r1 and loses b (omega_in r2/r1)^2 after the mesh:
    eta = eta_C - b omega_in r2^2/(tau_in r1^2)."""
    variants = derive_variants(_pair(a=", friction: {viscous: b}"))
    values = _values(variants, r1=20, r2=50, eta_C="0.98", b="0.01")
    values |= {INPUT_TORQUE: sympy.Integer(30), INPUT_SPEED: sympy.Integer(4)}
    expected = sympy.Rational(98, 100) - sympy.Rational(1, 100) * 4 * 50**2 / (30 * 20**2)
    assert variants.evaluate(values, input="B") == expected


def test_operating_point_names_are_reserved() -> None:
    """Refused on load, where the file writes them."""
    with pytest.raises(davies_sym.InputError, match=r"friction.viscous: 'tau_in' is the input torque of the formulas"):
        derive_variants(_pair(a=", friction: {viscous: tau_in*omega_in}"))


def test_ports_named_in_and_out_do_not_meet_the_operating_point_symbols() -> None:
    """Couplings called `in` and `out` have the magnitudes T_in, t_in, T_out: the input
    torque and speed of the formulas are tau_in and omega_in, so such a train derives, and
    its drag variant is the hand formula eta = eta_C - D r1 / (r2 tau_in) (drag on the output)."""
    text = (
        PAIR.format(a="", b=", friction: {drag: D}")
        .replace("A:", "in:")
        .replace("B:", "out:")
        .replace("{input: A, output: B}", "{input: in, output: out}")
    )
    variants = derive_variants(davies_sym.loads(text, "in_out.yaml"))
    values = _values(variants, r1=20, r2=50, eta_C="0.98", D="0.5")
    values |= {INPUT_TORQUE: sympy.Integer(10), INPUT_SPEED: sympy.Integer(7)}
    assert variants.evaluate(values) == sympy.Rational(98, 100) - sympy.Rational(1, 2) * 20 / (50 * 10)
