"""Meshes on skew axes: worm drives and crossed helical gears, derived from the screws of
the sliding contact, checked against the textbook forms (exactly, at rational points of
the unit circle), an independent numeric statics (tests/oracle/skew_pair.py), the
power balance, and the self-locking boundary mu = cos(alpha_n) tan(gamma)."""

from __future__ import annotations

import random
from fractions import Fraction
from math import atan, cos, pi, sin, tan

import pytest
import sympy
from harness.helpers import run_main
from oracle.skew_pair import SkewPair

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.errors import NotCoveredError
from davies_sym.losses.definitions import completed

WORM = """
name: worm pair
links: [0, 1, 2]
reference: 0
gears:
  w: {link: 1, radius: r1}
  g: {link: 2, radius: r2}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  W: {type: worm, gears: [w, g], lead_angle: gamma, pressure_angle: alpha_n, friction: {coulomb: mu}}
ports: {input: A, output: B}
"""

# The same drive written otherwise: other names, the wheel's link first, the mesh first,
# the ports on the other shafts' names, the friction symbol the default one.
WORM_OTHERWISE = """
name: worm pair, other spelling
links: [housing, wheelshaft, wormshaft]
gears:
  Z2: {link: wheelshaft, radius: b}
  Z1: {link: wormshaft, radius: a}
couplings:
  M: {type: worm, gears: [Z1, Z2], lead_angle: lam, pressure_angle: phi_n}
  out: {type: revolute, links: [wheelshaft, housing]}
  in: {type: revolute, links: [wormshaft, housing]}
ports: {input: in, output: out}
"""

CROSSED = """
name: crossed pair
links: [0, 1, 2]
reference: 0
gears:
  p: {link: 1, radius: r1}
  g: {link: 2, radius: r2}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  X: {type: crossed_helical, gears: [p, g], helix_angles: [beta_1, beta_2], pressure_angle: alpha_n,
      friction: {coulomb: mu}}
ports: {input: A, output: B}
"""


def _variants(text: str, name: str = "skew"):
    return derive_variants(davies_sym.loads(text, name))


def _circle_point(t: Fraction) -> tuple[Fraction, Fraction]:
    """(cos, sin) of 2 atan(t): a rational point of the unit circle."""
    return (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)


def _symbol(variants, name: str) -> sympy.Symbol:
    return variants.train.symbols[name]


def test_worm_equals_the_textbook_forms_exactly_at_rational_points() -> None:
    """Worm driving (cos a - mu tan g) / (cos a + mu cot g), wheel driving
    (cos a - mu cot g) / (cos a + mu tan g) (e.g. Shigley, Mott): exact equality at 30
    random rational points (angles with rational cos and sin)."""
    v = _variants(WORM)
    by_input = {x.input: x for x in v.variants}
    assert set(by_input) == {"A", "B"}
    rng = random.Random(11)
    s = {n: _symbol(v, n) for n in ("cos_gamma", "sin_gamma", "cos_alpha_n", "sin_alpha_n", "mu")}
    for _ in range(30):
        cg, sg = _circle_point(Fraction(rng.randint(1, 80), 100))
        ca, sa = _circle_point(Fraction(rng.randint(1, 40), 100))
        mu = Fraction(rng.randint(1, 200), 1000)
        point = {s["cos_gamma"]: cg, s["sin_gamma"]: sg, s["cos_alpha_n"]: ca, s["sin_alpha_n"]: sa, s["mu"]: mu}
        forward = (ca - mu * sg / cg) / (ca + mu * cg / sg)
        backward = (ca - mu * cg / sg) / (ca + mu * sg / cg)
        for port, expected in (("A", forward), ("B", backward)):
            value = by_input[port].efficiency_rf.evaluate(point)
            assert Fraction(int(value.p), int(value.q)) == expected


def test_worm_self_locking_condition_is_the_textbook_one() -> None:
    """Back-driving self-locks where mu >= cos(alpha_n) tan(gamma): the sign of the wheel
    input's efficiency is that of cos(alpha_n) sin(gamma) - mu cos(gamma)."""
    v = _variants(WORM)
    back = next(x for x in v.variants if x.input == "B")
    s = {n: _symbol(v, n) for n in ("cos_gamma", "sin_gamma", "cos_alpha_n", "mu")}
    boundary = s["cos_alpha_n"] * s["sin_gamma"] - s["mu"] * s["cos_gamma"]
    assert back.locking_expression is not None
    assert sympy.expand(back.locking_expression - boundary) == 0


