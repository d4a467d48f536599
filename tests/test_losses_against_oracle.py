"""Bearing friction, viscous and constant drag losses: the engine's variant formulas
against the independent torque balance of tests/oracle/lossy_balance.py, exactly.

The oracle shares no code with the package: it balances every member's torques with
the tooth forces, the mesh friction couples and each bearing's Coulomb, viscous and
drag torque, finding the power directions by iteration.  The engine's formula of the
variant that holds is evaluated at the oracle's input torque and speed; the two
efficiencies must be equal as fractions, in both directions of power flow.
"""

from __future__ import annotations

from fractions import Fraction as F

import pytest
import sympy
from oracle.balance import Gear, Member, Mesh
from oracle.lossy_balance import Bearing, LossyTrain, solve

import davies_sym
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.evaluation import evaluate

PAIR = """\
name: pair
links: [0, g1, g2]
reference: 0
gears:
  "1": {{link: g1, radius: r1}}
  "2": {{link: g2, radius: r2}}
couplings:
  A: {{type: revolute, links: [0, g1]{g1}}}
  B: {{type: revolute, links: [0, g2]{g2}}}
  C: {{type: mesh, gears: ["1", "2"]}}
ports: {{input: A, output: B}}
"""

PLANETARY = """\
name: planetary
links: [0, s, c, p]
reference: 0
gears:
  S: {{link: s, radius: rs}}
  P: {{link: p, radius: rp}}
  R: {{link: 0, radius: rr, internal: true}}
couplings:
  A: {{type: revolute, links: [0, s]{s}}}
  B: {{type: revolute, links: [0, c]{c}}}
  E: {{type: revolute, links: [c, p]{p}}}
  SP: {{type: mesh, gears: [S, P]}}
  RP: {{type: mesh, gears: [R, P]}}
ports: {{input: A, output: B}}
"""

LAWS = {"rho": "coulomb: rho_{m}", "viscous": "viscous: b_{m}", "drag": "drag: D_{m}"}


def _friction(losses: dict[str, dict[str, F]], member: str) -> str:
    laws = [LAWS[kind].format(m=member) for kind in losses.get(member, {})]
    return f", friction: {{{', '.join(laws)}}}" if laws else ""


def _engine(template: str, members: tuple[str, ...], losses: dict[str, dict[str, F]]):
    text = template.format(**{m: _friction(losses, m) for m in members})
    return derive_variants(davies_sym.loads(text, "train.yaml"))


def _check(
    variants,
    oracle_train: LossyTrain,
    values: dict[str, F],
    losses: dict[str, dict[str, F]],
    port: str,
    oracle_in: str,
    oracle_out: str,
    speed: F,
    load: F,
) -> None:
    result = solve(oracle_train, {oracle_in: speed}, oracle_out, load)
    symbols = variants.train.symbols
    point = {symbols[k]: sympy.Rational(v.numerator, v.denominator) for k, v in values.items()}
    for member, laws in losses.items():
        for kind, v in laws.items():
            name = {"rho": "rho", "viscous": "b", "drag": "D"}[kind]
            point[symbols[f"{name}_{member}"]] = sympy.Rational(v.numerator, v.denominator)
    torque = abs(result.torques[oracle_in])
    point[INPUT_TORQUE] = sympy.Rational(torque.numerator, torque.denominator)
    point[INPUT_SPEED] = sympy.Rational(abs(speed).numerator, abs(speed).denominator)
    got = variants.evaluate(point, input=port)
    want = result.efficiency
    assert got == sympy.Rational(want.numerator, want.denominator), (got, want)


PAIR_CASES = [
    {"g1": {"rho": F(1, 2)}},
    {"g2": {"rho": F(3, 4)}},
    {"g1": {"viscous": F(1, 200)}, "g2": {"viscous": F(1, 100)}},
    {"g2": {"drag": F(2)}},
    {"g1": {"drag": F(1), "rho": F(1, 4)}, "g2": {"viscous": F(1, 50), "rho": F(1, 3)}},
]


@pytest.mark.parametrize("losses", PAIR_CASES, ids=lambda c: "-".join(f"{m}:{'+'.join(v)}" for m, v in c.items()))
@pytest.mark.parametrize("reverse", [False, True], ids=["A_in", "B_in"])
def test_pair_with_bearing_losses(losses: dict[str, dict[str, F]], reverse: bool) -> None:
    r1, r2, eta = F(20), F(50), F(49, 50)
    members = (Member("0"), Member("g1"), Member("g2", None, (F(0), r1 + r2)))
    bearings = tuple(Bearing(m, **laws) for m, laws in losses.items())
    oracle = LossyTrain(
        "pair",
        members,
        (Gear("1", "g1", r1), Gear("2", "g2", r2)),
        (Mesh("C", ("1", "2"), eta),),
        "0",
        {"in": "g1", "out": "g2"},
        bearings,
    )
    variants = _engine(PAIR, ("g1", "g2"), losses)
    values = {"r1": r1, "r2": r2, "eta_C": eta}
    ports = ("B", "out", "in") if reverse else ("A", "in", "out")
    for speed, load in ((F(30), F(45)), (F(7), F(400))):
        # Gear 2 turns against gear 1: a resisting load on either is positive when its input turns forwards.
        _check(variants, oracle, values, losses, *ports, speed, load * r1 / r2 if reverse else load)


PLANETARY_CASES = [
    {"p": {"rho": F(1, 5)}},
    {"p": {"rho": F(1, 3)}, "c": {"drag": F(1, 2)}},
    {"s": {"viscous": F(1, 100)}, "p": {"rho": F(1, 10), "drag": F(1, 4)}},
]


