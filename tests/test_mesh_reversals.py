"""Meshes the losses reverse against their lossless direction (circulating power): the
variant that holds is printed with the conditions that hold where it is chosen.

With pure mesh efficiencies the direction of the power through a mesh under losses can
differ from its lossless (virtual power) direction near a turning condition.  The
variant of the neighbouring region's driving gears then holds, and it is printed as a
variant of the region the design lies in, "reversed by the losses", with the condition
on the reversed mesh's power.  At the two designs of the issue the number is the
independent per-member torque balance's (tests/oracle/balance.py: each mesh's loss by
its actual power direction, no code shared with the package), and every output (--eval,
JSON, LaTeX, the formula module) names the same variant, whose printed conditions,
read back from the text, hold there.  The slow test checks the same over every 6-link
atlas train and one 7-link file in 32 (the whole 7-link atlas with
DAVIES_SYM_WHOLE_ATLAS=1, for its cost): wherever the formula module or the engine gives
a number, the printed conditions of the variant it took hold.
"""

from __future__ import annotations

import json
import os
import warnings
from fractions import Fraction as F
from functools import cache
from pathlib import Path

import numpy as np
import pytest
import sympy
from harness.helpers import run_main
from oracle.balance import Gear, Member, Mesh, State, TrainSpec, in_state, solve, with_efficiencies

import davies_sym
from davies_sym.atlas.atlas_entries import Entry, entry, places
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.topology.states import train_in_state

#: The four mesh efficiencies of the issue, in the order of the meshes M0..M3.
ETAS = {"M0": F("0.980"), "M1": F("0.928"), "M2": F("0.969"), "M3": F("0.923")}


@cache
def _entries(links: int) -> dict[str, Entry]:
    return {e.name: e for e in (entry(place) for place in places(links)) if not e.not_drawable}


def _r23_d11() -> TrainSpec:
    """atlas6_r23_d11 at r1b=30 r2a=60 r4a=41 r5b2=12 (r5b = 11, r3ar = 82, r4ar = 83): the
    coaxial planets l1 and l5 on carrier l0 at the axis b = (0, r1b + r4a).  l5 turns in
    a bearing on l1, which turns in l0; both frictionless, so l5 is described as carried
    by l0 at the same axis (the same forces reach l0 there)."""
    b = (F(0), F(71))
    members = (
        Member("housing"),
        *(Member(f"l{k}") for k in (0, 2, 3, 4)),
        Member("l1", "l0", b),
        Member("l5", "l0", b),
    )
    gears = (
        Gear("G1b", "l1", F(30)),
        Gear("G2a", "l2", F(60)),
        Gear("G3ar", "l3", F(82), True),
        Gear("G4a", "l4", F(41)),
        Gear("G4ar", "l4", F(83), True),
        Gear("G5b", "l5", F(11)),
        Gear("G5b2", "l5", F(12)),
    )
    pairs = {"M0": ("G4a", "G1b"), "M1": ("G2a", "G5b"), "M2": ("G3ar", "G5b"), "M3": ("G4ar", "G5b2")}
    meshes = tuple(Mesh(n, g, ETAS[n]) for n, g in pairs.items())
    return TrainSpec("r23_d11", members, gears, meshes, "housing", {f"B{k}": f"l{k}" for k in (0, 2, 3, 4)}, "B3", "B4")


def _r25_d5() -> TrainSpec:
    """atlas6_r25_d5 at r1a=30 r5b=11 r5b2=12 r5b3=15 (r2ar = 52, r3ar = 53, r4ar = 56): the
    planet l5 on carrier l0 at the axis b = (0, r1a + r5b)."""
    members = (Member("housing"), *(Member(f"l{k}") for k in range(5)), Member("l5", "l0", (F(0), F(41))))
    gears = (
        Gear("G1a", "l1", F(30)),
        Gear("G2ar", "l2", F(52), True),
        Gear("G3ar", "l3", F(53), True),
        Gear("G4ar", "l4", F(56), True),
        Gear("G5b", "l5", F(11)),
        Gear("G5b2", "l5", F(12)),
        Gear("G5b3", "l5", F(15)),
    )
    pairs = {"M0": ("G1a", "G5b"), "M1": ("G2ar", "G5b"), "M2": ("G3ar", "G5b2"), "M3": ("G4ar", "G5b3")}
    meshes = tuple(Mesh(n, g, ETAS[n]) for n, g in pairs.items())
    return TrainSpec("r25_d5", members, gears, meshes, "housing", {f"B{k}": f"l{k}" for k in range(5)}, "B1", "B2")


