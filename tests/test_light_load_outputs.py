"""A one-input train at light load, through every output: the generated formula module,
the LaTeX, the text and JSON report and the CLI.

The train is a planetary (sun input, carrier output, ring held) with ordinary mesh
efficiencies, a drag and Coulomb friction in the planet bearing and a drag on the
carrier.  Below a carrier load of about 19 N m the planet's drag reverses the ring
mesh's tooth force (and the bearing reaction can turn with it), so the variant that
holds is not the lossless one.  Every number is compared with the independent torque
balance of tests/oracle/lossy_balance.py (exact rationals, power directions found by
iteration), which shares no code with the package.
"""

from __future__ import annotations

import json
import warnings
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest
import sympy
from hand.latex import document_equations, force_conditions, read_latex
from harness.helpers import run_main
from oracle.balance import Gear, Member, Mesh
from oracle.lossy_balance import Bearing, LossyTrain, solve

import davies_sym
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.latex import latex_document
from davies_sym.emit.python_module import python_module

TRAIN = """\
name: planetary at light load
links: [housing, sun, carrier, planet]
reference: housing
gears:
  S: {link: sun, radius: rs}
  P: {link: planet, radius: rp}
  R: {link: housing, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [housing, sun]}
  B: {type: revolute, links: [housing, carrier], friction: {drag: D_c}}
  E: {type: revolute, links: [carrier, planet], friction: {coulomb: rho_p, drag: D_p}}
  SP: {type: mesh, gears: [S, P]}
  RP: {type: mesh, gears: [R, P]}
ports: {input: A, output: B}
"""

RS, RP, ETA_SP, ETA_RP = F(3), F(2), F(97, 100), F(98, 100)
LOSSES = {"rho_p": F(1, 3), "D_p": F(2), "D_c": F(1)}
LOADS = (F(1, 10), F(1, 2), F(1), F(3), F(8), F(15), F(30), F(100))
SPEEDS = (F(50), F(1, 2))


def _oracle_points() -> list[dict[str, F]]:
    """Per load and speed: the oracle's input torque and efficiency."""
    members = (Member("0"), Member("s"), Member("c"), Member("p", "c", (F(0), RS + RP)))
    gears = (Gear("S", "s", RS), Gear("P", "p", RP), Gear("R", "0", RS + 2 * RP, True))
    meshes = (Mesh("SP", ("S", "P"), ETA_SP), Mesh("RP", ("R", "P"), ETA_RP))
    bearings = (Bearing("p", rho=LOSSES["rho_p"], drag=LOSSES["D_p"]), Bearing("c", drag=LOSSES["D_c"]))
    oracle = LossyTrain("planetary", members, gears, meshes, "0", {"in": "s", "out": "c"}, bearings)
    out = []
    for load in LOADS:
        for speed in SPEEDS:
            result = solve(oracle, {"in": speed}, "out", -load)
            out.append({"tau_in": abs(result.torques["in"]), "omega_in": speed, "eta": result.efficiency})
    return out


@pytest.fixture(scope="module")
def variants() -> VariantSet:
    return derive_variants(davies_sym.loads(TRAIN, "light.yaml"))


@pytest.fixture(scope="module")
def cases() -> list[dict[str, F]]:
    return _oracle_points()


def _fixed() -> dict[str, F]:
    # rr is not a parameter: the geometric constraint gives it (rr = rs + 2 rp).
    return {"rs": RS, "rp": RP, "eta_SP": ETA_SP, "eta_RP": ETA_RP, **LOSSES}


def _exact(variants: VariantSet, case: dict[str, F]) -> dict[sympy.Symbol, sympy.Expr]:
    symbols = variants.train.symbols
    point: dict[sympy.Symbol, sympy.Expr] = {
        symbols[k]: sympy.Rational(v.numerator, v.denominator) for k, v in _fixed().items()
    }
    point[INPUT_TORQUE] = sympy.Rational(case["tau_in"].numerator, case["tau_in"].denominator)
    point[INPUT_SPEED] = sympy.Rational(case["omega_in"].numerator, case["omega_in"].denominator)
    return point


def test_light_load_variants_are_derived(variants: VariantSet) -> None:
    """The sun input has a variant with the ring mesh's tooth force reversed; every
    variant states the signs its loaded forces need (the meshes' powers, the planet
    bearing), except the sun mesh's with the sun as input: the sun gives that power
    whatever the losses, and the geometry's signs prove it."""
    sun = [v for v in variants.variants if v.input == "A"]
    assert any("RP" in v.reversed_forces for v in sun)
    for v in variants.variants:
        assert set(v.loaded_forces) == ({"RP", "E"} if v.input == "A" else {"SP", "RP", "E"})
    names = [v.name for v in variants.variants]
    assert len(set(names)) == len(names)


