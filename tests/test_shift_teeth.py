"""Tooth numbers searched with the shift scheme (`derive shifts --teeth`): the Simpson
sets with their teeth as symbols give the published scheme at the published teeth
(sun 30, planets 20, rings 70) and at every other design of the same ratios; every
listed design's ratios are recomputed by Willis per set (test_shift_schemes, sharing no
code with the search), its efficiencies by deriving the written best design, and the
whole feasible set equals a brute force that runs the level-1 search on a file of
numbers for every tooth assignment."""

from __future__ import annotations

import json
from fractions import Fraction
from itertools import product
from pathlib import Path

import pytest
from harness.helpers import assert_refused, run_main
from test_shift_schemes import willis_ratio

from davies_sym.efficiency.variants import derive_variants
from davies_sym.synthesis.shift_kinematics import member_speeds
from davies_sym.synthesis.shift_schedules import GearTarget, ShiftQuestion, shift_schemes
from davies_sym.synthesis.shift_search import port_member
from davies_sym.synthesis.shift_teeth import ToothRanges, shift_teeth_search
from davies_sym.topology.loader import load
from davies_sym.topology.states import train_in_state

DATA = Path(__file__).resolve().parent / "data"
TEETH = DATA / "shifts_simpson_teeth.yaml"
NUMBERS = DATA / "shifts_simpson_sets.yaml"
TABLE = ["1=2.4286", "2=1.4286", "3=1", "R=-2.3333"]
MEMBERS = ["in", "s", "r1", "o", "c2"]


def _sets(teeth: dict[str, int]) -> list:
    """The Simpson sets (sun, ring, carrier) with the design's sun and ring teeth."""
    return [(("s", "r1", "o"), (teeth["zs"], teeth["zr1"])), (("s", "o", "c2"), (teeth["zs"], teeth["zr2"]))]


def _derive(args: list[str]) -> dict:
    result = run_main(["shifts", str(TEETH), "--target", *TABLE, "--tolerance", "0.005", "--json", "--quiet", *args])
    assert result.returncode == 0, result.describe()
    return json.loads(result.stdout)


def test_the_published_teeth_and_scheme_are_among_the_designs() -> None:
    answer = _derive(["--teeth", "zs=28:32", "zp1=18:22", "zp2=18:22", "--top", "100"])
    published = [
        c for c in answer["candidates"] if c["teeth"] == {"zs": 30, "zp1": 20, "zr1": 70, "zp2": 20, "zr2": 70}
    ]
    assert len(published) == 1
    design = published[0]
    assert sorted(map(tuple, (sorted(e.items()) for e in design["elements"].values()))) == sorted(
        [(("brake", "s"),), (("brake", "c2"),), (("clutch", ["in", "s"]),), (("clutch", ["in", "r1"]),)]
    )
    assert design["speed_ratio"]["R"] == pytest.approx(-7 / 3, rel=1e-15)


def test_every_design_keeps_its_ratios_by_willis_and_the_tooth_rules() -> None:
    """Willis per set at each listed design's teeth gives its ratios exactly; with three
    planets every set assembles ((sun + ring) divisible by 3) and no gear is below 17."""
    answer = _derive(["--teeth", "zs=20:44", "zp1=15:30", "zp2=15:30", "--planets", "3", "--top", "1000"])
    assert answer["feasible"] == len(answer["candidates"]) > 1
    for c in answer["candidates"]:
        teeth = c["teeth"]
        assert teeth["zr1"] == teeth["zs"] + 2 * teeth["zp1"] and teeth["zr2"] == teeth["zs"] + 2 * teeth["zp2"]
        assert min(teeth.values()) >= 17
        assert (teeth["zs"] + teeth["zr1"]) % 3 == 0 and (teeth["zs"] + teeth["zr2"]) % 3 == 0
        for gear, names in c["schedule"].items():
            engaged = [(e["brake"],) if "brake" in e else tuple(e["clutch"]) for e in (c["elements"][n] for n in names)]
            exact = willis_ratio(_sets(teeth), MEMBERS, engaged, ("in", "o"))
            assert c["speed_ratio"][gear] == pytest.approx(float(exact), rel=1e-15)
            target = Fraction(next(t for t in TABLE if t.startswith(f"{gear}=")).partition("=")[2])
            assert abs(exact - target) <= Fraction(5, 1000) * abs(target)


