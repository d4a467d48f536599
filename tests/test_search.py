"""``derive search``: the tooth numbers of a train with symbolic teeth that hit a speed ratio,
ranked by their efficiency, checked against a brute force written here (no code shared with
the search).

The oracle enumerates every pair of free tooth numbers (sun ``zs``, ring ``zr``) of a simple
planetary set in the given bounds and applies each rule of the command by hand:

- the planet's tooth number follows from the coaxiality of sun, planet and ring with one
  module, zr = zs + 2 zp, and must be whole (Niemann and Winter, Maschinenelemente II,
  2nd ed., 1983, section 24.2; Müller, Epicyclic Drive Trains, 1982, ch. 3);
- every tooth number, the planet's included, is at least ``--min-teeth`` (17 by default);
- the speed ratio, 1 + zr/zs with the sun in, the carrier out and the ring held (Willis),
  is within the relative tolerance of the target: |ratio - target| <= tol |target|;
- N planets can be equally spaced: (zs + zr)/N is whole (Müller, ch. 3; Niemann and Winter,
  section 24.2);
- neighbouring planets' tip circles clear each other: 2 a sin(pi/N) > m (zp + 2), with the
  orbit radius a = m (zs + zp)/2 and the planet's tip diameter m (zp + 2) (addendum of one
  module), decided exactly (the squares of sin(pi/N) for N = 2 to 6 are 1, 3/4, 1/2,
  (5 - sqrt 5)/8 and 1/4);
- the efficiency is in (0, 1].

The efficiency comes from a torque balance of the set's members in exact fractions (see
:func:`planetary_balance`), which reduces to the textbook closed forms (Müller, ch. 5):
eta = (1 + eta0 i0)/(1 + i0) with the sun in and the ring held, and eta = (i0 + eta0)/(i0 + 1)
with the ring in and the sun held, where i0 = zr/zs and eta0 = eta_M1 eta_M2 (the efficiency
of the set seen from the carrier, where sun, planet and ring turn about fixed axes).
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from fractions import Fraction as F
from pathlib import Path

import pytest
import yaml
from harness.helpers import run_main

DATA = Path(__file__).resolve().parent / "data"
PLANETARY = DATA / "search_planetary.yaml"
SPELLED = DATA / "search_planetary_spelled.yaml"
STATES = DATA / "search_states.yaml"

#: The efficiency of the set seen from the carrier: both meshes in series (the files' 0.98 and 0.99).
ETA0 = F(98, 100) * F(99, 100)
#: The spelled file's tooth-number names, as those of search_planetary.yaml.
SPELLED_NAMES = {"za": "zs", "zq": "zp", "zr_b": "zr"}
#: Every rule of the oracle, by the name used here (the command's own names are free).
RULES = ("whole", "min_teeth", "ratio", "assembly", "clearance", "efficiency")


# --- the oracle: a torque balance and the rules ---------------------------------------------------------------


def planetary_balance(zs: int, zr: int, eta0: F, driving: str, held: str) -> tuple[F, F]:
    """Speed ratio (driving member over carrier) and efficiency of a simple planetary set with the
    carrier as output, from the members' balances in exact fractions.

    Kinematics (Willis): seen from the carrier, sun and ring turn as a fixed-axis pair of ratio
    -zr/zs: ws - wc = -(zr/zs)(wr - wc).  Balances: the planets carry no outer torque, so the outer
    torques on sun, ring and carrier sum to zero, Ts + Tr + Tc = 0 (moments of the whole set about
    its axis).  Losses (Müller 1982, ch. 5; Davies' mesh efficiency per mesh): seen from the carrier
    no member carries a speed-dependent loss but the two meshes, so the power entering the set at
    the member that drives in the carrier's frame leaves at the other one times eta0 = eta_M1 eta_M2
    (sun -> planet -> ring, or ring -> planet -> sun).  Which member drives in the carrier's frame
    is read from the lossless balance and checked again with the losses.
    """
    i0 = F(zr, zs)
    wc = F(1)
    w = {"carrier": wc}
    if held == "ring":
        w["ring"] = F(0)
        w["sun"] = wc - i0 * (w["ring"] - wc)
    elif held == "sun":
        w["sun"] = F(0)
        w["ring"] = wc - (w["sun"] - wc) / i0
    else:
        raise ValueError(held)
    us, ur = w["sun"] - wc, w["ring"] - wc  # speeds seen from the carrier

    def torques(eta: F) -> dict[str, F]:
        # Lossless ring-to-sun torque ratio: Ts us + Tr ur = 0.
        lossless_k = -us / ur
        # The sun drives in the carrier's frame where Ts us > 0: Ts = 1 (sun in), or Ts = 1/k (ring in, Tr = 1).
        sun_drives = us > 0 if driving == "sun" else (1 / lossless_k) * us > 0
        k = -eta * us / ur if sun_drives else -us / (eta * ur)  # Tr = k Ts
        t = {"sun": F(1), "ring": k} if driving == "sun" else {"sun": 1 / k, "ring": F(1)}
        t["carrier"] = -(t["sun"] + t["ring"])
        assert (t["sun"] * us > 0) == sun_drives, "the member driving in the carrier's frame changed with the losses"
        return t

    t = torques(eta0)
    assert t["sun"] + t["ring"] + t["carrier"] == 0
    assert t[held] * w[held] == 0
    power_in = t[driving] * w[driving]
    power_out = -t["carrier"] * wc
    return w[driving] / wc, power_out / power_in


def clear_of_each_other(zs: int, zp: int, planets: int) -> bool:
    """Neighbouring planets' tip circles do not touch: 2 a sin(pi/N) > m (zp + 2), a = m (zs + zp)/2,
    i.e. (zs + zp) sin(pi/N) > zp + 2 (the module cancels), decided exactly on squares."""
    s, q = zs + zp, zp + 2
    if planets == 2:
        return s > q
    if planets == 3:
        return 3 * s * s > 4 * q * q
    if planets == 4:
        return s * s > 2 * q * q
    if planets == 5:  # s^2 (5 - sqrt 5)/8 > q^2  <=>  5 s^2 - 8 q^2 > sqrt(5) s^2
        lhs = 5 * s * s - 8 * q * q
        return lhs > 0 and lhs * lhs > 5 * s**4
    if planets == 6:
        return s > 2 * q
    raise ValueError(planets)


#: Per state: (driving member, held member); None is the state of a file without states.
STATE_MEMBERS = {None: ("sun", "ring"), "low": ("sun", "ring"), "high": ("ring", "sun")}


@dataclass(frozen=True)
class Space:
    """One search: the command's options and the oracle's reading of them."""

    id: str
    path: Path
    targets: dict[str | None, str]
    tolerance: str
    teeth: dict[str, tuple[int, int]]
    planets: int
    min_teeth: int | None = None  # None: the option left out (17)
    weights: dict[str, str] = field(default_factory=dict)
    top: int = 1000

    def args(self, *, top: int | None = None) -> list[str]:
        targets = [t if s is None else f"{s}={t}" for s, t in self.targets.items()]
        teeth = [f"{n}={lo}:{hi}" for n, (lo, hi) in self.teeth.items()]
        out = ["search", str(self.path), "--target", *targets, "--tolerance", self.tolerance, "--teeth", *teeth]
        out += ["--planets", str(self.planets)]
        if self.min_teeth is not None:
            out += ["--min-teeth", str(self.min_teeth)]
        if self.weights:
            out += ["--weights", *(f"{s}={w}" for s, w in self.weights.items())]
        return [*out, "--top", str(self.top if top is None else top), "--quiet"]


@dataclass(frozen=True)
class Design:
    teeth: dict[str, int]
    ratio: dict[str | None, F]
    efficiency: dict[str | None, F]
    score: F
    on_boundary: bool  # the ratio exactly on a tolerance bound (a float search may go either way)


_FEASIBLE: dict[tuple[str, frozenset[str]], list[Design]] = {}


def brute_force(space: Space, skip: frozenset[str] = frozenset()) -> list[Design]:
    """Every feasible design of ``space`` by enumeration, best first (``skip``: rules left out, to
    show that each rule decides something in the spaces tested); computed once per space."""
    key = (space.id, skip)
    if key not in _FEASIBLE:
        _FEASIBLE[key] = _enumerate(space, skip)
    return _FEASIBLE[key]


def _enumerate(space: Space, skip: frozenset[str]) -> list[Design]:
    (lo_s, hi_s), (lo_r, hi_r) = space.teeth["zs"], space.teeth["zr"]
    minimum = 17 if space.min_teeth is None else space.min_teeth
    tol = F(space.tolerance)
    out = []
    for zs in range(lo_s, hi_s + 1):
        for zr in range(lo_r, hi_r + 1):
            if (zr - zs) % 2 or zr <= zs:  # a planet of positive whole tooth number
                continue
            zp = (zr - zs) // 2
            if "min_teeth" not in skip and min(zs, zp, zr) < minimum:
                continue
            ratios, effs, boundary, ok = {}, {}, False, True
            for state, target_text in space.targets.items():
                driving, held = STATE_MEMBERS[state]
                ratio, eff = planetary_balance(zs, zr, ETA0, driving, held)
                target = F(target_text)
                error, allowed = abs(ratio - target), tol * abs(target)
                boundary = boundary or error == allowed
                if "ratio" not in skip and error > allowed:
                    ok = False
                if "efficiency" not in skip and not 0 < eff <= 1:
                    ok = False
                ratios[state], effs[state] = ratio, eff
            if not ok:
                continue
            if "assembly" not in skip and (zs + zr) % space.planets:
                continue
            if "clearance" not in skip and not clear_of_each_other(zs, zp, space.planets):
                continue
            if space.weights:
                weights = {s: F(w) for s, w in space.weights.items()}
                score = sum(weights[s] * effs[s] for s in effs) / sum(weights.values())
            else:
                score = sum(effs.values()) / len(effs)
            out.append(Design({"zs": zs, "zp": zp, "zr": zr}, ratios, effs, score, boundary))
    return sorted(out, key=lambda d: -d.score)


SPACES = [
    # The example of the command's description.
    Space("example", PLANETARY, {None: "4.6"}, "0.01", {"zs": (17, 60), "zr": (50, 150)}, 3, 17),
    # Four planets, at least 20 teeth, a tight tolerance.
    Space("four_planets", PLANETARY, {None: "3.5"}, "0.002", {"zs": (20, 45), "zr": (50, 120)}, 4, 20),
    # Five planets, --min-teeth left out, suns from 12 teeth.
    Space("five_planets", PLANETARY, {None: "4.1"}, "0.02", {"zs": (12, 40), "zr": (36, 130)}, 5),
    # A ratio of 7 leaves large planets: five of them never clear each other, nothing is feasible.
    Space("none_feasible", PLANETARY, {None: "7"}, "0.005", {"zs": (17, 30), "zr": (100, 200)}, 5),
]
#: Six planets: sin(pi/6) = 1/2 makes tip circles that just touch (zs = zp + 4) possible; they are refused.
#: --min-teeth left out: a planet of fewer than 17 teeth is refused by the default.
SIX = Space("six_planets", PLANETARY, {None: "3.6"}, "0.05", {"zs": (17, 40), "zr": (50, 130)}, 6)
#: A ratio exactly on the tolerance's bound: 1 + 77/25 = 4.08 = 4 (1 + 0.02) counts as within (|error| <= tol |target|).
ON_THE_BOUND = Space("on_the_bound", PLANETARY, {None: "4"}, "0.02", {"zs": (20, 30), "zr": (60, 90)}, 3, 17)
#: Two states, weighted: both ratios within the tolerance, ranked by the weighted mean efficiency.
TWO_STATES = Space(
    "two_states",
    STATES,
    {"low": "4.6", "high": "1.28"},
    "0.01",
    {"zs": (17, 60), "zr": (50, 150)},
    3,
    17,
    weights={"low": "3", "high": "1"},
)


def search(space: Space, *extra: str, top: int | None = None) -> dict:
    result = run_main([*space.args(top=top), "--json", *extra])
    assert result.returncode == 0, result.describe()
    assert "Traceback" not in result.stderr, result.describe()
    try:
        return json.loads(result.stdout)
    except json.JSONDecodeError as exc:  # pragma: no cover - the failure's report
        raise AssertionError(f"stdout is not one JSON document ({exc}):\n{result.describe()}") from exc


def teeth_key(teeth: dict[str, int]) -> tuple[tuple[str, int], ...]:
    return tuple(sorted(teeth.items()))


def per_state(value: object, state: str | None) -> float:
    """A candidate's speed ratio or efficiency: a number, or {STATE: number} for a file with states."""
    if state is None:
        assert isinstance(value, (int, float)) and not isinstance(value, bool), value
        return float(value)
    assert isinstance(value, dict), value
    return float(value[state])


def check_document(space: Space, doc: dict, expected: list[Design], top: int | None = None) -> None:
    """The document lists exactly the oracle's feasible designs, best first, with their values."""
    top = space.top if top is None else top
    for key in ("candidates", "searched", "feasible", "rules", "seconds"):
        assert key in doc, f"no {key!r} in the document: {sorted(doc)}"
    grid = math.prod(hi - lo + 1 for lo, hi in space.teeth.values())
    assert doc["feasible"] == len(expected), (doc["feasible"], len(expected))
    assert isinstance(doc["searched"], int) and len(expected) <= doc["searched"] <= grid, (doc["searched"], grid)
    assert isinstance(doc["rules"], list) and doc["rules"] and all(isinstance(r, str) for r in doc["rules"])
    assert isinstance(doc["seconds"], (int, float)) and doc["seconds"] >= 0
    candidates = doc["candidates"]
    assert len(candidates) == min(top, len(expected)), (len(candidates), top, len(expected))
    oracle = {teeth_key(d.teeth): d for d in expected}
    seen = set()
    for rank, cand in enumerate(candidates):
        teeth = cand["teeth"]
        assert set(teeth) == {"zs", "zp", "zr"}, teeth
        assert all(type(v) is int for v in teeth.values()), f"tooth numbers not integers: {teeth}"
        key = teeth_key(teeth)
        assert key not in seen, f"{teeth} listed twice"
        seen.add(key)
        assert key in oracle, f"candidate {rank} {teeth} is not feasible by the rules"
        design = oracle[key]
        for state in space.targets:
            assert per_state(cand["speed_ratio"], state) == pytest.approx(float(design.ratio[state]), rel=1e-12)
            assert per_state(cand["efficiency"], state) == pytest.approx(float(design.efficiency[state]), abs=1e-12)
        assert float(cand["score"]) == pytest.approx(float(design.score), abs=1e-12), (teeth, cand["score"])
        # Best first: the k-th candidate has the k-th best score (ties share their score).
        assert float(design.score) == pytest.approx(float(expected[rank].score), abs=1e-12), (rank, teeth)
    if top >= len(expected):
        assert seen == set(oracle), f"feasible designs missing: {sorted(set(oracle) - seen)[:10]}"


# --- the oracle checked ------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("zs", "zr"), [(17, 61), (21, 75), (24, 84), (30, 120), (40, 100)])
def test_balance_gives_the_closed_forms(zs: int, zr: int) -> None:
    """The torque balance reproduces Müller's closed forms (ch. 5) and Willis' ratios; a lossless
    set has efficiency 1 (a check of the balance itself)."""
    i0 = F(zr, zs)
    assert planetary_balance(zs, zr, ETA0, "sun", "ring") == (1 + i0, (1 + ETA0 * i0) / (1 + i0))
    assert planetary_balance(zs, zr, ETA0, "ring", "sun") == (1 + 1 / i0, (i0 + ETA0) / (i0 + 1))
    assert planetary_balance(zs, zr, F(1), "sun", "ring")[1] == 1
    assert planetary_balance(zs, zr, F(1), "ring", "sun")[1] == 1
    # The example's value at zs = 21, zr = 75 by hand: (21 + 0.9702 * 75)/96 = 0.97671875.
    assert planetary_balance(21, 75, ETA0, "sun", "ring")[1] == F(6251, 6400)


def test_clearance_rule_by_hand() -> None:
    """The tip-circle rule against its floating-point form away from equality, and strict at equality."""
    for planets in (2, 3, 4, 5, 6):
        for zs in range(10, 80):
            for zp in range(10, 80):
                margin = (zs + zp) * math.sin(math.pi / planets) - (zp + 2)
                if abs(margin) > 1e-9:
                    assert clear_of_each_other(zs, zp, planets) == (margin > 0), (planets, zs, zp)
    assert not clear_of_each_other(24, 20, 6)  # 2 a sin 30 deg = 44 m/2 = 22 m = m (20 + 2): touching


@pytest.mark.slow
def test_oracle_spaces() -> None:
    """The brute force gives sensible sets, and every rule excludes a design in the spaces tested
    (so that a search that forgets one fails a test)."""
    counts = {s.id: len(brute_force(s)) for s in [*SPACES, SIX, ON_THE_BOUND, TWO_STATES]}
    assert counts["example"] > 0 and counts["four_planets"] > 0 and counts["five_planets"] > 0
    assert counts["none_feasible"] == 0 and counts["six_planets"] > 0 and counts["two_states"] > 0
    assert counts["on_the_bound"] > 0
    for space in [*SPACES, SIX, TWO_STATES]:  # no float rounding decides these spaces
        assert not any(d.on_boundary for d in brute_force(space, frozenset(RULES))), space.id
    decisive = set()
    for space in [*SPACES, SIX, ON_THE_BOUND, TWO_STATES]:
        base = {teeth_key(d.teeth) for d in brute_force(space)}
        for rule in ("min_teeth", "ratio", "assembly", "clearance"):
            if {teeth_key(d.teeth) for d in brute_force(space, frozenset({rule}))} != base:
                decisive.add(rule)
    assert decisive == {"min_teeth", "ratio", "assembly", "clearance"}
    # The example: every design sun >= 17, ring >= 50 in the bounds, by hand for one of them.
    example = brute_force(SPACES[0])
    assert {"zs": 21, "zp": 27, "zr": 75} in [d.teeth for d in example]  # 96/3 = 32, 4.571 within 1 %
    # Nothing feasible at 7 only because of the clearance of five planets.
    assert brute_force(SPACES[3], frozenset({"clearance"}))
    # Six planets: some designs have touching tip circles, and are refused.
    six = {teeth_key(d.teeth) for d in brute_force(SIX)}
    unchecked = brute_force(SIX, frozenset({"clearance"}))
    touching = [d.teeth for d in unchecked if d.teeth["zs"] + d.teeth["zp"] == 2 * (d.teeth["zp"] + 2)]
    assert touching and not any(teeth_key(t) in six for t in touching)
    # On the bound: the design 25/26/77 (ratio exactly 4.08) is feasible.
    bound = [d for d in brute_force(ON_THE_BOUND) if d.on_boundary]
    assert [d.teeth for d in bound] == [{"zs": 25, "zp": 26, "zr": 77}] and bound[0].ratio[None] == F("4.08")
    # The default --min-teeth (17) decides in six_planets.
    assert SIX.min_teeth is None and six != {teeth_key(d.teeth) for d in brute_force(SIX, frozenset({"min_teeth"}))}


# --- the command against the oracle -----------------------------------------------------------------------------


@pytest.mark.parametrize("space", [*SPACES, SIX, ON_THE_BOUND, TWO_STATES], ids=lambda s: s.id)
def test_search_lists_exactly_the_feasible_designs(space: Space) -> None:
    """(a), (b): the candidates are the brute force's feasible designs (the same tooth numbers, the
    same count), each with the hand formula's speed ratio and efficiency, best first."""
    expected = brute_force(space)
    doc = search(space)
    check_document(space, doc, expected)
    if not expected:
        assert doc["candidates"] == []


def test_example_counts() -> None:
    """The example's feasible count, by the brute force, and its best design by hand: the efficiency
    (1 + eta0 i0)/(1 + i0) falls as i0 = zr/zs grows, so the best design has the smallest ratio
    within 1 % of 4.6."""
    expected = brute_force(SPACES[0])
    # Checked by hand: zr/zs in [3.554, 3.646], zr - zs even, 3 | zs + zr (the clearance of three
    # planets and the 17-teeth floor exclude none of these): 12 designs.
    assert sorted((d.teeth["zs"], d.teeth["zr"]) for d in expected) == [
        (17, 61), (21, 75), (22, 80), (25, 89), (26, 94), (30, 108),
        (31, 113), (34, 122), (35, 127), (38, 136), (39, 141), (42, 150),
    ]  # fmt: skip
    best = expected[0]
    assert best.ratio[None] == min(d.ratio[None] for d in expected)
    assert best.ratio[None] >= F("4.554")
    doc = search(SPACES[0])
    assert doc["feasible"] == len(expected)
    assert doc["candidates"][0]["efficiency"] == pytest.approx(float(best.efficiency[None]), abs=1e-12)


def test_top_keeps_the_best() -> None:
    """``--top 3`` lists the three best of the full list; ``feasible`` still counts every design."""
    space = SPACES[0]
    expected = brute_force(space)
    assert len(expected) > 3
    doc = search(space, top=3)
    check_document(space, doc, expected, top=3)


def test_out_file_holds_the_document(tmp_path: Path) -> None:
    """``-o FILE`` writes the JSON document to FILE."""
    space = SPACES[1]
    out = tmp_path / "found.json"
    result = run_main([*space.args(), "--json", "-o", str(out)])
    assert result.returncode == 0, result.describe()
    check_document(space, json.loads(out.read_text(encoding="utf-8")), brute_force(space))


def test_candidates_agree_with_eval() -> None:
    """(c): ``derive FILE --eval zs=.. zr=..`` (the last line of stdout is the efficiency) gives each
    candidate's efficiency, first, middle and last of the example's list."""
    doc = search(SPACES[0])
    candidates = doc["candidates"]
    assert candidates
    for cand in {0: candidates[0], 1: candidates[len(candidates) // 2], 2: candidates[-1]}.values():
        teeth = cand["teeth"]
        result = run_main([str(PLANETARY), "--eval", f"zs={teeth['zs']}", f"zr={teeth['zr']}", "--quiet"])
        assert result.returncode == 0, result.describe()
        evaluated = float(result.stdout.strip().splitlines()[-1])
        assert evaluated == pytest.approx(float(cand["efficiency"]), abs=1e-12), (teeth, result.describe())
        i0 = F(teeth["zr"], teeth["zs"])
        assert evaluated == pytest.approx(float((1 + ETA0 * i0) / (1 + i0)), abs=1e-12)


def test_states_agree_with_eval() -> None:
    """(c) for a file with states: each state's efficiency is what ``--state S --eval`` prints."""
    doc = search(TWO_STATES)
    cand = doc["candidates"][0]
    teeth = cand["teeth"]
    for state in ("low", "high"):
        args = [str(STATES), "--state", state, "--eval", f"zs={teeth['zs']}", f"zr={teeth['zr']}", "--quiet"]
        result = run_main(args)
        assert result.returncode == 0, result.describe()
        evaluated = float(result.stdout.strip().splitlines()[-1])
        assert evaluated == pytest.approx(per_state(cand["efficiency"], state), abs=1e-12), result.describe()


def test_write_best(tmp_path: Path) -> None:
    """(d): ``--write-best OUT`` writes the best design with numbers for the tooth symbols; ``derive OUT
    --eval`` (no values) gives the best candidate's efficiency; the input file is left as it was."""
    train = tmp_path / "planetary.yaml"
    train.write_bytes(PLANETARY.read_bytes())
    before = train.read_bytes()
    out = tmp_path / "best.yaml"
    space = SPACES[0]
    args = [*space.args(), "--json", "--write-best", str(out)]
    args[1] = str(train)
    result = run_main(args)
    assert result.returncode == 0, result.describe()
    assert train.read_bytes() == before
    best = json.loads(result.stdout)["candidates"][0]
    expected = brute_force(space)[0]
    assert best["teeth"] in [d.teeth for d in brute_force(space) if d.score == expected.score], best
    written = yaml.safe_load(out.read_text(encoding="utf-8"))
    gears = written["gears"]
    assert {name: gears[name]["teeth"] for name in ("sun", "planet", "ring")} == {
        "sun": best["teeth"]["zs"],
        "planet": best["teeth"]["zp"],
        "ring": best["teeth"]["zr"],
    }, gears
    result = run_main([str(out), "--eval", "--quiet"])
    assert result.returncode == 0, result.describe()
    evaluated = float(result.stdout.strip().splitlines()[-1])
    assert evaluated == pytest.approx(float(best["efficiency"]), abs=1e-12)
    assert evaluated == pytest.approx(float(expected.efficiency[None]), abs=1e-12)


@pytest.mark.parametrize("spelling", ["same", "dotdot", "symlink"])
def test_write_best_never_overwrites_the_input(tmp_path: Path, spelling: str) -> None:
    """(d): ``--write-best`` naming the input file (as given, through ``..``, or through a symbolic
    link to it) is refused with exit 2, and the input file is unchanged."""
    train = tmp_path / "planetary.yaml"
    train.write_bytes(PLANETARY.read_bytes())
    before = train.read_bytes()
    (tmp_path / "sub").mkdir()
    if spelling == "same":
        target = str(train)
    elif spelling == "dotdot":
        target = str(tmp_path / "sub" / ".." / "planetary.yaml")
    else:
        link = tmp_path / "link.yaml"
        os.symlink(train, link)
        target = str(link)
    args = [*SPACES[0].args(), "--write-best", target]
    args[1] = str(train)
    result = run_main(args)
    assert result.returncode == 2, result.describe()
    assert "Traceback" not in result.stderr, result.describe()
    assert "--write-best" in result.stderr, result.describe()
    assert train.read_bytes() == before


def test_spelling_does_not_change_the_designs() -> None:
    """(f): the same train with other names and another order of gears, couplings and free tooth
    numbers (tests/data/search_planetary_spelled.yaml) gives the same candidates, names mapped."""
    example = SPACES[0]
    spelled = Space("spelled", SPELLED, example.targets, example.tolerance, {"za": (17, 60), "zr_b": (50, 150)}, 3, 17)
    doc = search(spelled)
    mapped = {**doc, "candidates": []}
    for cand in doc["candidates"]:
        assert set(cand["teeth"]) == set(SPELLED_NAMES), cand["teeth"]
        mapped["candidates"].append({**cand, "teeth": {SPELLED_NAMES[k]: v for k, v in cand["teeth"].items()}})
    expected = brute_force(example)
    check_document(example, mapped, expected)
    original = search(example)
    assert {teeth_key(c["teeth"]): c["efficiency"] for c in original["candidates"]} == pytest.approx(
        {teeth_key(c["teeth"]): c["efficiency"] for c in mapped["candidates"]}, abs=1e-12
    )


# --- bad input ---------------------------------------------------------------------------------------------------

BASE = {
    "--target": ["4.6"],
    "--tolerance": ["0.01"],
    "--teeth": ["zs=17:60", "zr=50:150"],
    "--planets": ["3"],
}
STATE_BASE = {**BASE, "--target": ["low=4.6", "high=1.28"]}

#: (id, file, options replaced, what the message must name: an option, or one of several words)
BAD = [
    ("teeth_lo_above_hi", PLANETARY, {"--teeth": ["zs=60:17", "zr=50:150"]}, "--teeth"),
    ("teeth_empty_range", PLANETARY, {"--teeth": ["zs=", "zr=50:150"]}, "--teeth"),
    ("teeth_unknown_name", PLANETARY, {"--teeth": ["zs=17:60", "zr=50:150", "zq=17:60"]}, "--teeth"),
    ("teeth_dependent_name", PLANETARY, {"--teeth": ["zs=17:60", "zr=50:150", "zp=17:60"]}, "--teeth"),
    # A file with a symbol the search cannot give a value may be refused for it: the symbol named is enough.
    ("teeth_efficiency_symbol", "EFFICIENCY", {"--teeth": ["zs=17:60", "zr=50:150", "eta1=1:2"]}, ("--teeth", "eta1")),
    ("teeth_radius_symbol", "RADIUS", {"--teeth": ["zs=17:60", "zr=50:150", "rb=1:2"]}, ("--teeth", "rb")),
    ("teeth_free_without_bounds", PLANETARY, {"--teeth": ["zs=17:60"]}, "--teeth"),
    ("target_zero", PLANETARY, {"--target": ["0"]}, "--target"),
    ("tolerance_negative", PLANETARY, {"--tolerance": ["-0.01"]}, "--tolerance"),
    ("planets_zero", PLANETARY, {"--planets": ["0"]}, "--planets"),
    ("state_of_a_file_without_states", PLANETARY, {"--target": ["low=4.6"]}, "--target"),
    ("state_unknown", STATES, {"--target": ["low=4.6", "top=1.28"]}, "--target"),
    ("state_without_target", STATES, {"--target": ["low=4.6"]}, "--target"),
    ("weights_unknown_state", STATES, {"--weights": ["low=1", "top=2"]}, "--weights"),
]


def variant_file(kind: str, tmp_path: Path) -> Path:
    """The example with a symbolic mesh efficiency (eta1), or with a symbolic radius (rb) of an
    extra gear pair on the carrier, so that ``--teeth`` can name a symbol that is no tooth number."""
    text = PLANETARY.read_text(encoding="utf-8")
    if kind == "EFFICIENCY":
        text = text.replace("efficiency: 0.98}", "efficiency: eta1}")
        assert "eta1" in text
    else:
        text = text.replace("links: [H, S, P, C]", "links: [H, S, P, C, B]")
        text = text.replace(
            "  ring: {link: H, teeth: zr, module: 2, internal: true}\n",
            "  ring: {link: H, teeth: zr, module: 2, internal: true}\n"
            "  idler_a: {link: C, radius: 10}\n  idler_b: {link: B, radius: rb}\n",
        )
        text = text.replace(
            "  JP: {type: revolute, links: [C, P]}\n",
            "  JP: {type: revolute, links: [C, P]}\n  JB: {type: revolute, links: [H, B]}\n"
            "  M3: {type: mesh, gears: [idler_a, idler_b]}\n",
        )
        assert "rb" in text
    path = tmp_path / f"{kind.lower()}.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(("path", "replaced", "option"), [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_input_is_refused(
    tmp_path: Path, path: Path | str, replaced: dict[str, list[str]], option: str | tuple[str, ...]
) -> None:
    """(e): exit 2, one short message naming the option, no traceback, nothing on stdout."""
    if isinstance(path, str):
        path = variant_file(path, tmp_path)
    options = {**(STATE_BASE if path == STATES else BASE), **replaced}
    args = ["search", str(path)]
    for name, values in options.items():
        # ``--tolerance=-0.01``: one token, so that the value cannot be read as an option.
        args += [f"{name}={values[0]}"] if len(values) == 1 and name == "--tolerance" else [name, *values]
    result = run_main([*args, "--json", "--quiet"])
    why = result.describe()
    assert result.returncode == 2, why
    assert "Traceback" not in result.stderr, why
    assert any(word in result.stderr for word in ((option,) if isinstance(option, str) else option)), why
    assert len(result.stderr) < 2000, why
    assert result.stdout.strip() == "", why
