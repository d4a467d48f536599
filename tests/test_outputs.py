"""Outputs of ``derive``: LaTeX document, JSON variants, generated Python module, ``--eval``,
and every published check in the catalog."""

from __future__ import annotations

import glob
import importlib.util
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest
import sympy
from hand.latex import LatexError, document_equations, read_latex, same_rational_function

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.variant_report import mesh_text

from conftest import CATALOG, ROOT, TRAIN_FILES, S, catalog_path, read_text

TUPLIN_VALUES = ["r1=40", "r2=60", "r3=15", "r4=35", "eta_C=0.99", "eta_D=0.99"]


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "davies_sym.cli", *args], capture_output=True, text=True, check=False)


def test_latex_document_structure_and_formulas_parse_back(tmp_path):
    """`derive catalog/tuplin.yaml --latex -o t.tex`: a standalone document with the
    conditions table, the variants table (with the driving gear of every mesh) and one
    equation per variant whose LaTeX reads back to the derived formula."""
    out = tmp_path / "t.tex"
    result = run(catalog_path("tuplin"), "--latex", "-o", str(out))
    assert result.returncode == 0, result.stderr
    text = out.read_text()
    assert text.startswith(r"\documentclass") and text.rstrip().endswith(r"\end{document}")
    assert text.count(r"\begin{document}") == 1 and "Turning conditions" in text
    assert text.count("{") == text.count("}")
    for env in ("tabularx", "equation", "align*"):
        assert text.count(rf"\begin{{{env}}}") == text.count(rf"\end{{{env}}}")
    vs = derive_variants(davies_sym.load(catalog_path("tuplin")))
    equations = document_equations(text)
    assert sorted(equations) == [v.number for v in vs.variants] == [1, 2, 3, 4]
    symbols = davies_sym.load(catalog_path("tuplin")).symbols.values()
    for v in vs.variants:
        assert sympy.cancel(read_latex(equations[v.number], symbols) - v.efficiency) == 0
    # Each variant's row names the driving gear of every mesh as the text report does.
    rows = [line for line in text.splitlines() if re.match(r"\(\d+\) & ", line)]
    for v, row in zip(vs.variants, rows, strict=True):
        for mesh in mesh_text(vs, v):
            coupling, driver, driven = re.match(r"(\w+): gear (\w+) drives gear (\w+)", mesh).groups()
            assert rf"{coupling}:~{driver}$\to${driven}" in row, (row, mesh)


def test_json_variants():
    """`--json` adds `turning_conditions`, `meshes` and `variants` (input, output,
    conditions with their signs, efficiency as a sympy string, latex)."""
    result = run(catalog_path("tuplin"), "--json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert [c["simplified"] for c in doc["turning_conditions"]] == ["-r1 + r2"]
    assert {m["coupling"]: m["carrier"] for m in doc["meshes"]} == {"C": "5", "D": "5"}
    variants = doc["variants"]
    assert [(v["input"], v["output"], v["conditions"][0]["sign"]) for v in variants] == [
        ("A", "B", 1),
        ("A", "B", -1),
        ("B", "A", 1),
        ("B", "A", -1),
    ]
    symbols = davies_sym.load(catalog_path("tuplin")).symbols
    vs = derive_variants(davies_sym.load(catalog_path("tuplin")))
    for item, v in zip(variants, vs.variants, strict=True):
        parsed = sympy.sympify(item["efficiency"], locals=dict(symbols))
        assert sympy.cancel(parsed - v.efficiency) == 0
        assert same_rational_function(read_latex(item["latex"], symbols.values()), v.efficiency), item["latex"]
        assert item["derivative_check"] == "positive"


def test_latex_read_back_catches_a_wrong_formula():
    """The LaTeX check reads the text: a truncated formula, a swapped sign, another
    symbol or another exponent fails it; the emitted text passes."""
    symbols = davies_sym.load(catalog_path("tuplin")).symbols
    r1, r2, eta_c = symbols["r1"], symbols["r2"], symbols["eta_C"]
    expected = eta_c * (r1 - r2) ** 2 / (r1 + r2)
    text = r"\frac{\eta_{C} \left(r_{1} - r_{2}\right)^{2}}{r_{1} + r_{2}}"
    assert same_rational_function(read_latex(text, symbols.values()), expected)
    for wrong in (
        text.replace("-", "+"),
        text.replace("r_{2}}", "r_{3}}"),
        text.replace("^{2}", "^{3}"),
        text.replace(r"\eta_{C}", r"\eta_{D}"),
    ):
        assert not same_rational_function(read_latex(wrong, symbols.values()), expected), wrong
    for broken in (text[:-1], text[:-12], text.replace(r"\right", ""), text.replace("r_{1}", "r_{9}"), "r1 + r2"):
        with pytest.raises(LatexError):
            read_latex(broken, symbols.values())


def test_eval_prints_the_efficiency_last():
    """Laus 0.9462 (A input) and 0.9443 (B input, eq. (78)) as the last output line."""
    a = run(catalog_path("tuplin"), "--eval", *TUPLIN_VALUES)
    assert a.returncode == 0, a.stderr
    assert round(float(a.stdout.strip().splitlines()[-1]), 4) == 0.9462
    b = run(catalog_path("tuplin"), "--eval", *TUPLIN_VALUES, "--input", "B")
    assert round(float(b.stdout.strip().splitlines()[-1]), 4) == 0.9443
    same = run(catalog_path("tuplin"), "--eval", *TUPLIN_VALUES, "--output", "A")
    assert same.stdout.strip().splitlines()[-1] == b.stdout.strip().splitlines()[-1]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--eval", "r9=1"], "unknown symbol 'r9'"),
        (["--eval", "r1=40"], "missing values for"),
        (["--eval", "r1=abc"], "'abc' is not a number"),
        ([*["--eval", *TUPLIN_VALUES], "--input", "Z"], "'Z' is not a port"),
    ],
)
def test_eval_errors_are_clear(args, message):
    result = run(catalog_path("tuplin"), *args)
    assert result.returncode == 2 and message in result.stderr
    assert "Traceback" not in result.stderr


