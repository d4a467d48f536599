"""``derive shifts``: the issue's eight-speed example as written, the efficiencies of the
best scheme equal to ``derive --state GEAR --eval`` of the file it writes, hand
formulas of the Simpson gears, the open elements' slip speeds by Willis, and the
refusals (exit status 2 for bad input, 3 for a table no scheme reaches)."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import pytest

from davies_sym.cli import main

DATA = Path(__file__).resolve().parent / "data"
CATALOG = Path(__file__).resolve().parent.parent / "davies_sym" / "catalog"
SIMPSON = DATA / "shifts_simpson_sets.yaml"
EIGHT = DATA / "shifts_eight_speed.yaml"
EIGHT_TARGETS = ["R=-3.2968", "1=4.6957", "2=3.1304", "3=2.1039", "4=1.6667", "5=1.2845", "6=1", "7=0.8392", "8=0.6667"]
SIMPSON_TARGETS = ["1=2.4286", "2=1.4286", "3=1", "R=-2.3333"]


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    try:
        status = main(argv)
    except SystemExit as exc:
        status = int(exc.code or 0)
    out, err = capsys.readouterr()
    return status, out, err


def test_the_eight_speed_example_and_its_written_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The issue's example: the ZF 8HP70 sets and connections, nine published ratios,
    five elements; the best scheme written as a train file derives, gear by gear, to
    the efficiency the search ranked it by."""
    best = tmp_path / "best.yaml"
    argv = ["shifts", str(EIGHT), "--target", *EIGHT_TARGETS, "--tolerance", "0.005", "--elements", "5", "--json"]
    status, out, err = _run([*argv, "--write-best", str(best), "--quiet"], capsys)
    assert status == 0, err
    document = json.loads(out)
    assert document["feasible"] == 1 and document["searched"] > 0 and document["rules"]
    (candidate,) = document["candidates"]
    assert candidate["elements"]["A"] == {"brake": "s12"} and candidate["elements"]["B"] == {"brake": "r1"}
    assert candidate["schedule"]["1"] == ["A", "B", "C"] and candidate["schedule"]["6"] == ["C", "D", "E"]
    assert candidate["speed_ratio"]["5"] == pytest.approx(8826 / 6871, abs=1e-12)
    for gear, efficiency in candidate["efficiency"].items():
        status, out, err = _run([str(best), "--state", gear, "--eval", "--json"], capsys)
        assert status == 0, err
        assert json.loads(out)["efficiency"] == pytest.approx(efficiency, abs=1e-12), gear
    assert candidate["efficiency"]["6"] == 1.0  # direct drive: every member turns together
    assert candidate["score"] == pytest.approx(sum(candidate["efficiency"].values()) / 9)


def test_the_simpson_gears_by_hand(capsys: pytest.CaptureFixture[str]) -> None:
    """Sun 30, rings 70, mesh efficiencies 0.98 (sun) and 0.99 (ring), eta0 = 0.98 * 0.99:
    2nd (sun held, ring in, carrier out): (R + S eta0) / (R + S); 3rd (locked): 1;
    reverse (rear carrier held, sun in, rear ring out): eta0."""
    status, out, err = _run(["shifts", str(SIMPSON), "--target", *SIMPSON_TARGETS, "--json", "--quiet"], capsys)
    assert status == 0, err
    (candidate,) = json.loads(out)["candidates"]
    eta0 = 0.98 * 0.99
    assert candidate["efficiency"]["2"] == pytest.approx((70 + 30 * eta0) / 100, abs=1e-12)
    assert candidate["efficiency"]["3"] == 1.0
    assert candidate["efficiency"]["R"] == pytest.approx(eta0, abs=1e-12)


def test_open_elements_slip_at_the_willis_speeds(capsys: pytest.CaptureFixture[str]) -> None:
    """1st gear of the Simpson sets (front ring at input speed 1, rear carrier held):
    rear set o = -(3/7) s, front set s - o = -(7/3)(1 - o), so s = -49/51; the open sun
    brake slips at -49/51 and the open clutch input-sun at 1 + 49/51 = 100/51."""
    _, out, _ = _run(["shifts", str(SIMPSON), "--target", *SIMPSON_TARGETS, "--json", "--quiet"], capsys)
    (candidate,) = json.loads(out)["candidates"]
    names = {v["brake"] if "brake" in v else tuple(v["clutch"]): k for k, v in candidate["elements"].items()}
    first = candidate["open_speed"]["1"]
    assert first[names["s"]] == pytest.approx(float(Fraction(-49, 51)), abs=1e-12)
    assert first[names[("in", "s")]] == pytest.approx(float(Fraction(100, 51)), abs=1e-12)
    assert set(candidate["open_speed"]["3"].values()) == {1.0}  # direct drive: the brakes slip at input speed


