"""A machine's closed forms as LaTeX (``derive slider_crank.yaml --latex``): every
numbered efficiency, read back by the independent reader of tests/hand/latex.py, is Laus
eq. (117) (crank input) or its inverse from eq. (122) (slider input) with the friction
mode's sign; the conditions read back are the regions of eq. (114); the document
compiles with pdflatex and fits the page."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import sympy
from hand.latex import document_equations, read_latex, same_rational_function
from harness.helpers import run_main
from test_latex_compiles import compile_log, layout_problems, needs_pdflatex, prose_problems

from conftest import CATALOG, ROOT

SLIDER_CRANK = Path(CATALOG) / "slider_crank.yaml"
BX, BY, CX, MU = sympy.symbols("B_x B_y C_x mu_D", real=True)
A1, A2, THETA = sympy.symbols("a1 a2 theta", real=True)


@pytest.fixture(scope="module")
def document() -> str:
    result = run_main([SLIDER_CRANK, "--latex", "--quiet"])
    assert result.returncode == 0, result.describe()
    return result.stdout


def laus_117(sign: int) -> sympy.Expr:
    """Crank input: -P_out / P_in = 1 + mu_D B_y a / (B_x - C_x), a = sign(V_D) sign(u_D)."""
    return 1 + MU * BY * sign / (BX - CX)


def test_variants_read_back_are_laus_eq_117_and_its_inverse(document):
    equations = document_equations(document)
    assert sorted(equations) == [1, 2, 3, 4]
    symbols = [BX, BY, CX, MU]
    crank = [read_latex(equations[n], symbols) for n in (1, 2)]
    slider = [read_latex(equations[n], symbols) for n in (3, 4)]
    for sign, eta in zip((1, -1), crank, strict=True):
        assert same_rational_function(eta, laus_117(sign))
    for sign, eta in zip((1, -1), slider, strict=True):
        assert same_rational_function(eta, 1 / laus_117(sign))  # eq. (122): input and output swapped


def test_crank_regions_are_the_sign_of_theta(document):
    """Eq. (114): with the crank driving, the mode a_D = +1 holds where sin(theta) > 0."""
    section = document.split(r"\subsection*{Input slider")[0]
    found = re.findall(r"\\begin\{equation\*\}\n(.*) ([<>]) 0\n\\end\{equation\*\}", section)
    assert [(read_latex(text, [THETA]), relation) for text, relation in found] == [
        (sympy.sin(THETA), ">"),
        (sympy.sin(THETA), "<"),
    ]


def test_the_document_names_the_cycle_equations_and_has_no_program_syntax(document):
    assert "Laus eq. (120)" in document and "Laus eq. (123)" in document
    assert not prose_problems(document)


@needs_pdflatex
def test_slider_crank_document_compiles_and_fits(document, tmp_path):
    assert not layout_problems(compile_log(document, tmp_path))


def test_the_out_dir_writes_the_latex_beside_the_text(tmp_path):
    result = run_main([SLIDER_CRANK, "--out", tmp_path, "--quiet"])
    assert result.returncode == 0, result.describe()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slider_crank.tex", "slider_crank.txt"]
    derived = Path(ROOT) / "derivations"
    assert (tmp_path / "slider_crank.tex").read_text() == (derived / "slider_crank.tex").read_text()


def test_a_machine_without_closed_forms_refuses_latex_with_the_reason():
    result = run_main([Path(CATALOG) / "four_bar.yaml", "--latex", "--quiet"])
    assert result.returncode == 2, result.describe()
    assert "no closed form to typeset" in result.stderr and "eq. (133)" in result.stderr
