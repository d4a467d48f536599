"""The Humpage bevel gear (Laus 2011, section 3.5.1, Fig. 9, Table 6, App. C).

Two geometries are checked.  The catalog file's consistent one (planet axis
perpendicular to the diameter of gear 2's pitch circle that joins its pitch points with
gears 1 and 5), and Laus's printed planet axis of eq. (80), which is not: with the
printed axis the engine reproduces Table 6 and the 42.5 % of section 3.5.1.2; with the
consistent one it predicts 63.26 %.  Both routes (Davies and the virtual-power balance)
agree on each geometry; the geometries differ in the carrier speed only.
"""

from __future__ import annotations

import random

import pytest
import sympy
from published_layouts import laus_humpage_layout

import davies_sym
from davies_sym.algebra.radicals import RadicalTable, restore
from davies_sym.algebra.signs import SignOracle
from davies_sym.efficiency.variants import derive_variants
from davies_sym.efficiency.virtual_power_balance import virtual_power_balance
from davies_sym.errors import GeometryError
from davies_sym.geometry import train_layout

from conftest import catalog_path, equal, read_text

TRAIN = davies_sym.load(catalog_path("humpage"))
SYM = TRAIN.symbols
r1, r2, r3, r4, r5 = (SYM[f"r{k}"] for k in range(1, 6))
NELSON_CIPRA = {r1: 20, r2: 56, r3: 24, r4: 35, r5: 76}
ALL_098 = {s: sympy.Rational(98, 100) for n, s in SYM.items() if n.startswith("eta")}

# Table 6 of Laus, with A as the input.
TABLE_6 = (
    ((r5 - 3 * r1) * r2**2 + r1 * (r5 - r1) ** 2) * (r5 - r1),
    ((r1 - 3 * r5) * r2**2 + r5 * (r5 - r1) ** 2) * (r5 - r1) * (r2 * r4 - r3 * r5),
    (r4 * ((r5 - r1) ** 2 - 2 * r2**2) - r3 * r2 * (r5 - r1)) * (r5 - r1) * (r2 * r4 - r3 * r5),
)


def printed_layout():
    """Laus's geometry: pitch points of App. C, planet axis p_G of eq. (80)."""
    return laus_humpage_layout(TRAIN)


def _real(layout, expr):
    return restore(sympy.sympify(expr), layout.radicals)


def test_cone_geometry_is_consistent():
    """Pitch points at the stated distances from both gear axes, on one pitch circle of
    gear 2 (ends of a diameter, which the planet axis is perpendicular to), all axes
    through the apex, and equal to Laus's App. C points (0, r1, -e/sqrt(b)), (0, r5,
    d/sqrt(b)), (0, r4, f/sqrt(b)) of eq. (83)."""
    layout = train_layout(TRAIN)
    (radical,) = layout.radicals
    assert sympy.expand(radical.radicand - (4 * r2**2 - (r5 - r1) ** 2)) == 0
    b = radical.radicand
    d, e, f = 2 * r2**2 - r5 * (r5 - r1), 2 * r2**2 + r1 * (r5 - r1), 2 * r2 * r3 - r4 * (r5 - r1)
    laus = {"C": (0, r1, -e / sympy.sqrt(b)), "D": (0, r5, d / sympy.sqrt(b)), "E": (0, r4, f / sympy.sqrt(b))}
    rng = random.Random(3)
    for _ in range(5):
        values = {r1: rng.randint(10, 40), r2: rng.randint(30, 60), r3: rng.randint(10, 40), r4: rng.randint(20, 50)}
        values[r5] = values[r1] + rng.randint(1, 2 * values[r2] - 1)
        point = {n: tuple(_real(layout, x).subs(values) for x in layout.coupling_points[n]) for n in "CDE"}
        axis = {g: tuple(_real(layout, x).subs(values) for x in layout.gear_axes[g]) for g in "12345"}
        for mesh, gears in (("C", "12"), ("D", "52"), ("E", "43")):
            assert all(sympy.radsimp(a - sympy.sympify(c).subs(values)) == 0
                       for a, c in zip(point[mesh], laus[mesh], strict=True))
            for g in gears:
                p, u = sympy.Matrix(point[mesh]), sympy.Matrix(axis[g])
                assert sympy.radsimp(p.cross(u).norm() ** 2 - values[SYM[f"r{g}"]] ** 2) == 0, (mesh, g)
        chord = sympy.Matrix(point["D"]) - sympy.Matrix(point["C"])
        assert sympy.radsimp(chord.norm() ** 2 - 4 * values[r2] ** 2) == 0
        assert sympy.radsimp(chord.dot(sympy.Matrix(axis["2"]))) == 0
        assert all(sympy.radsimp(sympy.Matrix(axis[g]).norm() - 1) == 0 for g in "12345")
    # Every bearing and every relative motion passes through the apex (the origin).
    assert all(all(x == 0 for x in layout.coupling_points[c]) for c in "ABFG")


