"""The Ravigneaux set of the ZF 3HP12 drawn in 2-D (planet-planet mesh off the centre line).

Published for the ZF 3HP12 (the `source` of catalog/ravigneaux.yaml): suns 25 and 32,
ring 64 and the ratios reverse -2.000, 1st 2.560, 2nd 1.520, 3rd 1.000.  The engine's
kinematics must equal the textbook ratio formulas of every state, and the efficiency
must not depend on the placement direction of the planets.
"""

from __future__ import annotations

import random

import pytest
import sympy

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
    assert equal(constraint.expression, rs2 + 2 * SYM["rpl"] - rr) or equal(constraint.expression,
                                                                            rr - rs2 - 2 * SYM["rpl"])
    centre = {g: sympy.Matrix([restore(sympy.sympify(x), layout.radicals).subs(ZF) for x in layout.gear_centres[g][:2]])
              for g in ("S1", "PS", "PL")}
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


def test_second_gear_efficiency_both_routes():
    """A prediction (planet teeth chosen): every mesh at 0.98 gives 96.70 % in second
    gear; the virtual-power balance on the same 2-D layout gives the same number."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = train_in_state(TRAIN, TRAIN.state("second"))
    values = {**ZF, **{s: sympy.Rational(98, 100) for n, s in SYM.items() if n.startswith("eta")}}
    davies = derive_variants(train).evaluate(values)
    assert davies == virtual_power_balance(train, values).efficiency
    assert abs(float(davies) - 0.966985) < 1e-6
