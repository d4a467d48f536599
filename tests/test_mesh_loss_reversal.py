"""Mesh losses that reverse a small mesh power near a turning condition.

The turning conditions are the signs of the lossless mesh powers (Laus eqs. (86)-(88)).
Near one, the power through a mesh is small, and the friction in the other meshes can
turn it round: the lossless rule then names the wrong driving gear and its formula is a
wrong number.  The engine takes, among its variants, the one whose driving gears agree
with the power flow of its own lossy solution; the oracle (tests/oracle/balance.py, no
code shared) tries every assignment of driving gears and keeps the consistent one.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy
from oracle.balance import solve
from oracle.compare import OK, compare
from oracle.random_trains import generate, spelling

import davies_sym
from davies_sym.efficiency.variants import derive_variants

#: A Wolfrom set with the sun held, the carrier free, ring 2 in and ring 1 out (found by
#: tests/test_properties.py): rs 10, rp1 31/2, rp2 20, eta 0.9227, 0.9155, 0.9036.  The
#: lossless power through the sun mesh C is 0.025 of the 0.22 entering at E: S and P1
#: swap roles once the losses of D and E are counted.
WOLFROM = generate("wolfrom", 999999)


@pytest.mark.parametrize("name", ["catalog", "numeric+reversed", "reversed+renamed"])
def test_the_driving_gear_follows_the_lossy_power_flow(name: str) -> None:
    """Every spelling (symbolic radii with a turning condition; numbers, where the lossless
    rule fixes the direction outright; gears written the other way round): both inputs
    equal the oracle exactly."""
    outcomes = compare(WOLFROM, spelling(WOLFROM, name))
    bad = [f"{o.case}: {o.kind} {o.detail} engine {o.engine} oracle {o.oracle}" for o in outcomes if o.kind != OK]
    assert not bad, "\n".join(bad)
    assert sum(o.quantity == "efficiency" for o in outcomes) == 2


def test_the_lossless_rule_alone_would_be_wrong_here() -> None:
    """The oracle's consistent assignment has S driving P1, which the lossless flow does
    not; the engine's choice is the variant with those drivers, and Laus's variant for the
    lossless sign differs by more than 1e-4 (a silent wrong number before)."""
    sp = spelling(WOLFROM, "catalog")
    (state,) = WOLFROM.oracle_states()  # the sun held
    oracle = solve(WOLFROM.oracle(), "A", state)
    lossless = solve(WOLFROM.oracle(), "A", state, lossless=True)
    assert oracle.first_drives["C"] != lossless.first_drives["C"]
    vs = derive_variants(davies_sym.loads(sp.yaml, "wolfrom.yaml"))
    values = {k: sympy.Rational(v.numerator, v.denominator) for k, v in sp.values.items()}
    chosen = vs.variant_for(values, "A")
    assert chosen.first_drives["C"] == oracle.first_drives["C"]
    assert Fraction(str(vs.evaluate(values, "A"))) == oracle.efficiency
    # The chosen variant lies in the design's own region, with C reversed by the losses;
    # Laus's variant is that region's lossless one.
    assert chosen.reversed_forces == {"C"}
    laus = next(v for v in vs.variants if v.input == "A" and v.signs == chosen.signs and not v.reversed_forces)
    named = {vs.train.symbols[k]: v for k, v in values.items()}
    assert abs(float(laus.efficiency.subs(named)) - float(oracle.efficiency)) > 1e-4