def test_self_locking_flagged_exactly_at_the_boundary() -> None:
    """tan(gamma) = 1/7, cos(alpha_n) = 4/5: the wheel drives while mu < 4/35, not at 4/35
    (there the efficiency is exactly 0: refused as self-locking, decided exactly)."""
    v = _variants(WORM)
    gamma, alpha = sympy.atan(sympy.Rational(1, 7)), sympy.acos(sympy.Rational(4, 5))
    limit = sympy.Rational(4, 35)
    at = {"gamma": gamma, "alpha_n": alpha, "mu": limit, "r1": 1, "r2": 2}
    with pytest.raises(NotCoveredError, match=r"self-locks .* gives 0 exactly"):
        v.evaluate(at, input="B")
    below = v.evaluate({**at, "mu": limit - sympy.Rational(1, 10**6)}, input="B")
    assert 0 < below < sympy.Rational(1, 10**4)
    forward = v.evaluate(at, input="A")
    assert 0 < forward < 1


def test_crossed_helical_equals_the_friction_angle_form() -> None:
    """Gear 1 driving: cos b1 cos(b2 + phi) / (cos b2 cos(b1 - phi)), tan phi = mu / cos a_n;
    gear 2 driving: the same with the gears exchanged; at random angles."""
    v = _variants(CROSSED)
    rng = random.Random(5)
    for _ in range(12):
        b1, b2 = rng.uniform(0.05, 0.9), rng.uniform(0.05, 0.9)
        a, mu = rng.uniform(0.1, 0.45), rng.uniform(0.005, 0.15)
        phi = atan(mu / cos(a))
        values = {"beta_1": b1, "beta_2": b2, "alpha_n": a, "mu": mu, "r1": 3, "r2": 5}
        exact = {k: sympy.Float(x, 30) for k, x in values.items()}
        first = cos(b1) * cos(b2 + phi) / (cos(b2) * cos(b1 - phi))
        second = cos(b2) * cos(b1 + phi) / (cos(b1) * cos(b2 - phi))
        assert float(v.evaluate(exact, input="A")) == pytest.approx(first, rel=1e-12)
        assert float(v.evaluate(exact, input="B")) == pytest.approx(second, rel=1e-12)


def test_crossed_helical_maximum_efficiency() -> None:
    """At beta_1 = (theta + phi) / 2 the efficiency is (1 + cos(theta + phi)) / (1 + cos(theta - phi))
    (the classic maximum of spiral gears), here with alpha_n = 0 so that tan phi = mu."""
    v = _variants(CROSSED)
    for theta, phi in ((55, 6), (80, 8), (40, 3)):
        t, f = theta * pi / 180, phi * pi / 180
        values = {"beta_1": (t + f) / 2, "beta_2": (t - f) / 2, "alpha_n": 0, "mu": tan(f), "r1": 1, "r2": 2}
        # alpha_n = 0 lies outside the admissible (0, pi/2): the formula's own value there.
        keyed = {v.train.symbols[k]: sympy.Float(x, 30) for k, x in values.items()}
        value = float(v.variant_for(keyed, "A").efficiency.subs(completed(keyed, v.train.definitions)))
        assert value == pytest.approx((1 + cos(t + f)) / (1 + cos(t - f)), rel=1e-12)


@pytest.mark.parametrize("text", [WORM, WORM_OTHERWISE])
def test_worm_against_independent_statics(text: str) -> None:
    """The numeric statics of tests/oracle/skew_pair.py, both inputs, 20 random designs;
    where it finds the pair self-locking the engine's efficiency is <= 0."""
    v = _variants(text)
    names = ("gamma", "alpha_n", "mu") if "gamma" in v.train.symbols else ("lam", "phi_n", "mu_M")
    inputs = (v.train.ports.input, v.train.ports.output)
    rng = random.Random(3)
    for _ in range(20):
        g, a, mu = rng.uniform(0.03, 0.6), rng.uniform(0.2, 0.45), rng.uniform(0.01, 0.25)
        values = {n: sympy.Float(x, 30) for n, x in zip(names, (g, a, mu), strict=True)}
        values.update({"r1": 1, "r2": 2} if "r1" in v.train.symbols else {"a": 1, "b": 2})  # the speed ratio's
        pair = SkewPair(1.0, 2.0, pi / 2 - g, g, a, mu)
        for gear, port in zip((1, 2), inputs, strict=True):
            expected = pair.efficiency(gear)
            if expected is None:
                with pytest.raises(NotCoveredError, match="self-locks"):
                    v.evaluate(values, input=port)
            else:
                assert float(v.evaluate(values, input=port)) == pytest.approx(expected, rel=1e-9)


