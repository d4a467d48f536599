"""``derive search`` on trains with several operating states: the ZF 8HP70 eight-speed
(benchmarks/search_eight_speed.yaml, nine states), a Simpson set written with tooth numbers
(tests/data/search_simpson.yaml, four states) and the ranking by the weighted efficiency of two
states (tests/data/search_states.yaml).  Every expected value is computed here by hand:
the speed ratios from the Willis equation of each simple planetary set, the feasible designs by
a brute force that applies the rules of the command (docs of `davies_sym.synthesis.rules`) one
by one, written without code of the search.

Willis' equation of a simple set (sun s, ring r, carrier c; Müller, Epicyclic Drive Trains,
1982, ch. 2): seen from the carrier sun and ring form a fixed-axis pair of ratio -zr/zs,
ws - wc = -(zr/zs)(wr - wc), i.e.

    zs ws + zr wr = (zs + zr) wc.

The rules of the brute force (as in tests/test_search.py): the planet's tooth number follows
from one module and coaxiality, zp = (zr - zs)/2, and must be whole; every gear has at least 17
teeth (--min-teeth's default); each state's ratio lies within the relative tolerance of its
target, |ratio - target| <= tol |target|; N planets are equally spaced, (zs + zr)/N whole for each
simple set (Müller 1982, ch. 3); neighbouring planets' tip circles clear, 2 a sin(pi/N) > m (zp + 2)
with a = m (zs + zp)/2, for N = 3: 3 (zs + zp)^2 > 4 (zp + 2)^2 (the module cancels; decided on
squares, exactly).
"""

from __future__ import annotations

import itertools
import json
import re
from collections.abc import Mapping
from fractions import Fraction as F
from pathlib import Path

import pytest
from harness.helpers import run_main

ROOT = Path(__file__).resolve().parents[1]
EIGHT_SPEED = ROOT / "benchmarks" / "search_eight_speed.yaml"
SIMPSON = ROOT / "tests" / "data" / "search_simpson.yaml"
STATES = ROOT / "tests" / "data" / "search_states.yaml"

MIN_TEETH = 17


def search(*args: str) -> dict:
    """``derive search ... --json --quiet`` in this process: the JSON document."""
    result = run_main(["search", *map(str, args), "--json", "--quiet"])
    assert result.returncode == 0, result.describe()
    assert "Traceback" not in result.stderr, result.describe()
    return json.loads(result.stdout)


def within(ratio: F, target: F, tolerance: F) -> bool:
    return abs(ratio - target) <= tolerance * abs(target)


def simple_set_rules(zs: int, zr: int, planets: int) -> bool:
    """The rules one simple set must meet alone (see the module's docstring), for N = 3 planets."""
    assert planets == 3
    if (zr - zs) % 2 or zr <= zs:
        return False
    zp = (zr - zs) // 2
    if min(zs, zp, zr) < MIN_TEETH:
        return False
    if (zs + zr) % planets:
        return False
    return 3 * (zs + zp) ** 2 > 4 * (zp + 2) ** 2


# --- the ZF 8HP70 ------------------------------------------------------------------------------------------------

#: Published tooth numbers of the 8HP70 (the file's source: S1/R1 48/96, S2/R2 48/96, S3/R3 69/111, S4/R4 23/85).
PUBLISHED = {"zs1": 48, "zr1": 96, "zs2": 48, "zr2": 96, "zs3": 69, "zr3": 111, "zs4": 23, "zr4": 85}
#: Published ratios (ZF; the file's source), reverse negative as the file writes it.
PUBLISHED_RATIOS = {
    "first": "4.696",
    "second": "3.130",
    "third": "2.104",
    "fourth": "1.667",
    "fifth": "1.285",
    "sixth": "1.000",
    "seventh": "0.839",
    "eighth": "0.667",
    "reverse": "-3.297",
}
EIGHT_TOLERANCE = F("0.005")
#: Each free tooth number within this many teeth of the published one.
SPREAD = 6