def test_inconsistent_cone_distances_are_refused(tmp_path):
    """A planet whose two pitch points are not on one pitch circle is bad input."""
    text = read_text(catalog_path("humpage"))
    text = text.replace('"2": {link: p, radius: r2, axis: tilted}', '"2": {link: p, radius: r2, axis: y}')
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(GeometryError, match="one pitch circle") as caught:
        train_layout(davies_sym.load(str(path)))
    assert "couplings.D" in str(caught.value)


def test_radical_table_reduces_exactly():
    table = RadicalTable()
    s = table.sqrt(4 * r2**2 - (r5 - r1) ** 2)
    assert s.is_Symbol
    assert table.sqrt((16 * r2**2 - 4 * (r5 - r1) ** 2) / r2**2) == 2 * s / r2
    assert table.reduce(s**3 + s * (r5 - r1) ** 2) == 4 * r2**2 * s
    assert table.reduce(1 / s - s / (4 * r2**2 - (r5 - r1) ** 2)) == 0
    assert table.sqrt(9 * r1**2) == 3 * r1


@pytest.fixture(scope="module")
def consistent():
    return derive_variants(TRAIN)


def test_consistent_geometry_one_condition(consistent):
    """Gear 1 always drives gear 2 with A as input (its carrier-frame speed is
    w_1 r5 / (r1 + r5)); meshes D and E turn with r2 r4 - r3 r5: four variants."""
    (condition,) = consistent.conditions
    assert sympy.cancel(condition.expression / (r2 * r4 - r3 * r5)).is_number
    assert len(consistent.variants) == 4
    for v in consistent.variants:
        assert v.first_drives["C"] == (v.input == "A")
        assert equal(v.efficiency.subs({e: 1 for e in ALL_098}), 1)
        assert v.derivative_check == "positive"


def test_consistent_speed_ratio(consistent):
    """w_1 / w_4 = (r1 + r5) r2 r4 / (r1 (r2 r4 - r3 r5)); the carrier turns at
    w_1 r1 / (r1 + r5), as in a bevel differential with gear 5 held."""
    ratio = consistent.analysis.speed_ratio().to_expr()
    assert equal(ratio, (r1 + r5) * r2 * r4 / (r1 * (r2 * r4 - r3 * r5)))
    values = {**NELSON_CIPRA, **ALL_098}
    chen = virtual_power_balance(TRAIN, values)
    assert chen.speeds["6"] == sympy.Rational(20, 96)


@pytest.mark.parametrize("port", ["A", "B"])
def test_consistent_both_routes(consistent, port):
    """Davies route = virtual-power balance, exactly, at the Nelson-Cipra tooth numbers
    with every mesh at 0.98 (63.26 % with A as input) and at other points."""
    rng = random.Random(11)
    points = [NELSON_CIPRA] + [{r1: rng.randint(10, 30), r2: rng.randint(40, 60), r3: rng.randint(10, 40),
                                r4: rng.randint(20, 50), r5: rng.randint(60, 90)} for _ in range(3)]
    for point in points:
        values = {**point, **{e: sympy.Rational(rng.randint(90, 99), 100) for e in ALL_098}}
        if point is NELSON_CIPRA:
            values = {**point, **ALL_098}
        davies = consistent.evaluate(values, port)
        chen = virtual_power_balance(TRAIN, values, port)
        assert davies == chen.efficiency
    value = float(consistent.evaluate({**NELSON_CIPRA, **ALL_098}))
    assert abs(value - 0.632647) < 1e-6


@pytest.mark.slow
def test_printed_geometry_reproduces_table_6_and_42_5_percent():
    """Laus 2011, Table 6 and section 3.5.1.2: with the printed planet axis (eq. (80)) the
    engine finds the three turning conditions of Table 6 (up to a constant factor),
    sixteen variants, the signs (+, -, -) at z = 20, 56, 24, 35, 76 with gear 1 driving
    gear 2, gear 2 driving gear 5 and gear 4 driving gear 3, and 42.5 % at 0.98 per mesh;
    the virtual-power balance on the same geometry gives the same number."""
    layout = printed_layout()
    vs = derive_variants(TRAIN, layout=layout)
    assert len(vs.conditions) == 3
    assert len(vs.variants) == 16
    for condition, laus in zip(vs.conditions, TABLE_6, strict=True):
        ratio = sympy.cancel(condition.expression / sympy.expand(laus))
        assert ratio.is_number and ratio != 0, (condition.name, ratio)
        assert SignOracle().sign(laus.subs(NELSON_CIPRA)) == (1 if laus is TABLE_6[0] else -1)
    values = {**NELSON_CIPRA, **ALL_098}
    chosen = vs.variant_for(values)
    assert dict(chosen.first_drives) == {"C": True, "D": False, "E": True}
    value = vs.evaluate(values)
    assert abs(float(value) - 0.425) < 5e-4
    assert virtual_power_balance(TRAIN, values, layout=layout).efficiency == value
    # Only the carrier speed differs from the consistent geometry: the ratio is the same.
    printed = virtual_power_balance(TRAIN, values, layout=layout)
    consistent = virtual_power_balance(TRAIN, values)
    assert printed.speeds["4"] == consistent.speeds["4"]
    assert printed.speeds["6"] == sympy.Rational(55, 112) != consistent.speeds["6"]
