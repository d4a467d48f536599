"""Regions of turning-condition signs that no admissible design reaches are proved empty
and their variants are not built.

The prover (`davies_sym.algebra.linear_regions`) is checked against scipy's linear
programming on random systems and against random points on random products; its use on
the Ravigneaux set against the placement's triangle inequality, written here from the
drawing, not from the package's layout.
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linprog

import davies_sym
from davies_sym.algebra.linear_regions import Inequality, Requirement, empty_region, feasible
from davies_sym.efficiency.parameter_domain import ParameterDomain
from davies_sym.efficiency.variant_result import ExcludedVariant
from davies_sym.efficiency.variants import derive_variants
from davies_sym.topology.states import train_in_state

from conftest import ROOT, catalog_path, catalog_trains

X = sympy.symbols("x0:3")
ZF_SECOND = ["rs1=25", "rs2=32", "rps=16", "rr=64", "eta_1=0.98", "eta_2=0.98", "eta_3=0.98", "eta_4=0.98"]

coefficient = st.integers(-3, 3)
row = st.tuples(st.lists(coefficient, min_size=3, max_size=3), st.integers(-4, 4), st.booleans())


def _lp_feasible(rows: list[tuple[list[int], int, bool]]) -> bool | None:
    """Feasibility by linear programming (scipy, floating point): maximise the slack t of
    the strict rows, A x + b >= t; None where t is too close to zero to tell."""
    a_ub, b_ub = [], []
    for coefficients, constant, strict in rows:
        a_ub.append([-c for c in coefficients] + [1 if strict else 0])
        b_ub.append(constant)
    bounds = [(None, None)] * 3 + [(None, 1)]
    result = linprog([0, 0, 0, -1], A_ub=a_ub, b_ub=b_ub, bounds=bounds, method="highs")
    if result.status == 2:
        return False
    assert result.status == 0
    if not any(strict for _, _, strict in rows):
        return True
    t = -result.fun
    return None if abs(t) < 1e-9 else t > 0


@given(st.lists(row, min_size=1, max_size=7))
def test_fourier_motzkin_agrees_with_linear_programming(rows):
    """Exact elimination and scipy's LP give the same answer on every random system of
    strict and non-strict inequalities in three variables (up to LP's rounding at t = 0)."""
    system = [
        Inequality(tuple((x, Fraction(c)) for x, c in zip(X, cs, strict=True)), Fraction(b), strict)
        for cs, b, strict in rows
    ]
    expected = _lp_feasible(rows)
    if expected is not None:
        assert feasible(system) is expected


linear = st.tuples(st.lists(st.integers(-2, 2), min_size=3, max_size=3), st.integers(-2, 2))
product = st.lists(linear, min_size=1, max_size=3)


@given(st.lists(st.tuples(product, st.sampled_from([">", ">=", "<"])), min_size=1, max_size=4))
def test_a_proof_of_emptiness_is_never_contradicted_by_a_point(requirements):
    """Where a region of random products of linear factors is proved empty, no random
    point satisfies every requirement (evaluated in floating point, apart from the
    prover)."""
    reqs = []
    for factors, relation in requirements:
        expr = sympy.Mul(*(sum(c * x for c, x in zip(cs, X, strict=True)) + b for cs, b in factors))
        reqs.append(Requirement(expr, relation))
    if empty_region(reqs) is None:
        return
    rng = np.random.default_rng(0)
    points = rng.uniform(-5, 5, size=(4000, 3))
    functions = [sympy.lambdify(X, r.expression, "numpy") for r in reqs]
    holds = np.ones(len(points), dtype=bool)
    for r, f in zip(reqs, functions, strict=True):
        value = np.broadcast_to(f(*points.T), (len(points),))
        holds &= {">": value > 0, ">=": value >= 0, "<": value < 0}[r.relation]
    assert not holds.any()


def test_a_nonlinear_factor_is_left_out_not_guessed():
    """x^2 + y^2 < 1 is not linear: it takes no part in a proof, so x > 1 and
    x^2 + y^2 < 1 are not proved empty (they are, but not by this prover), while x > 1
    and x < 0 are."""
    x, y = sympy.symbols("x y")
    assert empty_region([Requirement(x - 1, ">"), Requirement(x**2 + y**2 - 1, "<")]) is None
    proof = empty_region([Requirement(x - 1, ">"), Requirement(x**2 + y**2 - 1, "<"), Requirement(x, "<")])
    assert proof is not None
    assert {r.expression for r in proof.core} == {x - 1, x}


def test_a_boundary_point_keeps_its_region():
    """x >= 0 with x <= 0 (x = 0) is not empty: the sign +1 of a turning condition
    includes its boundary, where the variant is still chosen."""
    x = sympy.Symbol("x")
    assert empty_region([Requirement(x, ">="), Requirement(-x, ">=")]) is None
    assert empty_region([Requirement(x, ">="), Requirement(-x, ">")]) is not None


RAVIGNEAUX = davies_sym.load(catalog_path("ravigneaux"))
SECOND = train_in_state(RAVIGNEAUX, RAVIGNEAUX.state("second"))


def _triangle_closes(rs1: float, rs2: float, rps: float, rr: float) -> bool:
    """The ZF 3HP12 drawing: small sun and short planet at centre distance rs1 + rps, long
    planet on the circle rr - rpl = rs2 + rpl, the planets at rps + rpl; the three
    centres must form a triangle, and every radius is positive."""
    rpl = (rr - rs2) / 2
    a, b, c = rs1 + rps, rs2 + rpl, rps + rpl
    return min(rs1, rs2, rps, rpl) > 0 and abs(a - b) < c < a + b


def test_ravigneaux_second_gear_small_sun_never_outgrows_the_ring():
    """2nd gear of the ZF 3HP12 (large sun held): its turning condition is rs1 - rr; the
    triangle of the drawing makes rs1 < rr (triangle inequality: rs1 + rps < (rr - rpl)
    + (rps + rpl)), so the combination c1 > 0 is proved empty for both inputs, not
    derived, and the proof uses that side of the placement's triangle.  Checked against 20000 random
    drawings by the triangle itself."""
    vs = derive_variants(SECOND)
    (c1,) = vs.conditions
    assert sympy.expand(c1.expression - (SECOND.symbols["rs1"] - SECOND.symbols["rr"])) == 0
    assert [(v.number, v.input, v.signs["c1"]) for v in vs.excluded] == [(1, "A", 1), (3, "D", 1)]
    assert [v.number for v in vs.listed] == [1, 2, 3, 4, 5]
    (proof,) = {tuple(str(r) for r in v.facts) for v in vs.excluded}
    assert any("rr - rs1 > 0" in fact and "triangle" in fact for fact in proof)  # a side of the triangle
    rng = random.Random(7)
    closes = 0
    for _ in range(20000):
        rs1, rs2, rps, rr = (rng.uniform(1, 100) for _ in range(4))
        if _triangle_closes(rs1, rs2, rps, rr):
            closes += 1
            assert rs1 < rr
    assert closes > 1000


def test_the_losses_case_of_the_empty_region_is_still_derived():
    """The driving pattern of the empty region (G3: large sun drives) is reached by the
    losses near the turning condition (rs1 > eta_1 eta_2 eta_4 rr, with rs1 < rr): that
    case is derived as variant (5) with the region c1 < 0, and passes Laus's
    partial-derivative rule at a point where it holds."""
    vs = derive_variants(SECOND)
    (five,) = [v for v in vs.variants if v.number == 5]
    (one,) = [v for v in vs.excluded if v.number == 1]
    assert five.signs["c1"] == -1 and dict(five.first_drives) == dict(one.first_drives)
    assert five.reversed_forces == frozenset({"G3"})
    assert five.derivative_check == "positive"


@pytest.mark.parametrize(("name", "train"), catalog_trains(), ids=[name for name, _ in catalog_trains()])
def test_no_region_a_sample_reaches_is_excluded(name, train):
    """Sound on the catalog: every excluded combination of every train and state has no
    point among 400 admissible samples drawn with another seed than the derivation's."""
    vs = derive_variants(train)
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    points = list(domain.samples(400, seed=11))
    for v in vs.excluded:
        for point in points:
            signs = {c.name: 1 if domain.value(c.expression, point) >= 0 else -1 for c in vs.conditions}
            assert signs != dict(v.signs)
    assert (name == "ravigneaux[second]") == bool(vs.excluded)


def _derive(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", *args], cwd=ROOT, capture_output=True, text=True, check=False
    )


@pytest.mark.slow
def test_documents_list_the_excluded_variant_without_a_formula():
    """Text, JSON and LaTeX keep the number and say why it never holds; no formula."""
    text = _derive(catalog_path("ravigneaux"), "--state", "second", "--quiet").stdout
    block = text.split("  (1) ")[1].split("  (2) ")[0]
    assert "never holds" in block and "eta =" not in block
    document = json.loads(_derive(catalog_path("ravigneaux"), "--state", "second", "--json", "--quiet").stdout)
    first = document["variants"][0] if "variants" in document else document["states"]["second"]["variants"][0]
    assert first["number"] == 1 and first["efficiency"] is None and "rr - rs1" in first["never_holds"]["reason"]
    latex = _derive(catalog_path("ravigneaux"), "--state", "second", "--latex", "--quiet").stdout
    assert r"\paragraph{Variant (1)}" in latex and "Never holds" in latex


@pytest.mark.slow
def test_values_outside_the_admissible_geometry_are_refused():
    """A small sun of 70 in a ring of 64 breaks the triangle of the drawing: exit 2 with
    the fact named, never a number (it used to print variant (1)'s value)."""
    result = _derive(catalog_path("ravigneaux"), "--state", "second", "--eval", "rs1=70", *ZF_SECOND[1:], "--quiet")
    assert result.returncode == 2 and result.stdout == ""
    assert "(rr - rs1)" in result.stderr and "no admissible design" in result.stderr
    assert "Traceback" not in result.stderr
    # Without the short planet's radius the triangle's radicand cannot be checked; its side
    # rr - rs1 > 0 (the radius cancels) can.
    unplaced = [v for v in ZF_SECOND[1:] if not v.startswith("rps")]
    result = _derive(catalog_path("ravigneaux"), "--state", "second", "--eval", "rs1=70", *unplaced, "--quiet")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert "rr - rs1 > 0 (a triangle of the drawing that closes), which is -6 here" in result.stderr
    good = _derive(catalog_path("ravigneaux"), "--state", "second", "--eval", *ZF_SECOND, "--quiet")
    assert good.returncode == 0 and good.stdout.startswith("variant (2)")


def test_excluded_combination_is_refused_by_the_api_even_past_the_facts():
    """Asking the variant of an excluded region directly (values that pass the facts
    cannot reach it, so the conditions are given a point of their own) is a design
    error naming the variant, not an internal error."""
    from davies_sym.efficiency.variant_choice import holding_variant
    from davies_sym.errors import DesignError

    vs = derive_variants(SECOND)
    s = SECOND.symbols
    with pytest.raises(DesignError, match=r"variant \(1\)"):
        holding_variant(vs.variants, vs.conditions, "A", {s["rs1"]: 70, s["rr"]: 64}, None, vs.excluded)
    assert all(isinstance(v, ExcludedVariant) for v in vs.excluded)


@pytest.mark.parametrize("name", ["ravigneaux[second]", "tuplin", "humpage", "wolfrom"])
def test_the_float_look_at_a_drawn_point_agrees_with_the_exact_test(name):
    """The sampler decides a drawn point in floating point only where the exact test
    decides it the same way (the float look decides clear cases, beyond a bound on its
    rounding, and leaves the rest to the exact test), so the samples, and every
    document, are those of the exact sampler."""
    train = dict(catalog_trains())[name]
    vs = derive_variants(train)
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    free = sorted(
        {s for g in vs.train.gears for s in sympy.sympify(g.radius).free_symbols} - set(domain.eliminated), key=str
    )
    rng = random.Random(5)
    verdicts = {True: 0, False: 0, None: 0}
    for _ in range(3000):
        drawn = {s: rng.randint(100, 10000) for s in free}
        point = {s: sympy.Rational(v, 100) for s, v in drawn.items()}
        for symbol, expr in domain.eliminated.items():
            point[symbol] = domain.value(expr, point)
        verdict = domain._float_verdict(drawn)
        verdicts[verdict] += 1
        if verdict is not None:
            assert domain._admissible(domain.args(point)) is verdict, (drawn, verdict)
    assert verdicts[True] > 100, verdicts  # the float look spares the exact test
    if name in ("ravigneaux[second]", "tuplin"):  # narrow domains: many draws fall outside
        assert verdicts[False] > 100, verdicts


def test_a_search_beyond_its_budget_gives_no_answer():
    """Twelve linear factors in three products: the sign patterns outnumber the budget of
    eliminations, so the prover gives no answer (the variant is then derived and
    sampled) instead of searching on; a small contradiction among them is still found."""
    x = sympy.symbols("x0:6")
    f1 = sympy.Mul(*[x[i] - x[(i + 1) % 6] + 1 for i in range(6)])
    f2 = sympy.Mul(*[x[i] + x[(i + 2) % 6] - 3 for i in range(6)])
    wide = [Requirement(f1, ">"), Requirement(f2, ">"), Requirement(f1 * f2, "<")]
    assert empty_region(wide) is None
    small = [Requirement(f1, ">"), Requirement(x[0] - x[1], ">"), Requirement(x[1] - x[0], ">")]
    proof = empty_region(small)
    assert proof is not None and {r.expression for r in proof.core} == {x[0] - x[1], x[1] - x[0]}


def _ravigneaux_second_module():
    import importlib.util

    spec = importlib.util.spec_from_file_location("gen_rav_second", f"{ROOT}/derivations/ravigneaux_second.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_module_knows_the_implied_relation_and_the_excluded_region():
    """The module of Ravigneaux 2nd gear does not take the short planet's radius (its
    formulas do not use it), so the triangle cannot be checked there; the relation the
    proof implies, rr - rs1 > 0, is in RELATIONS, and the excluded region's code in
    EXCLUDED: a small sun of 70 in a ring of 64 gives NaN and a DesignWarning, not the
    value of a variant; each of the two checks does so on its own."""
    module = _ravigneaux_second_module()
    assert "rr - rs1 > 0" in module.RELATIONS
    assert module.EXCLUDED == (0,)  # c1 >= 0: no condition negative
    values = {"rs1": np.array([25.0, 70.0]), "rs2": 32.0, "rr": 64.0, **{f"eta_{k}": 0.98 for k in range(1, 5)}}
    with pytest.warns(module.DesignWarning, match="1 design point"):
        eta = module.efficiency(**values)
    assert np.isfinite(eta[0]) and np.isnan(eta[1])
    arrays = {k: np.asarray(v, dtype=float) for k, v in values.items()}
    relations = dict(module._RELATIONS)
    implied = relations.pop("rr - rs1 > 0")
    module._RELATIONS = relations  # the excluded region alone
    assert list(module._admissible(arrays)) == [True, False]
    module._RELATIONS, module.EXCLUDED = {**relations, "rr - rs1 > 0": implied}, ()  # the relation alone
    assert list(module._admissible(arrays)) == [True, False]