def eight_speed_ratios(t: Mapping[str, int]) -> dict[str, F]:
    """Input over output speed of every gear of the 8HP, derived by hand from the file's
    connections: input = carrier 2 (C2), output = carrier 4 (C4), S1 = S2 (brake A), R1 (brake
    B), C1 = R4, R2 = S3, R3 = S4; clutch C joins the input and S4, clutch D joins C3 and the
    output, clutch E joins S3 and S4 (R2 = S3 = R3 = S4: set 3 turns as one block).  Input speed 1,
    x the output speed; Willis per set k: zsk Sk + zrk Rk = (zsk + zrk) Ck.

    - 1st (A B C): S1 = 0, R1 = 0, so C1 = R4 = 0; S4 = 1 (C).  Set 4: zs4 = (zs4 + zr4) x,
      ratio 1 + zr4/zs4.
    - 2nd (A B E): R4 = 0; set 2 with S2 = 0, C2 = 1: R2 = (zs2 + zr2)/zr2 = S4 (E).  Set 4:
      ratio (1 + zr4/zs4)/(1 + zs2/zr2).
    - 3rd (B C E): S4 = R3 = S3 = R2 = 1 (C, E); set 2 has C2 = R2 = 1, so S2 = S1 = 1; set 1 with
      R1 = 0: C1 = R4 = k1 = zs1/(zs1 + zr1).  Set 4: zs4 + zr4 k1 = (zs4 + zr4) x,
      ratio (zs4 + zr4)/(zs4 + zr4 k1).
    - 4th (B D E): C3 = x (D), set 3 a block (E): S4 = R2 = x = C4, so set 4 is a block too:
      R4 = C1 = x.  Set 1 (R1 = 0): S1 = (zs1 + zr1) x/zs1 = S2; set 2:
      zs2 S2 + zr2 x = zs2 + zr2, ratio ((zs1 + zr1)/zs1 + zr2/zs2)/((zs2 + zr2)/zs2).
    - 5th (B C D): S4 = R3 = 1, C3 = x.  Set 3: S3 = R2 = ((zs3 + zr3) x - zr3)/zs3; set 2:
      S2 = S1 = (zs2 + zr2 - zr2 R2)/zs2; set 1: R4 = C1 = k1 S1; set 4:
      zs4 + zr4 R4 = (zs4 + zr4) x.  Linear in x:
      ratio = (zs4 + zr4 + zr4 k1 zr2 (zs3 + zr3)/(zs2 zs3)) / (zs4 + zr4 k1 (zs2 + zr2 + zr2 zr3/zs3)/zs2).
    - 6th (C D E): S4 = 1, C3 = C4 = x and set 3 a block: ratio 1.
    - 7th (A C D): S2 = 0, so R2 = S3 = (zs2 + zr2)/zr2 (set 2); R3 = 1 (C), C3 = x (D); set 3:
      ratio (zs3 + zr3)/(zs3 (zs2 + zr2)/zr2 + zr3).
    - 8th (A D E): S2 = 0, R2 = x (set 3 a block with C3 = x); set 2: zr2 x = zs2 + zr2,
      ratio zr2/(zs2 + zr2).
    - reverse (A B D): R4 = 0, so set 4: S4 = R3 = (zs4 + zr4) x/zs4; set 2 (S2 = 0):
      S3 = R2 = (zs2 + zr2)/zr2; set 3 with C3 = x:
      ratio ((zs3 + zr3) - zr3 (zs4 + zr4)/zs4) / (zs3 (zs2 + zr2)/zr2).
    """
    zs1, zr1, zs2, zr2 = (F(t[k]) for k in ("zs1", "zr1", "zs2", "zr2"))
    zs3, zr3, zs4, zr4 = (F(t[k]) for k in ("zs3", "zr3", "zs4", "zr4"))
    k1 = zs1 / (zs1 + zr1)
    return {
        "first": 1 + zr4 / zs4,
        "second": (1 + zr4 / zs4) / (1 + zs2 / zr2),
        "third": (zs4 + zr4) / (zs4 + zr4 * k1),
        "fourth": ((zs1 + zr1) / zs1 + zr2 / zs2) / ((zs2 + zr2) / zs2),
        "fifth": (zs4 + zr4 + zr4 * k1 * zr2 * (zs3 + zr3) / (zs2 * zs3))
        / (zs4 + zr4 * k1 * (zs2 + zr2 + zr2 * zr3 / zs3) / zs2),
        "sixth": F(1),
        "seventh": (zs3 + zr3) / (zs3 * (zs2 + zr2) / zr2 + zr3),
        "eighth": zr2 / (zs2 + zr2),
        "reverse": ((zs3 + zr3) - zr3 * (zs4 + zr4) / zs4) / (zs3 * (zs2 + zr2) / zr2),
    }


