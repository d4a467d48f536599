"""The outputs of a train driven on two shafts (the Andantex SR20 of Mantriota and
Pennestri 2003): the generated formula module, the LaTeX document and the region figures,
checked against the independent torque balance of tests/oracle/lossy_balance.py (exact
fractions), not against the derivation that wrote them."""

from __future__ import annotations

import importlib.util
import random
import warnings
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest
import sympy
from hand.latex import document_equations, force_conditions, read_latex
from harness.helpers import run_main
from oracle.lossy_balance import NoConsistentSolution, sr20, sr20_at_row

import davies_sym
from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.emit.several_inputs_latex import several_inputs_latex
from davies_sym.emit.several_inputs_module import several_inputs_module

from conftest import catalog_path

#: Catalog radii (module x teeth / 2) over the oracle's radii in metres.
CATALOG_PER_METRE = 27625

#: The SR20 with every kind of loss: mesh efficiencies per mesh, planet-bearing Coulomb
#: friction and drag, viscous friction and drag on the input shaft d1.
LOSSY = (
    Path(catalog_path("sr20_differential"))
    .read_text(encoding="utf-8")
    .replace("friction: {drag: D_P}", "friction: {coulomb: rho_P, drag: D_P}")
    .replace(
        "  A: {type: revolute, links: [0, d1], at: 0}",
        "  A: {type: revolute, links: [0, d1], at: 0, friction: {drag: D_A, viscous: b_A}}",
    )
    .replace("efficiency: eta_M}\n  M2", "efficiency: eta_1}\n  M2")
    .replace('["4", "3"], efficiency: eta_M}', '["4", "3"], efficiency: eta_2}')
    .replace("  fit: [eta_M, D_P]\n  start: {eta_M: 0.95, D_P: 0.1}", "  fit: [eta_1, D_P]")
)


@pytest.fixture(scope="module")
def lossy():
    return derive_several_inputs(davies_sym.loads(LOSSY, "sr20_lossy.yaml"))


@pytest.fixture(scope="module")
def module(lossy, tmp_path_factory):
    path = tmp_path_factory.mktemp("module") / "sr20_lossy.py"
    path.write_text(several_inputs_module(lossy), encoding="utf-8")
    spec = importlib.util.spec_from_file_location("sr20_lossy", path)
    loaded = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(loaded)
    return loaded


def _cases(seed: int, count: int) -> list[dict[str, F]]:
    """Random operating points in every direction of the input speeds, with random losses,
    and the oracle's torques and efficiency (points where it finds no consistent solution,
    losses larger than the load, are left out)."""
    rng = random.Random(seed)
    out = []
    while len(out) < count:
        w_a, w_k = F(rng.randint(-600, 600)), F(rng.randint(-600, 600))
        if 0 in (w_a, w_k, w_a + w_k, w_a - w_k):
            continue
        # Half the points at light load against large drags, where the drag reverses a tooth
        # force and the mesh's driving gear swaps.
        light = len(out) % 2 == 1
        case = {
            "omega_A": w_a,
            "omega_K": w_k,
            "tau_out": F(rng.randint(1, 100), 100) if light else F(rng.randint(20, 80)),
            "eta_1": F(rng.randint(90, 99), 100),
            "eta_2": F(rng.randint(90, 99), 100),
            "rho_P": F(rng.randint(0, 30), 1000),
            "D_P": F(rng.randint(0, 500 if light else 20), 100),
            "D_A": F(rng.randint(0, 20), 100),
            "b_A": F(rng.randint(0, 5), 10000),
        }
        train = sr20(
            eta_1=case["eta_1"],
            eta_2=case["eta_2"],
            drag={"p": case["D_P"], "d1": case["D_A"]},
            viscous={"d1": case["b_A"]},
            rho={"p": case["rho_P"] / CATALOG_PER_METRE},
        )
        load = -case["tau_out"] if w_a + w_k > 0 else case["tau_out"]
        try:
            truth = sr20_at_row({"w_A": w_a, "w_K": w_k, "T_O": load}, train=train)
        except NoConsistentSolution:
            continue
        out.append({**case, "T_A": truth.T_A, "T_K": truth.T_K, "eta": truth.eta})
    return out


