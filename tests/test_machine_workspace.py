"""A machine outside its workspace or through a singular position is refused with the
time step or position named (exit 3), never a number: workspace limits written in the
file, split sliders whose contacts pass each other, dead centres between two samples,
and cycles the linkage cannot run through."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from harness.helpers import run_main

from davies_sym.machines.machine_loader import build_machine
from davies_sym.machines.passages import passed, split_sliders
from davies_sym.machines.task import run_task
from davies_sym.topology.documents import read_document

from conftest import CATALOG

THREE_UPU = Path(CATALOG) / "three_upu.yaml"
SLIDER_CRANK = Path(CATALOG) / "slider_crank.yaml"
FOUR_BAR = Path(CATALOG) / "four_bar.yaml"
LIFT = "path: {M_x: 0.1, M_y: 0.2, M_z: 0.5 + 0.4*t}"
LIMITS = "limits:\n  mouth1: dot(B - C, s1) > 0\n  mouth2: dot(F - G, s2) > 0\n  mouth3: dot(J - K, s3) > 0\n"


def _write(tmp_path: Path, text: str, name: str = "machine.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _limb_lengths(mx: float, my: float, mz: float) -> list[float]:
    """|e2| of Laus eq. (125) for the three limbs (r_b = 1, r_t = 0.5)."""
    return [
        math.hypot(mx - 0.5 * math.cos(a), my - 0.5 * math.sin(a), mz) for a in (0.0, 2 * math.pi / 3, -2 * math.pi / 3)
    ]


def _first_step_beyond(stroke: float, mz) -> int:
    """The first time sample (step 0.005 s) where a limb is longer than ``stroke``."""
    return next(k for k in range(201) if max(_limb_lengths(0.1, 0.2, mz(k * 0.005))) >= stroke)


def test_catalog_three_upu_declares_its_strokes():
    machine = build_machine(read_document(THREE_UPU))
    assert [limit.name for limit in machine.limits] == ["mouth1", "mouth2", "mouth3"]
    pairs = {(a.name, b.name) for a, b in split_sliders(machine.couplings)}
    assert pairs == {("B", "C"), ("F", "G"), ("J", "K")}


def test_a_lift_past_the_stroke_is_refused_at_the_first_step_outside(tmp_path):
    """Lifting 0.8 m: a limb grows longer than l_B + l_C = 1.2 m (its rod's contact C would
    leave the tube at B).  The step is the first whose limb length, computed here from
    Laus eq. (125), reaches 1.2 m."""
    text = THREE_UPU.read_text(encoding="utf-8").replace(LIFT, "path: {M_x: 0.1, M_y: 0.2, M_z: 0.5 + 0.8*t}", 1)
    step = _first_step_beyond(1.2, lambda t: 0.5 + 0.8 * t)
    result = run_main([_write(tmp_path, text), "--task", "lift", "--quiet"])
    assert result.returncode == 3, result.describe()
    assert f"step {step} (t = {step * 0.005:.6g} s)" in result.stdout
    assert "outside the workspace" in result.stdout and "mouth" in result.stdout
    assert "Traceback" not in result.stdout + result.stderr


def test_without_limits_the_slider_coming_apart_is_still_refused_between_two_steps(tmp_path):
    """The same lift in a file without limits: the two contacts of limb 3's slider pass each
    other between two samples, a rank-two singularity (the determinant keeps its sign), and
    the two steps around it are named."""
    text = THREE_UPU.read_text(encoding="utf-8").replace(LIFT, "path: {M_x: 0.1, M_y: 0.2, M_z: 0.5 + 0.8*t}", 1)
    assert LIMITS in text
    step = _first_step_beyond(1.2, lambda t: 0.5 + 0.8 * t)
    result = run_main([_write(tmp_path, text.replace(LIMITS, "")), "--task", "lift", "--quiet"])
    assert result.returncode == 3, result.describe()
    assert f"between step {step - 1} " in result.stdout and f"and step {step} " in result.stdout
    assert "the contacts J and K of one slider pass each other" in result.stdout


def test_a_task_starting_outside_is_refused_at_step_0(tmp_path):
    text = THREE_UPU.read_text(encoding="utf-8").replace(LIFT, "path: {M_x: 0.1, M_y: 0.2, M_z: 1.3 + 0.1*t}", 1)
    result = run_main([_write(tmp_path, text), "--task", "lift", "--quiet"])
    assert result.returncode == 3, result.describe()
    assert "step 0 (t = 0 s): outside the workspace: the limit mouth" in result.stdout


def test_passed_names_only_the_signs_that_change():
    before = {"a": 1.0, "b": -1.0, "c": 0.0}
    assert passed(before, {"a": 1.0, "b": 1.0, "c": -1.0}) == ["b"]
    assert passed(before, before) == []


def test_catalog_tasks_stay_inside_and_keep_their_numbers():
    """The limits and passage checks leave Laus's three tasks whole (no refusal, every
    sample solved)."""
    machine = build_machine(read_document(THREE_UPU))
    for task, count in (("lift", 201), ("lift_half", 101), ("ellipse", 201)):
        assert len(run_task(machine, task).steps) == count


@pytest.mark.parametrize(
    ("values", "words"),
    [
        (["a1=3", "a2=1", "mu_D=0.1"], "no cycle efficiency: at theta = "),
        (["a1=3", "a2=1", "mu_D=0.1", "theta=2"], "cannot be assembled"),
        (["a1=1", "a2=1", "mu_D=0.1"], "singular position"),
    ],
)
def test_slider_crank_that_cannot_turn_is_exit_3_with_a_reason(values, words):
    """A crank longer than its rod has no full turn (and no position at theta = 2); a crank
    as long as its rod folds onto it at theta = pi, where ln((a1 + a2)/(a2 - a1)) of Laus
    eq. (120) is infinite."""
    result = run_main([SLIDER_CRANK, "--quiet", "--eval", *values])
    assert result.returncode == 3, result.describe()
    assert words in result.stdout and "Traceback" not in result.stdout + result.stderr


@pytest.mark.parametrize(
    ("limit", "words"),
    [
        ("stroke: dot(B, x)", "one inequality"),
        ("stroke: dot(B, x) < 1 < 2", "one inequality"),
        ("stroke: B < 1", "a scalar is wanted"),
    ],
)
def test_bad_limits_are_exit_2_with_their_line(tmp_path, limit, words):
    text = SLIDER_CRANK.read_text(encoding="utf-8").replace("couplings:\n", f"limits:\n  {limit}\ncouplings:\n", 1)
    path = _write(tmp_path, text, "bad.yaml")
    result = run_main([path, "--quiet"])
    assert result.returncode == 2, result.describe()
    assert words in result.stderr and f"{path}:" in result.stderr and "limits.stroke" in result.stderr


def test_a_limit_refuses_positions_and_cycles_of_the_slider_crank(tmp_path):
    """A guide of length 3.5 (C_x < 3.5): the crank at theta = 0 puts C at a1 + a2 = 4."""
    text = SLIDER_CRANK.read_text(encoding="utf-8").replace(
        "couplings:\n", "limits:\n  guide: dot(C, x) < 3.5\ncouplings:\n", 1
    )
    path = _write(tmp_path, text)
    inside = run_main([path, "--quiet", "--eval", "a1=1", "a2=3", "mu_D=0.1", "theta=2"])
    assert inside.returncode == 0, inside.describe()
    outside = run_main([path, "--quiet", "--eval", "a1=1", "a2=3", "mu_D=0.1", "theta=0"])
    assert outside.returncode == 3 and "the limit guide (dot(C, x) < 3.5)" in outside.stdout, outside.describe()
    cycle = run_main([path, "--quiet", "--eval", "a1=1", "a2=3", "mu_D=0.1"])
    assert cycle.returncode == 3 and "no cycle efficiency" in cycle.stdout, cycle.describe()