def test_eight_speed_ratio_formulas_give_the_published_ratios() -> None:
    """The hand formulas at the published teeth give the exact ratios of the file's comment
    (108/23, 72/23, 162/77, 5/3, 8826/6871, 1, 120/143, 2/3, -1744/529) and ZF's rounded ones."""
    ratios = eight_speed_ratios(PUBLISHED)
    exact = ["108/23", "72/23", "162/77", "5/3", "8826/6871", "1", "120/143", "2/3", "-1744/529"]
    assert ratios == dict(zip(PUBLISHED_RATIOS, map(F, exact), strict=True))
    for state, rounded in PUBLISHED_RATIOS.items():
        assert abs(ratios[state] - F(rounded)) <= F(1, 2000), state


def eight_speed_brute_force() -> list[dict[str, int]]:
    """Every design within `SPREAD` of the published teeth that meets the rules (module
    docstring) with 3 planets, by enumeration: the sets' own rules first, then the ratio windows
    in the order the formulas need the sets (1st: set 4 alone; 8th: set 2 alone; 2nd: sets 2 and 4;
    4th: sets 1 and 2; 7th: sets 2 and 3), finally every window with every set."""
    targets = {s: F(r) for s, r in PUBLISHED_RATIOS.items()}
    sets = {}
    for k in (1, 2, 3, 4):
        zs0, zr0 = PUBLISHED[f"zs{k}"], PUBLISHED[f"zr{k}"]
        sets[k] = [
            (zs, zr)
            for zs in range(zs0 - SPREAD, zs0 + SPREAD + 1)
            for zr in range(zr0 - SPREAD, zr0 + SPREAD + 1)
            if simple_set_rules(zs, zr, 3)
        ]

    def ok(state: str, ratio: F) -> bool:
        return within(ratio, targets[state], EIGHT_TOLERANCE)

    set4 = [(zs, zr) for zs, zr in sets[4] if ok("first", 1 + F(zr, zs))]
    set2 = [(zs, zr) for zs, zr in sets[2] if ok("eighth", F(zr, zs + zr))]
    out = []
    for (zs2, zr2), (zs4, zr4) in itertools.product(set2, set4):
        if not ok("second", (1 + F(zr4, zs4)) / (1 + F(zs2, zr2))):
            continue
        set1 = [(zs, zr) for zs, zr in sets[1] if ok("fourth", (F(zs + zr, zs) + F(zr2, zs2)) / F(zs2 + zr2, zs2))]
        set3 = [(zs, zr) for zs, zr in sets[3] if ok("seventh", F(zs + zr) / (zs * F(zs2 + zr2, zr2) + zr))]
        for (zs1, zr1), (zs3, zr3) in itertools.product(set1, set3):
            teeth = {"zs1": zs1, "zr1": zr1, "zs2": zs2, "zr2": zr2, "zs3": zs3, "zr3": zr3, "zs4": zs4, "zr4": zr4}
            if all(ok(s, r) for s, r in eight_speed_ratios(teeth).items()):
                out.append(teeth)
    return out