def test_lossless_meshes_give_efficiency_one(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    lossless = tmp_path / "lossless.yaml"
    text = SIMPSON.read_text(encoding="utf-8").replace("efficiency: 0.98", "efficiency: 1")
    lossless.write_text(text.replace("efficiency: 0.99", "efficiency: 1"), encoding="utf-8")
    status, out, err = _run(["shifts", str(lossless), "--target", *SIMPSON_TARGETS, "--json", "--quiet"], capsys)
    assert status == 0, err
    assert set(json.loads(out)["candidates"][0]["efficiency"].values()) == {1.0}


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        ([str(CATALOG / "simpson.yaml"), "--target", "1=2.5"], "states: derive shifts finds the gears itself"),
        ([str(CATALOG / "simple_pair.yaml"), "--target", "1=2.5"], "1 degree of freedom: nothing to shift"),
        ([str(SIMPSON), "--target", "1=2.4", "1=1.4"], "--target: gear 1 is named twice"),
        ([str(SIMPSON), "--target", "1=0"], "--target: 1: a speed ratio is not zero"),
        ([str(SIMPSON), "--target", "1=fast"], "--target: 1: expected a number"),
        ([str(SIMPSON), "--target", *SIMPSON_TARGETS, "--elements", "1"], "--elements: at least 2"),
        ([str(SIMPSON), "--target", *SIMPSON_TARGETS, "--engaged", "3"], "--engaged: the train has 3 degrees"),
        ([str(SIMPSON), "--target", *SIMPSON_TARGETS, "--weights", "9=1"], "--weights: '9' is not a gear"),
    ],
)
def test_bad_input_is_refused_with_one_message(argv: list[str], says: str, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = _run(["shifts", *argv, "--quiet"], capsys)
    assert status == 2, err
    assert says in err and "Traceback" not in err, err
    assert out == ""


def test_sets_running_on_the_input_shaft_have_nothing_to_brake(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Every central member and carrier in a bearing of the input shaft, not of the
    housing: only the shafts could be held, and holding either stops the drive."""
    text = (DATA / "shifts_two_sets.yaml").read_text(encoding="utf-8")
    for member in ("s1", "r1", "c1", "s2", "r2", "c2"):
        text = text.replace(f"links: [0, {member}]", f"links: [in, {member}]")
    path = tmp_path / "on_shaft.yaml"
    path.write_text(text, encoding="utf-8")
    status, out, err = _run(["shifts", str(path), "--target", "1=2", "--quiet"], capsys)
    assert status == 2 and out == ""
    assert "couplings: no member can be braked" in err


def test_a_table_no_scheme_reaches_names_the_closest(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = _run(["shifts", str(SIMPSON), "--target", "1=2.4286", "2=1.9", "--quiet"], capsys)
    assert status == 3
    assert "gear 2: no elements give 1.9; the closest: " in err and out == ""


def test_the_ravigneaux_scheme_and_the_catalogs_own_states(capsys: pytest.CaptureFixture[str]) -> None:
    """The ZF 3HP12 Ravigneaux set given an input shaft (tests/data/shifts_ravigneaux.yaml)
    and its four published ratios: clutches from the input shaft to either sun, brakes
    on the carrier and on the large sun, third gear locked; each gear's efficiency is
    what the catalog's hand-written states (catalog/ravigneaux.yaml) give at the same
    numbers."""
    argv = ["shifts", str(DATA / "shifts_ravigneaux.yaml"), "--target", "R=-2.000", "1=2.560", "2=1.520", "3=1.000"]
    status, out, err = _run([*argv, "--json", "--quiet"], capsys)
    assert status == 0, err
    (candidate,) = json.loads(out)["candidates"]
    engaged = {
        gear: sorted(str(candidate["elements"][k].get("brake", candidate["elements"][k].get("clutch"))) for k in ks)
        for gear, ks in candidate["schedule"].items()
    }
    assert engaged == {
        "1": ["['in', 's1']", "c"],
        "2": ["['in', 's1']", "s2"],
        "3": ["['in', 's1']", "['in', 's2']"],
        "R": ["['in', 's2']", "c"],
    }
    values = ["rs1=25", "rs2=32", "rps=16", "rr=64", "eta_1=0.98", "eta_2=0.98", "eta_3=0.98", "eta_4=0.99"]
    for gear, state in (("1", "first"), ("2", "second"), ("3", "third"), ("R", "reverse")):
        status, out, err = _run(
            [str(CATALOG / "ravigneaux.yaml"), "--state", state, "--eval", *values, "--json"], capsys
        )
        assert status == 0, err
        assert json.loads(out)["efficiency"] == pytest.approx(candidate["efficiency"][gear], abs=1e-12), gear


def test_drag_lowers_the_score_by_the_slip_speeds(capsys: pytest.CaptureFixture[str]) -> None:
    """With --drag c each gear loses c times the sum of its open elements' squared slip
    speeds: the score falls by c times the mean of those sums over the gears."""
    argv = ["shifts", str(SIMPSON), "--target", *SIMPSON_TARGETS, "--json", "--quiet"]
    _, plain, _ = _run(argv, capsys)
    _, dragged, _ = _run([*argv, "--drag", "1/100"], capsys)
    (free,), (held,) = json.loads(plain)["candidates"], json.loads(dragged)["candidates"]
    sums = [sum(v * v for v in slips.values()) for slips in free["open_speed"].values()]
    assert held["score"] == pytest.approx(free["score"] - 0.01 * sum(sums) / len(sums), abs=1e-12)
    assert held["efficiency"] == free["efficiency"]


def test_connections_and_the_file_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The issue's two-set example: three joins, four elements; the JSON lists the joins,
    and the best design written as a train file (joins as clutches in every state)
    derives to the efficiencies it was ranked by."""
    best = tmp_path / "best.yaml"
    argv = ["shifts", str(DATA / "shifts_two_sets.yaml"), "--target", *SIMPSON_TARGETS, "--connections", "3"]
    status, out, err = _run([*argv, "--elements", "4", "--json", "--quiet", "--write-best", str(best)], capsys)
    assert status == 0, err
    document = json.loads(out)
    first = document["candidates"][0]
    assert len(first["connections"]) == 3 and document["feasible"] >= 1
    for gear, efficiency in first["efficiency"].items():
        status, out, err = _run([str(best), "--state", gear, "--eval", "--json"], capsys)
        assert status == 0, err
        assert json.loads(out)["efficiency"] == pytest.approx(efficiency, abs=1e-12), gear


def test_a_gear_joining_input_and_output_is_noted_not_written() -> None:
    """A scheme whose third gear clutches the input to the output member directly (a
    direct drive through no mesh): the written file says so in a comment and holds the
    other gears as states, each of which derives to the Simpson ratio by hand; derive
    refuses a state whose ports are one member, so none is written for it."""
    from davies_sym.cli.shifts_command import best_scheme_text
    from davies_sym.efficiency.variants import derive_variants
    from davies_sym.synthesis.shift_elements import ShiftElement
    from davies_sym.synthesis.shift_schedules import ShiftScheme
    from davies_sym.synthesis.shift_search import ShiftCandidate, ShiftResult
    from davies_sym.topology.loader import load, loads
    from davies_sym.topology.states import train_in_state

    elements = (ShiftElement(("s",)), ShiftElement(("c2",)), ShiftElement(("in", "r1")), ShiftElement(("in", "o")))
    ratios = {"1": Fraction(17, 7), "2": Fraction(10, 7), "3": Fraction(1)}
    scheme = ShiftScheme(elements, {"1": (1, 2), "2": (0, 2), "3": (2, 3)}, ratios)
    candidate = ShiftCandidate(scheme, {g: None for g in ratios}, {g: {} for g in ratios}, 0.5)
    text = best_scheme_text(str(SIMPSON), load(SIMPSON), ShiftResult((candidate,), 1, 0.0))
    assert "# gear 3 (C D) joins the input and output members" in text
    written = loads(text, str(SIMPSON))
    assert sorted(s.name for s in written.states) == ["1", "2"]
    for state in written.states:
        ratio = derive_variants(train_in_state(written, state)).analysis.speed_ratio().to_expr()
        assert ratio == ratios[state.name]  # sun 30, rings 70: (70 + 100) / 70 and 100 / 70