def test_eval_refuses_values_that_break_the_geometry():
    """r4 = 30 with r1, r2, r3 = 40, 60, 15 breaks r1 - r3 = r2 - r4 (r4 = 35): refused, exit 2,
    with the relation, both values and the difference; no number is printed."""
    values = [v if not v.startswith("r4") else "r4=30" for v in TUPLIN_VALUES]
    result = run(catalog_path("tuplin"), "--eval", *values)
    assert result.returncode == 2 and result.stdout == ""
    assert "geometric constraint r1 - r3 = r2 - r4" in result.stderr and "gives 35" in result.stderr
    assert "difference is -5" in result.stderr
    # r4 follows from the constraint: leaving it out breaks nothing.
    without_r4 = run(catalog_path("tuplin"), "--eval", *(v for v in TUPLIN_VALUES if not v.startswith("r4")))
    assert without_r4.returncode == 0 and "geometric constraint" not in without_r4.stderr


def test_python_module_picks_the_variant_element_by_element(tmp_path):
    """The generated module: one function per variant, conditions, and `efficiency` on
    arrays that straddle the turning condition r1 = r2, checked against the exact result."""
    out = tmp_path / "tuplin_eff.py"
    assert run(catalog_path("tuplin"), "--python", str(out)).returncode == 0
    spec = importlib.util.spec_from_file_location("tuplin_eff", out)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    vs = derive_variants(davies_sym.load(catalog_path("tuplin")))
    assert all(hasattr(module, v.name) for v in vs.variants)
    r1 = np.array([30.0, 40.0, 70.0, 80.0])
    r2 = np.array([60.0, 60.0, 60.0, 60.0])
    r3 = np.array([15.0, 15.0, 20.0, 25.0])
    for port in ("A", "B"):
        got = module.efficiency(input=port, r1=r1, r2=r2, r3=r3, eta_C=0.99, eta_D=0.98)
        for i in range(len(r1)):
            values = {
                S("r1"): sympy.Rational(r1[i]),
                S("r2"): sympy.Rational(r2[i]),
                S("r3"): sympy.Rational(r3[i]),
                S("eta_C", "efficiency"): sympy.Rational(99, 100),
                S("eta_D", "efficiency"): sympy.Rational(98, 100),
            }
            assert got[i] == pytest.approx(float(vs.evaluate(values, port)), rel=1e-12)
    with pytest.raises(ValueError, match="input must be one of"):
        module.efficiency(input="Z", r1=1.0, r2=2.0, r3=0.5, eta_C=0.9, eta_D=0.9)


