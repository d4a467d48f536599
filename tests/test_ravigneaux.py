"""The Ravigneaux set of the ZF 3HP12 drawn in 2-D (planet-planet mesh off the centre line).

Published for the ZF 3HP12 (the `source` of catalog/ravigneaux.yaml): suns 25 and 32,
ring 64 and the ratios reverse -2.000, 1st 2.560, 2nd 1.520, 3rd 1.000.  The engine's
kinematics must equal the textbook ratio formulas of every state, and the efficiency
must not depend on the placement direction of the planets.
"""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
import sympy
from hand import surds
from hand.surds import root
from oracle import balance
from oracle.balance import Gear, Member, Mesh, State, TrainSpec, solve

import davies_sym
from davies_sym.algebra.radicals import restore
from davies_sym.efficiency.variants import derive_variants
from davies_sym.geometry import train_layout
from davies_sym.topology.states import train_in_state

from conftest import catalog_path, equal, read_text

TRAIN = davies_sym.load(catalog_path("ravigneaux"))
SYM = TRAIN.symbols
rs1, rs2, rr = SYM["rs1"], SYM["rs2"], SYM["rr"]
ZF = {rs1: 25, rs2: 32, rr: 64, SYM["rpl"]: 16, SYM["rps"]: 16}
TEXTBOOK = {
    "reverse": (-rr / rs2, sympy.Rational(-2)),
    "first": (rr / rs1, sympy.Rational(256, 100)),
    "second": (rr * (rs1 + rs2) / (rs1 * (rs2 + rr)), sympy.Rational(152, 100)),
    "third": (sympy.Integer(1), sympy.Integer(1)),
}


@pytest.mark.parametrize("state", list(TEXTBOOK))
def test_state_ratios(state):
    """Every state's speed ratio equals the textbook formula (Willis, carrier held:
    rr/rs1 from the small sun through both planets, -rr/rs2 from the large sun) and the
    published ratio at 25, 32, 64 teeth."""
    train = train_in_state(TRAIN, TRAIN.state(state))
    ratio = derive_variants(train).analysis.speed_ratio().to_expr()
    formula, published = TEXTBOOK[state]
    assert equal(ratio.subs(SYM["rpl"], (rr - rs2) / 2), formula)
    assert ratio.subs(ZF) == published


def test_long_and_short_planets_are_off_the_centre_line():
    """The short planet closes the triangle small sun - short planet - long planet:
    centre distances 41, 32 and 48 (16-tooth planets), exactly."""
    layout = train_layout(TRAIN)
    (constraint,) = layout.constraints  # ring = large sun + two long-planet radii
    assert equal(constraint.expression, rs2 + 2 * SYM["rpl"] - rr) or equal(
        constraint.expression, rr - rs2 - 2 * SYM["rpl"]
    )
    centre = {
        g: sympy.Matrix([restore(sympy.sympify(x), layout.radicals).subs(ZF) for x in layout.gear_centres[g][:2]])
        for g in ("S1", "PS", "PL")
    }
    assert sympy.radsimp((centre["PS"] - centre["S1"]).norm()) == 41
    assert sympy.radsimp((centre["PL"] - centre["PS"]).norm()) == 32
    assert sympy.radsimp((centre["PL"] - centre["S1"]).norm()) == 48
    assert sympy.radsimp(centre["PL"][0]) != 0


@pytest.mark.slow
@pytest.mark.parametrize("placement", ["[3, 4]", "30", "[-1, 0]"])
def test_efficiency_does_not_depend_on_the_placement(placement):
    """Second gear (small sun in, large sun held, both planet sets working): the same
    variants, formulas and conditions whichever direction the planets are drawn in."""
    text = read_text(catalog_path("ravigneaux")).replace("placement: [0, 1]", f"placement: {placement}")
    turned = davies_sym.loads(text, "ravigneaux-turned")
    base = derive_variants(train_in_state(TRAIN, TRAIN.state("second")))
    other = derive_variants(train_in_state(turned, turned.state("second")))
    assert [c.expression for c in other.conditions] == [c.expression for c in base.conditions]
    assert len(other.variants) == len(base.variants)
    for a, b in zip(base.variants, other.variants, strict=True):
        assert (a.input, a.signs) == (b.input, b.signs)
        assert equal(a.efficiency, b.efficiency)
    rng = random.Random(5)
    values = {**ZF, **{s: sympy.Rational(rng.randint(90, 99), 100) for n, s in SYM.items() if n.startswith("eta")}}
    assert base.evaluate(values) == other.evaluate(values)


