"""The atlas's train files: the catalog's planetary sets found in the atlas, every
written train's speed ratios against Willis' equations solved here (no code shared with
the Davies network), the files derived, and ``derive atlas`` as a command."""

from __future__ import annotations

import json
import random
import re
from dataclasses import replace
from fractions import Fraction
from fractions import Fraction as F
from pathlib import Path
from types import MappingProxyType

import pytest
import sympy
import yaml
from harness.helpers import Result, run_main_in
from oracle.balance import Gear, Member, Mesh, State, TrainSpec, in_state, solve

import davies_sym
from davies_sym.atlas.atlas_entries import Entry, entry, places
from davies_sym.atlas.enumeration import atlas, canonical_code
from davies_sym.atlas.recognition import OutsideAtlas, train_graph
from davies_sym.atlas.search import MESHES, oriented, search_file
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.network.analysis import analyse
from davies_sym.topology.loader import load_mapping
from davies_sym.topology.states import train_in_state


def run_derive(args: list[str], cwd: Path) -> Result:
    """``derive ARGS`` in this process, from the folder ``cwd``."""
    return run_main_in(cwd, args, timeout=3600)


def _entries(links: int) -> list[Entry]:
    return [entry(place) for place in places(links)]


@pytest.fixture(scope="module")
def entries() -> dict[int, list[Entry]]:
    return {n: _entries(n) for n in (4, 5, 6)}


@pytest.mark.parametrize(
    ("name", "held", "links"),
    [
        ("tuplin", None, 4),  # Laus Fig. 7: two annuli, one carrier
        ("wolfrom", None, 5),
        ("ravigneaux", "c", 6),  # ZF 3HP12, carrier held (1st gear and reverse)
        ("ravigneaux", "s2", 6),  # large sun held (2nd gear)
        ("simpson", "c2", 6),  # rear carrier held (1st gear)
        ("simpson", "s", 6),  # sun held (2nd gear)
    ],
)
def test_the_catalog_planetary_sets_lie_in_the_atlas(name: str, held: str | None, links: int) -> None:
    """Read from the catalog files (not typed here): each set with one member held is a
    displacement graph of the atlas of its link count."""
    graph = train_graph(davies_sym.load(davies_sym.catalog_file(name)), held)
    assert graph.links == links
    codes = {d.code for d in atlas(links).displacements}
    assert canonical_code(graph) in codes


def test_a_train_outside_the_atlas_is_named_with_its_coupling() -> None:
    with pytest.raises(OutsideAtlas, match=r"coupling W \(type: worm\)"):
        train_graph(davies_sym.load(davies_sym.catalog_file("worm_drive")))


def _willis_ratio(e: Entry, state: str, values: dict[sympy.Symbol, Fraction]) -> Fraction:
    """Input over output speed from Willis' equation of every mesh about its carrier,
    (w_a - w_k) r_a = -+(w_b - w_k) r_b (external -, internal +), the held member at
    rest and the input at speed 1, solved exactly."""
    document = yaml.safe_load(e.train_text())
    train = resolved_train(davies_sym.loads(e.train_text()))
    radius = {g.name: Fraction(str(sympy.sympify(g.radius).subs(values))) for g in train.gears}
    internal = {g.name for g in train.gears if g.internal}
    link_of = {name: int(gear["link"][1:]) for name, gear in document["gears"].items()}
    chosen = e.choices[[c.name for c in e.choices].index(state)]
    held, into, out = chosen.held, chosen.input, chosen.output
    n = e.graph.links
    rows, rhs = [_unit(n, held)], [Fraction(0)]
    rows.append(_unit(n, into))
    rhs.append(Fraction(1))
    for index, pair in enumerate(e.drawn.meshes):
        g, h = document["couplings"][f"M{index}"]["gears"]
        a, b, k = link_of[g], link_of[h], pair.pair.carrier
        sign = 1 if internal & {g, h} else -1
        row = [Fraction(0)] * n
        row[a] += radius[g]
        row[k] -= radius[g]
        row[b] -= sign * radius[h]
        row[k] += sign * radius[h]
        rows.append(row)
        rhs.append(Fraction(0))
    return 1 / _solve(rows, rhs)[out]


def _unit(n: int, k: int) -> list[Fraction]:
    return [Fraction(int(j == k)) for j in range(n)]