@pytest.mark.slow
def test_generated_module_is_deterministic(tmp_path):
    a, b = tmp_path / "a.py", tmp_path / "b.py"
    run(catalog_path("tuplin"), "--python", str(a))
    run(catalog_path("tuplin"), "--python", str(b))
    assert a.read_bytes() == b.read_bytes()


def _expected_checks():
    for path in TRAIN_FILES:
        train = davies_sym.load(path)
        for i, check in enumerate(train.expected):
            yield pytest.param(path, check, id=f"{train.path.rsplit('/', 1)[-1]}[{i}]")


@pytest.mark.parametrize(("path", "check"), list(_expected_checks()))
def test_catalog_published_numbers(path, check):
    """Every `expected` entry of every catalog file, through `derive --eval`."""
    args = [path, "--eval", *(f"{k}={v}" for k, v in check.values.items())]
    if check.input:
        args += ["--input", check.input]
    if check.state:
        args += ["--state", check.state]
    result = run(*args)
    assert result.returncode == 0, result.stderr
    value = float(result.stdout.strip().splitlines()[-1])
    if check.differs:
        # A published number the file's geometry explains it does not reproduce: it must stay different.
        assert abs(value - check.value) > check.tolerance, (check.source, value)
    else:
        assert abs(value - check.value) <= check.tolerance, (check.source, value)


def test_catalog_files_have_sources():
    for path in sorted(glob.glob(f"{CATALOG}/*.yaml")):
        assert "source:" in read_text(path), path


DERIVATIONS = os.path.join(ROOT, "derivations")


@pytest.mark.slow
def test_derivations_are_current(tmp_path):
    """`derive catalog/*.yaml --out derivations/` gives exactly the committed files
    (regenerate with that command when this fails)."""
    files = sorted(glob.glob(f"{CATALOG}/*.yaml"))
    result = run(*files, "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    fresh = sorted(p.name for p in tmp_path.iterdir())
    committed = sorted(n for n in os.listdir(DERIVATIONS) if n.endswith((".py", ".tex", ".txt")))
    assert fresh == committed
    for name in fresh:
        with open(os.path.join(DERIVATIONS, name), "rb") as handle:
            assert handle.read() == (tmp_path / name).read_bytes(), f"derivations/{name} is stale"


def test_code_and_generated_code_pass_the_lint():
    """ruff (configuration in pyproject.toml) on the package, tests, benchmarks and the
    generated modules."""
    result = subprocess.run(
        [sys.executable, "-m", "ruff", "check", "davies_sym", "tests", "benchmarks", "derivations"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_progress_on_stderr_and_quiet_silences_it(tmp_path):
    """Which step and which variant, on standard error; nothing with --quiet."""
    loud = run(catalog_path("tuplin"), "--python", str(tmp_path / "a.py"))
    assert loud.returncode == 0
    assert "derive: variant 1 of 4: input A" in loud.stderr and "derive: solving the lossless actions" in loud.stderr
    quiet = run(catalog_path("tuplin"), "--python", str(tmp_path / "b.py"), "--quiet")
    assert quiet.returncode == 0 and quiet.stderr == ""


@pytest.mark.slow
def test_plot_writes_a_png_and_names_bad_arguments(tmp_path):
    """--plot with the file's published design as the fixed values; --vs for the region map."""
    one, two = tmp_path / "one.png", tmp_path / "two.png"
    assert run(catalog_path("litvin_face_drive"), "--plot", "N4=60:99", "-o", str(one), "--quiet").returncode == 0
    assert (
        run(
            catalog_path("tuplin"),
            "--plot",
            "r1=20:100",
            "--vs",
            "r2=20:100",
            "--at",
            "r3=15",
            "-o",
            str(two),
            "--quiet",
        ).returncode
        == 0
    )
    for path in (one, two):
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for args, message in (
        (["--plot", "N9=1:2"], "unknown symbol 'N9'"),
        (["--plot", "N4=9:2"], "is empty"),
        (["--plot", "N4=60"], "expected NAME=START:STOP"),
        (["--plot", "N4=60:99", "--at", "N1=x"], "not a number"),
    ):
        result = run(catalog_path("litvin_face_drive"), *args, "-o", str(tmp_path / "x.png"), "--quiet")
        assert result.returncode == 2 and message in result.stderr and "Traceback" not in result.stderr
    missing = run(catalog_path("litvin_face_drive"), "--plot", "N4=60:99", "--quiet")
    assert missing.returncode == 2 and "-o FILE.png" in missing.stderr
