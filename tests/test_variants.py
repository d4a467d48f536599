"""Every turning-condition variant in ordinary efficiencies (Laus Table 5, Chen Table 4.1,
Chen example 1), and the two independent routes (Davies, Chen's virtual-power balance)
agreeing on catalog trains and on trains described here."""

from __future__ import annotations

import os
import random

import pytest
import sympy

import davies_sym
from davies_sym.efficiency.parameter_domain import ParameterDomain, efficiency_symbols
from davies_sym.efficiency.variants import derive_variants
from davies_sym.efficiency.virtual_power_balance import balance_at, virtual_power_balance
from davies_sym.errors import MissingValuesError, NotCoveredError
from davies_sym.losses.definitions import completed

from conftest import ROOT, S, catalog_path, catalog_trains, equal, read_text

r1, r2, r3, r4 = (S(f"r{i}") for i in range(1, 5))
eC, eD = S("eta_C", "efficiency"), S("eta_D", "efficiency")
PLANAR = {r4: r2 - r1 + r3}
DATA = os.path.join(ROOT, "tests", "data")


def tuplin_variants():
    return derive_variants(davies_sym.load(catalog_path("tuplin")))


def test_tuplin_table5_all_four_variants_exact():
    """Laus Table 5, eqs. (76)-(79), with eta_13 = eta_31 = eta_C, eta_42 = eta_24 = eta_D
    and the condition r1 < r2 (derived as the sign of r2 - r1 on r1 - r3 = r2 - r4)."""
    vs = tuplin_variants()
    (c1,) = vs.conditions
    assert equal(c1.simplified, r2 - r1)
    k = eC * eD
    table = {
        ("A", 1): k * (r1 * r4 - r2 * r3) / (r1 * r4 - k * r2 * r3),  # (76)
        ("A", -1): (r2 * r3 - r1 * r4) / (r2 * r3 - k * r1 * r4),  # (77)
        ("B", 1): (r2 * r3 - k * r1 * r4) / (r2 * r3 - r1 * r4),  # (78)
        ("B", -1): (r1 * r4 - k * r2 * r3) / (k * (r1 * r4 - r2 * r3)),  # (79)
    }
    assert len(vs.variants) == 4
    for v in vs.variants:
        assert equal(v.efficiency, table[(v.input, v.signs["c1"])], PLANAR), v.number
        assert v.feasible and v.derivative_check == "positive"
    # Gear 1 drives gear 3 and gear 4 drives gear 2 for A input and r1 < r2 (eqs. (69)-(70)).
    first = vs.variant_for({r1: 40, r2: 60, r3: 15}, "A")
    assert dict(first.first_drives) == {"C": True, "D": False}


def test_tuplin_published_numbers_and_wrong_variant():
    """Laus p. 1247-1256: r = 40, 60, 15, 35 mm, eta = 0.99: eq. (76) gives 0.9462; the
    wrong variant (78) would give 0.9443."""
    vs = tuplin_variants()
    values = {r1: 40, r2: 60, r3: 15, r4: 35, eC: sympy.Rational(99, 100), eD: sympy.Rational(99, 100)}
    assert round(float(vs.evaluate(values)), 4) == 0.9462
    wrong = next(v for v in vs.variants if v.input == "B" and v.signs["c1"] == 1)
    assert round(float(wrong.efficiency.subs(values)), 4) == 0.9443


def test_values_that_leave_the_efficiency_open_are_named():
    """MissingValuesError (an InputError: exit status 2) names what a condition or the
    formula still needs; the documentation shows such a published number as not evaluated."""
    vs = tuplin_variants()
    with pytest.raises(MissingValuesError, match=r"missing values for eta_C, eta_D, r1$"):
        vs.evaluate({r2: 60, r3: 15})
    with pytest.raises(MissingValuesError, match=r"missing values for eta_C, eta_D$"):
        vs.evaluate({r1: 40, r2: 60, r3: 15, r4: 35})
    assert issubclass(MissingValuesError, davies_sym.InputError)


def test_chen_angeles_form_for_r1_greater_than_r2():
    """Laus after Table 5: eq. (77) = 1 / ((l1 + l2 - l1 l2)(k - 1) + 1), l1 = 1 - eta_31,
    l2 = 1 - eta_24, k = r2 r3 / (r2 r3 - r1 r4)."""
    vs = tuplin_variants()
    v = next(v for v in vs.variants if v.input == "A" and v.signs["c1"] == -1)
    l1, l2 = 1 - eC, 1 - eD
    k = r2 * r3 / (r2 * r3 - r1 * r4)
    assert equal(v.efficiency, 1 / ((l1 + l2 - l1 * l2) * (k - 1) + 1), PLANAR)


