"""A train drawn along a symbolic placement direction derives what its upright spelling
derives: the Ravigneaux set of tests/data/ravigneaux_placement.yaml (planets along
[px, py], no `at:`) gives the catalog's variants in every state.  Its speed is measured
by benchmarks/placement_spelling.py, never here.

What made that spelling slow is checked for what it computes: the rank of screws with
square roots decided exactly (``exact_rank``), and the turned equations solved in the
drawing's frame giving the very magnitudes the plain elimination gives."""

from __future__ import annotations

import os
import random

import pytest
import sympy

import davies_sym
from davies_sym.algebra.linalg import exact_rank
from davies_sym.algebra.square_root_symbol import Radical
from davies_sym.geometry import train_layout
from davies_sym.network import null_space
from davies_sym.network.analysis import Analysis
from davies_sym.topology.states import train_in_state

from conftest import ROOT, catalog_path, read_text

PLACEMENT_FILE = os.path.join(ROOT, "tests", "data", "ravigneaux_placement.yaml")
#: The ZF 3HP12 radii (tooth numbers, one module) and one friction design.
ZF = {"rs1": 25, "rs2": 32, "rps": 16, "rr": 64}


def test_the_spelling_is_a_turned_drawing() -> None:
    """The planets' centres carry the symbolic direction; no bearing gives an `at`."""
    train = davies_sym.load(PLACEMENT_FILE)
    assert "at:" not in read_text(PLACEMENT_FILE).split("couplings:")[1]
    layout = train_layout(train)
    px, py = train.symbols["px"], train.symbols["py"]
    assert {px, py} <= set().union(*(sympy.sympify(x).free_symbols for x in layout.frame))
    assert any(r.radicand == px**2 + py**2 for r in layout.radicals)
    assert layout.gear_centres["PS"][0] != 0


@pytest.mark.parametrize("state", ["reverse", "first", "second", "third"])
def test_placement_spelling_derives_the_catalog_variants(state: str) -> None:
    """Every state: the same turning conditions, the same variants (ports, signs, driving
    gears) with the same formulas, free of the direction, and the same exact values."""
    catalog, spelled = davies_sym.load(catalog_path("ravigneaux")), davies_sym.load(PLACEMENT_FILE)
    base = davies_sym.derive(train_in_state(catalog, catalog.state(state)))
    other = davies_sym.derive(train_in_state(spelled, spelled.state(state)))
    assert [c.expression for c in other.conditions] == [c.expression for c in base.conditions]
    assert [(v.number, v.input, v.output, dict(v.signs), dict(v.first_drives)) for v in other.variants] == [
        (v.number, v.input, v.output, dict(v.signs), dict(v.first_drives)) for v in base.variants
    ]
    direction = {spelled.symbols["px"], spelled.symbols["py"]}
    for a, b in zip(base.variants, other.variants, strict=True):
        assert b.efficiency == a.efficiency
        assert not b.efficiency.free_symbols & direction
    rng = random.Random(11)
    etas = {n: sympy.Rational(rng.randint(90, 99), 100) for n in catalog.symbols if n.startswith("eta")}
    values = {**ZF, **etas}
    for port in sorted({v.input for v in base.variants}):
        assert other.evaluate(values, port) == base.evaluate(values, port)


DOUBLE_PINION = read_text(os.path.join(ROOT, "tests", "data", "double_pinion.yaml"))


@pytest.mark.parametrize("placement", ["30", "[3, 4]"])
def test_turned_equations_give_the_plain_magnitudes(placement: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A double-pinion set drawn turned: solving its equations in the drawing's frame gives
    every motion and action magnitude (bearing reactions along x and y included) exactly
    as the elimination of the equations as written."""
    train = davies_sym.loads(f"{DOUBLE_PINION}placement: {placement}\n", "double_pinion.yaml")

    def magnitudes() -> dict[str, object]:
        analysis = Analysis(train)  # everything it solves is formed here, before any patch
        names = [v.name for v in analysis.network.actions]
        lossless = analysis.lossless_action_coefficients
        return {
            "motions": dict(analysis.motion_coefficients),
            "lossless": {n: lossless[n] for n in names if n in lossless},
            "actions": {n: analysis.action_magnitudes[n] for n in names},
            "efficiency": analysis.efficiency_rf,
        }

    network = Analysis(train).network
    assert null_space.drawing_frame(network) is not None
    assert null_space.force_pairs(network.actions)  # bearing reactions turn with it
    turned = magnitudes()
    monkeypatch.setattr(null_space, "drawing_frame", lambda network: None)
    assert magnitudes() == turned


def test_exact_rank_knows_the_square_roots() -> None:
    """[[s, 1], [3, s]] with s = sqrt(3) is singular (s^2 - 3 = 0); a radical symbol
    taken for a free one gives rank 2."""
    s = sympy.Symbol("sqrt1_", positive=True)
    matrix = sympy.Matrix([[s, 1], [3, s]])
    assert matrix.rank() == 2
    assert exact_rank(matrix, [Radical(s, sympy.Integer(3))]) == 1
    x = sympy.Symbol("x", positive=True)
    assert exact_rank(sympy.Matrix([[x, 1], [x**2, x]])) == 1
    assert exact_rank(sympy.Matrix([[x, 1], [1, x]])) == 2
    assert exact_rank(sympy.zeros(2, 3)) == 0
