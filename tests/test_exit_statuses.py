"""One test per exit status of ``derive`` and what ``--eval`` prints (docs/errors.md).

0: a result; with ``--eval`` three lines: the variant, the speed ratio, the efficiency
alone on the last line.  2: bad input (file, option or values).  3: a valid design the
formulas do not cover (self-locking, a port that does not turn); the last line is the
reason, never a number.  ``--json`` answers with ``status`` (and ``reason``).
Expected numbers are hand-derived (Willis) or published, never produced by the code.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import pytest
from harness.helpers import run_main

from conftest import catalog_path

TUPLIN = ["r1=40", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"]

PAIR = """\
name: numeric pair
links: [0, 1, 2]
reference: 0
gears:
  S: {link: 1, radius: 20}
  W: {link: 2, radius: 50}
couplings:
  A: {type: revolute, links: [0, 1], at: 0}
  B: {type: revolute, links: [0, 2]}
  C: {type: mesh, gears: [S, W], efficiency: 0.98}
ports: {input: A, output: B}
"""


def _number(line: str) -> float:
    return float(line)


def test_eval_prints_variant_speed_ratio_then_the_efficiency():
    """Tuplin, Laus section 3.4.1.6: 0.9462 with A as input.  Speed ratio by Willis with
    the carrier 5 as input and annulus 3/4 as output: i = r2 r3 / ((r1 - r2)(r1 - r3))
    = 60*15 / ((-20)(25)) = -9/5."""
    result = run_main([catalog_path("tuplin"), "--quiet", "--eval", *TUPLIN])
    assert result.returncode == 0, result.describe()
    variant, ratio, value = result.stdout.splitlines()[-3:]
    assert variant.startswith("variant (1): input A, output B")
    assert ratio == f"speed ratio (A over B): {-9 / 5!r}"
    assert _number(value) == pytest.approx(0.9462, abs=5e-5)


def test_eval_json_carries_both_numbers_and_the_exact_values():
    """With B as input: 0.9443 (Laus section 3.4.1.6); the speed ratio is the inverse, -5/9."""
    result = run_main([catalog_path("tuplin"), "--quiet", "--json", "--input", "B", "--eval", *TUPLIN])
    assert result.returncode == 0, result.describe()
    answer = json.loads(result.stdout)
    assert answer["status"] == "ok" and answer["input"] == "B" and answer["output"] == "A"
    assert Fraction(answer["speed_ratio_exact"]) == Fraction(-5, 9)
    assert answer["efficiency"] == pytest.approx(0.9443, abs=5e-5)
    assert float(Fraction(answer["efficiency_exact"])) == answer["efficiency"]


def test_eval_without_values_when_every_quantity_is_a_number(tmp_path):
    """An external pair of radii 20 and 50 with a mesh efficiency 0.98: the efficiency is
    0.98 and the speed ratio -50/20 (the output turns the other way, slower)."""
    path = tmp_path / "pair.yaml"
    path.write_text(PAIR)
    result = run_main([str(path), "--quiet", "--eval"])
    assert result.returncode == 0, result.describe()
    ratio, value = result.stdout.splitlines()[-2:]
    assert ratio == "speed ratio (A over B): -2.5"
    assert _number(value) == 0.98


def test_bad_values_are_exit_2_and_json_says_why():
    result = run_main(
        [catalog_path("tuplin"), "--quiet", "--json", "--eval", "r1=-40", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"]
    )
    assert result.returncode == 2, result.describe()
    answer = json.loads(result.stdout)
    assert answer == {"status": "bad input", "exit_status": 2, "reason": result.stderr.strip()}
    assert "r1 = -40 must be positive" in answer["reason"]


def test_an_efficiency_above_one_is_bad_input():
    result = run_main(
        [catalog_path("tuplin"), "--quiet", "--eval", "r1=40", "r2=60", "r3=15", "eta_C=1.5", "eta_D=0.99"]
    )
    assert result.returncode == 2, result.describe()
    assert "eta_C = 1.5 is not an efficiency" in result.stderr


def test_self_locking_is_exit_3_with_a_reason_as_the_last_line():
    """Tuplin with B as input self-locks where eta_C eta_D r1 (r1 - r2 - r3) + r2 r3 <= 0
    (the numerator of variant (3)); with eta = 0.7: 0.49 * 40 * (-35) + 900 = 214 > 0 is
    still positive, but the efficiency 214 / (-500) is negative: the output would have
    to drive."""
    result = run_main(
        [
            catalog_path("tuplin"),
            "--quiet",
            "--input",
            "B",
            "--eval",
            "r1=40",
            "r2=60",
            "r3=15",
            "eta_C=0.7",
            "eta_D=0.7",
        ]
    )
    assert result.returncode == 3, result.describe()
    last = result.stdout.splitlines()[-1]
    assert "self-locks" in last and "B as input" in last
    with pytest.raises(ValueError):
        float(last)
    answer = json.loads(
        run_main(
            [
                catalog_path("tuplin"),
                "--quiet",
                "--json",
                "--input",
                "B",
                "--eval",
                "r1=40",
                "r2=60",
                "r3=15",
                "eta_C=0.7",
                "eta_D=0.7",
            ]
        ).stdout
    )
    assert answer["status"] == "not covered" and answer["exit_status"] == 3 and "self-locks" in answer["reason"]


def test_a_port_that_does_not_turn_is_exit_3():
    """Tuplin with r1 = r2: the two annuli have the same ratio to their planets, the
    output annulus stands still (Willis: r1 - r2 = 0 in the denominator of the ratio)."""
    result = run_main(
        [catalog_path("tuplin"), "--quiet", "--eval", "r1=60", "r2=60", "r3=15", "eta_C=0.9", "eta_D=0.9"]
    )
    assert result.returncode == 3, result.describe()
    assert "port B does not turn" in result.stdout.splitlines()[-1]


def test_json_document_says_ok():
    result = run_main([catalog_path("simple_pair"), "--quiet", "--json"])
    assert result.returncode == 0
    assert json.loads(result.stdout)["status"] == "ok"


def test_idle_meshes_are_reported_as_carrying_no_power():
    """Simpson's second gear: the front set works (its annulus driven, its sun held); the
    rear set's meshes E and F carry nothing.  In the third gear (direct drive, both sets
    locked together) no mesh carries power and the efficiency is exactly 1."""
    second = run_main([catalog_path("simpson"), "--quiet", "--state", "second"]).stdout
    assert "E: carries no power" in second and "F: carries no power" in second
    assert "C: carries no power" not in second and "D: carries no power" not in second
    third = run_main([catalog_path("simpson"), "--quiet", "--json", "--state", "third"])
    meshes = json.loads(third.stdout)["states"]["third"]["meshes"]
    assert [m["carries_power"] for m in meshes] == [False] * 4
    value = run_main(
        [
            catalog_path("simpson"),
            "--quiet",
            "--state",
            "third",
            "--eval",
            "eta_C=0.9",
            "eta_D=0.9",
            "eta_E=0.9",
            "eta_F=0.9",
            "rs=20",
            "rr1=50",
            "rr2=50",
        ]
    )
    assert value.returncode == 0, value.describe()
    assert value.stdout.splitlines()[-1] == "1.0"


def test_dependent_motion_screws_are_located_bad_input(tmp_path):
    """Two unit motions of coupling C along the same screw (the second twice the first):
    exit 2 at the coupling's line and entry, not a bare message."""
    from conftest import ROOT

    source = tmp_path / "screws.yaml"
    text = (Path(ROOT) / "tests" / "data" / "tuplin_screws.yaml").read_text()
    doubled = "motions: {t_C: {t: 1, u: r1}, s_C: {t: 2, u: 2*r1}}"
    source.write_text(text.replace("motions: {t_C: {t: 1, u: r1}}", doubled))
    result = run_main([str(source), "--quiet"])
    assert result.returncode == 2, result.describe()
    assert f"{source}:8: couplings.C.motions: its unit motion screws are not independent" in result.stderr