def tooth_train(na: int, nb: int, nc: int, nd: int) -> davies_sym.Train:
    """Chen Fig. 4.6 with Chen's names: pinion A meshes annulus B (mesh C of Laus),
    pinion C meshes annulus D (mesh D); modules chosen so the centre distances match
    (Chen footnote 2, Laus section 3.4.1.6)."""
    m1, m2 = nd - nc, nb - na
    return davies_sym.loads(
        f"""
name: Tuplin train, Chen Table 4.1 ({na}/{nb}/{nc}/{nd})
links: [1, 2, 3/4, 5]
reference: 1
gears:
  1: {{link: 1, teeth: {nb}, module: {m1}, internal: true}}
  2: {{link: 2, teeth: {nd}, module: {m2}, internal: true}}
  3: {{link: 3/4, teeth: {na}, module: {m1}}}
  4: {{link: 3/4, teeth: {nc}, module: {m2}}}
couplings:
  A: {{type: revolute, links: [1, 5]}}
  B: {{type: revolute, links: [1, 2]}}
  C: {{type: mesh, gears: [1, 3]}}
  D: {{type: mesh, gears: [2, 4]}}
  E: {{type: revolute, links: [3/4, 5]}}
ports: {{input: A, output: B}}
""",
        "chen-table-4.1",
    )


@pytest.mark.parametrize(
    ("teeth", "published"), [((16, 34, 15, 32), 0.223), ((48, 102, 45, 96), 0.462), ((96, 119, 90, 112), 0.824)]
)
def test_chen_table_4_1(teeth, published):
    """Chen 2006 Table 4.1 ('This work' column): lambda = (1/N_pinion - 1/N_gear)/5,
    eta = 1 - lambda per mesh, carrier input."""
    na, nb, nc, nd = teeth
    train = tooth_train(*teeth)
    vs = derive_variants(train)
    eta1 = 1 - (sympy.Rational(1, na) - sympy.Rational(1, nb)) / 5
    eta2 = 1 - (sympy.Rational(1, nc) - sympy.Rational(1, nd)) / 5
    value = vs.evaluate({eC: eta1, eD: eta2}, "A")
    assert round(float(value), 3) == published
    assert value == virtual_power_balance(train, {eC: eta1, eD: eta2}).efficiency


def test_planetary_simple_chen_example_1():
    """Chen section 4.7: eta = (gamma + 1)(1 - lambda) / (gamma + 1 - lambda), gamma = N_A / N_B."""
    vs = derive_variants(davies_sym.load(catalog_path("planetary_simple")))
    rA, rB, eG = S("rA"), S("rB"), S("eta_G", "efficiency")
    gamma, lam = rA / rB, 1 - eG
    (forward,) = [v for v in vs.variants if v.input == "I"]
    assert equal(forward.efficiency, (gamma + 1) * (1 - lam) / (gamma + 1 - lam))
    assert forward.derivative_check == "positive"


def test_simple_pair_eqs36_37():
    """Laus eqs. (36)-(37): P_B = -eta_12 T_A t_A with A as input, and with B as input
    P_B = -T_A t_A / eta_21: the efficiency is the ordinary efficiency both ways."""
    vs = derive_variants(davies_sym.load(catalog_path("simple_pair")))
    assert [(v.input, v.efficiency) for v in vs.variants] == [("A", eC), ("B", eC)]
    assert [dict(v.first_drives) for v in vs.variants] == [{"C": True}, {"C": False}]


