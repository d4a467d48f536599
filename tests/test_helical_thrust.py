"""Helical gears on parallel axes: the tooth force thrusts along the axes by F tan(beta),
the bearings take it, and a thrust face's Coulomb friction (``thrust: {mu, radius}``) sees
it.  Expected values are torque balances of each shaft written in the docstrings (the
tangential tooth force F, the thrust F tan(beta), the friction moment zeta |thrust|),
evaluated exactly at rational points of the unit circle; the countershaft checks the
textbook rule that two gears of the same hand on one shaft oppose their thrusts.
"""

from __future__ import annotations

import random

import pytest
import sympy
from harness.helpers import run_main

import davies_sym
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.variants import derive_variants
from davies_sym.losses.definitions import completed
from davies_sym.network.analysis import Analysis

PAIR = """
name: helical pair
links: [0, 1, 2]
reference: 0
gears:
  "1": {{link: 1, radius: r1}}
  "2": {{link: 2, radius: r2}}
couplings:
  A: {{type: revolute, links: [0, 1]{a}}}
  B: {{type: revolute, links: [0, 2]}}
  C: {{type: mesh, gears: {gears}, helix_angle: {helix}{hand}}}
ports: {{input: A, output: B}}
"""

COUNTERSHAFT = """
name: helical countershaft
links: [0, 1, 2, 3]
reference: 0
gears:
  a: {{link: 1, radius: ra}}
  b: {{link: 2, radius: rb}}
  c: {{link: 2, radius: rc}}
  d: {{link: 3, radius: rd}}
couplings:
  A: {{type: revolute, links: [0, 1]}}
  B: {{type: revolute, links: [0, 2], friction: {{thrust: {{mu: mu, radius: s}}}}}}
  D: {{type: revolute, links: [0, 3]}}
  C1: {{type: mesh, gears: [a, b], helix_angle: beta1, hand: right, efficiency: 1}}
  C2: {{type: mesh, gears: [c, d], helix_angle: beta2, hand: {hand}, efficiency: 1}}
ports: {{input: A, output: D}}
"""


def _pair(a: str = "", gears: str = '["1", "2"]', helix: str = "beta", hand: str = "") -> davies_sym.Train:
    return davies_sym.loads(PAIR.format(a=a, gears=gears, helix=helix, hand=hand), "pair.yaml")


def _values(variants, **numbers: object) -> dict[sympy.Symbol, sympy.Expr]:
    symbols = dict(variants.train.symbols) | {str(s): s for s in (INPUT_TORQUE, INPUT_SPEED)}
    return {symbols[k]: sympy.nsimplify(v) for k, v in numbers.items()}


def _unit_circle(rng: random.Random) -> tuple[sympy.Rational, sympy.Rational]:
    """cos and sin of an angle in (0, 90 deg) at a rational point of the unit circle."""
    t = sympy.Rational(rng.randint(1, 99), 100)
    return (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)


@pytest.mark.parametrize(
    ("gears", "hand"),
    [('["1", "2"]', ""), ('["1", "2"]', ", hand: left"), ('["2", "1"]', ", hand: left"), ('["2", "1"]', "")],
)
def test_thrust_face_on_the_input_shaft_by_hand(gears: str, hand: str) -> None:
    """Gear 1 (input A) on a thrust face of friction radius zeta = mu a.  The tooth force's
    tangential part F drives gear 2 and its axial part F tan(beta) presses gear 1 on the
    face, whose moment zeta F tan(beta) opposes the rotation: T_in = F (r1 + zeta_C) +
    zeta F tan(beta), and eta_C of F (r1 + zeta_C) w1 reaches gear 2 (zeta_C = r1 r2
    (1 - eta_C)/(r1 + eta_C r2), Laus eq. (33)).  So eta = eta_C (r1 + zeta_C) / (r1 +
    zeta_C + zeta tan(beta)), whichever gear is written first and whatever the hand."""
    train = _pair(a=", friction: {thrust: {mu: mu_A, radius: a_A}}", gears=gears, hand=hand)
    variants = derive_variants(train)
    rng = random.Random(5)
    for _ in range(6):
        cos, sin = _unit_circle(rng)
        r1, r2 = sympy.Rational(rng.randint(10, 60)), sympy.Rational(rng.randint(10, 60))
        eta_c, mu, a = sympy.Rational(rng.randint(90, 99), 100), sympy.Rational(rng.randint(1, 15), 100), 3
        zeta_c = r1 * r2 * (1 - eta_c) / (r1 + eta_c * r2)
        expected = eta_c * (r1 + zeta_c) / (r1 + zeta_c + mu * a * sin / cos)
        values = _values(variants, r1=r1, r2=r2, eta_C=eta_c, mu_A=mu, a_A=a, cos_beta=cos, sin_beta=sin)
        assert variants.evaluate(values) == expected