def test_module_equals_the_oracle_element_by_element(module) -> None:
    """One call on arrays of 80 points in every direction, half at light load against large
    drags: each point's efficiency and port torques equal the oracle's (to float rounding),
    the region picked per element, the regions where the drag reverses a tooth force
    included."""
    cases = _cases(3, 80)
    names = [p["name"] for p in module.PARAMETERS]
    arrays = {n: np.array([float(c[n]) for c in cases]) for n in names}
    eta = module.efficiency(errors="raise", **arrays)
    torques = module.torques(errors="raise", **arrays)
    np.testing.assert_allclose(eta, [float(c["eta"]) for c in cases], rtol=1e-10)
    np.testing.assert_allclose(torques["A"], [float(c["T_A"]) for c in cases], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(torques["K"], [float(c["T_K"]) for c in cases], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(
        torques["O"], [float(-c["tau_out"] if c["omega_A"] + c["omega_K"] > 0 else c["tau_out"]) for c in cases]
    )
    numbers = module.region(**arrays)
    reversing = {r["number"] for r in module.REGIONS if r["reversed"]}
    assert len({r["code"] for r in module.REGIONS if r["number"] in set(numbers)}) == 8
    assert reversing & set(numbers), "no point where the drag reverses a tooth force"


def test_module_speeds_mantriota_pennestri_section_6(module) -> None:
    """w_o = (w_d1 + w_d2)/2: Table I's first row, 180 = (309 + 51)/2."""
    speeds = module.speeds(omega_A=np.array([309.0, -120.0]), omega_K=np.array([51.0, 40.0]))
    np.testing.assert_array_equal(speeds["O"], [180.0, -40.0])
    np.testing.assert_array_equal(speeds["A"], [309.0, -120.0])


def test_module_refuses_where_the_formulas_do_not_hold(module) -> None:
    """NaN with a warning on a speed-condition line (w_A = w_K: the planet does not turn
    relative to the carrier, which way its drag acts is undecided) and outside the
    parameters' ranges; errors='raise' raises, errors='ignore' is silent."""
    base = {"eta_1": 0.95, "eta_2": 0.95, "rho_P": 0.0, "D_P": 0.1, "D_A": 0.0, "b_A": 0.0}
    with pytest.warns(module.DesignWarning, match="1 on a speed-condition line"):
        eta = module.efficiency(omega_A=[100.0, 100.0], omega_K=[100.0, 50.0], tau_out=10.0, **base)
    assert np.isnan(eta[0]) and 0 < eta[1] < 1
    with pytest.raises(module.DesignError, match="1 point\\(s\\) outside the parameters' ranges"):
        module.efficiency(errors="raise", omega_A=300.0, omega_K=100.0, tau_out=10.0, **{**base, "eta_1": 1.5})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(module.efficiency(errors="ignore", omega_A=100.0, omega_K=100.0, tau_out=1.0, **base))


def test_a_large_array_is_evaluated_in_blocks_with_the_same_values(module) -> None:
    """More points than one block (`_BLOCK`), over every region, on condition lines and
    outside the ranges: efficiency and torques equal, bit for bit, the same points
    evaluated a row at a time, and the one warning counts every bad point of the whole
    array; the module imports nothing of the package (the block code is copied in)."""
    rng = np.random.default_rng(2)
    rows = module._BLOCK // 50 + 3
    speeds = rng.choice([-100.0, -40.0, 0.0, 40.0, 100.0], size=(2, rows, 50))
    values = {"omega_A": speeds[0], "omega_K": speeds[1], "tau_out": 10.0, "eta_2": 0.95, "rho_P": 0.0}
    values |= {"D_P": rng.uniform(0.0, 0.2, 50), "D_A": 0.0, "b_A": 0.0, "eta_1": rng.uniform(0.9, 1.05, (rows, 1))}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", module.DesignWarning)
        eta = module.efficiency(**values)
        torques = module.torques(**values)
    assert eta.shape == (rows, 50) and len(caught) == 2
    bad = int(np.count_nonzero(np.isnan(eta)))
    counts = [int(w) for w in str(caught[0].message).replace(",", " ").replace("(", " ").split() if w.isdigit()]
    assert 0 < bad < eta.size and sum(counts) == bad
    for k in range(0, rows, 211):
        row = {n: (np.broadcast_to(v, eta.shape)[k] if np.ndim(v) else v) for n, v in values.items()}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", module.DesignWarning)
            assert np.array_equal(module.efficiency(**row), eta[k], equal_nan=True)
            alone = module.torques(**row)
        for port, part in torques.items():
            assert np.array_equal(alone[port], part[k], equal_nan=True)
    source = Path(module.__file__).read_text(encoding="utf-8")
    assert "davies_sym" not in "".join(line for line in source.splitlines() if line.startswith(("import", "from")))


@pytest.mark.slow
def test_module_is_deterministic_and_lists_its_regions(lossy, module) -> None:
    assert several_inputs_module(lossy) == several_inputs_module(
        derive_several_inputs(davies_sym.loads(LOSSY, "sr20_lossy.yaml"))
    )
    assert module.INPUTS == ("A", "K") and module.OUTPUT == "O"
    assert [r["number"] for r in module.REGIONS] == list(range(1, len(lossy.regions) + 1))
    assert len({r["code"] for r in module.REGIONS}) == 8
    assert {p["name"] for p in module.PARAMETERS} == {
        "omega_A",
        "omega_K",
        "tau_out",
        "eta_1",
        "eta_2",
        "rho_P",
        "D_P",
        "D_A",
        "b_A",
    }


@pytest.mark.slow
def test_latex_document_formulas_equal_the_oracle(lossy) -> None:
    """Each region's eta* equation, parsed back from the LaTeX, equals the oracle's
    efficiency at a point of that region, and the conditions on its loaded forces, read
    back, hold there; the document is standalone and balanced."""
    text = several_inputs_latex(lossy)
    assert text.startswith(r"\documentclass") and text.rstrip().endswith(r"\end{document}")
    assert text.count("{") == text.count("}")
    for env in ("tabularx", "equation", "align*"):
        assert text.count(rf"\begin{{{env}}}") == text.count(rf"\end{{{env}}}")
    assert r"\omega_{O} &= \frac{\omega_{A}}{2} + \frac{\omega_{K}}{2}" in text
    equations = document_equations(text, "\\eta^*")
    assert sorted(equations) == list(range(1, len(lossy.regions) + 1))
    symbols = [*lossy.train.symbols.values(), *lossy.speeds, sympy.Symbol("tau_out", positive=True)]
    seen = set()
    for case in _cases(5, 120):
        point = {s: sympy.Rational(case[str(s)].numerator, case[str(s)].denominator) for s in symbols if str(s) in case}
        number = lossy.region_at(point).number
        if number in seen:
            continue
        seen.add(number)
        value = read_latex(equations[number], symbols).subs(point)
        assert value == sympy.Rational(case["eta"].numerator, case["eta"].denominator)
        # The region's own conditions on its loaded forces, read back, hold at the point.
        section = text.split(rf"\paragraph{{Region ({number})}}")[1].split(r"\paragraph")[0]
        held = force_conditions(section)
        assert len(held) == len(lossy.regions[number - 1].loaded_forces)
        for body, relation in held:
            force = read_latex(body, symbols).subs(point)
            assert force > 0 if relation == ">" else force < 0
    assert len({lossy.regions[n - 1].reversed for n in seen}) > 1 and len(seen) >= 12


def test_cli_latex_python_plot_and_out_dir(tmp_path: Path) -> None:
    """derive on the catalog SR20: --latex, --python, the region map over both input
    speeds and the efficiency against one; --out DIR writes its .tex and .py."""
    train = catalog_path("sr20_differential")
    latex = run_main([train, "--latex", "--quiet"])
    assert latex.returncode == 0 and latex.stdout.count(r"\tag{") == 12
    module_path = tmp_path / "sr20.py"
    assert run_main([train, "--python", str(module_path), "--quiet"]).returncode == 0
    assert "def efficiency(" in module_path.read_text() and "def region_12(" in module_path.read_text()
    fixed = ["--at", "tau_out=5", "eta_M=0.957", "D_P=0.639", "-o"]
    two, one = tmp_path / "regions.png", tmp_path / "line.png"
    result = run_main([train, "--plot", "omega_A=-40:40", "--vs", "omega_K=-40:40", *fixed, str(two), "--quiet"])
    assert result.returncode == 0, result.stderr
    result = run_main([train, "--plot", "omega_K=-40:40", *fixed[:-1], "omega_A=30", "-o", str(one), "--quiet"])
    assert result.returncode == 0, result.stderr
    for path in (one, two):
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    out = tmp_path / "derivations"
    assert run_main([train, catalog_path("simple_pair"), "--out", str(out), "--quiet"]).returncode == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "simple_pair.py",
        "simple_pair.tex",
        "sr20_differential.py",
        "sr20_differential.tex",
    ]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--plot", "omega_A=-40:40", "--at", "tau_out=5", "eta_M=0.9", "-o", "x.png"], "missing values for D_P"),
        (
            ["--plot", "omega_A=-40:40", "--at", "tau_out=5", "eta_M=0.9", "D_P=0", "omega_K=1", "mu=2", "-o", "x.png"],
            "unknown symbol mu",
        ),
        (["--plot", "w_A=-40:40", "-o", "x.png"], "unknown symbol 'w_A'"),
        (["--plot", "omega_A=-40:40", "--at", "tau_out=5"], "-o FILE.png"),
        (["--eval", "omega_A=1", "--input", "A"], "has no single input"),
        (["--state", "low"], "one degree of freedom only"),
        (["--at", "tau_out=5"], "only with --plot"),
    ],
)
def test_cli_refuses_bad_options_with_a_located_message(tmp_path: Path, args: list[str], message: str) -> None:
    args = [str(tmp_path / a) if a.endswith(".png") else a for a in args]
    result = run_main([catalog_path("sr20_differential"), *args, "--quiet"])
    assert result.returncode == 2 and message in result.stderr, result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "x.png").exists()