#: (atlas file, state, input, output, held member, the design's values, its oracle description)
CASES = [
    (
        "atlas6_r23_d11",
        "h2_i3_o4",
        "B4",
        "B3",
        "l2",
        {"r1b": 30, "r2a": 60, "r3ar": 82, "r4a": 41, "r4ar": 83, "r5b": 11, "r5b2": 12},
        _r23_d11,
    ),
    (
        "atlas6_r25_d5",
        "h1_i2_o3",
        "B3",
        "B2",
        "l1",
        {"r1a": 30, "r5b": 11, "r5b2": 12, "r5b3": 15},
        _r25_d5,
    ),
]


def _holds(text: str, values: dict[str, object]) -> bool:
    """Whether a printed condition ``EXPR > 0`` (or ``< 0``), read back by sympy's parser,
    holds at ``values`` (exactly)."""
    what = text.split(": ", 1)[-1]
    expression, relation = (what[:-4], what[-3:]) if what.endswith((" > 0", " < 0")) else (what, "")
    value = sympy.sympify(expression).subs({sympy.Symbol(k): sympy.nsimplify(v) for k, v in values.items()})
    assert relation in ("> 0", "< 0") and value.is_number, text
    return bool(value > 0) if relation == "> 0" else bool(value < 0)


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_the_reversed_mesh_variant_holds_where_it_is_printed(case, tmp_path: Path) -> None:
    """--eval gives the oracle's efficiency and names a variant reversed by the losses;
    its printed turning condition and force conditions (text and JSON) hold at the
    design; the formula module takes the same variant and value; the lossless direction
    of the reversed mesh (the oracle's lossless balance) is the other one."""
    name, state, port_in, port_out, held, geometry, spec = case
    path = tmp_path / f"{name}.yaml"
    path.write_text(_entries(6)[name].train_text())
    oracle_train = in_state(spec(), State(state, port_in, port_out, (held,)))
    truth = solve(oracle_train)
    lossless = solve(with_efficiencies(oracle_train, F(1)), lossless=True)
    assert solve(with_efficiencies(oracle_train, F(1))).efficiency == 1
    # P_in + P_out + losses = 0 (the losses as the power the meshes take), each mesh's
    # loss by its actual power direction.
    assert truth.power_in + truth.power_out - sum(truth.losses.values()) == 0
    assert all(loss >= 0 for loss in truth.losses.values())
    values = {**geometry, **{f"eta_{m}": str(v) for m, v in ETAS.items()}}
    args = [str(path), "--state", state, "--input", port_in, "--quiet"]
    result = run_main([*args, "--eval", *(f"{k}={v}" for k, v in values.items()), "--json"])
    assert result.returncode == 0, result.stderr
    answer = json.loads(result.stdout)
    exact = sympy.Rational(truth.efficiency.numerator, truth.efficiency.denominator)
    assert sympy.Rational(answer["efficiency_exact"]) == exact
    number = answer["variant"]["number"]
    report = json.loads(run_main([str(path), "--state", state, "--json", "--quiet"]).stdout)
    listed = {v["number"]: v for v in report["states"][state]["variants"]}
    chosen = listed[number]
    turned = [m for m in truth.first_drives if truth.first_drives[m] != lossless.first_drives[m] and truth.losses[m]]
    assert chosen["input"] == port_in and chosen["reversed_forces"] == sorted(turned) and turned
    for c in chosen["conditions"]:
        assert _holds(f"{c['expression']} {'>' if c['sign'] > 0 else '<'} 0", values)
    for force in chosen["loaded_forces"]:
        assert _holds(f"{force['expression']} {'>' if force['sign'] > 0 else '<'} 0", values)
    assert any("reversed by the losses" in force["force"] for force in chosen["loaded_forces"])
    text = run_main([str(path), "--state", state, "--quiet"]).stdout
    section = text.split(f"  ({number}) input {port_in}, output {port_out}, where ")[1].split("\n  (")[0]
    where = section.split(":\n", 1)[0]
    assert all(_holds(part, values) for part in where.split(" and "))
    held_lines = [line.strip()[len("holds where the ") :] for line in section.splitlines() if "holds where" in line]
    assert held_lines and all(_holds(line, values) for line in held_lines)
    module_text = run_main([*args[:3], "--python", str(tmp_path / "m.py")])
    assert module_text.returncode == 0, module_text.stderr
    module = compiled_module((tmp_path / "m.py").read_text(), name)
    floats = {k: float(F(str(v))) for k, v in values.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert int(module.variant(input=port_in, **floats)) == number
        assert float(module.efficiency(input=port_in, **floats)) == pytest.approx(float(truth.efficiency), rel=1e-12)
    assert [v["reversed"] for v in module.VARIANTS if v["number"] == number] == [tuple(sorted(turned))]
    latex = run_main([*args[:3], "--latex"]).stdout
    assert rf"\paragraph{{Variant ({number})}}" in latex and "reversed by the losses" in latex


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_the_efficiency_tends_to_one_without_losses(case) -> None:
    """At the same designs the efficiency is exactly 1 with every ordinary efficiency 1
    and tends to 1 as they do (1 - 10^-k), with the oracle's value at each."""
    name, state, port_in, port_out, held, geometry, spec = case
    train = davies_sym.loads(_entries(6)[name].train_text())
    variants = davies_sym.derive(train_in_state(train, state))
    oracle_train = in_state(spec(), State(state, port_in, port_out, (held,)))
    assert variants.evaluate({**geometry, **{f"eta_{m}": 1 for m in ETAS}}, port_in) == 1
    for k in (2, 4, 6):
        eta = 1 - F(1, 10**k)
        value = variants.evaluate(
            {**geometry, **{f"eta_{m}": sympy.Rational(1) - sympy.Rational(1, 10**k) for m in ETAS}}, port_in
        )
        truth = solve(with_efficiencies(oracle_train, eta)).efficiency
        assert value == sympy.Rational(truth.numerator, truth.denominator)
        assert 0 < 1 - value < 10 * sympy.Rational(1, 10**k)


#: Shards of the atlas files per number of links (the slow test spreads over workers).
SHARDS = {6: 4, 7: 32}
#: The 7-link shards the slow tier runs: one of the 32 (about 20 files); the whole 7-link
#: atlas, about an hour of one core, runs with DAVIES_SYM_WHOLE_ATLAS=1.
WHOLE_ATLAS = os.environ.get("DAVIES_SYM_WHOLE_ATLAS") == "1"
#: Designs drawn per state: radii whole numbers in [5, 60], ordinary efficiencies in [1/2, 1).
DRAWS = 300


def _read(text: str) -> tuple[object, float]:
    """A printed condition ``[what: ]EXPR > 0`` as a numpy function of its symbols' names
    and the sign it needs."""
    what = text.split(": ", 1)[-1]
    assert what.endswith((" > 0", " < 0")), text
    expression = sympy.sympify(what[:-4])
    names = sorted(map(str, expression.free_symbols))
    function = sympy.lambdify([sympy.Symbol(n) for n in names], expression, "numpy")
    return (function, names), 1.0 if what.endswith("> 0") else -1.0


def _drawn(module, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Random designs for a formula module's parameters (the dependent ones left out)."""
    out = {}
    for p in module.PARAMETERS:
        if p["name"] in module.DEPENDENT:
            continue
        if p["name"].startswith("eta_"):
            out[p["name"]] = rng.integers(500, 1000, DRAWS) / 1000
        else:
            out[p["name"]] = rng.integers(5, 61, DRAWS).astype(float)
    return out


def _positive_radii(module, values: dict[str, np.ndarray]) -> np.ndarray:
    """Where every dependent pitch radius (the module's DEPENDENT relations, read back)
    is positive: the designs the engine admits (a state's module leaves out relations
    that only other states' formulas need)."""
    ok = np.ones(DRAWS, dtype=bool)
    for relation in module.DEPENDENT.values():
        (function, names), _ = _read(relation.split(" = ", 1)[1] + " > 0")
        if all(n in values for n in names):
            ok &= np.asarray(function(*(values[n] for n in names))) > 0
    return ok


def _printed_hold(module, numbers: np.ndarray, values: dict[str, np.ndarray]) -> list[str]:
    """The printed conditions (turning conditions and loaded forces, as the module's
    VARIANTS write them) that fail at a point where the module took their variant."""
    failed = []
    for number in sorted(set(numbers.tolist()) - {0}):
        (variant,) = [v for v in module.VARIANTS if v["number"] == number]
        rows = numbers == number
        for text in (*variant["conditions"], *variant["forces"]):
            (function, names), sign = _read(text)
            value = sign * np.broadcast_to(np.asarray(function(*(values[n][rows] for n in names)), float), rows.sum())
            if np.any(value < -1e-9):
                failed.append(f"variant ({number}) at {int(np.sum(value < -1e-9))} point(s): {text[:80]}")
    return failed


def _check_state(train: davies_sym.Train, state: str, rng: np.random.Generator) -> list[str]:
    """Every failure of the contract in one state: where the module gives a number, the
    printed conditions of the variant it took hold, and the engine (exact) takes the same
    variant at two of those designs."""
    try:
        variants = davies_sym.derive(train_in_state(train, state))
    except davies_sym.DaviesError as exc:  # every state of an atlas file derives
        return [f"{state}: refused: {exc}"]
    module = compiled_module(python_module(variants), "state")
    values = _drawn(module, rng)
    failed = []
    for port in module.PORTS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            numbers = np.asarray(module.variant(input=port, errors="ignore", **values), dtype=int)
            # The points the formulas evaluate: a number, not a refusal (NaN).
            numbers[~np.isfinite(module.efficiency(input=port, errors="ignore", **values))] = 0
        numbers[~_positive_radii(module, values)] = 0
        failed += [f"{state} input {port}: {why}" for why in _printed_hold(module, numbers, values)]
        for k in np.flatnonzero(numbers)[:2]:
            point = {n: sympy.Rational(str(float(v[k]))) for n, v in values.items()}  # drawn k / 1000: exact
            try:
                chosen = variants.design_point(point, port).variant.number
            except davies_sym.DaviesError as exc:
                if "does not decide" in str(exc) and f"({numbers[k]})" in str(exc):
                    # Several power flows agree with their forces (the friction does not
                    # decide): the engine refuses, the module takes the first of them.
                    continue
                failed.append(f"{state} input {port}: the module took ({numbers[k]}), the engine refused: {exc}")
                continue
            if chosen != numbers[k]:
                failed.append(f"{state} input {port}: the module took ({numbers[k]}), the engine ({chosen})")
    return failed


def _shards() -> list[tuple[int, int]]:
    return [(n, k) for n, count in SHARDS.items() for k in range(count) if n == 6 or WHOLE_ATLAS or k == 0]


def _shard(links: int, shard: int) -> list[Entry]:
    """The drawable files of one shard, formed alone (the whole 7-link atlas takes
    minutes to form): every SHARDS-th by name."""
    chosen = sorted(places(links), key=lambda p: f"atlas{links}_r{p.rotation:02d}_d{p.index}")
    return [e for e in map(entry, chosen[shard :: SHARDS[links]]) if not e.not_drawable]


@pytest.mark.slow
@pytest.mark.parametrize(("links", "shard"), _shards())
def test_every_atlas_train_holds_where_its_variant_is_printed(links: int, shard: int) -> None:
    """Every 6- and 7-link atlas file, every state, both inputs: at random designs
    (ordinary efficiencies down to 1/2, so that the losses reverse meshes near the turning
    conditions) the variant the formula module takes has its printed turning conditions
    and force conditions true, and the engine takes the same variant."""
    files = _shard(links, shard)
    rng = np.random.default_rng(1000 * links + shard)
    failed = []
    for e in files:
        train = davies_sym.loads(e.train_text())
        for state in train.states:
            failed += [f"{e.name} {why}" for why in _check_state(train, state.name, rng)]
    assert files and not failed, "\n".join(failed[:20])


def test_a_design_whose_planets_triangle_cannot_close_is_refused_by_every_route() -> None:
    """atlas7_r142_d17 in state h4_i1_o3, where the module took variant (5) at designs its
    printed c3 > 0 did not hold: the planet axes b (r1a + r5b from the main axis) and c
    (r2a + r6c) lie r5b + r6c apart, a triangle that closes only where r1a < r2a + 2 r6c
    (r5b cancels; it is no symbol of this state's formulas, and the radicand with it was
    all the formulas had).  At r1a = 49, r2a = 26, r6c = 9 the module and the engine both
    refuse; at r1a = 40 both take one variant, whose printed conditions hold there."""
    (place,) = [p for p in places(7) if (p.rotation, p.index) == (142, 17)]
    train = davies_sym.loads(entry(place).train_text())
    variants = davies_sym.derive(train_in_state(train, "h4_i1_o3"))
    module = compiled_module(python_module(variants), "r142_d17")
    etas = {p["name"]: 0.9 for p in module.PARAMETERS if p["name"].startswith("eta_")}
    assert any(r.replace(" ", "") == "-r1a+r2a+2*r6c>0" for r in module.RELATIONS), module.RELATIONS
    outside = {"r1a": 49.0, "r2a": 26.0, "r6c": 9.0, "r6c2": 19.0}
    with pytest.raises(module.DesignError, match="outside the admissible parameters"):
        module.efficiency(input="B1", errors="raise", **outside, **etas)
    with pytest.raises(davies_sym.DesignError, match="triangle"):
        variants.design_point({**outside, **etas}, "B1")
    inside = {**outside, "r1a": 40.0}
    number = int(module.variant(input="B1", **inside, **etas))
    assert variants.design_point({**inside, **etas}, "B1").variant.number == number
    values = {k: np.array([v]) for k, v in {**inside, **etas}.items()}
    assert _printed_hold(module, np.array([number]), values) == []


def test_a_relation_in_the_speed_ratios_symbols_alone_is_checked_by_the_module() -> None:
    """atlas7_r138_d15 in state h0_i1_o4: a series of fixed-axis meshes whose efficiency,
    eta_M0 eta_M3 eta_M4, takes no radius, while the speed ratio takes r1a, r3a and r6c,
    and the planets' triangle closes only where r3a + 2 r6c > r1a.  A module given those
    radii refuses a design that breaks it, as the engine does (the module took variant
    (1) there, the engine refused); given the efficiencies alone, both answer."""
    (place,) = [p for p in places(7) if (p.rotation, p.index) == (138, 15)]
    train = davies_sym.loads(entry(place).train_text())
    variants = davies_sym.derive(train_in_state(train, "h0_i1_o4"))
    module = compiled_module(python_module(variants), "r138_d15")
    etas = {"eta_M0": 0.9, "eta_M3": 0.95, "eta_M4": 0.97}
    outside = {"r1a": 49.0, "r3a": 26.0, "r6c": 9.0}
    with pytest.raises(module.DesignError, match="outside the admissible parameters"):
        module.efficiency(input="B1", errors="raise", **outside, **etas)
    with pytest.raises(davies_sym.DesignError, match="triangle"):
        variants.design_point({**outside, **etas}, "B1")
    inside = {**outside, "r1a": 40.0}
    product = F("0.9") * F("0.95") * F("0.97")
    assert float(module.efficiency(input="B1", errors="raise", **inside, **etas)) == pytest.approx(float(product))
    assert variants.evaluate({k: sympy.Rational(str(v)) for k, v in {**inside, **etas}.items()}, "B1") == product
    assert float(module.efficiency(input="B1", errors="raise", **etas)) == pytest.approx(float(product))