def _both_routes(train: davies_sym.Train, points: int = 6, seed: int = 7) -> int:
    """Compare the Davies variant and the virtual-power balance at sampled points."""
    vs = derive_variants(train)
    rng = random.Random(seed)
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    etas = efficiency_symbols(train)
    checked = 0
    for point in domain.samples(points, seed=seed):
        values = {**point, **{e: sympy.Rational(rng.randint(90, 99), 100) for e in etas}}
        for port in (train.ports.input, train.ports.output):
            try:
                davies = vs.evaluate(values, port)
            except NotCoveredError as locked:
                # Self-locked: both refuse, with the same reason; which drivers give the value
                # is moot (the engine keeps the lossless ones where no variant agrees with its
                # own flow), the balance's own value is not in (0, 1] either.
                assert "self-locks" in str(locked)
                with pytest.raises(NotCoveredError, match="self-locks"):
                    virtual_power_balance(train, values, port)
                assert balance_at(train, values, port).efficiency <= 0, (train.name, port, values)
                continue
            chen = virtual_power_balance(train, values, port)
            assert davies == chen.efficiency, (train.name, port, values)
            # Which gear drives matters only where virtual power crosses the mesh.
            loaded = {m for m, loss in chen.losses.items() if loss != 0}
            davies_roles = dict(vs.variant_for(values, port).first_drives)
            assert {m: davies_roles[m] for m in loaded} == {m: chen.first_drives[m] for m in loaded}
            assert chen.input_power + chen.output_power == sum(chen.losses.values())
            checked += 1
    return checked


#: Chen's balance takes each mesh's ordinary efficiency; a skew mesh has a sliding friction
#: coefficient instead, and is checked against the statics of tests/oracle/skew_pair.py
#: (tests/test_skew_axes.py) and the product of the stages (catalog/worm_planetary.yaml).
SKEW = {"crossed_helical", "worm_drive", "worm_planetary"}
#: A mesh efficiency from the tooth geometry (Laus App. A) is given by its flank friction
#: coefficient, a transcendental function of it; Chen's balance is exact in rationals only:
#: `test_tooth_geometry_pair_efficiency_is_its_mesh_efficiency` checks it instead.
TOOTH_GEOMETRY = {"buckingham_pair"}
#: Chen's balance covers gear pairs, bearings and lossless sliders; the rack and its pressed
#: guide are checked against their hand derivation (tests/test_rack_pinion.py), where the
#: balance's refusal is checked too, and the chain-driven hub against its own
#: (tests/test_bicycle_hub.py).
OUTSIDE_BALANCE = {"rack_pinion", "bicycle_hub[low]", "bicycle_hub[normal]", "bicycle_hub[high]"}


@pytest.mark.parametrize(
    ("name", "train"),
    # Humpage and the Ravigneaux states take 3-8 s each: the slow tier checks them.
    [
        pytest.param(n, t, marks=pytest.mark.slow) if n.startswith(("humpage", "ravigneaux")) else (n, t)
        for n, t in catalog_trains()
        if n not in SKEW | TOOTH_GEOMETRY | OUTSIDE_BALANCE
    ],
    ids=[n for n, _ in catalog_trains() if n not in SKEW | TOOTH_GEOMETRY | OUTSIDE_BALANCE],
)
def test_both_routes_agree_on_every_catalog_train(name, train):
    """Every catalog train (bevel and face-gear trains too) and every operating state of
    the multi-speed sets, but the skew-axis ones (`SKEW`)."""
    assert _both_routes(train) > 0, name


def test_tooth_geometry_pair_efficiency_is_its_mesh_efficiency():
    """Laus eqs. (36)-(37): a single external pair's efficiency is the ordinary efficiency
    of its mesh in the driving direction; here that efficiency comes from the tooth
    geometry (App. A, eqs. (134)-(136)) at the flank friction coefficient mu, so the value
    at mu equals the definition's own value, both inputs."""
    train = davies_sym.load(catalog_path("buckingham_pair"))
    vs = derive_variants(train)
    defined = {str(d.symbol): d.symbol for d in train.definitions}
    rng = random.Random(4)
    for _ in range(3):
        mu = sympy.Rational(rng.randint(5, 60), 1000)
        values = {"mu": mu, **{n: v for n, v in train.published_design(None).items() if n != "mu"}}
        keyed = completed({train.symbols[k]: sympy.sympify(v) for k, v in values.items()}, train.definitions)
        for port, eta in (("A", "eta_C_1_2"), ("B", "eta_C_2_1")):
            assert sympy.N(vs.evaluate(values, port) - keyed[defined[eta]], 40) == 0


OWN_TRAINS = ["double_pinion", "two_carriers", "idler_internal", "dependent_conditions"]


def own(name: str) -> davies_sym.Train:
    """Trains described here (tests/data): not from the references."""
    return davies_sym.load(os.path.join(DATA, f"{name}.yaml"))