def _solve(rows: list[list[Fraction]], rhs: list[Fraction]) -> list[Fraction]:
    """The unique solution of a square system, by Gauss-Jordan elimination in fractions."""
    n = len(rows)
    augmented = [[*row, value] for row, value in zip(rows, rhs, strict=True)]
    for column in range(n):
        pivot = next(r for r in range(column, n) if augmented[r][column] != 0)
        augmented[column], augmented[pivot] = augmented[pivot], augmented[column]
        for r in range(n):
            if r != column and augmented[r][column] != 0:
                factor = augmented[r][column] / augmented[column][column]
                augmented[r] = [x - factor * y for x, y in zip(augmented[r], augmented[column], strict=True)]
    return [augmented[r][n] / augmented[r][r] for r in range(n)]


def _agrees_with_willis(e: Entry, state: str, ratio: sympy.Expr, chooser: random.Random) -> None:
    """The package's speed ratio ``ratio`` of ``state`` (null space of M_N) equals Willis'
    at a random point of positive radii where the output turns."""
    resolved = resolved_train(davies_sym.loads(e.train_text()))
    free = sorted({s for g in resolved.gears for s in sympy.sympify(g.radius).free_symbols}, key=str)
    for _ in range(200):
        values = {s: Fraction(chooser.randint(5, 60)) for s in free}
        at = ratio.subs(values)
        if all(sympy.sympify(g.radius).subs(values) > 0 for g in resolved.gears) and at.is_finite and at != 0:
            break
    assert Fraction(str(at)) == _willis_ratio(e, state, values), (e.name, state)


@pytest.mark.parametrize("links", [4, 5])
def test_every_written_train_turns_as_willis_says(entries: dict[int, list[Entry]], links: int) -> None:
    """Every state of every drawable train turns as Willis says (6 links: in the slow
    tier's derivation of every file, which forms the same speed ratios)."""
    chooser = random.Random(links)
    checked = 0
    for e in entries[links]:
        if e.not_drawable:
            continue
        train = davies_sym.loads(e.train_text())
        for state in train.states:
            _agrees_with_willis(e, state.name, analyse(train_in_state(train, state)).speed_ratio().to_expr(), chooser)
            checked += 1
    assert checked >= {4: 3, 5: 12}[links]


@pytest.mark.parametrize("links", [4, 5, 6])
def test_every_written_train_turns_about_the_axes_of_its_graph(entries: dict[int, list[Entry]], links: int) -> None:
    """The train file draws its own displacement graph: the gears of the links that
    turn about one axis of the graph are centred on one point of the layout, those of
    different axes on different points (a file that left two coaxial planets on axes of
    their own would draw another graph, with one geometric condition fewer)."""
    checked = 0
    for e in entries[links]:
        train = davies_sym.loads(e.train_text())
        layout = train_layout(train)
        drawn = e.drawn
        centres: dict[int, set[tuple[sympy.Expr, ...]]] = {}
        for gear in drawn.gears:
            point = tuple(sympy.expand(x) for x in layout.gear_centres[gear.name][:2])
            centres.setdefault(gear.axis, set()).add(point)
        assert all(len(points) == 1 for points in centres.values()), e.name
        assert len({next(iter(points)) for points in centres.values()}) == len(centres), e.name
        checked += sum(len(axis) - (axis != e.graph.axes[drawn.main_axis]) > 1 for axis in e.graph.axes)
    assert checked >= {4: 0, 5: 1, 6: 18}[links]


def test_the_atlas_draws_every_six_link_train(entries: dict[int, list[Entry]]) -> None:
    """All 81 six-link trains are written (9 with a gear centred on a pin its link holds,
    `about:`); the loop of four planets between two coaxial suns, whose quadrilateral of
    axes keeps one free shape, with the distance of its idler planet's axis from the
    main axis a parameter (`at: ed`) and the train file saying so."""
    assert len(entries[6]) == 81
    assert not [e.name for e in entries[6] if e.not_drawable]
    assert sum("about:" in e.train_text() for e in entries[6]) >= 9
    (loop,) = [e for e in entries[6] if e.free_axes]
    assert loop.code == "L6|0.1.2,0.3,0.4,0.5|1-3,2-4,3-5,4-5"
    text = loop.train_text()
    assert "at: ed}" in text and "the efficiency does not depend on it" in text
    assert len(loop.choices) == 3


#: Ordinary efficiencies of the meshes M0, M1, ... of the oracle's drawings below.
ORACLE_ETAS = (F(97, 100), F(49, 50), F(24, 25), F(99, 100), F(19, 20))