def zf_second_gear_oracle(eta: Fraction, side: int = 1) -> TrainSpec:
    """The catalog's Ravigneaux set at the ZF radii as a description for the independent
    oracle (tests/oracle/balance.py), in second gear (the large sun braked).

    Members 0 (housing), s1, s2, c, r on the main axis; the short planet ps on c at
    (0, 41) = rs1 + rps from the axis; the long planet pl on c at (x, y) with
    x^2 + y^2 = 48^2 (rs2 + rpl = rr - rpl) and x^2 + (y - 41)^2 = 32^2 (rps + rpl):
    y = (48^2 - 32^2 + 41^2) / 82 = 2961/82, x = sqrt(48^2 - y^2) = 165 sqrt(247)/82
    (``side`` -1: the mirror image).  The triangle 41, 32, 48 has an irrational area, so
    no rational layout exists: the coordinates are exact numbers of Q(sqrt(247))."""
    x, y = side * root(247, Fraction(165, 82)), Fraction(2961, 82)
    return TrainSpec(
        "ZF 3HP12 Ravigneaux",
        (
            Member("0"),
            Member("s1"),
            Member("s2"),
            Member("c"),
            Member("r"),
            Member("ps", "c", (Fraction(0), Fraction(41))),
            Member("pl", "c", (x, y)),
        ),
        (
            Gear("S1", "s1", Fraction(25)),
            Gear("S2", "s2", Fraction(32)),
            Gear("PS", "ps", Fraction(16)),
            Gear("PL", "pl", Fraction(16)),
            Gear("R", "r", Fraction(64), internal=True),
        ),
        (
            Mesh("G1", ("S1", "PS"), eta),
            Mesh("G2", ("PS", "PL"), eta),
            Mesh("G3", ("S2", "PL"), eta),
            Mesh("G4", ("R", "PL"), eta),
        ),
        "0",
        {"A": "s1", "B": "s2", "C": "c", "D": "r"},
        "A",
        "D",
        (State("second", "A", "D", brake=("s2",)),),
    )


def test_second_gear_efficiency_both_routes(monkeypatch):
    """A prediction (the planet teeth are chosen, no efficiency is published): every mesh
    at 0.98 gives 861221/890625 = 96.698 % in second gear.  The virtual-power balance on
    the same 2-D layout gives the same number, and so does the independent oracle
    (per-member torque and force balance, Willis kinematics, carrier-frame ordinary
    efficiency; no code shared with the engine) on the set described by hand in
    :func:`zf_second_gear_oracle`: speed ratio 38/25 = 1.52 (the published 2nd gear),
    small sun driving the short planet and the short planet the long one, the long planet
    driving the large sun and the ring, exactly 861221/890625 on either side of the centre
    line.  The oracle works in Q(sqrt(247)) (tests/hand/surds.py supplies the field and
    its linear solver); the irrational parts cancel and its answer is a Fraction."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = train_in_state(TRAIN, TRAIN.state("second"))
    values = {**ZF, **{s: sympy.Rational(98, 100) for n, s in SYM.items() if n.startswith("eta")}}
    davies = derive_variants(train).evaluate(values)
    assert davies == virtual_power_balance(train, values).efficiency
    # The oracle's own solver converts its entries to Fraction; over Q(sqrt(247)) it
    # takes the same elimination without that conversion.
    monkeypatch.setattr(balance, "solve_linear", surds.solve_linear)
    for side in (1, -1):
        oracle = solve(zf_second_gear_oracle(Fraction(98, 100), side), state="second")
        assert isinstance(oracle.efficiency, Fraction) and isinstance(oracle.speed_ratio, Fraction)
        assert oracle.speed_ratio == Fraction(152, 100)
        assert oracle.first_drives == {"G1": True, "G2": True, "G3": False, "G4": False}
        assert sum(oracle.losses.values()) == oracle.power_in + oracle.power_out
        assert oracle.efficiency == Fraction(861221, 890625)
        assert davies == sympy.Rational(oracle.efficiency.numerator, oracle.efficiency.denominator)