def _numbers(teeth: dict[str, int], folder: Path) -> Path:
    """The file of numbers of one tooth assignment (the symbols written as numbers)."""
    text = TEETH.read_text(encoding="utf-8")
    for name in ("zr1", "zr2", "zp1", "zp2", "zs"):
        text = text.replace(f"teeth: {name},", f"teeth: {teeth[name]},")
    path = folder / f"simpson_{teeth['zs']}_{teeth['zp1']}_{teeth['zp2']}.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_the_feasible_designs_are_those_of_a_brute_force(tmp_path: Path) -> None:
    """Every tooth assignment of small ranges written as a file of numbers and searched
    at level 1 alone: the same (teeth, elements, schedule) as the tooth search."""
    targets = tuple(GearTarget(g, Fraction(r)) for g, r in (t.split("=") for t in TABLE))
    question = ShiftQuestion(targets, Fraction(2, 100), elements=None)
    ranges = ToothRanges({"zs": (26, 34), "zp1": (17, 23), "zp2": (17, 23)})
    result = shift_teeth_search(load(TEETH), question, ranges)
    found = {
        (
            tuple(c.teeth[n] for n in ("zs", "zp1", "zp2")),
            tuple(e.members for e in c.scheme.elements),
            tuple(sorted(c.scheme.schedule.items())),
        )
        for c in result.candidates
    }
    assert result.feasible == len(found) > 0
    brute = set()
    for zs, zp1, zp2 in product(range(26, 35), range(17, 24), range(17, 24)):
        teeth = {"zs": zs, "zp1": zp1, "zp2": zp2, "zr1": zs + 2 * zp1, "zr2": zs + 2 * zp2}
        train = load(_numbers(teeth, tmp_path))
        ports = (port_member(train, train.ports.input), port_member(train, train.ports.output))
        for scheme in shift_schemes(member_speeds(train), ports, question):
            brute.add(
                ((zs, zp1, zp2), tuple(e.members for e in scheme.elements), tuple(sorted(scheme.schedule.items())))
            )
    assert found == brute


def test_the_written_best_design_derives_to_the_ranked_efficiencies(tmp_path: Path) -> None:
    best = tmp_path / "best.yaml"
    answer = _derive(["--teeth", "zs=26:34", "zp1=17:23", "zp2=17:23", "--write-best", str(best)])
    top = answer["candidates"][0]
    train = load(best)
    assert {g.name: int(g.teeth) for g in train.gears} == {
        "S": top["teeth"]["zs"], "P1": top["teeth"]["zp1"], "R1": top["teeth"]["zr1"],
        "P2": top["teeth"]["zp2"], "R2": top["teeth"]["zr2"],
    }  # fmt: skip
    for state in train.states:
        variants = derive_variants(train_in_state(train, state))
        assert float(variants.design_point({}).efficiency) == pytest.approx(top["efficiency"][state.name], rel=1e-12)
        assert float(variants.analysis.speed_ratio().to_expr()) == pytest.approx(top["speed_ratio"][state.name])


@pytest.mark.parametrize(
    ("file", "extra", "entry"),
    [
        (NUMBERS, ["--teeth", "zs=20:40"], "gears"),  # no symbolic tooth number
        (TEETH, [], "couplings"),  # symbols without --teeth: the hint names --teeth
        (TEETH, ["--teeth", "zs=20:40", "zp1=15:25"], "--teeth"),  # zp2 has no bounds
        (TEETH, ["--teeth", "zs=20:40", "zp1=15:25", "zp2=15:25", "zq=1:2"], "--teeth"),
        (TEETH, ["--teeth", "zs=20:40", "zp1=15:25", "zp2=15:25", "--connections", "1"], "--teeth"),
        (NUMBERS, ["--planets", "3"], "--planets"),
        (TEETH, ["--teeth", "zs=1:3000", "zp1=1:3000", "zp2=1:30"], "--teeth"),  # beyond the designs' bound
    ],
)
def test_bad_tooth_searches_are_refused(file: Path, extra: list[str], entry: str) -> None:
    result = run_main(["shifts", str(file), "--target", *TABLE, "--tolerance", "0.005", "--quiet", *extra])
    assert_refused(result, None if entry.startswith("--") else file, (entry,), line=False)
    if not extra:
        assert "--teeth" in result.stderr


def test_a_screen_beyond_its_bound_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    """Classes times combinations of engaged elements is bounded (work, not seconds)."""
    import davies_sym.synthesis.shift_teeth as shift_teeth

    monkeypatch.setattr(shift_teeth, "MAX_SCREENED", 100)
    result = run_main(
        ["shifts", str(TEETH), "--target", *TABLE, "--teeth", "zs=26:30", "zp1=17:19", "zp2=17:19", "--quiet"]
    )
    assert_refused(result, None, ("--teeth",), line=False)
    assert "narrow the --teeth ranges" in result.stderr


def test_ranges_no_design_fits_exit_3_with_the_count() -> None:
    """A first gear of 2.5 that no design of these small ranges gives within 0.5 %: exit
    3, the 6 x 3 x 3 = 54 designs of the ranges counted (every one admissible: the
    rings follow from sun and planet, all above 17 teeth)."""
    table = ["1=2.5", *TABLE[1:]]
    result = run_main(
        ["shifts", str(TEETH), "--target", *table, "--teeth", "zs=20:25", "zp1=17:19", "zp2=17:19", "--quiet"]
    )
    assert result.returncode == 3 and "none of the 54 admissible tooth designs" in result.stderr