def test_crossed_helical_against_independent_statics_in_both_gear_orders() -> None:
    """Writing the gears the other way round (and their helix angles with them) describes
    the same pair: both spellings match the oracle for both inputs."""
    swapped = CROSSED.replace(
        "gears: [p, g], helix_angles: [beta_1, beta_2]", "gears: [g, p], helix_angles: [beta_2, beta_1]"
    )
    assert swapped != CROSSED
    rng = random.Random(8)
    for text in (CROSSED, swapped):
        v = _variants(text)
        for _ in range(10):
            b1, b2 = rng.uniform(0.05, 1.0), rng.uniform(0.05, 1.0)
            a, mu = rng.uniform(0.1, 0.4), rng.uniform(0.01, 0.2)
            values = {"beta_1": b1, "beta_2": b2, "alpha_n": a, "mu": mu, "r1": 2, "r2": 7}
            exact = {k: sympy.Float(x, 30) for k, x in values.items()}
            pair = SkewPair(2.0, 7.0, b1, b2, a, mu)
            for gear, port in ((1, "A"), (2, "B")):
                expected = pair.efficiency(gear)
                if expected is None:
                    with pytest.raises(NotCoveredError, match="self-locks"):
                        v.evaluate(exact, input=port)
                else:
                    assert float(v.evaluate(exact, input=port)) == pytest.approx(expected, rel=1e-9)


def test_power_balance_with_the_sliding_loss() -> None:
    """P_in + P_out + P_friction = 0 exactly (as rational functions), and the friction power
    is -mu |N| times the sliding speed r1 w1 / cos(gamma) (sliding along the thread)."""
    train = davies_sym.loads(WORM, "worm")
    for ports in (train.ports, train.ports.swapped()):
        a = davies_sym.analyse(train.with_ports(ports))
        p_in, p_out = a.port_power_rf(ports.input), a.port_power_rf(ports.output)
        friction = next(v.name for v in a.network.actions if v.role == "friction")
        loss = a.power_rf("W", [friction])
        assert (p_in + p_out + loss).is_zero()
        assert not loss.is_zero()
    a = davies_sym.analyse(train)
    s = train.symbols
    normal = a.action_magnitudes["N_W"]
    speed = next(a.motion_magnitudes[v.name] for v in a.network.coupling_motions("A"))
    sliding = a.ring.rational(s["r1"] / s["cos_gamma"]) * speed
    loss = a.power_rf("W", ["F_W"])
    rng = random.Random(2)
    for _ in range(10):
        cg, sg = _circle_point(Fraction(rng.randint(1, 90), 100))
        ca, sa = _circle_point(Fraction(rng.randint(1, 40), 100))
        point = {s["cos_gamma"]: cg, s["sin_gamma"]: sg, s["cos_alpha_n"]: ca, s["sin_alpha_n"]: sa}
        point |= {s["mu"]: Fraction(rng.randint(1, 300), 1000), s["r1"]: Fraction(rng.randint(1, 50), 7)}
        point |= {a.input_action.symbol: 1, a.input_motion.symbol: 1}
        # The normal force opposes the input torque here (|N| = -N): loss = mu N v < 0.
        assert loss.evaluate(point) == (a.ring.rational(s["mu"]) * normal * sliding).evaluate(point) < 0


def test_lossless_limit_and_parallel_limit() -> None:
    """mu -> 0 gives efficiency 1 both ways; crossed helical gears with both helix angles 0
    are parallel spur gears: efficiency 1 (no sliding at the pitch point) and the speed
    ratio -r2 / r1 of a spur pair."""
    worm = _variants(WORM)
    for port in ("A", "B"):
        lossless = {"gamma": sympy.Rational(1, 5), "alpha_n": sympy.Rational(1, 3), "mu": 0, "r1": 1, "r2": 3}
        assert worm.evaluate(lossless, port) == 1
    # Helix angles of 0 lie outside the admissible (0, pi/2): the limit of the formula itself.
    crossed = _variants(CROSSED)
    parallel = {"beta_1": 0, "beta_2": 0, "alpha_n": sympy.Rational(1, 3), "mu": sympy.Rational(1, 10)}
    keyed = {crossed.train.symbols[k]: sympy.sympify(x) for k, x in parallel.items()}
    assert crossed.variants[0].efficiency.subs(completed(keyed, crossed.train.definitions)) == 1
    with pytest.raises(davies_sym.DesignError, match="beta_1 = 0 is outside the admissible range"):
        crossed.evaluate({**parallel, "r1": 1, "r2": 2})
    s = crossed.train.symbols
    ratio = crossed.analysis.speed_ratio().to_expr()
    parallel = ratio.subs({s["cos_beta_1"]: 1, s["sin_beta_1"]: 0, s["cos_beta_2"]: 1, s["sin_beta_2"]: 0})
    assert sympy.simplify(parallel + s["r2"] / s["r1"]) == 0