def _planets_between_suns(
    name: str, radii: dict[str, int], pairs: list[tuple[str, str]], at: dict[str, tuple[int, int]]
) -> TrainSpec:
    """The oracle's description of an atlas train of two suns l1, l2 at the origin and
    planets on carrier l0 at the whole coordinates ``at``: gear G<k><axis> of radius
    ``radii`` on link l<k>, meshes M0, M1, ... between ``pairs`` (`ORACLE_ETAS`)."""
    members = (
        Member("housing"),
        *(Member(f"l{k}") for k in range(3)),
        *(Member(link, "l0", (F(x), F(y))) for link, (x, y) in at.items()),
    )
    return TrainSpec(
        name,
        members,
        tuple(Gear(gear, f"l{gear[1]}", F(r)) for gear, r in radii.items()),
        tuple(Mesh(f"M{k}", pair, ORACLE_ETAS[k]) for k, pair in enumerate(pairs)),
        "housing",
        {f"B{k}": f"l{k}" for k in range(3)},
        "B1",
        "B2",
    )


def _agrees_with_the_balance(train: davies_sym.Train, spec: TrainSpec, designs: list[dict[str, object]]) -> int:
    """Every state and both directions of ``train``: the efficiency at each of ``designs``
    (radii, and the free distance ed where given) equals the oracle's, and the formulas
    do not take ed; the number of (state, direction) checked."""
    etas = {f"eta_{m.name}": m.eta for m in spec.meshes}
    checked = 0
    for state in train.states:
        variants = davies_sym.derive(train_in_state(train, state))
        assert "ed" not in {str(p) for p in variants.parameters}
        brake = tuple(state.brake)
        ports = (str(state.input), str(state.output))
        for port_in, port_out in (ports, ports[::-1]):
            expected = solve(in_state(spec, State(state.name, port_in, port_out, brake))).efficiency
            for design in designs:
                assert variants.evaluate(design | etas, port_in) == expected, (state.name, port_in, design)
            checked += 1
    return checked


def test_the_loop_of_planets_balances_as_the_oracle_says(entries: dict[int, list[Entry]]) -> None:
    """The loop of four planets (atlas6_r10_d6), every state and both directions: the
    efficiency derived from the written file (free distance ed) equals the independent
    per-member torque and force balance (tests/oracle/balance.py) at a drawing with whole
    coordinates, and does not change with ed, on which the formulas do not depend.  The
    drawing: the planets at b = (-16, 12), c = (35, 12) and d = (0, 12); |Ob| = 20 = r1 +
    r3, |bd| = 16 = r3 + r5, |Oc| = 37 = r2 + r4, |cd| = 35 = r4 + r5, with r = 7, 5, 13,
    32, 3."""
    (loop,) = [e for e in entries[6] if e.free_axes]
    radii = {"G1a": 7, "G2a": 5, "G3b": 13, "G4c": 32, "G5d": 3}
    pairs = [("G1a", "G3b"), ("G2a", "G4c"), ("G3b", "G5d"), ("G4c", "G5d")]
    spec = _planets_between_suns("loop of planets", radii, pairs, {"l3": (-16, 12), "l4": (35, 12), "l5": (0, 12)})
    sizes = {f"r{g[1:]}": r for g, r in radii.items()}
    designs = [sizes | {"ed": ed} for ed in (12, 15)]
    assert _agrees_with_the_balance(davies_sym.loads(loop.train_text()), spec, designs) == 6


def test_the_pentagon_of_planets_is_drawn_and_balances_as_the_oracle_says() -> None:
    """atlas7_r43_d15, a chain of four planets between two coaxial suns whose pentagon of
    axes keeps two free shapes: drawn with the distance ed of one planet's axis free and
    the next triangle closed on the side where ed > r2a + r4c (its mirror drawing has
    the same efficiency), so that all 647 trains of 7 links are written.  Every state, both
    directions: the efficiency equals the independent per-member balance and does not
    take ed.  The drawing: b = (-16, 12), d = (0, 12), e = (20, 12), c = (35, 12); |Ob| =
    20 = r1 + r3, |bd| = 16 = r3 + r5, |de| = 20 = r5 + r6, |ec| = 15 = r6 + r4, |Oc| = 37
    = r2 + r4, with r = 14, 32, 6, 5, 10, 10."""
    (place,) = [p for p in places(7) if (p.rotation, p.index) == (43, 15)]
    e = entry(place)
    assert e.not_drawable is None and len(e.choices) == 3
    text = e.train_text()
    assert "at: ed}" in text and "the efficiency does not depend on it" in text
    radii = {"G1a": 14, "G2a": 32, "G3b": 6, "G4c": 5, "G5d": 10, "G6e": 10}
    pairs = [("G1a", "G3b"), ("G2a", "G4c"), ("G3b", "G5d"), ("G4c", "G6e"), ("G5d", "G6e")]
    at = {"l3": (-16, 12), "l4": (35, 12), "l5": (0, 12), "l6": (20, 12)}
    spec = _planets_between_suns("pentagon of planets", radii, pairs, at)
    sizes = {f"r{g[1:]}": r for g, r in radii.items()}
    assert _agrees_with_the_balance(davies_sym.loads(text), spec, [sizes]) == 6