def test_helical_mesh_alone_keeps_the_spur_efficiency_and_thrusts_by_tan_beta() -> None:
    """Without bearing friction the thrust costs nothing: the helical pair's efficiency is
    the spur pair's, eta_C one way and eta_C the other.  The bearing of gear 1 takes the
    axial reaction F tan(beta) for a tangential tooth force F (W_A / U_C = +-tan(beta)),
    and its tilting moment r1 F tan(beta) about the tangent."""
    train = _pair()
    variants = derive_variants(train)
    eta = train.symbols["eta_C"]
    assert {v.efficiency for v in variants.variants} == {eta}
    analysis = Analysis(train)
    actions = analysis.lossless_action_coefficients
    cos, sin = train.symbols["cos_beta"], train.symbols["sin_beta"]
    ratio = (actions["W_A"] / actions["U_C"]).to_expr()
    assert sympy.cancel(ratio**2 - (sin / cos) ** 2) == 0
    tilt = (actions["R_A"] / actions["U_C"]).to_expr()
    assert sympy.cancel(tilt**2 - (train.symbols["r1"] * sin / cos) ** 2) == 0


def test_journal_in_a_helical_train_sees_the_radial_force_only() -> None:
    """A journal (``bearing``) on the input shaft is loaded by the radial reaction, the
    tangential tooth force F, whatever the helix: eta = eta_C (r1 + zeta_C)/(r1 + zeta_C +
    mu a), the spur value (Laus App. D), at every helix angle."""
    train = _pair(a=", friction: {bearing: {mu: mu_A, radius: a_A}}")
    variants = derive_variants(train)
    rng = random.Random(8)
    for _ in range(4):
        cos, sin = _unit_circle(rng)
        r1, r2, eta_c, mu = 20, 45, sympy.Rational(97, 100), sympy.Rational(rng.randint(1, 9), 100)
        zeta_c = sympy.Rational(r1 * r2) * (1 - eta_c) / (r1 + eta_c * r2)
        expected = eta_c * (r1 + zeta_c) / (r1 + zeta_c + mu * 2)
        values = _values(variants, r1=r1, r2=r2, eta_C=eta_c, mu_A=mu, a_A=2, cos_beta=cos, sin_beta=sin)
        assert variants.evaluate(values) == expected


def _countershaft_by_hand(ra, rb, rc, rd, t1, t2, zeta, same_hand: bool):
    """The countershaft's torque balance with lossless meshes: F1 = T / ra on gear b, F2 on
    gear c, F1 rb - F2 rc - zeta |thrust| = 0.  The thrusts F1 tan(beta1) and F2 tan(beta2)
    add on gears of opposite hands and oppose on gears of the same hand (the textbook rule
    for countershafts).  eta = F2 rc / (F1 rb); with the thrust's sign s:
    F2 (rc + s zeta t2 q) = F1 (rb - s zeta t1), q = -1 for the same hand, else +1."""
    q = -1 if same_hand else 1
    for s in (1, -1):
        ratio = (rb - s * zeta * t1) / (rc + s * zeta * t2 * q)  # F2 / F1
        thrust = t1 + q * ratio * t2
        if thrust * s > 0:
            return ratio * rc / rb
    raise AssertionError("no consistent thrust sign")