def test_worm_speed_ratio() -> None:
    """w_worm / w_wheel = -r2 / (r1 tan(gamma)): z2 / z1 for a worm of z1 starts."""
    v = _variants(WORM)
    s = v.train.symbols
    ratio = v.analysis.speed_ratio().to_expr()
    assert sympy.simplify(ratio + s["r2"] * s["cos_gamma"] / (s["r1"] * s["sin_gamma"])) == 0


def test_cli_eval_and_self_locking_exit(tmp_path) -> None:
    path = tmp_path / "worm.yaml"
    path.write_text(WORM)
    args = [str(path), "--quiet", "--eval", "gamma=0.1", "alpha_n=0.35", "mu=0.05", "r1=1", "r2=2"]
    r = run_main(args)
    assert r.returncode == 0, r.describe()
    g, a, mu = 0.1, 0.35, 0.05
    assert float(r.stdout.strip().splitlines()[-1]) == pytest.approx(
        (cos(a) - mu * tan(g)) / (cos(a) + mu / tan(g)), rel=1e-12
    )
    r = run_main([*args[:-3], "mu=0.2", "r1=1", "r2=2", "--input", "B"])
    assert r.returncode == 3, r.describe()
    assert "self-locks" in r.stdout + r.stderr and "Traceback" not in r.stderr
    assert sin(g) > 0  # the angles are radians: 0.1 rad, not 0.1 degrees


@pytest.mark.parametrize(
    ("entry", "path", "words"),
    [
        ("lead_angle: 0", "couplings.W.lead_angle", "strictly between 0 and 90"),
        ("lead_angle: 90", "couplings.W.lead_angle", "strictly between 0 and 90"),
        ("lead_angle: -5", "couplings.W.lead_angle", "strictly between 0 and 90"),
        ("lead_angle: 120", "couplings.W.lead_angle", "strictly between 0 and 90"),
        ("lead_angle: true", "couplings.W.lead_angle", "expected an angle"),
    ],
)
def test_bad_lead_angles_are_refused(tmp_path, entry: str, path: str, words: str) -> None:
    text = WORM.replace("lead_angle: gamma", entry)
    file = tmp_path / "bad.yaml"
    file.write_text(text)
    r = run_main([str(file), "--quiet"])
    assert r.returncode == 2, r.describe()
    assert path in r.stderr and words in r.stderr and "Traceback" not in r.stderr


def test_worm_without_a_wheel_is_refused(tmp_path) -> None:
    for text, words in (
        (WORM.replace("gears: [w, g]", "gears: [w]"), "expected a list of two gear names [worm, wheel]"),
        (WORM.replace("gears: [w, g]", "gears: [w, nowheel]"), "unknown gear"),
        (
            WORM.replace("  W: {type: worm, gears: [w, g], lead_angle: gamma,", "  W: {type: worm, gears: [w, g],"),
            "lead_angle",
        ),
        (WORM.replace("g: {link: 2, radius: r2}", "g: {link: 2, radius: r2, internal: true}"), "external"),
    ):
        file = tmp_path / "bad.yaml"
        file.write_text(text)
        r = run_main([str(file), "--quiet"])
        assert r.returncode == 2, r.describe()
        assert "couplings.W" in r.stderr and words in r.stderr and "Traceback" not in r.stderr


def test_worm_link_with_another_gear_is_refused(tmp_path) -> None:
    text = WORM.replace("  g: {link: 2, radius: r2}", "  g: {link: 2, radius: r2}\n  h: {link: 1, radius: r3}")
    file = tmp_path / "bad.yaml"
    file.write_text(text)
    r = run_main([str(file), "--quiet"])
    assert r.returncode == 2, r.describe()
    assert "couplings.W" in r.stderr and "a link of its own" in r.stderr and "Traceback" not in r.stderr
