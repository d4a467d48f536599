"""Closed-form sensitivities: every catalog module's ``sensitivity(wrt=NAME)`` agrees with
central finite differences of its own ``efficiency`` wherever the variant does not change
within the step, for every parameter; ``derive --sensitivity`` prints the derivative of
each variant, checked on Tuplin's train against the derivative of Laus eq. (76) taken by
hand."""

from __future__ import annotations

import glob
import importlib.util
import os
import random
import warnings
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
import sympy
from harness.helpers import assert_refused, run_main

import davies_sym

from conftest import ROOT, catalog_path

DERIVATIONS = os.path.join(ROOT, "derivations")
#: The modules of trains driven at one port whose efficiency has parameters.
ONE_INPUT = sorted(
    p
    for p in glob.glob(os.path.join(DERIVATIONS, "*.py"))
    if "def sensitivity(" in (text := Path(p).read_text(encoding="utf-8"))
    and "SENSITIVE: Final[tuple[str, ...]] = ()" not in text
)


def _module(path: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"sens_{os.path.basename(path)[:-3]}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _inside(module: ModuleType, count: int, seed: int) -> dict[str, np.ndarray]:
    """Designs drawn inside every parameter's range (efficiencies from 0.8, friction
    coefficients from 0.01 to 0.1, as in a working drive)."""
    rng = random.Random(seed)
    out = {}
    for p in module.PARAMETERS:
        low, high = p["low"], min(p["high"], p["low"] + 100.0)
        if p["name"].startswith("mu"):
            low, high = 0.01, 0.1
        low = 0.8 if p["name"].startswith("eta") else low + 0.05 * (high - low)
        out[p["name"]] = np.array([rng.uniform(low, high * 0.98) for _ in range(count)])
    return out


def test_every_module_with_parameters_has_a_sensitivity() -> None:
    assert {os.path.basename(p) for p in ONE_INPUT} >= {"tuplin.py", "humpage.py", "worm_drive.py", "rack_pinion.py"}


@pytest.mark.parametrize("path", ONE_INPUT, ids=[os.path.basename(p)[:-3] for p in ONE_INPUT])
def test_sensitivity_is_the_central_difference_of_the_efficiency(path: str) -> None:
    module = _module(path)
    points = _inside(module, 60, seed=len(path))
    checked = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for port in module.PORTS:
            eta = module.efficiency(input=port, **points)
            number = module.variant(input=port, **points)
            for name in module.SENSITIVE:
                step = 1e-6 * (1 + np.abs(points[name]))
                up = {**points, name: points[name] + step}
                down = {**points, name: points[name] - step}
                same = (module.variant(input=port, **up) == number) & (module.variant(input=port, **down) == number)
                difference = (module.efficiency(input=port, **up) - module.efficiency(input=port, **down)) / (2 * step)
                exact = module.sensitivity(wrt=name, input=port, **points)
                usable = same & np.isfinite(eta) & np.isfinite(difference)
                assert np.array_equal(np.isnan(exact), np.isnan(eta)), name
                assert np.allclose(exact[usable], difference[usable], rtol=1e-5, atol=1e-8), (port, name)
                checked += int(usable.sum())
    assert checked > 0


def test_sensitivity_refuses_a_name_it_does_not_take() -> None:
    module = _module(os.path.join(DERIVATIONS, "simple_pair.py"))
    with pytest.raises(ValueError, match="wrt must be one of"):
        module.sensitivity(wrt="zeta_C", eta_C=0.98)


def test_command_line_derivative_of_tuplin_is_laus_eq_76_by_hand() -> None:
    """Laus eq. (76): eta = eta_C eta_D (r1 - r2)(r1 - r3) / (eta_C eta_D r2 r3 + r1^2 - r1 r2
    - r1 r3); with N = eta_D (r1 - r2)(r1 - r3), a = eta_D r2 r3, b = r1^2 - r1 r2 - r1 r3,
    eta = eta_C N / (eta_C a + b) and d eta / d eta_C = N b / (eta_C a + b)^2."""
    result = run_main([catalog_path("tuplin"), "--sensitivity", "eta_C", "--quiet"])
    assert result.returncode == 0, result.describe()
    line = next(x for x in result.stdout.splitlines() if x.strip().startswith("(1)"))
    printed = sympy.sympify(line.split(" = ", 1)[1])
    eta_c, eta_d, r1, r2, r3 = sympy.symbols("eta_C eta_D r1 r2 r3")
    n, a, b = eta_d * (r1 - r2) * (r1 - r3), eta_d * r2 * r3, r1**2 - r1 * r2 - r1 * r3
    by_hand = n * b / (eta_c * a + b) ** 2
    rng = random.Random(2)
    for _ in range(4):
        point = {s: sympy.Rational(rng.randint(1, 90), rng.randint(1, 9)) for s in (eta_c, eta_d, r1, r2, r3)}
        assert printed.subs(point) == by_hand.subs(point)


def test_command_line_sensitivity_refusals_and_latex(tmp_path: Path) -> None:
    assert_refused(run_main([catalog_path("tuplin"), "--sensitivity", "zeta_C", "--quiet"]), None, ("--sensitivity",))
    latex = run_main([catalog_path("tuplin"), "--sensitivity", "r1", "--latex", "--quiet"])
    assert latex.returncode == 0 and r"\partial \eta_{(1)}" in latex.stdout and r"\end{document}" in latex.stdout


@pytest.mark.parametrize("name", ["tuplin", "worm_drive", "rack_pinion", "wolfrom"])
def test_c_sensitivity_is_the_python_modules(name: str, tmp_path: Path) -> None:
    """`derive --emit c` writes sensitivity_<name>(..., input_port) for every parameter: compiled
    (-Wall -Wextra -Werror), it gives the Python module's sensitivity, NaN where it does."""
    import ctypes
    import shutil
    import subprocess

    from davies_sym.efficiency.variants import derive_variants
    from davies_sym.emit.derived_result import OneInputResult
    from davies_sym.emit.languages import emit_code
    from davies_sym.emit.languages.registry import program_of

    compiler = shutil.which("cc")
    if compiler is None:
        pytest.skip("no C compiler")
    train = davies_sym_load(name)
    variants = derive_variants(train)
    derived = OneInputResult(train, (("", variants),))
    program = program_of(derived, "c")
    source = tmp_path / f"{name}.c"
    source.write_text(emit_code(derived, "c"), encoding="utf-8")
    library_path = tmp_path / "lib.so"
    flags = ["-O1", "-std=c99", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC"]
    subprocess.run([compiler, *flags, str(source), "-o", str(library_path), "-lm"], check=True, capture_output=True)
    library = ctypes.CDLL(str(library_path))
    module = _module(os.path.join(DERIVATIONS, f"{name}.py"))
    points = _inside(module, 40, seed=5)
    names = program.parameters
    compared = 0
    for parameter in module.SENSITIVE:
        function = getattr(library, f"sensitivity_{parameter}")
        function.argtypes = [ctypes.c_double] * len(names) + [ctypes.c_int]
        function.restype = ctypes.c_double
        for k, port in enumerate(module.PORTS):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                want = module.sensitivity(wrt=parameter, input=port, **points)
            got = np.array([function(*(float(points[n][i]) for n in names), k) for i in range(len(want))])
            assert np.allclose(got, want, rtol=1e-10, atol=1e-13, equal_nan=True), (parameter, port)
            compared += int(np.isfinite(want).sum())
    assert compared > 0


def davies_sym_load(name: str) -> object:
    import davies_sym

    return davies_sym.load(catalog_path(name))


SIMPSON_TEETH = """\
name: Simpson set in teeth
links: [0, s, rf, pf, o, pr, cr]
reference: 0
independent: [zs, zrf, zrr]
gears:
  S: {link: s, teeth: zs, module: 2}
  Pf: {link: pf, teeth: zpf, module: 2}
  Rf: {link: rf, teeth: zrf, module: 2, internal: true}
  Pr: {link: pr, teeth: zpr, module: 2}
  Rr: {link: o, teeth: zrr, module: 2, internal: true}
couplings:
  A: {type: revolute, links: [0, rf]}
  B: {type: revolute, links: [0, o]}
  G: {type: revolute, links: [0, s]}
  K: {type: revolute, links: [0, cr]}
  fs: {type: mesh, gears: [S, Pf]}
  fr: {type: mesh, gears: [Rf, Pf]}
  rs: {type: mesh, gears: [S, Pr]}
  rr: {type: mesh, gears: [Rr, Pr]}
  H: {type: revolute, links: [pf, o]}
  J: {type: revolute, links: [pr, cr]}
ports: {input: A, output: B}
states:
  low: {input: A, output: B, brake: [cr]}
  second: {input: A, output: B, brake: [s]}
"""


def test_a_parameter_of_some_states_is_derived_in_those(tmp_path: Path) -> None:
    """In second gear the rear set turns as one block with no load, so its meshes' efficiencies
    are no parameter there: --sensitivity eta_rr answers for the state that takes it, and a
    name no state takes is refused with what each state takes.  Low gear by hand (Simpson,
    rear carrier held, input front ring): eta = (E zrr + eta_fr eta_fs zs + zrf) / (zrf + zrr + zs)
    with E = eta_fr eta_fs eta_rr eta_rs, so d eta / d eta_rr = eta_fr eta_fs eta_rs zrr / (zrf + zrr + zs)."""
    path = tmp_path / "simpson.yaml"
    path.write_text(SIMPSON_TEETH)
    result = run_main([path, "--sensitivity", "eta_rr", "--quiet"])
    assert result.returncode == 0, result.describe()
    assert "Simpson set in teeth, low: partial derivatives" in result.stdout and ", second:" not in result.stdout
    (first,) = [line for line in result.stdout.splitlines() if line.strip().startswith("(1)")]
    form = sympy.sympify(first.split("=", 1)[1])
    e = {n: sympy.Symbol(n) for n in ("eta_fr", "eta_fs", "eta_rs", "zrf", "zrr", "zs")}
    assert sympy.expand(form * (e["zrf"] + e["zrr"] + e["zs"])) == e["eta_fr"] * e["eta_fs"] * e["eta_rs"] * e["zrr"]
    refused = run_main([path, "--sensitivity", "eta_xx", "--quiet"])
    assert refused.returncode == 2
    assert "'eta_xx' is not a parameter of the formulas in any state (state low: eta_fr," in refused.stderr
    assert "; state second: eta_fr, eta_fs, zrf, zs)" in refused.stderr, refused.describe()


def test_a_printed_derivative_keeps_no_terms_that_cancel(tmp_path: Path) -> None:
    """Each factor of a printed derivative's numerator has as many terms written as it has
    once expanded (sympy's own derivative of a quotient left ``a + b*(-c - d) + ...`` with
    terms that cancel), and the form is the derivative of the variant's formula."""
    path = tmp_path / "simpson.yaml"
    path.write_text(SIMPSON_TEETH)
    result = run_main([path, "--sensitivity", "eta_rr", "--quiet"])
    variants = davies_sym.derive(davies_sym.load(str(path)), state="low")
    point = {"eta_fr": sympy.Rational(97, 100), "eta_fs": sympy.Rational(96, 100), "eta_rr": sympy.Rational(95, 100)}
    point |= {"eta_rs": sympy.Rational(94, 100), "zrf": 70, "zrr": 74, "zs": 30}
    lines = result.stdout.splitlines()[1:]
    assert len(lines) == len(variants.variants) == 2
    for line, variant in zip(lines, variants.variants, strict=True):
        form = sympy.sympify(line.split("=", 1)[1])
        by_name = {str(s): s for s in variant.efficiency.free_symbols}
        want = sympy.diff(variant.efficiency, by_name["eta_rr"]).subs({by_name[k]: v for k, v in point.items()})
        assert form.subs({sympy.Symbol(k): v for k, v in point.items()}) == want, line
        numerator, _ = sympy.fraction(form)
        for factor in sympy.Mul.make_args(numerator):
            base = factor.base if factor.is_Pow else factor
            assert len(sympy.Add.make_args(base)) == len(sympy.Add.make_args(sympy.expand(base))), (line, factor)