def _planted(monkeypatch: pytest.MonkeyPatch) -> None:
    """An exception no stage turns into a refusal, planted where every derivation passes."""
    from davies_sym.network import analysis

    def fault(*args: object, **kwargs: object) -> None:
        raise ZeroDivisionError("planted fault")

    monkeypatch.setattr(analysis, "constraint_substitutions", fault)


@pytest.mark.parametrize("json_answer", [False, True], ids=["text", "json"])
def test_status_4_an_exception_past_the_stages_is_an_internal_error(
    monkeypatch: pytest.MonkeyPatch, json_answer: bool
) -> None:
    """docs/errors.md: a fault of the package is exit 4 with the file, the step that was
    running (the state too) and where in the package it happened; never a traceback."""
    _planted(monkeypatch)
    result = run_main([catalog_path("simpson"), "--state", "second", "--quiet", *(["--json"] if json_answer else [])])
    assert result.returncode == 4, result.describe()
    assert "Traceback" not in result.stderr
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"internal error: {catalog_path('simpson')}: state second, building the coupling network: ")
    assert "ZeroDivisionError: planted fault (in davies_sym/network/analysis.py:" in line
    assert "please report it" in line
    if json_answer:
        answer = json.loads(result.stdout)
        assert answer == {"status": "internal error", "exit_status": 4, "reason": line}


def test_status_4_in_a_subcommand(monkeypatch: pytest.MonkeyPatch) -> None:
    """The subcommands answer a fault of the package alike (here `derive search`)."""
    from davies_sym.cli import search_command

    def fault(args: object, parser: object) -> int:
        raise KeyError("planted fault")

    monkeypatch.setattr(search_command, "run", fault)
    result = run_main(["search", catalog_path("planetary_simple"), "--target", "4", "--teeth", "zs=17:20"])
    assert result.returncode == 4, result.describe()
    assert "Traceback" not in result.stderr
    assert result.stderr.startswith("internal error: derive search: running search "), result.describe()
