"""The FMU of a train driven at two shafts (the SR20 differential, Mantriota and Pennestri
2003, Fig. 7) in a real FMI runtime (FMPy): the torques each shaft applies, step by step
through every sector of the two input speeds, the lines between them (both shafts at one
speed, the output at rest, a shaft at rest) and zero load, against the Python formula
module's ``torques`` (its regions by a route that shares no C), and the power balance."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from harness.helpers import assert_refused, run_main, unheard

from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.several_inputs_module import several_inputs_module
from davies_sym.topology.loader import load

from conftest import catalog_path

fmpy = pytest.importorskip("fmpy")
validation = pytest.importorskip("fmpy.validation")

pytestmark = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler (cc)")

SR20 = catalog_path("sr20_differential")
START = {"eta_M": 0.95, "D_P": 0.4}
OUTPUTS = ["omega_A", "omega_K", "tau_out", "tau_A", "tau_K", "omega_out", "P_loss", "efficiency", "variant", "status"]

#: Input speeds through every sector and onto every line: A = K (the meshes do not roll),
#: A = -K (the output at rest), a shaft at rest, both at rest; each line reached from a
#: side, so that the unit takes the limit from that side.
SPEEDS = [
    (10.0, 4.0),
    (5.0, 5.0),
    (4.0, 10.0),
    (6.0, 6.0),
    (10.0, -4.0),
    (3.0, -3.0),
    (-4.0, 10.0),
    (0.0, 7.0),
    (-10.0, -4.0),
    (-5.0, -5.0),
    (-4.0, -10.0),
    (0.0, 0.0),
    (7.0, 0.0),
    (-3.0, 3.0),
    (2.0, 9.0),
    (0.0, 0.0),
]


def _module():
    si = derive_several_inputs(load(SR20))
    return compiled_module(several_inputs_module(si), "sr20_fmu_check")


@pytest.fixture(scope="module")
def unit(tmp_path_factory: pytest.TempPathFactory) -> Path:
    target = tmp_path_factory.mktemp("sr20") / "sr20.fmu"
    at = [f"{k}={v}" for k, v in START.items()]
    result = run_main([SR20, "--emit", "fmu", "-o", str(target), "--at", *at, "--quiet"])
    assert result.returncode == 0, result.describe()
    return target


def _run(unit: Path, speeds: list[tuple[float, float]], loads: list[float], **options: object) -> np.ndarray:
    times = np.arange(len(speeds), dtype=float)
    signal = np.array(
        [(t, a, k, q) for t, (a, k), q in zip(times, speeds, loads, strict=True)],
        dtype=[("time", float), ("omega_A", float), ("omega_K", float), ("tau_out", float)],
    )
    options.setdefault("logger", unheard)
    return fmpy.simulate_fmu(
        str(unit), stop_time=times[-1], output_interval=1.0, input=signal, output=OUTPUTS, **options
    )


def _resisting(speeds: list[tuple[float, float]], magnitude: float) -> list[float]:
    """A load of ``magnitude`` resisting the output's motion (w_O = (w_A + w_K)/2), at rest
    resisting the direction it last had (forwards before any)."""
    out, side = [], 1.0
    for a, k in speeds:
        side = np.sign(a + k) if a + k != 0 else side
        out.append(-magnitude * side)
    return out


def _expected_torques(module, speeds: tuple[float, float], before: tuple[float, float], load: float):
    """The module's torques at ``speeds``; on a line (where it has none) the limit from the
    side of ``before``: the module at a point between them, next to ``speeds``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for weight in (0.0, 1e-7):
            a = speeds[0] + weight * (before[0] - speeds[0])
            k = speeds[1] + weight * (before[1] - speeds[1])
            if a == 0 and k == 0:
                a, k = 1e-7 * before[0], 1e-7 * before[1]
            torques = module.torques(errors="ignore", **START, omega_A=a, omega_K=k, tau_out=abs(load) or 1e-300)
            if np.isfinite(torques["A"]):
                return float(torques["A"]), float(torques["K"]), (a, k)
    raise AssertionError(f"the module has no torques near {speeds}")