@pytest.mark.parametrize("name", OWN_TRAINS)
def test_both_routes_agree_on_trains_described_here(name):
    """Planet-planet mesh, two carriers (each mesh measured from its own), an internal
    idler: exact agreement of efficiency and driving gears, and the power balance."""
    train = own(name)
    assert _both_routes(train) > 0
    vs = derive_variants(train)
    for v in vs.variants:
        if v.feasible:
            assert v.derivative_check == "positive", (v.number, v.derivative_check)


def test_two_carriers_are_found_per_mesh():
    vs = derive_variants(own("two_carriers"))
    assert {r.coupling: r.flow.carrier for r in vs.roles} == {"C": "c1", "D": "c1", "E": "c2", "F": "c2"}


def test_ideal_limit_and_self_locking():
    """Every variant -> 1 when every mesh efficiency -> 1; Tuplin driven from the output
    self-locks for some admissible radii (the sampled point proves it)."""
    vs = tuplin_variants()
    for v in vs.variants:
        assert sympy.cancel(v.efficiency.subs({eC: 1, eD: 1})) == 1
    back = [v for v in vs.variants if v.input == "B"]
    assert all(v.self_locking_point is not None for v in back)
    for v in back:
        assert v.efficiency_rf.evaluate(v.self_locking_point) <= 0


def test_two_efficiency_symbols_per_mesh():
    """`efficiency: [eta_12, eta_21]`: eta_12 when gear 1 drives (A input), eta_21 when
    gear 2 drives (B input), Laus eqs. (32) and (34)."""
    text = read_text(catalog_path("simple_pair")).replace(
        "friction: {coulomb: zeta_C}}", "friction: {coulomb: zeta_C}, efficiency: [eta_12, eta_21]}"
    )
    vs = derive_variants(davies_sym.loads(text, "pair-two-etas"))
    e12, e21 = S("eta_12", "efficiency"), S("eta_21", "efficiency")
    assert [(v.input, v.efficiency) for v in vs.variants] == [("A", e12), ("B", e21)]


def test_unreachable_condition_combination_is_proved_empty_and_not_derived():
    """Stage 2 has annuli ra1 and rb1 + dd: its condition dd - ra1 + rb1 is positive
    whenever stage 1's rb1 - ra1 is (dd > 0), so no design has (c1 > 0, c2 < 0).  That
    combination is proved empty from exactly these three facts and listed without a
    formula, for both inputs, keeping its number; the other three regions are derived."""
    vs = derive_variants(own("dependent_conditions"))
    c1, c2 = vs.conditions
    assert equal(c1.expression, S("rb1") - S("ra1")) and equal(c2.expression, S("dd") - S("ra1") + S("rb1"))
    assert len(vs.variants) == 6 and all(v.feasible for v in vs.variants)
    assert [v.number for v in vs.listed] == list(range(1, 9))
    assert {(v.input, v.signs["c1"], v.signs["c2"]) for v in vs.excluded} == {("A1", 1, -1), ("B2", 1, -1)}
    for v in vs.excluded:
        assert {(str(r.expression), r.relation) for r in v.conditions} == {
            (str(c1.expression), ">="),
            (str(c2.expression), "<"),
        }
        assert [(r.expression, r.relation) for r in v.facts] == [(S("dd"), ">")]
    for v in vs.variants:
        assert v.derivative_check == "positive"


def test_partial_derivative_rule_flags_a_wrong_power_direction():
    """Laus section 3.6.2: with the right driver in every mesh the efficiency increases
    with each mesh efficiency; a variant whose mesh C runs the wrong way (eta_C where
    1/eta_C belongs) has a negative partial derivative in eta_C, and the check says so."""
    from dataclasses import replace

    from davies_sym.efficiency.variant_checks import checked_variant

    vs = tuplin_variants()
    right = vs.variants[0]
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    (c1,) = vs.conditions
    region = [p for p in domain.samples(60, seed=3) if domain.value(c1.expression, p) * right.signs[c1.name] > 0]
    assert region
    etas = efficiency_symbols(vs.train)
    ring = right.efficiency_rf.ring
    wrong = replace(right, efficiency_rf=ring.rational(right.efficiency.subs(eC, 1 / eC)))
    args = (region, etas, vs.analysis, vs.conditions, random.Random(1))
    assert checked_variant(right, *args).derivative_check == "positive"
    assert checked_variant(wrong, *args).derivative_check == "failed: eta_C"