def test_generated_module_equals_the_oracle_at_every_load(variants: VariantSet, cases) -> None:
    """One vectorised call over all loads and speeds: efficiency equal to the oracle's
    (rtol 1e-12), the light-load rows taken by reversed variants, no warning; the losses
    add up to 1 - efficiency in every row (power balance P_in + P_out + losses = 0)."""
    module = compiled_module(python_module(variants), "light")
    arrays = {
        "tau_in": np.array([float(c["tau_in"]) for c in cases]),
        "omega_in": np.array([float(c["omega_in"]) for c in cases]),
    }
    fixed = {k: float(v) for k, v in _fixed().items()}
    # Without viscous friction the formulas do not take the speed.
    arrays = {k: v for k, v in arrays.items() if k in {p["name"] for p in module.PARAMETERS}}
    assert "tau_in" in arrays
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        eta = module.efficiency(input="A", **fixed, **arrays)
        numbers = module.variant(input="A", **fixed, **arrays)
        losses = module.losses(input="A", **fixed, **arrays)
    np.testing.assert_allclose(eta, [float(c["eta"]) for c in cases], rtol=1e-12)
    reversed_rows = [k for k, n in enumerate(numbers) if module.VARIANTS[n - 1]["reversed"]]
    assert reversed_rows and all(float(cases[k]["tau_in"]) < 10 for k in reversed_rows)
    np.testing.assert_allclose(sum(losses.values()), 1 - eta, rtol=1e-10, atol=1e-12)
    # The lossless-direction variant alone would be wrong at those rows.
    lossless = next(v for v in module.VARIANTS if v["input"] == "A" and not v["reversed"])
    function, names = module._EFFICIENCY[lossless["name"]]
    values = {**fixed, **arrays}
    wrong = function(**{n: values[n] for n in names})
    assert not np.allclose(wrong[reversed_rows], eta[reversed_rows], rtol=1e-6)


def test_eval_text_json_and_latex_agree_with_the_oracle(variants: VariantSet, cases, tmp_path: Path) -> None:
    """--eval at a light load prints the oracle's number and names the reversed variant;
    the LaTeX equation of that variant, read back, equals it, and its conditions on the
    loaded forces, read back, hold there; the JSON report lists the reversal."""
    train = tmp_path / "light.yaml"
    train.write_text(TRAIN)
    case = next(c for c in cases if c["tau_in"] < 5)
    # Without viscous friction the formulas take the input torque, not the speed.
    values = {**_fixed(), "tau_in": case["tau_in"]}
    result = run_main([str(train), "--eval", *(f"{k}={v}" for k, v in values.items()), "--json", "--quiet"])
    assert result.returncode == 0, result.stderr
    answer = json.loads(result.stdout)
    assert sympy.Rational(answer["efficiency_exact"]) == sympy.Rational(case["eta"].numerator, case["eta"].denominator)
    assert answer["status"] == "ok"
    number = answer["variant"]["number"]
    variant = variants.variants[number - 1]
    assert variant.reversed_forces
    text = latex_document(variants)
    equations = document_equations(text)
    symbols = [*variants.train.symbols.values(), INPUT_TORQUE, INPUT_SPEED]
    point = _exact(variants, case)
    truth = sympy.Rational(case["eta"].numerator, case["eta"].denominator)
    assert read_latex(equations[number], symbols).subs(point) == truth
    section = text.split(rf"\paragraph{{Variant ({number})}}")[1].split(r"\paragraph")[0]
    held = force_conditions(section)
    assert len(held) == len(variant.loaded_forces) == 2 and "reversed by the losses" in section
    for body, relation in held:
        force = read_latex(body, symbols).subs(point)
        assert force > 0 if relation == ">" else force < 0
    report = json.loads(run_main([str(train), "--json", "--quiet"]).stdout)
    listed = {v["number"]: v for v in report["variants"]}
    assert listed[number]["reversed_forces"] == sorted(variant.reversed_forces)
    assert len(listed[number]["loaded_forces"]) == len(variant.loaded_forces) == 2


def test_plot_over_the_input_torque(tmp_path: Path) -> None:
    """--plot over the input torque (from light to heavy load) with the losses held by
    --at draws the efficiency with the light-load variants shaded; a name the formulas
    do not take is refused with exit status 2."""
    train = tmp_path / "light.yaml"
    train.write_text(TRAIN)
    held = [f"{k}={v}" for k, v in _fixed().items()]
    figure = tmp_path / "eta.png"
    result = run_main([str(train), "--plot", "tau_in=0.1:100", "--at", *held, "-o", str(figure), "--quiet"])
    assert result.returncode == 0, result.stderr
    assert figure.read_bytes().startswith(b"\x89PNG")
    refused = run_main([str(train), "--plot", "omega_in=1:10", "--at", *held, "-o", str(figure), "--quiet"])
    assert refused.returncode == 2 and "omega_in" in refused.stderr