@pytest.mark.parametrize(("hand", "same_hand"), [("left", True), ("right", False)])
def test_countershaft_thrusts_oppose_on_gears_of_the_same_hand(hand: str, same_hand: bool) -> None:
    """Gear b is left-handed (mesh C1's first gear a is right-handed); gear c is the first
    gear of C2 with the given hand.  The thrust face of the countershaft sees the
    difference of the two thrusts when b and c have the same hand, their sum otherwise;
    where the difference changes sign (rb tan(beta2) = rc tan(beta1)) the variant changes."""
    train = davies_sym.loads(COUNTERSHAFT.format(hand=hand), "countershaft.yaml")
    variants = derive_variants(train)
    rng = random.Random(11)
    seen_signs = set()
    for _ in range(12):
        (c1, s1), (c2, s2) = _unit_circle(rng), _unit_circle(rng)
        ra, rb, rc, rd = (sympy.Rational(rng.randint(10, 80)) for _ in range(4))
        mu, s = sympy.Rational(rng.randint(1, 15), 100), sympy.Rational(rng.randint(1, 5))
        t1, t2 = s1 / c1, s2 / c2
        expected = _countershaft_by_hand(ra, rb, rc, rd, t1, t2, mu * s, same_hand)
        values = _values(
            variants, ra=ra, rb=rb, rc=rc, rd=rd, mu=mu, s=s, cos_beta1=c1, sin_beta1=s1, cos_beta2=c2, sin_beta2=s2
        )
        assert variants.evaluate(values) == expected
        seen_signs.add(rb * t2 > rc * t1)
    assert not same_hand or seen_signs == {True, False}, "both thrust senses drawn"
    # Opposite hands add the thrusts: one variant per input, no geometric split.
    assert len(variants.variants) == (4 if same_hand else 2)


def test_helix_in_degrees_is_the_symbolic_formula_at_that_angle() -> None:
    """``helix_angle: 20`` (degrees) gives the symbolic formula's value at beta = pi/9."""
    degrees = derive_variants(_pair(a=", friction: {thrust: {mu: 0.1, radius: 2}}", helix="20"))
    symbolic = derive_variants(_pair(a=", friction: {thrust: {mu: 0.1, radius: 2}}"))
    numbers = {"r1": 20, "r2": 50, "eta_C": sympy.Rational(98, 100)}
    beta = sympy.pi / 9
    a = degrees.evaluate(_values(degrees, **numbers, c_beta_C=sympy.cos(beta), s_beta_C=sympy.sin(beta)))
    b = symbolic.evaluate(_values(symbolic, **numbers, cos_beta=sympy.cos(beta), sin_beta=sympy.sin(beta)))
    assert abs(float(a) - float(b)) < 1e-12
    assert 0.9 < float(a) < 0.98


def test_small_helix_and_no_friction_limits() -> None:
    """beta -> 0 (cos 1, sin 0) gives the spur pair with a thrust face that carries nothing:
    eta_C; mu -> 0 gives eta_C at any helix."""
    variants = derive_variants(_pair(a=", friction: {thrust: {mu: mu_A, radius: a_A}}"))
    base = {"r1": 30, "r2": 70, "eta_C": sympy.Rational(95, 100), "a_A": 4}
    # sin_beta = 0 lies outside the admissible helix (0, 90 deg): the formula's own limit there.
    at = _values(variants, **base, mu_A=sympy.Rational(1, 10), cos_beta=1, sin_beta=0)
    near = _values(
        variants, **base, mu_A=sympy.Rational(1, 10), cos_beta=sympy.Rational(99, 101), sin_beta=sympy.Rational(20, 101)
    )
    flat = variants.variant_for(near, "A").efficiency.subs(at)
    assert flat == sympy.Rational(95, 100)
    # mu_A = 0 lies outside the admissible (0, inf) of a loss model's coefficient: the limit.
    helix = {"cos_beta": sympy.Rational(3, 5), "sin_beta": sympy.Rational(4, 5)}
    lossless = _values(variants, **base, mu_A=0, **helix)
    free = variants.variant_for(_values(variants, **base, mu_A=sympy.Rational(1, 10), **helix), "A").efficiency
    free = free.subs(completed(lossless, variants.train.definitions))
    assert free == sympy.Rational(95, 100)


def test_cli_eval_with_the_helix_in_radians() -> None:
    """``--eval`` takes the helix angle beta in radians and fills cos_beta and sin_beta."""
    text = PAIR.format(a=", friction: {thrust: {mu: mu_A, radius: a_A}}", gears='["1", "2"]', helix="beta", hand="")
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp, "pair.yaml")
        path.write_text(text)
        result = run_main(
            [str(path), "--eval", "beta=0.3", "r1=20", "r2=50", "eta_C=1", "mu_A=0.1", "a_A=2", "--quiet"]
        )
    assert result.returncode == 0, result.describe()
    expected = 20 / (20 + 0.1 * 2 * __import__("math").tan(0.3))  # eta_C = 1: T_in = F r1 + zeta F tan(beta)
    assert abs(float(result.stdout.splitlines()[-1]) - expected) < 1e-12