@pytest.mark.parametrize("magnitude", [20.0, 0.0])
def test_two_shaft_torques_through_every_sector_and_line(unit: Path, magnitude: float) -> None:
    """Every step covered, nothing NaN, each shaft's torque the module's (to 1e-12) or
    its limit on a line, the region's number the module's, and the power balance
    P_A + P_K + P_O = P_loss >= 0; the efficiency is the module's where it has one."""
    assert validation.validate_fmu(str(unit)) == []
    module = _module()
    rows = _run(unit, SPEEDS, _resisting(SPEEDS, magnitude))
    before = (1.0, 1.0)  # the unit's memory before any motion
    for row in rows[1:]:  # the first row is the start, before the inputs are read
        speeds = (float(row["omega_A"]), float(row["omega_K"]))
        assert row["status"] == 0, row
        assert np.isfinite([row["tau_A"], row["tau_K"], row["P_loss"], row["efficiency"]]).all(), row
        tau_a, tau_k, near = _expected_torques(module, speeds, before, float(row["tau_out"]))
        assert row["tau_A"] == pytest.approx(tau_a, rel=1e-12, abs=1e-12)
        assert row["tau_K"] == pytest.approx(tau_k, rel=1e-12, abs=1e-12)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            region = module.region(**START, omega_A=near[0], omega_K=near[1], tau_out=abs(row["tau_out"]) or 1e-300)
        assert row["variant"] == int(region)
        assert row["omega_out"] == pytest.approx((speeds[0] + speeds[1]) / 2, rel=1e-15)
        powers = row["tau_A"] * speeds[0] + row["tau_K"] * speeds[1] + row["tau_out"] * row["omega_out"]
        assert row["P_loss"] == pytest.approx(powers, rel=1e-9, abs=1e-12) and row["P_loss"] >= -1e-12
        if magnitude and speeds != (0.0, 0.0):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                eta = module.efficiency(
                    errors="ignore", **START, omega_A=speeds[0], omega_K=speeds[1], tau_out=magnitude
                )
            if np.isfinite(eta):
                assert row["efficiency"] == pytest.approx(float(eta), rel=1e-12)
        if speeds != (0.0, 0.0):
            before = speeds


def test_a_load_that_drives_the_output_gives_a_status_and_a_logged_reason(unit: Path) -> None:
    logged: list[str] = []
    speeds = [(10.0, 4.0)] * 3
    rows = _run(unit, speeds, [-20.0, 20.0, 20.0], logger=lambda *a: logged.append(str(a)), debug_logging=True)
    assert rows[-1]["status"] == 5 and np.isnan([rows[-1]["tau_A"], rows[-1]["tau_K"], rows[-1]["P_loss"]]).all()
    assert any("the load drives the output port" in line for line in logged)


def test_outside_the_parameters_ranges_gives_a_status_not_a_number(unit: Path) -> None:
    logged: list[str] = []
    rows = _run(
        unit,
        [(10.0, 4.0), (10.0, 4.0)],
        [-20.0, -20.0],
        start_values={"eta_M": 1.2},
        logger=lambda *a: logged.append(str(a)),
        debug_logging=True,
    )
    assert (rows["status"] == 1).all() and np.isnan(rows["tau_A"]).all()
    assert any("outside the parameters' ranges" in line for line in logged)


@pytest.mark.parametrize(
    ("at", "words"),
    [([], "give the start value of D_P, eta_M"), (["eta_M=0.9", "D_P=0.1", "omega_A=3"], "unknown symbol omega_A")],
)
def test_start_values_are_asked_for_by_name(tmp_path: Path, at: list[str], words: str) -> None:
    args = [SR20, "--emit", "fmu", "-o", str(tmp_path / "s.fmu"), "--quiet", *(["--at", *at] if at else [])]
    result = run_main(args)
    assert_refused(result, SR20, ("--at",), line=False)
    assert words in result.stderr
    assert not (tmp_path / "s.fmu").exists()


def test_an_fmu_without_its_file_is_refused() -> None:
    result = run_main([SR20, "--emit", "fmu", "--at", "eta_M=0.9", "D_P=0.1", "--quiet"])
    assert_refused(result, SR20, ("--emit",), line=False)
    assert "-o TRAIN.fmu" in result.stderr
