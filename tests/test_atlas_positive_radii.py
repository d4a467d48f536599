"""Every train file `derive atlas` writes can be built: the relations its layout imposes
on the radii (the loops of meshes closed on a line or in 2-D, Laus section 3.4.1.6) hold
with every radius positive and every fact of the layout positive (an annulus larger than
its pinion, a triangle of planet axes that closes).

The check here exhibits such a design: the relations solved by Gauss-Jordan elimination,
the radii they leave free drawn as whole numbers; the atlas chooses its drawing with a
proof of the contrary (Fourier-Motzkin elimination), which this check does not use.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
import sympy
from harness.helpers import Result, run_main_in

import davies_sym
from davies_sym.atlas.atlas_entries import Entry, entry, places
from davies_sym.geometry import train_layout

Design = dict[sympy.Symbol, sympy.Rational]


def _positive_design(train: davies_sym.Train, tries: int = 2000) -> Design | None:
    """Whole radii from 1 to 60 for the radii the layout's relations leave free (seeded
    draws), the others solved from the relations (all linear in the radii), such that
    every radius and every fact of the layout is positive; None when no draw is."""
    layout = train_layout(train)
    positive = [sympy.sympify(g.radius) for g in train.gears] + [sympy.sympify(f) for f in layout.positive_facts]
    symbols = sorted(set().union(*(e.free_symbols for e in positive)), key=str)
    relations = [c.expression for c in layout.constraints]
    if relations:
        matrix, rhs = sympy.linear_eq_to_matrix(relations, symbols)
        try:
            solution, parameters = matrix.gauss_jordan_solve(rhs)
        except ValueError:  # the relations contradict each other
            return None
    else:
        solution, parameters = sympy.Matrix(symbols), sympy.Matrix(symbols)
    chooser = random.Random(7)
    for _ in range(tries):
        drawn = {p: sympy.Integer(chooser.randint(1, 60)) for p in parameters}
        design = {s: x.xreplace(drawn) for s, x in zip(symbols, solution, strict=True)}
        if all(e.xreplace(design) > 0 for e in positive):
            return design
    return None


def _named(links: int, names: set[str]) -> dict[str, Entry]:
    """The atlas entries of these names, each drawn alone."""
    return {
        e.name: e
        for place in places(links)
        if f"atlas{links}_r{place.rotation:02d}_d{place.index}" in names
        for e in [entry(place)]
    }


def _derive(args: list[str], cwd: Path) -> Result:
    return run_main_in(cwd, args, timeout=3600)


def test_the_planet_between_a_sun_and_a_planet_is_drawn_inward(tmp_path) -> None:
    """atlas6_r10_d11: planet c (l3) meshes the sun G5a and the gear G4b of planet b; b
    also meshes the suns G1a and G5a (through G2b). Drawn with c outward of b, the line
    asked r2b = -r4b. Drawn with c between the main axis and b: |ac| = r5a + r3c and
    |cb| = r3c + r4b, so |ab| = r5a + 2 r3c + r4b, which G1a (r1a + r4b) and G5a with G2b
    (r5a + r2b) must give: r1a = r5a + 2 r3c and r2b = 2 r3c + r4b. With l0 held the
    train is three external meshes in series (l1 - l4 - l3 - l5): speed ratio -r5a/r1a,
    efficiency eta^3; every state is lossless without losses."""
    e = _named(6, {"atlas6_r10_d11"})["atlas6_r10_d11"]
    (tmp_path / "train.yaml").write_text(e.train_text())
    train = davies_sym.load(tmp_path / "train.yaml")
    relations = [c.expression for c in train_layout(train).constraints]
    radius = {str(s): s for x in relations for s in x.free_symbols}
    hand = {radius["r1a"]: radius["r5a"] + 2 * radius["r3c"], radius["r2b"]: 2 * radius["r3c"] + radius["r4b"]}
    assert len(relations) == 2
    assert all(sympy.expand(x.xreplace(hand)) == 0 for x in relations)
    assert _positive_design(train) is not None
    sizes = ["r3c=5", "r4b=7", "r5a=20", "r1a=30", "r2b=17"]
    for eta, efficiency in (("0.98", 0.98**3), ("1", 1.0)):
        etas = [f"eta_M{k}={eta}" for k in range(4)]
        result = _derive(["train.yaml", "--state", "h0_i1_o5", "--quiet", "--eval", *sizes, *etas], tmp_path)
        assert result.returncode == 0, result.stderr
        *_, ratio, value = result.stdout.splitlines()
        assert float(ratio.split(":")[-1]) == pytest.approx(-20 / 30)
        assert float(value) == pytest.approx(efficiency, rel=1e-12)
    for state in ("h1_i0_o5", "h5_i0_o1"):
        etas = [f"eta_M{k}=1" for k in range(4)]
        result = _derive(["train.yaml", "--state", state, "--quiet", "--eval", *sizes, *etas], tmp_path)
        assert result.returncode == 0, result.stderr
        assert float(result.stdout.splitlines()[-1]) == pytest.approx(1.0, rel=1e-12), state


def test_seven_link_trains_whose_line_asked_a_negative_radius() -> None:
    """Three of the 7-link trains whose line asked a negative radius (r3b = -r5b,
    r3c = -r4c): two are drawn on a line with the planets in another order, the third,
    whose every line drawing asks one, in 2-D. atlas7_r43_d14, whose housing had no
    admissible choice on that line (r4d = -r5d), was drawn with a frame in 2-D; it is now
    drawn in its housing, on a line, with its three coaxial members."""
    names = {"atlas7_r50_d15", "atlas7_r116_d3", "atlas7_r43_d31", "atlas7_r43_d14"}
    named = _named(7, names)
    assert set(named) == names
    assert {n for n in names if named[n].planar} == {"atlas7_r43_d31"}
    assert all(e.drawn.frame is None for e in named.values())
    for name, e in named.items():
        assert len(e.choices) == 3, name
        assert _positive_design(davies_sym.loads(e.train_text())) is not None, name


@pytest.mark.slow
def test_every_six_and_seven_link_file_has_positive_radii(tmp_path) -> None:
    """Every file `derive atlas --links 6|7 --out DIR` writes has a design of positive
    radii (81 and 647 files)."""
    for links, count in ((6, 81), (7, 647)):
        folder = tmp_path / f"atlas{links}"
        result = _derive(["atlas", "--links", str(links), "--out", str(folder), "--jobs", "2", "--quiet"], tmp_path)
        assert result.returncode == 0, result.stderr
        files = sorted(folder.glob("*.yaml"))
        assert len(files) == count
        without = [p.stem for p in files if _positive_design(davies_sym.load(p)) is None]
        assert without == [], without
