"""The generated formula modules (derivations/*.py) against the exact symbolic results.

Each module is imported and evaluated at sampled admissible designs and along lines that
cross a turning condition; the exact value comes from the variant set (sympy rationals).
Also: losses add up to 1 - efficiency and equal the exact fractions, the speed ratio,
NaN with a warning (or an error) where the design self-locks or is not admissible, and
ruff and mypy --strict on the generated code.
"""

from __future__ import annotations

import functools
import importlib.util
import inspect
import os
import random
import subprocess
import sys
import warnings

import numpy as np
import pytest
import sympy
from harness.helpers import run_main

from davies_sym.efficiency.parameter_domain import ParameterDomain, Point, efficiency_symbols
from davies_sym.efficiency.parameters import admissible_relations, formula_symbols, parameter_table
from davies_sym.efficiency.power_losses import loss_fractions, lossy_couplings
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.errors import NotCoveredError
from davies_sym.losses.definitions import completed, parameters_of, substituted

from conftest import ROOT, catalog_trains

DERIVATIONS = os.path.join(ROOT, "derivations")
TRAINS = dict(catalog_trains())


@functools.lru_cache(maxsize=None)
def variant_set(name: str) -> VariantSet:
    return derive_variants(TRAINS[name])


def module_of(name: str):
    stem = name.replace("[", "_").replace("]", "")
    spec = importlib.util.spec_from_file_location(f"gen_{stem}", os.path.join(DERIVATIONS, f"{stem}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def admissible(vs: VariantSet, values: Point) -> bool:
    """Every parameter in its range and every relation positive, exactly."""
    for p in parameter_table(vs):
        v = values[vs.train.symbols[p.name]] if p.name in vs.train.symbols else None
        if v is not None and not (p.low < v <= p.high):
            return False
    return all(sympy.sympify(r.subs(values)) > 0 for r in admissible_relations(vs))


def expected(vs: VariantSet, values: Point, port: str) -> float:
    """The exact efficiency, NaN where the design is not admissible or self-locks."""
    if not admissible(vs, values):
        return float("nan")
    try:
        return float(vs.evaluate(values, port))
    except NotCoveredError:  # self-locks: the module's NaN
        return float("nan")


def design_points(vs: VariantSet, count: int, seed: int) -> list[Point]:
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    rng = random.Random(seed)
    out = []
    # Parameters of loss models (a flank friction coefficient) are drawn small, like other coefficients.
    models = parameters_of([d.symbol for d in vs.train.definitions], vs.train.definitions)
    # The sliding friction coefficient of a skew mesh too (a law's coefficient, not a model's).
    models |= {s for law in vs.analysis.network.laws for s in law.coefficient.free_symbols if str(s).startswith("mu")}
    for point in domain.samples(count, seed=seed, extra=models, extra_range=(1, 100)):
        values = {**point, **{e: sympy.Rational(rng.randint(80, 100), 100) for e in efficiency_symbols(vs.train)}}
        out.append({s: values[s] for s in formula_symbols(vs)})
    return out


def kwargs_of(points: list[Point], symbols) -> dict[str, np.ndarray]:
    return {str(s): np.array([float(p[s]) for p in points]) for s in symbols}


def agree(got: np.ndarray, want: list[float]) -> bool:
    want_array = np.array(want)
    got = np.broadcast_to(got, want_array.shape)  # a train without parameters gives one value
    same_nan = np.array_equal(np.isnan(got), np.isnan(want_array))
    finite = ~np.isnan(want_array)
    return same_nan and np.allclose(got[finite], want_array[finite], rtol=1e-12, atol=0)


#: Humpage's module takes 10-20 s per test to build and check: those cases run in the slow tier.
NAMES = sorted(TRAINS)
PARAMETRISED = [pytest.param(n, marks=pytest.mark.slow) if n == "humpage" else n for n in NAMES]


@pytest.mark.parametrize("name", PARAMETRISED)
def test_module_efficiency_equals_the_exact_variant(name):
    """efficiency() on an array of sampled designs, both input ports, to 1e-12 relative;
    every variant function on the points of its own region."""
    vs, module = variant_set(name), module_of(name)
    points = design_points(vs, 12, seed=5)
    kwargs = kwargs_of(points, formula_symbols(vs))
    for port in (vs.train.ports.input, vs.train.ports.output):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", module.DesignWarning)
            got = module.efficiency(input=port, **kwargs)
        assert agree(got, [expected(vs, p, port) for p in points])
    for v in vs.variants:
        mine = [p for p in points if vs.variant_for(p, v.input) is v]
        if mine:
            function = getattr(module, v.name)
            used = parameters_of(v.efficiency.free_symbols, vs.train.definitions)
            args = {str(s): float(mine[0][s]) for s in used}
            exact = v.efficiency.subs(completed(mine[0], vs.train.definitions))
            assert float(function(**args)) == pytest.approx(float(exact), rel=1e-12)


#: Turning conditions per catalog train and state, from the sources: Laus Table 5 (Tuplin,
#: sign of r2 - r1) and Table 6 (Humpage, one condition on r3 r5 - r2 r4), Chen section
#: 4.4 (Litvin's face-gear drive, N1 N3 - N2 N4); the Wolfrom set's two annuli (sign of
#: rp2 - rp1).  A sun-planet-annulus set with a held member has a negative basic ratio and
#: no turning condition (planetary_simple, Simpson, simple pair and Buckingham's pair); the Ravigneaux second
#: gear has one (rs1 - rr) that an admissible design never changes (the annulus is larger
#: than its sun), so one region only.
TURNING_CONDITIONS = {
    "bicycle_hub[high]": 0,
    "bicycle_hub[low]": 0,
    "bicycle_hub[normal]": 0,
    "buckingham_pair": 0,
    "crossed_helical": 0,
    "humpage": 1,
    "litvin_face_drive": 1,
    "planetary_simple": 0,
    "rack_pinion": 0,
    "ravigneaux[first]": 0,
    "ravigneaux[second]": 1,
    "ravigneaux[third]": 0,
    "ravigneaux[reverse]": 0,
    "simple_pair": 0,
    "simpson[first]": 0,
    "simpson[second]": 0,
    "simpson[third]": 0,
    "simpson[reverse]": 0,
    "tuplin": 1,
    "wolfrom": 1,
    "worm_drive": 0,
    "worm_planetary": 0,
}
#: The trains whose admissible designs reach two condition regions.
TWO_REGIONS = ("humpage", "litvin_face_drive", "tuplin", "wolfrom")


def test_turning_conditions_per_catalog_state_are_pinned():
    assert sorted(TURNING_CONDITIONS) == NAMES
    got = {name: len(variant_set(name).conditions) for name in NAMES}
    assert got == TURNING_CONDITIONS
    for name in NAMES:
        regions = {
            tuple(v.signs.values())
            for v in variant_set(name).variants
            if v.feasible and v.input == TRAINS[name].ports.input
        }
        assert len(regions) == (2 if name in TWO_REGIONS else 1), name


@pytest.mark.parametrize("name", TWO_REGIONS)
def test_arrays_straddling_a_turning_condition(name):
    """A line of designs from one condition region to another: each element gets its own
    variant (exact values on dyadic points, so the floats are exact inputs)."""
    vs, module = variant_set(name), module_of(name)
    points = design_points(vs, 40, seed=11)
    signs = [tuple(sympy.sign(c.expression.subs(p)) for c in vs.conditions) for p in points]
    pairs = [(p, q) for i, p in enumerate(points) for j, q in enumerate(points) if signs[i] != signs[j]]
    assert pairs, "sampled designs in two regions"
    p, q = pairs[0]
    line = [{s: p[s] + sympy.Rational(k, 16) * (q[s] - p[s]) for s in p} for k in range(17)]
    crossed = {tuple(sympy.sign(c.expression.subs(x)) for c in vs.conditions) for x in line}
    assert len(crossed) >= 2
    kwargs = kwargs_of(line, vs.symbols)
    for port in (vs.train.ports.input, vs.train.ports.output):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", module.DesignWarning)
            got = module.efficiency(input=port, **kwargs)
        assert agree(got, [expected(vs, x, port) for x in line])


@pytest.mark.parametrize("train", ["simpson", "ravigneaux"])
def test_the_modules_of_one_files_states_share_one_signature(train):
    """Design code calls every gear alike: each state's functions take every parameter of
    the file (those a state does not use are accepted, listed in IGNORED, and ignored)."""
    states = [n for n in NAMES if n.startswith(f"{train}[")]
    modules = {n: module_of(n) for n in states}
    for function in ("efficiency", "losses", "speed_ratio"):
        names = {n: frozenset(inspect.signature(getattr(m, function)).parameters) for n, m in modules.items()}
        assert len(set(names.values())) == 1, names
    for n, m in modules.items():
        used = {p["name"] for p in m.PARAMETERS}
        assert set(m.IGNORED).isdisjoint(used), n


@pytest.mark.parametrize("name", PARAMETRISED)
def test_module_agrees_with_derive_eval(name):
    """The module's efficiency and speed ratio equal what ``derive --eval`` prints (its
    last line and the line before) at sampled designs, both input ports."""
    vs, module = variant_set(name), module_of(name)
    train = name.split("[")[0]
    state = ["--state", name.split("[")[1].rstrip("]")] if "[" in name else []
    # One admissible design (each call derives the train afresh, as a user's would).
    for point in [p for p in design_points(vs, 6, seed=13) if admissible(vs, p)][:1]:
        pairs = [f"{s}={point[s]}" for s in point]
        for port in (vs.train.ports.input, vs.train.ports.output):
            result = run_main(
                [os.path.join(ROOT, "catalog", f"{train}.yaml"), "--quiet", *state, "--input", port, "--eval", *pairs]
            )
            kwargs = {str(s): float(v) for s, v in point.items()}
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", module.DesignWarning)
                value = float(module.efficiency(input=port, **kwargs))
            if result.returncode == 3:
                assert np.isnan(value), (port, value)
                continue
            assert result.returncode == 0, result.describe()
            ratio_line, value_line = result.stdout.splitlines()[-2:]
            assert value == pytest.approx(float(value_line), rel=1e-12)
            geometry = {k: v for k, v in kwargs.items() if k in inspect.signature(module.speed_ratio).parameters}
            ratio = float(module.speed_ratio(input=port, **geometry))
            assert ratio == pytest.approx(float(ratio_line.rsplit(": ", 1)[1]), rel=1e-12)


@pytest.mark.parametrize("name", (*TWO_REGIONS, "ravigneaux[second]", "simpson[second]"))
def test_the_scoring_module_scores_as_the_full_module(name):
    """The module a search compiles (no gradient, no losses) gives the full module's
    efficiency and speed ratio bit for bit, both inputs, NaN where it does, and each agrees
    with the exact variant; it writes neither gradient nor loss functions."""
    vs = variant_set(name)
    full = module_of(name)
    scoring = compiled_module(python_module(vs, scoring=True), name)
    assert not scoring._LOSSES and not scoring._GRADIENT and full._LOSSES
    points = design_points(vs, 12, seed=11)
    kwargs = kwargs_of(points, formula_symbols(vs))
    for port in (vs.train.ports.input, vs.train.ports.output):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", full.DesignWarning)
            warnings.simplefilter("ignore", scoring.DesignWarning)
            got = scoring.efficiency(input=port, **kwargs)
            want = full.efficiency(input=port, **kwargs)
            ratios = (scoring.speed_ratio(input=port, **kwargs), full.speed_ratio(input=port, **kwargs))
        assert np.array_equal(got, want, equal_nan=True)
        assert np.array_equal(*ratios, equal_nan=True)
        assert agree(got, [expected(vs, p, port) for p in points])


@pytest.mark.parametrize("name", PARAMETRISED)
def test_losses_add_up_and_equal_the_exact_fractions(name):
    """losses(): one entry per friction element, each equal to the exact -P_k/P_in of
    the variant, together 1 - efficiency; speed_ratio equals the exact ratio."""
    vs, module = variant_set(name), module_of(name)
    points = design_points(vs, 6, seed=7)
    kwargs = kwargs_of(points, formula_symbols(vs))
    assert lossy_couplings(vs) == module.LOSSY
    for port in (vs.train.ports.input, vs.train.ports.output):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", module.DesignWarning)
            eta = np.broadcast_to(module.efficiency(input=port, **kwargs), (len(points),))
            parts = {k: np.broadcast_to(v, eta.shape) for k, v in module.losses(input=port, **kwargs).items()}
        ok = ~np.isnan(eta)
        total = eta + sum(parts.values())
        assert np.allclose(total[ok], 1.0, rtol=0, atol=1e-12)
        for i, point in enumerate(points):
            if ok[i]:
                exact = loss_fractions(vs, vs.variant_for(point, port))
                for coupling, value in parts.items():
                    want = exact[coupling].to_expr().subs(completed(point, vs.train.definitions))
                    assert value[i] == pytest.approx(float(want), rel=1e-12, abs=1e-13)
    ratio = substituted(vs.analysis.speed_ratio().to_expr(), vs.train.definitions)
    geometry = kwargs_of(points, sorted(ratio.free_symbols, key=str))
    got = module.speed_ratio(**geometry)
    want = [float(ratio.subs(p)) for p in points]
    assert np.allclose(np.broadcast_to(got, (len(points),)), want, rtol=1e-12)
    back = module.speed_ratio(input=vs.train.ports.output, **geometry)
    assert np.allclose(np.broadcast_to(back, (len(points),)), 1 / np.array(want), rtol=1e-12)


def test_self_locking_and_inadmissible_designs_give_nan_with_a_warning_or_an_error():
    """Tuplin with B as input self-locks where the numerator of variant (3),
    eta_C eta_D r1 (r1 - r2 - r3) + r2 r3, is <= 0 (checked exactly below, not a
    published number); a mesh efficiency above 1 and a pinion larger than its annulus
    are outside the admissible parameters."""
    vs, module = variant_set("tuplin"), module_of("tuplin")
    r1, r2, r3 = (vs.train.symbols[n] for n in ("r1", "r2", "r3"))
    eta_c, eta_d = (vs.train.symbols[n] for n in ("eta_C", "eta_D"))
    design = {r1: 40, r2: 60, r3: 15}
    # Variant B_to_A_c1_pos; it locks where eta^2 r1 (r1 - r2 - r3) + r2 r3 <= 0: eta^2 <= 900/1400.
    locked = {**design, eta_c: sympy.Rational(7, 10), eta_d: sympy.Rational(7, 10)}
    assert vs.variant_for(locked, "B").efficiency.subs(locked) <= 0
    with pytest.raises(NotCoveredError, match="self-locks"):
        vs.evaluate(locked, "B")
    kwargs = {
        "r1": [40.0, 40.0, 40.0],
        "r2": 60.0,
        "r3": [15.0, 15.0, 45.0],
        "eta_C": [0.99, 0.7, 0.99],
        "eta_D": [0.99, 0.7, 0.99],
    }
    with pytest.warns(module.DesignWarning, match="1 design point.* outside .* 1 where the train self-locks"):
        got = module.efficiency(input="B", **kwargs)
    assert got[0] == pytest.approx(
        float(vs.evaluate({**design, eta_c: sympy.Rational(99, 100), eta_d: sympy.Rational(99, 100)}, "B")), rel=1e-12
    )
    assert np.isnan(got[1]) and np.isnan(got[2])
    with pytest.raises(module.DesignError, match="self-locks"):
        module.efficiency(input="B", errors="raise", **kwargs)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = module.efficiency(input="B", errors="ignore", **kwargs)
    assert np.isnan(quiet[1])
    # Just below zero (not below -1): still self-locking, still NaN.
    barely = {**design, eta_c: sympy.Rational(79, 100), eta_d: sympy.Rational(79, 100)}
    assert -1 < vs.variant_for(barely, "B").efficiency.subs(barely) < 0
    with pytest.raises(NotCoveredError, match="self-locks"):
        vs.evaluate(barely, "B")
    with pytest.warns(module.DesignWarning, match="1 where the train self-locks"):
        assert np.isnan(module.efficiency(input="B", r1=40, r2=60, r3=15, eta_C=0.79, eta_D=0.79))
    with pytest.warns(module.DesignWarning):
        assert np.isnan(module.efficiency(r1=40, r2=60, r3=15, eta_C=1.2, eta_D=0.99))
    with pytest.raises(ValueError, match="errors must be"):
        module.efficiency(errors="loud", r1=40, r2=60, r3=15, eta_C=0.9, eta_D=0.9)


def test_parameters_and_variants_tables():
    """PARAMETERS name every argument with meaning, unit and range; VARIANTS carry the
    conditions and the formula as text and LaTeX, equal to the variant set's."""
    vs, module = variant_set("tuplin"), module_of("tuplin")
    assert [p["name"] for p in module.PARAMETERS] == [str(s) for s in formula_symbols(vs)]
    r1 = next(p for p in module.PARAMETERS if p["name"] == "r1")
    assert r1["meaning"] == "pitch radius of internal gear 1 (link 1)" and r1["low"] == 0.0
    assert module.RELATIONS == ("-r1 + r2 + r3 > 0", "r1 - r3 > 0")
    for row, v in zip(module.VARIANTS, vs.variants, strict=True):
        assert row["name"] == v.name and sympy.sympify(row["formula"], locals=dict(vs.train.symbols)) == v.efficiency
        from hand.latex import read_latex, same_rational_function  # the LaTeX read back, not printed again

        assert same_rational_function(read_latex(row["latex"], vs.train.symbols.values()), v.efficiency), row["latex"]
    assert "Laus 2011, Fig. 7" in module.__doc__ and "r4 = -r1 + r2 + r3" in module.__doc__


@pytest.mark.slow
def test_generated_modules_pass_mypy_strict():
    """mypy --strict on every generated module (type hints are part of the output)."""
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", "derivations"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("name", TWO_REGIONS)
def test_a_large_array_is_evaluated_in_blocks_with_the_same_values(name):
    """More design points than one block (`_BLOCK`), in a 2-D grid of both regions and
    inadmissible points: efficiency and losses equal, element by element and bit for
    bit, the same points evaluated a few at a time (no blocks), and the warning counts
    every bad point of the whole array once."""
    vs, module = variant_set(name), module_of(name)
    points = design_points(vs, 40, seed=3)
    base = kwargs_of(points, vs.symbols)
    rows = module._BLOCK // len(points) + 7
    rng = np.random.default_rng(5)
    # Each row scales each geometric parameter on its own (some to a negative length).
    grid = {
        k: v if k.startswith("eta") else v[np.newaxis, :] * rng.uniform(-0.1, 1.5, (rows, 1)) for k, v in base.items()
    }
    assert np.broadcast_shapes(*(v.shape for v in grid.values())) == (rows, len(points))
    for port in (vs.train.ports.input, vs.train.ports.output):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", module.DesignWarning)
            whole = module.efficiency(input=port, **grid)
            losses = module.losses(input=port, **grid)
        assert whole.shape == (rows, len(points))
        for k in range(0, rows, 97):
            row = {n: np.broadcast_to(v, whole.shape)[k] for n, v in grid.items()}
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", module.DesignWarning)
                alone = module.efficiency(input=port, **row)
                alone_losses = module.losses(input=port, **row)
            assert np.array_equal(whole[k], alone, equal_nan=True)
            for part in losses:
                assert np.array_equal(losses[part][k], alone_losses[part], equal_nan=True)
        bad = int(np.count_nonzero(np.isnan(whole)))
        assert bad > 0 and len(caught) == 2
        counts = [int(w) for w in str(caught[0].message).replace(",", " ").split() if w.isdigit()]
        assert sum(counts) == bad


def test_a_large_array_of_a_train_with_a_constant_speed_ratio():
    """Buckingham's pair has numeric radii: its speed ratio and ranges depend on none of
    the arrays, so those results of a block are single values; an array larger than a
    block is evaluated as the same points one by one (Laus eqs. (36)-(37): the pair's
    efficiency is its mesh's, a function of the flank friction coefficient mu alone)."""
    module = module_of("buckingham_pair")
    mu = np.linspace(0.01, 0.1, module._BLOCK + 11)
    whole = module.efficiency(mu=mu)
    assert whole.shape == mu.shape
    picked = [0, 1, module._BLOCK - 1, module._BLOCK, len(mu) - 1]
    assert np.array_equal(whole[picked], [float(module.efficiency(mu=mu[k])) for k in picked])
    assert module.losses(mu=mu)["C"].shape == mu.shape