def test_a_gear_about_another_links_axis_is_read_and_checked(tmp_path) -> None:
    """`about:` names the link whose axis a gear is centred on; a name that is not a link,
    or `about` with a bevel `axis`, is refused at its entry."""
    e = next(x for x in _entries(5) if "about:" in x.train_text())
    text = e.train_text()
    train = davies_sym.loads(text)
    assert any(g.about is not None and g.about != g.link for g in train.gears)
    line = next(t for t in text.splitlines() if "about:" in t)
    for wrong, says in [("about: l9", "gears.G"), ("about: l0, axis: z", "drop `axis`")]:
        edited = text.replace(line, line.replace(line[line.index("about:") : line.index("}")], wrong))
        with pytest.raises(davies_sym.TopologyError, match=re.escape(says)):
            davies_sym.loads(edited)


def _as_built(train: davies_sym.Train) -> davies_sym.Train:
    """The train without the lines of its file (a train built from a mapping has none)."""
    return replace(train, locations=MappingProxyType({}))


def test_the_atlas_builds_the_train_its_file_reads(entries: dict[int, list[Entry]]) -> None:
    """The train the atlas builds from its train-file value (no YAML in between) is the
    one the written file reads as, for every drawn train of 4 and 5 links, with symbolic
    radii and, for the search, with tooth numbers and every direction as a state."""
    compared = 0
    for e in (x for n in (4, 5) for x in entries[n] if not x.not_drawable):
        assert e.train() == _as_built(davies_sym.loads(e.train_text())), e.name
        if e.loaded:
            searched = search_file(e, oriented(e.loaded), MESHES)
            assert searched.independent
            assert searched.train() == _as_built(davies_sym.loads(searched.text(""))), e.name
            assert yaml.safe_load(searched.text("")) == searched.document()
        compared += 1
    assert compared == 16


def test_a_train_built_from_a_mapping_is_refused_at_its_entries() -> None:
    """`load_mapping` checks what `loads` checks; without a file its problems are located
    by their entry paths."""
    with pytest.raises(davies_sym.TopologyError) as caught:
        load_mapping({"format": 1, "name": "broken", "links": ["l0"], "couplings": {}}, "atlas4_r01_d1")
    message = str(caught.value)
    assert "atlas4_r01_d1: links: a machine needs at least two links" in message, message