@pytest.mark.parametrize("losses", PLANETARY_CASES, ids=lambda c: "-".join(f"{m}:{'+'.join(v)}" for m, v in c.items()))
@pytest.mark.parametrize("reverse", [False, True], ids=["sun_in", "carrier_in"])
def test_planetary_with_mesh_efficiencies_and_planet_bearing_friction(
    losses: dict[str, dict[str, F]], reverse: bool
) -> None:
    """The issue's case: a planetary with ordinary mesh efficiencies and friction in the
    planet bearing (loaded by the sum of the two tooth forces), sun or carrier driving."""
    rs, rp, eta1, eta2 = F(3), F(2), F(97, 100), F(98, 100)
    members = (Member("0"), Member("s"), Member("c"), Member("p", "c", (F(0), rs + rp)))
    gears = (Gear("S", "s", rs), Gear("P", "p", rp), Gear("R", "0", rs + 2 * rp, True))
    meshes = (Mesh("SP", ("S", "P"), eta1), Mesh("RP", ("R", "P"), eta2))
    bearings = tuple(Bearing(m, **laws) for m, laws in losses.items())
    oracle = LossyTrain("planetary", members, gears, meshes, "0", {"in": "s", "out": "c"}, bearings)
    variants = _engine(PLANETARY, ("s", "c", "p"), losses)
    values = {"rs": rs, "rp": rp, "eta_SP": eta1, "eta_RP": eta2}
    ratio = (2 * rs + 2 * rp) / rs  # sun over carrier speed
    for speed, load in ((F(50), F(20)), (F(9), F(300))):
        if reverse:
            _check(variants, oracle, values, losses, "B", "out", "in", speed, -load / ratio)
        else:
            _check(variants, oracle, values, losses, "A", "in", "out", speed, -load)


LIGHT_LOAD_CASES = [
    {"p": {"drag": F(5)}},
    {"p": {"rho": F(1, 3), "drag": F(2)}, "c": {"drag": F(1)}},
    {"s": {"viscous": F(1, 10)}, "p": {"rho": F(1, 2), "drag": F(3)}},
    {"c": {"rho": F(1, 2)}, "p": {"drag": F(4)}},
]


@pytest.mark.parametrize("losses", LIGHT_LOAD_CASES, ids=lambda c: "-".join(f"{m}:{'+'.join(v)}" for m, v in c.items()))
@pytest.mark.parametrize("reverse", [False, True], ids=["sun_in", "carrier_in"])
def test_light_loads_that_reverse_loaded_forces_take_their_own_variant(
    losses: dict[str, dict[str, F]], reverse: bool
) -> None:
    """Drag in the planet bearing against a light load: below a load of about 19 (sun
    input, drag 5) the drag reverses the ring mesh's tooth force, the oracle's ring mesh
    changes its driving gear (and with Coulomb friction a bearing reaction can turn too).
    --eval takes the variant derived with those forces reversed, whose loaded forces have
    the signs it assumes, and equals the oracle exactly at every load, from 1/10 to 100,
    at a fast and a slow input; the lossless-direction variant would be wrong there."""
    rs, rp, eta1, eta2 = F(3), F(2), F(97, 100), F(98, 100)
    members = (Member("0"), Member("s"), Member("c"), Member("p", "c", (F(0), rs + rp)))
    gears = (Gear("S", "s", rs), Gear("P", "p", rp), Gear("R", "0", rs + 2 * rp, True))
    meshes = (Mesh("SP", ("S", "P"), eta1), Mesh("RP", ("R", "P"), eta2))
    bearings = tuple(Bearing(m, **laws) for m, laws in losses.items())
    oracle = LossyTrain("planetary", members, gears, meshes, "0", {"in": "s", "out": "c"}, bearings)
    variants = _engine(PLANETARY, ("s", "c", "p"), losses)
    symbols = variants.train.symbols
    point = {
        symbols[k]: sympy.Rational(v.numerator, v.denominator)
        for k, v in {"rs": rs, "rp": rp, "eta_SP": eta1, "eta_RP": eta2}.items()
    }
    for member, laws in losses.items():
        for kind, v in laws.items():
            name = {"rho": "rho", "viscous": "b", "drag": "D"}[kind]
            point[symbols[f"{name}_{member}"]] = sympy.Rational(v.numerator, v.denominator)
    port, oracle_in, oracle_out = ("B", "out", "in") if reverse else ("A", "in", "out")
    reversed_seen = 0
    for load in (F(1, 10), F(1), F(5), F(10), F(30), F(100)):
        for speed in (F(50), F(1, 2)):
            # The carrier turns 5 times slower than the sun: its load is 5 times larger.
            result = solve(oracle, {oracle_in: speed}, oracle_out, -load / 5 if reverse else -load)
            torque = abs(result.torques[oracle_in])
            values = point | {
                INPUT_TORQUE: sympy.Rational(torque.numerator, torque.denominator),
                INPUT_SPEED: sympy.Rational(speed.numerator, speed.denominator),
            }
            truth = sympy.Rational(result.efficiency.numerator, result.efficiency.denominator)
            answer = evaluate(variants, values, port)
            assert answer.efficiency == truth, (load, speed)
            if answer.variant.reversed_forces:
                reversed_seen += 1
                lossless = next(v for v in variants.variants if v.input == port and not v.reversed_forces)
                assert lossless.efficiency.subs(values) != truth
    # With the carrier driving, its torque overcomes the planet's drag before the sun mesh
    # could reverse: only the sun input reaches the reversed variants.
    assert reversed_seen >= 2 if not reverse else reversed_seen == 0
