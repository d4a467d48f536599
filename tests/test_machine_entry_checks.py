"""A machine file's mistakes are refused where they are written (FILE:LINE: ENTRY), before
the numerics: unknown keys, repeated names, a zero axis, values that are not numbers, a
negative friction coefficient, a task, cycle or check that names what the file lacks.
Five of these ended in a traceback inside the numeric route (a generated sweep of 75
machine-file cases)."""

from __future__ import annotations

import pytest
from harness.helpers import CATALOG, assert_at, assert_edit_refused, line_of, replaced, run_main, write

FOUR_BAR = (CATALOG / "four_bar.yaml").read_text(encoding="utf-8")
SLIDER = (CATALOG / "slider_crank.yaml").read_text(encoding="utf-8")
UPU = (CATALOG / "three_upu.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("source", "old", "new", "at", "entry", "words"),
    [
        (FOUR_BAR, "mu: 0.2,", "mu: -0.2,", "values:", "values.mu", "friction coefficient: write a number >= 0"),
        (FOUR_BAR, "a: 1,", "a: one,", "values:", "values.a", "one has no value"),
        (
            FOUR_BAR,
            "links: [ground, crank, coupler, rocker]",
            "links: [ground, crank, coupler, rocker, crank]",
            "links:",
            "links",
            "'crank' is written twice",
        ),
        (
            FOUR_BAR,
            "crank: {coupling: A}",
            "crank: {coupling: A, speed: 3}",
            "crank: {coupling",
            "ports.crank.speed",
            "unknown entry 'speed'",
        ),
        (
            FOUR_BAR,
            "at: [0, 0, 0], axis: z,",
            "at: [0, 0, 0], axis: [0, 0, 0],",
            "axis: [0, 0, 0]",
            "couplings.A.axis",
            "zero vector",
        ),
        (SLIDER, "variable: theta,", "variable: phi,", "cycle:", "cycle.variable", "phi is not a position variable"),
        (SLIDER, "from: -pi, to: pi", "from: pi, to: -pi", "cycle:", "cycle.to", "to > from"),
        (
            SLIDER,
            "quantity: cycle_efficiency",
            "quantity: speed",
            "quantity: speed",
            "expected[0].quantity",
            "unknown quantity 'speed'",
        ),
        (UPU, "time: [0, 1]", "time: [0, T_end]", "time: [0, T_end]", "tasks.lift.time", "numbers of seconds"),
        (
            UPU,
            "loads: {payload: -W}",
            "loads: {payload: -W*q}",
            "loads: {payload: -W*q}",
            "tasks.lift.loads.payload",
            "q is not t or a value",
        ),
        (UPU, "loads: {payload: -W}", "loads: {}", "loads: {}", "tasks.lift.loads", "at least one port"),
        (UPU, "drive: M", "drive: Q", "drive: Q", "tasks.lift.drive", "name the coupling the path moves"),
        (
            UPU,
            "path: {M_x: 0.1, M_y: 0.2, M_z: 0.5 + 0.4*t}",
            "path: {M_x: 0.1, M_y: 0.2, M_z: 0.5 + 0.4*t, M_w: t}",
            "M_w: t",
            "tasks.lift.path.M_w",
            "M_w is not a position variable",
        ),
        (
            UPU,
            "drive: M\n    loads: {payload: -W}\n  lift_half",
            "drive: C\n    loads: {payload: -W}\n  lift_half",
            "drive: C",
            "tasks.lift.drive",
            "freedoms for 3 position variables",
        ),
        (FOUR_BAR, "position: theta", "position: phi", "position: phi", "position", "phi moves nothing"),
    ],
    ids=[
        "negative-mu",
        "value-a-word",
        "link-twice",
        "port-key",
        "zero-axis",
        "cycle-variable",
        "cycle-reversed",
        "check-quantity",
        "task-time-symbol",
        "load-unknown-symbol",
        "no-loads",
        "unknown-drive",
        "path-extra",
        "drive-freedoms",
        "position-unused",
    ],
)
def test_a_machine_mistake_is_refused_at_its_entry(tmp_path, source, old, new, at, entry, words):
    assert_edit_refused(tmp_path, source, old, new, at, entry, words, "machine.yaml")


def test_a_normal_along_the_axis_is_refused_at_its_entry(tmp_path):
    """The slider crank's slide D with its normal along its axis: no frame (it derived to
    'no closed form' with exit 0)."""
    line = next(x for x in SLIDER.splitlines() if x.strip().startswith("D: {type"))
    axis = "x" if "axis: x" in line else line.split("axis: ")[1].split(",")[0].split("}")[0]
    text = replaced(SLIDER, line, line.replace(f"axis: {axis}", f"axis: {axis}, normal: {axis}"))
    path = write(tmp_path, text, "machine.yaml")
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, "normal:"), "couplings.D.normal")
    assert "parallel to the axis" in result.stderr, result.describe()


def test_a_task_whose_loads_do_no_work_has_no_efficiency(tmp_path):
    """Laus's lift with no payload: the drive supplies nothing, so the task efficiency is
    not a number (it printed nan with exit 0); exit 3 with the reason."""
    text = replaced(UPU, "loads: {payload: -W}\n  lift_half", "loads: {payload: 0}\n  lift_half")
    path = write(tmp_path, text, "machine.yaml")
    result = run_main([path, "--quiet", "--task", "lift"])
    assert result.returncode == 3, result.describe()
    assert "the drive supplies no energy over the task" in result.stdout + result.stderr, result.describe()
