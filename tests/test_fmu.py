"""`derive FILE --emit fmu -o TRAIN.fmu`: the FMI 2.0 co-simulation unit of every catalog
train driven at one port, loaded and simulated in a real FMI runtime (FMPy) through all
four quadrants of speed and load torque.  At every step the input torque equals what the
Python formula module gives for the variant of the power flow's direction (1e-12
relative), the variant is the module's, the power balance P_in + P_out = P_loss >= 0
holds, and a sweep through zero speed and zero torque gives no NaN.  Designs the
formulas do not cover give the status output and a logged reason, never a number."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from harness.helpers import assert_refused, run_main, unheard

from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.topology.loader import load
from davies_sym.topology.states import train_in_state

from conftest import catalog_path

fmpy = pytest.importorskip("fmpy")
validation = pytest.importorskip("fmpy.validation")
pytestmark = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler (cc)")

#: Catalog trains driven at one port whose formulas take the geometry and efficiencies
#: alone, with the state simulated (None: the train as written) and the parameters' start
#: values (None: the file's first published check).
TRAINS = [
    ("planetary_simple", None, None),
    ("simple_pair", None, None),
    ("buckingham_pair", None, None),
    ("crossed_helical", None, None),
    ("humpage", None, None),
    ("litvin_face_drive", None, None),
    ("rack_pinion", None, None),
    ("tuplin", None, None),
    ("wolfrom", None, ["eta_C=0.98", "eta_D=0.99", "eta_E=0.99", "rs=20", "rp1=20", "rp2=18"]),
    ("worm_drive", None, None),
    ("worm_planetary", None, None),
    ("simpson", "first", ["eta_C=0.98", "eta_D=0.99", "eta_E=0.98", "eta_F=0.99", "rs=30", "rr1=70", "rr2=70"]),
    ("ravigneaux", "second", ["eta_1=0.98", "eta_2=0.98", "eta_3=0.99", "eta_4=0.99", "rs1=20", "rs2=30", "rr=80"]),
    ("bicycle_hub", "low", None),
]


def _build(name: str, state: str | None, folder: Path, at: list[str] | None = None) -> Path:
    target = folder / f"{name}.fmu"
    args = [catalog_path(name), "--emit", "fmu", "-o", str(target), "--quiet"]
    args += ["--state", state] if state else []
    args += ["--at", *at] if at else []
    result = run_main(args)
    assert result.returncode == 0, result.describe()
    return target


def _module(name: str, state: str | None):  # the Python formula module of the same formulas
    train = load(catalog_path(name))
    if state is not None:
        train = train_in_state(train, next(s for s in train.states if s.name == state))
    variants = derive_variants(train)
    return variants, compiled_module(python_module(variants), name)


def _sweep(unit: Path, speeds: np.ndarray, torques: np.ndarray) -> np.ndarray:
    times = np.arange(len(speeds), dtype=float)
    signal = np.array(
        list(zip(times, speeds, torques, strict=True)),
        dtype=[("time", np.float64), ("omega_in", np.float64), ("tau_out", np.float64)],
    )
    return fmpy.simulate_fmu(
        str(unit),
        stop_time=times[-1],
        output_interval=1.0,
        input=signal,
        output=["omega_in", "tau_out", "tau_in", "omega_out", "P_loss", "efficiency", "variant", "status"],
        logger=unheard,
    )


@pytest.mark.parametrize(("name", "state", "at"), TRAINS)
def test_four_quadrants_agree_with_the_formula_module(
    name: str, state: str | None, at: list[str] | None, tmp_path: Path
) -> None:
    unit = _build(name, state, tmp_path, at)
    assert validation.validate_fmu(str(unit)) == []
    description = fmpy.read_model_description(str(unit))
    parameters = {v.name: float(v.start) for v in description.modelVariables if v.causality == "parameter"}
    variants, module = _module(name, state)
    ports = (variants.train.ports.input, variants.train.ports.output)
    ratio = float(np.asarray(module.speed_ratio(**_taking(module.speed_ratio, parameters))))
    # Speeds and torques of both signs, zero included: every quadrant and both crossings.
    speeds = np.array([3.0, 3.0, -2.0, -2.0, 0.0, 0.0, 5.0, -5.0])
    torques = np.array([1.5, -1.5, 1.5, -1.5, 2.0, -2.0, 0.0, 0.0]) * abs(ratio)
    rows = _sweep(unit, speeds, torques)
    last = 1.0  # at zero speed: the limit from the side the speed last came from (+ before any)
    for row in rows[1:]:  # the first row is the start, before the inputs are read
        omega, tau_out, tau_in, omega_out = row["omega_in"], row["tau_out"], row["tau_in"], row["omega_out"]
        assert row["status"] == 0 and np.isfinite([tau_in, row["P_loss"], row["efficiency"]]).all()
        assert omega_out == pytest.approx(omega / ratio, rel=1e-12, abs=1e-300)
        side = last = np.sign(omega) if omega != 0 else last
        driving_output = tau_out * side / ratio > 0
        port = ports[1] if driving_output else ports[0]
        eta = float(module.efficiency(input=port, **_taking(module.efficiency, parameters)))
        expected = -eta * tau_out * side / ratio / side if driving_output else -(tau_out * side / ratio) / eta / side
        assert tau_in == pytest.approx(expected, rel=1e-12, abs=1e-12 * abs(tau_out))
        assert row["variant"] == int(module.variant(input=port, **_taking(module.variant, parameters)))
        balance = tau_in * omega + tau_out * omega_out
        assert row["P_loss"] == pytest.approx(balance, rel=1e-9, abs=1e-12) and row["P_loss"] >= -1e-12


def _taking(function, values: dict[str, float]) -> dict[str, float]:
    import inspect

    accepted = inspect.signature(function).parameters
    return {k: v for k, v in values.items() if k in accepted}


def test_a_self_locking_worm_held_against_its_load(tmp_path: Path) -> None:
    """A worm of lead angle 5 deg with friction 0.2 self-locks backwards: where the load
    would drive, the status says 3 and the input still drives, by the back variant's own
    (negative) efficiency: P_in = -eta_back P_out >= 0, and the loss is both powers."""
    unit = _build("worm_drive", None, tmp_path, ["alpha_n=0.3491", "gamma=0.08727", "mu=0.2"])
    variants, module = _module("worm_drive", None)
    parameters = {"alpha_n": 0.3491, "gamma": 0.08727, "mu": 0.2}
    ratio = float(np.asarray(module.speed_ratio(**_taking(module.speed_ratio, parameters))))
    rows = _sweep(unit, np.array([2.0, 2.0, 2.0]), np.array([-1.0, 1.0, 1.0]) * np.sign(ratio))
    loaded, overhauling = rows[1], rows[2]
    assert loaded["status"] == 0 and overhauling["status"] == 3
    back = next(v for v in variants.variants if v.input == variants.train.ports.output)
    raw = float(getattr(module, back.name)(**_taking(getattr(module, back.name), parameters)))
    assert raw < 0 and overhauling["efficiency"] == pytest.approx(raw, rel=1e-12)
    power_out = overhauling["tau_out"] * overhauling["omega_out"]
    assert overhauling["tau_in"] * overhauling["omega_in"] == pytest.approx(-raw * power_out, rel=1e-12)
    assert overhauling["P_loss"] > power_out > 0


def test_outside_the_admissible_parameters_gives_a_status_not_a_number(tmp_path: Path) -> None:
    unit = _build("planetary_simple", None, tmp_path)
    logged: list[str] = []
    rows = fmpy.simulate_fmu(
        str(unit),
        stop_time=1.0,
        output_interval=1.0,
        start_values={"rA": -20.0},
        input=np.array(
            [(0.0, 1.0, 1.0), (1.0, 1.0, 1.0)], dtype=[("time", float), ("omega_in", float), ("tau_out", float)]
        ),
        output=["tau_in", "status"],
        logger=lambda *args: logged.append(str(args)),
        debug_logging=True,
    )
    assert (rows["status"] == 1).all() and np.isnan(rows["tau_in"]).all()
    assert any("outside the admissible parameters" in line for line in logged)


def test_the_same_formulas_give_the_same_bytes(tmp_path: Path) -> None:
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first, second = (_build("humpage", None, tmp_path / k) for k in "ab")
    assert first.read_bytes() == second.read_bytes()


@pytest.mark.parametrize(
    ("args", "entry"),
    [
        (["--emit", "fmu"], "--emit"),  # no -o
        (["--emit", "fmu", "-o", "x.fmu", "--at", "rA=-1"], "--at"),
    ],
)
def test_bad_fmu_requests_are_refused(args: list[str], entry: str, tmp_path: Path) -> None:
    result = run_main([catalog_path("planetary_simple"), *args, "--quiet"])
    assert_refused(result, catalog_path("planetary_simple"), (entry,), line=False)


def test_a_multi_speed_file_needs_its_state(tmp_path: Path) -> None:
    result = run_main([catalog_path("simpson"), "--emit", "fmu", "-o", str(tmp_path / "s.fmu"), "--quiet"])
    assert_refused(result, catalog_path("simpson"), ("--state",), line=False)


def test_no_c_compiler_is_one_message(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("CC", "no-such-compiler")
    result = run_main([catalog_path("planetary_simple"), "--emit", "fmu", "-o", str(tmp_path / "p.fmu"), "--quiet"])
    assert result.returncode == 2 and "C compiler" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "p.fmu").exists()


def test_the_docs_page_simulates_the_readme_planetary(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """docs/simulation.md as a reader runs it: the README's planetary built as the page's
    console line says, then the page's script: four quadrants, the figure written, the
    variant changing with the power flow and every step covered."""
    import re

    root = Path(__file__).resolve().parent.parent
    page = (root / "docs" / "simulation.md").read_text(encoding="utf-8")
    readme = (root / "README.md").read_text(encoding="utf-8")
    (tmp_path / "planetary.yaml").write_text(re.findall(r"```yaml\n(.*?)```", readme, re.S)[0], encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    command = re.findall(r"\$ derive (.*)", page)[0].split()
    assert run_main(command).returncode == 0
    script = re.findall(r"```python\n(.*?)```", page, re.S)[0]
    scope: dict[str, object] = {}
    exec(compile(script, "docs/simulation.md", "exec"), scope)  # the page's own code
    rows = scope["rows"]
    assert (tmp_path / "quadrants.png").stat().st_size > 10_000
    assert (rows["status"] == 0).all() and np.isfinite(rows["tau_in"]).all() and (rows["P_loss"] >= -1e-9).all()
    assert set(np.unique(rows["variant"])) == {1, 2}