def with_planets(teeth: Mapping[str, int], sets: int) -> dict[str, int]:
    """Every tooth number, the planets' zpk = (zrk - zsk)/2 added."""
    out = dict(teeth)
    for k in range(1, sets + 1):
        out[f"zp{k}"] = (teeth[f"zr{k}"] - teeth[f"zs{k}"]) // 2
    return out


def test_eight_speed_brute_force_holds_the_published_design() -> None:
    """The brute force itself: the published design meets every rule ((48 + 96)/3 = 48,
    (69 + 111)/3 = 60, (23 + 85)/3 = 36; planets 24, 24, 21, 31 teeth) and is found."""
    assert PUBLISHED in eight_speed_brute_force()


@pytest.mark.slow
def test_eight_speed_search_finds_the_published_teeth() -> None:
    """``derive search`` of the 8HP70 with ZF's nine published ratios as targets (tolerance 0.005,
    3 planets, every free tooth number within 6 of the published one): the published teeth are a
    candidate; every candidate's exact ratios are the hand formulas' (`eight_speed_ratios`) at its
    teeth; ``feasible`` is the brute force's count and the candidates are its designs.  (The
    rule that the train runs, every efficiency in (0, 1], is not in the brute force: no design
    here comes near self-locking, each state's efficiency is checked in (0, 1] below.)"""
    bounds = [f"{k}={v - SPREAD}:{v + SPREAD}" for k, v in PUBLISHED.items()]
    targets = [f"{s}={r}" for s, r in PUBLISHED_RATIOS.items()]
    doc = search(
        EIGHT_SPEED,
        "--target",
        *targets,
        "--tolerance",
        str(EIGHT_TOLERANCE),
        "--teeth",
        *bounds,
        "--planets",
        "3",
        "--top",
        "100000",
    )
    expected = eight_speed_brute_force()
    assert doc["feasible"] == len(expected), (doc["feasible"], len(expected))
    candidates = doc["candidates"]
    assert len(candidates) == len(expected)
    found = [c["teeth"] for c in candidates]
    assert with_planets(PUBLISHED, 4) in found
    assert sorted(map(sorted, (t.items() for t in found))) == sorted(
        map(sorted, (with_planets(t, 4).items() for t in expected))
    )
    for cand in candidates:
        teeth = cand["teeth"]
        ratios = eight_speed_ratios(teeth)
        assert {s: F(r) for s, r in cand["speed_ratio_exact"].items()} == ratios, teeth
        for state, ratio in ratios.items():
            assert cand["speed_ratio"][state] == pytest.approx(float(ratio), rel=1e-12)
            assert 0 < cand["efficiency"][state] <= 1, (teeth, state)


# --- the Simpson set ---------------------------------------------------------------------------------------------

#: Tooth numbers chosen here (catalog/simpson.yaml has radii, no numbers): sun 30, rings 66 and 72
#: (planets 18 and 21), different rings so that a mix-up of the two shows.
SIMPSON_TEETH = {"zs": 30, "zr1": 66, "zr2": 72}


def simpson_ratios(zs: int, zr1: int, zr2: int) -> dict[str, F]:
    """Input over output speed of the Simpson set in each state (catalog/simpson.yaml's links),
    by hand: front set sun S, ring R1, carrier o; rear set sun S, ring R2 on o, carrier c2.
    Output o, speed x; Willis per set (module docstring).

    - first (input R1 = 1, c2 held): rear set zs S + zr2 x = 0, so zs S = -zr2 x; front set
      zs S + zr1 = (zs + zr1) x, so zr1 = (zs + zr1 + zr2) x: ratio (zs + zr1 + zr2)/zr1.
    - second (input R1 = 1, sun held): front set zr1 = (zs + zr1) x: ratio 1 + zs/zr1.
    - third (R1 and S clutched): the front set turns as a block: ratio 1.
    - reverse (input S = 1, c2 held): rear set zs + zr2 x = 0: ratio -zr2/zs.

    These are the catalog's textbook ratios (its ``source:``) and test_catalog_trains.py's.
    """
    zs_, zr1_, zr2_ = F(zs), F(zr1), F(zr2)
    return {
        "first": (zs_ + zr1_ + zr2_) / zr1_,
        "second": 1 + zs_ / zr1_,
        "third": F(1),
        "reverse": -zr2_ / zs_,
    }


