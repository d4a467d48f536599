"""The example notebook (examples/tuplin.ipynb), run cell by cell as a notebook runs it:
each cell's last expression is what the notebook displays, through the objects'
``_repr_html_`` / ``_repr_latex_``.  The displayed values are checked against Laus 2011
(section 3.4.1.6: 0.9462 with A as input, 0.9443 with B as input) and the displayed
formulas are read back from their LaTeX."""

from __future__ import annotations

import ast
import json
import os
import re

import pytest
from hand.latex import equal_at_random_points, read_latex

from conftest import ROOT

NOTEBOOK = os.path.join(ROOT, "examples", "tuplin.ipynb")


def _run(path: str) -> list[object]:
    """Every code cell executed in one namespace; each cell's displayed value (the value
    of a last expression statement, else None)."""
    with open(path, encoding="utf-8") as handle:
        notebook = json.load(handle)
    assert notebook["nbformat"] == 4
    namespace: dict[str, object] = {}
    shown: list[object] = []
    for cell in notebook["cells"]:
        if cell["cell_type"] != "code":
            continue
        tree = ast.parse("".join(cell["source"]))
        last = tree.body[-1] if tree.body and isinstance(tree.body[-1], ast.Expr) else None
        body = tree.body[:-1] if last is not None else tree.body
        exec(compile(ast.Module(body, []), path, "exec"), namespace)
        shown.append(eval(compile(ast.Expression(last.value), path, "eval"), namespace) if last else None)
    return shown


@pytest.fixture(scope="module")
def shown() -> list[object]:
    return _run(NOTEBOOK)


def _formulas(latex: str) -> list[str]:
    """The right sides of ``\\eta... = formula \\qquad (...)`` in a LaTeX display."""
    return [m.group(1) for m in re.finditer(r"\\eta_\{\(\d+\)\} = (.*?) \\qquad", latex)]


def test_train_shows_its_links_and_couplings(shown):
    html = shown[0]._repr_html_()
    assert "Tuplin" in html and "<th>coupling</th>" in html
    for coupling in ("A", "B", "C", "D", "E"):
        assert f"<td>{coupling}</td>" in html


def test_analysis_shows_mobility_ratio_and_efficiency(shown):
    analysis = shown[1]
    latex = analysis._repr_latex_()
    assert latex.startswith("$$F_N = 1,")
    ratio = latex.split(r"\frac{\omega_{\mathrm{A}}}{\omega_{\mathrm{B}}} = ", 1)[1].split(r",\qquad", 1)[0]
    r = {n: analysis.train.symbols[n] for n in ("r1", "r2", "r3")}
    # Laus eq. (57): the speed ratio of Tuplin's train, input A over output B.
    laus = r["r2"] * r["r3"] / ((r["r1"] - r["r2"]) * (r["r1"] - r["r3"]))
    assert equal_at_random_points(read_latex(ratio, analysis.train.symbols.values()), laus)


def test_variants_show_every_formula(shown):
    variants = shown[2]
    latex = variants._repr_latex_()
    formulas = _formulas(latex)
    assert len(formulas) == len(variants.variants) == 4  # two signs of c1, two inputs (Laus Table 5)
    for text, variant in zip(formulas, variants.variants, strict=True):
        assert equal_at_random_points(read_latex(text, variants.train.symbols.values()), variant.efficiency)
    html = variants._repr_html_()
    assert html.count("<tr>") == len(variants.variants) + 1


def test_design_evaluates_to_laus_numbers(shown):
    """Laus 2011 sec. 3.4.1.6: 0.9462 (A input, eq. (76)) and 0.9443 (B input)."""
    variant, (from_a, from_b) = shown[3], shown[4]
    assert variant.input == "A" and variant._repr_latex_().startswith(r"$$\eta_{(")
    assert abs(from_a - 0.9462) < 5e-5 and abs(from_b - 0.9443) < 5e-5


def test_notebook_cells_have_no_stored_outputs():
    """The notebook is kept without outputs, so what it shows is what the tests run."""
    with open(NOTEBOOK, encoding="utf-8") as handle:
        notebook = json.load(handle)
    assert all(not c.get("outputs") for c in notebook["cells"] if c["cell_type"] == "code")