@pytest.mark.parametrize(
    ("edit", "entry", "words"),
    [
        (("helix_angle: beta", "helix_angle: 95"), "couplings.C.helix_angle", "strictly between 0 and 90"),
        (("helix_angle: beta", "helix_angle: beta, hand: up"), "couplings.C.hand", "`right` or `left`"),
        (("helix_angle: beta", "hand: left"), "couplings.C.hand", "give `helix_angle` too"),
        (
            ("[0, 2]}", "[0, 2], friction: {thrust: {mu: 0.1, radius: 1}, bearing: {mu: 0.1, radius: 1}}}"),
            "couplings.B.friction",
            "not both",
        ),
        (
            ("helix_angle: beta", "helix_angle: beta, friction: {thrust: {mu: 0.1, radius: 1}}"),
            "couplings.C.friction.thrust",
            "write it on a revolute",
        ),
    ],
)
def test_bad_helical_input_is_refused_with_the_entry(tmp_path, edit: tuple[str, str], entry: str, words: str) -> None:
    text = PAIR.format(a="", gears='["1", "2"]', helix="beta", hand="").replace(*edit)
    path = tmp_path / "pair.yaml"
    path.write_text(text)
    result = run_main([str(path), "--quiet"])
    assert result.returncode == 2, result.describe()
    assert entry in result.stderr and words in result.stderr, result.describe()
    assert "Traceback" not in result.stderr


def test_thrust_face_in_a_spur_train_is_refused(tmp_path) -> None:
    """Spur gears thrust nothing: a thrust face would carry no load, said with the entry."""
    text = PAIR.format(a=", friction: {thrust: {mu: 0.1, radius: 1}}", gears='["1", "2"]', helix="beta", hand="")
    path = tmp_path / "spur.yaml"
    path.write_text(text.replace(", helix_angle: beta", ""))
    result = run_main([str(path), "--quiet"])
    assert result.returncode == 2, result.describe()
    assert "couplings.A.friction.thrust" in result.stderr and "helix_angle" in result.stderr


PLANETARY = """
name: helical planetary
links: [0, s, p, c]
reference: 0
gears:
  S: {link: s, radius: rs}
  P: {link: p, radius: rp}
  R: {link: 0, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  E: {type: revolute, links: [c, p]}
  M1: {type: mesh, gears: [S, P], helix_angle: beta}
  M2: {type: mesh, gears: [P, R], helix_angle: beta, hand: left}
ports: {input: A, output: B}
"""


def test_planet_thrusts_cancel_into_a_tilting_moment() -> None:
    """Textbook: on a planet meshing sun and ring, the two tangential tooth forces F are
    equal and the thrusts F tan(beta) opposite, so the planet pin takes no thrust but the
    couple 2 r_p F tan(beta); the sun's bearing takes the thrust F tan(beta) and its moment
    r_s F tan(beta).  Lossless reactions per unit input torque (F = 1/r_s)."""
    train = davies_sym.loads(PLANETARY, "planetary.yaml")
    actions = {k: v.to_expr() for k, v in Analysis(train).lossless_action_coefficients.items()}
    rs, rp = train.symbols["rs"], train.symbols["rp"]
    tan = train.symbols["sin_beta"] / train.symbols["cos_beta"]
    assert actions["W_E"] == 0 and actions["W_B"] == 0
    assert sympy.cancel(actions["R_E"] ** 2 - (2 * rp * tan / rs) ** 2) == 0
    assert sympy.cancel(actions["W_A"] ** 2 - (tan / rs) ** 2) == 0
    assert sympy.cancel(actions["R_A"] ** 2 - tan**2) == 0


def test_a_planet_with_two_hands_is_refused(tmp_path) -> None:
    """M2 names the planet (its first gear) right-handed, M1 makes it left-handed (the second
    gear of an external mesh with a right-handed sun): refused at couplings.M2.hand."""
    path = tmp_path / "planetary.yaml"
    path.write_text(PLANETARY.replace("hand: left", "hand: right"))
    result = run_main([str(path), "--quiet"])
    assert result.returncode == 2 and "couplings.M2.hand" in result.stderr, result.describe()
    path.write_text(
        PLANETARY.replace(
            "M2: {type: mesh, gears: [P, R], helix_angle: beta, hand: left}", "M2: {type: mesh, gears: [P, R]}"
        )
    )
    result = run_main([str(path), "--quiet"])
    assert result.returncode == 2 and "helical in mesh M1 but spur in mesh M2" in result.stderr, result.describe()