#: Loose enough that several designs pass (nine), so that the comparison with the brute force decides something.
SIMPSON_TOLERANCE = F("0.05")
SIMPSON_BOUNDS = {"zs": (24, 36), "zr1": (60, 72), "zr2": (66, 78)}


def simpson_brute_force(targets: Mapping[str, F]) -> list[dict[str, int]]:
    """Every Simpson design in `SIMPSON_BOUNDS` meeting the rules with 3 planets (both sets)."""
    out = []
    (ls, hs), (l1, h1), (l2, h2) = SIMPSON_BOUNDS.values()
    for zs, zr1, zr2 in itertools.product(range(ls, hs + 1), range(l1, h1 + 1), range(l2, h2 + 1)):
        if not (simple_set_rules(zs, zr1, 3) and simple_set_rules(zs, zr2, 3)):
            continue
        ratios = simpson_ratios(zs, zr1, zr2)
        if all(within(ratios[s], targets[s], SIMPSON_TOLERANCE) for s in targets):
            out.append({"zs": zs, "zp1": (zr1 - zs) // 2, "zr1": zr1, "zp2": (zr2 - zs) // 2, "zr2": zr2})
    return out


def test_simpson_search_finds_the_teeth_its_ratios_come_from() -> None:
    """tests/data/search_simpson.yaml with the exact ratios of `SIMPSON_TEETH` as targets
    (28/11, 16/11, 1, -12/5), 3 planets: those teeth are a candidate, every candidate's ratios are
    `simpson_ratios` at its teeth and the candidates are the brute force's designs."""
    targets = simpson_ratios(**SIMPSON_TEETH)
    assert targets == {"first": F(28, 11), "second": F(16, 11), "third": F(1), "reverse": F(-12, 5)}
    doc = search(
        SIMPSON,
        "--target",
        *(f"{s}={r}" for s, r in targets.items()),
        "--tolerance",
        str(SIMPSON_TOLERANCE),
        "--teeth",
        *(f"{n}={lo}:{hi}" for n, (lo, hi) in SIMPSON_BOUNDS.items()),
        "--planets",
        "3",
        "--top",
        "100000",
    )
    found = [c["teeth"] for c in doc["candidates"]]
    assert {"zs": 30, "zp1": 18, "zr1": 66, "zp2": 21, "zr2": 72} in found
    for cand in doc["candidates"]:
        t = cand["teeth"]
        expected = simpson_ratios(t["zs"], t["zr1"], t["zr2"])
        assert {s: F(r) for s, r in cand["speed_ratio_exact"].items()} == expected, t
        assert (t["zp1"], t["zp2"]) == ((t["zr1"] - t["zs"]) // 2, (t["zr2"] - t["zs"]) // 2)
    expected_designs = simpson_brute_force(targets)
    assert doc["feasible"] == len(expected_designs)
    assert sorted(tuple(t.items()) for t in found) == sorted(tuple(t.items()) for t in expected_designs)


# --- the ranking with weights ------------------------------------------------------------------------------------

#: Efficiency of the set seen from the carrier: both meshes of search_states.yaml in series.
ETA0 = F(98, 100) * F(99, 100)
STATES_ARGS = (
    STATES,
    "--target",
    "low=4.6",
    "high=1.28",
    "--tolerance",
    "0.01",
    "--teeth",
    "zs=17:60",
    "zr=50:150",
    "--planets",
    "3",
)


def state_efficiencies(zs: int, zr: int) -> dict[str, F]:
    """Müller's closed forms (Epicyclic Drive Trains, 1982, ch. 5), i0 = zr/zs: low (ring held,
    sun in, carrier out) (1 + eta0 i0)/(1 + i0); high (sun held, ring in) (i0 + eta0)/(i0 + 1)."""
    i0 = F(zr, zs)
    return {"low": (1 + ETA0 * i0) / (1 + i0), "high": (i0 + ETA0) / (i0 + 1)}


@pytest.mark.parametrize("weights", [{"low": 3, "high": 1}, {"low": 1, "high": 5}, {"low": 1, "high": 1}])
def test_score_is_the_weighted_mean_of_the_state_efficiencies(weights: dict[str, int]) -> None:
    """Two states weighted w_low, w_high: every candidate's score is
    (w_low eta_low + w_high eta_high)/(w_low + w_high) of the efficiencies it prints (to 1e-12),
    those efficiencies are Müller's closed forms, and the candidates come best score first."""
    doc = search(*STATES_ARGS, "--weights", *(f"{s}={w}" for s, w in weights.items()), "--top", "1000")
    candidates = doc["candidates"]
    assert len(candidates) >= 2
    total = sum(weights.values())
    for cand in candidates:
        eta = cand["efficiency"]
        assert cand["score"] == pytest.approx(sum(weights[s] * eta[s] for s in weights) / total, abs=1e-12)
        hand = state_efficiencies(cand["teeth"]["zs"], cand["teeth"]["zr"])
        for state in weights:
            assert eta[state] == pytest.approx(float(hand[state]), abs=1e-12)
    scores = [c["score"] for c in candidates]
    assert scores == sorted(scores, reverse=True)


def test_weights_reorder_the_candidates() -> None:
    """Weighting one state heavily ranks by its efficiency: with ``--weights low=100 high=1`` and
    ``low=1 high=100`` the first candidate is the one of largest weighted mean by hand (Müller's
    closed forms, `state_efficiencies`) among the candidates listed, and the two firsts differ."""
    firsts = []
    for weights in ({"low": 100, "high": 1}, {"low": 1, "high": 100}):
        doc = search(*STATES_ARGS, "--weights", *(f"{s}={w}" for s, w in weights.items()), "--top", "1000")

        def by_hand(cand: dict, weights: dict[str, int] = weights) -> F:
            hand = state_efficiencies(cand["teeth"]["zs"], cand["teeth"]["zr"])
            return sum(weights[s] * hand[s] for s in weights) / sum(weights.values())

        best = max(doc["candidates"], key=by_hand)
        assert by_hand(doc["candidates"][0]) == by_hand(best), (doc["candidates"][0]["teeth"], best["teeth"])
        firsts.append(doc["candidates"][0]["teeth"])
    assert firsts[0] != firsts[1], firsts


_LINE = re.compile(r"efficiency low (?P<low>[0-9.]+)\s+high (?P<high>[0-9.]+)\s+score (?P<score>[0-9.]+)")


def test_text_table_score_is_the_weighted_mean() -> None:
    """The text table (no --json) prints efficiencies to 5 decimals and the score to 6: the
    score is the weighted mean of the printed efficiencies within the rounding (0.5e-5 + 0.5e-6)."""
    result = run_main(["search", *map(str, STATES_ARGS), "--weights", "low=3", "high=1", "--quiet"])
    assert result.returncode == 0, result.describe()
    lines = [m for m in map(_LINE.search, result.stdout.splitlines()) if m]
    assert lines, result.stdout
    for m in lines:
        mean = (3 * float(m["low"]) + float(m["high"])) / 4
        assert abs(float(m["score"]) - mean) <= 0.5e-5 + 0.5e-6 + 1e-12, m.group(0)