def test_derive_atlas_counts_and_json(tmp_path, entries: dict[int, list[Entry]]) -> None:
    """Yang & Ding (2019): 27 rotation graphs and 81 displacement graphs of 6 links; the
    JSON of every graph (here of 5 links), and of the 6-link entries the 81 train files
    and the 8 with a use in which every mesh carries a tooth force (docs/atlas.md)."""
    result = run_derive(["atlas", "--links", "6", "--count", "--json"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert (document["rotation_graphs"], document["displacement_graphs"]) == (27, 81)
    assert document["published"]["rotation_graphs"] == 27
    result = run_derive(["atlas", "--links", "5", "--json", "--quiet"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    graphs = json.loads(result.stdout)["graphs"]
    assert len(graphs) == 13
    fields = {"code", "rotation_code", "levels", "gears", "coaxial", "frame", "held", "choices", "train_file"}
    assert all(fields <= set(g) for g in graphs)
    assert all(g["choices"] for g in graphs if g["train_file"])
    assert sum(not e.not_drawable for e in entries[6]) == 81
    assert sum(bool(e.loaded) for e in entries[6]) == 8


def test_the_four_and_five_link_files_derive(tmp_path) -> None:
    """Every file written derives as written, every state."""
    for links in ("4", "5"):
        result = run_derive(["atlas", "--links", links, "--out", "trains", "--quiet"], cwd=tmp_path)
        assert result.returncode == 0, result.stderr
    files = sorted(str(p) for p in (tmp_path / "trains").glob("*.yaml"))
    assert len(files) >= 6
    result = run_derive([*files, "--out", "derived", "--quiet"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr + result.stdout
    assert len(list((tmp_path / "derived").glob("*.tex"))) == len(files)


def lossless_efficiency(variants: davies_sym.VariantSet, train: davies_sym.Train, chooser: random.Random) -> object:
    """The efficiency with every ordinary mesh efficiency 1 at the first drawn point of the
    design space (every radius and layout fact positive; radii and the formulas' other
    lengths whole numbers in [5, 60]); None where no draw of 400 is a design."""
    resolved = resolved_train(train)
    free = sorted({s for g in resolved.gears for s in sympy.sympify(g.radius).free_symbols}, key=str)
    free += sorted({s for s in variants.parameters if not str(s).startswith("eta_")} - set(free), key=str)
    lossless = {p: 1 for p in variants.parameters if str(p).startswith("eta_")}
    for _ in range(400):
        values: dict[object, object] = {s: chooser.randint(5, 60) for s in free} | lossless
        try:
            return variants.evaluate(values)
        except davies_sym.DesignError:
            continue
    return None


@pytest.mark.slow
def test_every_six_link_file_derives(entries: dict[int, list[Entry]]) -> None:
    """Every 6-link train file derives as written, every state (both directions of the
    power), each turning as Willis says; and its first state tends to efficiency 1 as the
    meshes lose nothing (every ordinary efficiency 1, at a point of positive radii)."""
    drawn = [e for e in entries[6] if not e.not_drawable]
    assert len(drawn) == 81
    chooser = random.Random(6)
    states = 0
    for e in drawn:
        train = davies_sym.loads(e.train_text())
        derived = {}
        for state in train.states:
            variants = davies_sym.derive(train_in_state(train, state))
            assert variants.variants, (e.name, state.name)
            _agrees_with_willis(e, state.name, variants.analysis.speed_ratio().to_expr(), chooser)
            derived[state.name] = variants
            states += 1
        assert lossless_efficiency(derived[train.states[0].name], train, chooser) == 1, e.name
    assert states >= 200


def test_out_and_draw_are_reproducible_and_never_overwrite_an_edit(tmp_path) -> None:
    args = ["atlas", "--links", "4", "--out", "trains", "--draw", "--quiet"]
    assert run_derive(args, cwd=tmp_path).returncode == 0
    first = {p.name: p.read_bytes() for p in (tmp_path / "trains").iterdir()}
    assert any(name.endswith(".graph.svg") for name in first) and any(name.endswith(".layout.svg") for name in first)
    assert run_derive(args, cwd=tmp_path).returncode == 0  # the same files again: written alike
    assert {p.name: p.read_bytes() for p in (tmp_path / "trains").iterdir()} == first
    edited = next(p for p in (tmp_path / "trains").iterdir() if p.suffix == ".yaml")
    edited.write_text(edited.read_text() + "# my note\n")
    result = run_derive(args, cwd=tmp_path)
    assert result.returncode == 2
    assert edited.name in result.stderr and "left as it is" in result.stderr
    assert edited.read_text().endswith("# my note\n")


def test_count_alone(tmp_path) -> None:
    """Yang & Ding (2019): 152 rotation graphs and 647 displacement graphs of 7 links."""
    result = run_derive(["atlas", "--links", "7", "--count", "--json"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert (document["rotation_graphs"], document["displacement_graphs"]) == (152, 647)
    assert "graphs" not in document


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--links", "4", "--count", "--out", "x"], "--count writes no train file"),
        (["--links", "2"], "--links: expected a number of links from 3 to 8"),
        (["--links", "six"], "--links: expected a number of links"),
        (["--links", "4", "--draw"], "--draw writes the drawings beside the train files: add --out DIR"),
        (["--links", "4", "--jobs", "0"], "--jobs: expected a number of processes"),
    ],
)
def test_bad_atlas_options_get_one_clear_message(tmp_path, args: list[str], says: str) -> None:
    result = run_derive(["atlas", *args], cwd=tmp_path)
    assert result.returncode == 2
    assert says in result.stderr
    assert "Traceback" not in result.stderr
