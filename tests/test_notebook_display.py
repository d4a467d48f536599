"""What a notebook shows of a train, an analysis, a turning condition and a variant: each
has LaTeX and HTML, and the formulas they show read back to the exact expressions
(Laus 2011 section 3.4.1.6, Tuplin's train: the turning condition r2 - r1 of Table 6);
MathML writes a power of a subscripted symbol as one msubsup."""

from __future__ import annotations

import re

import sympy
from hand.latex import read_latex, same_rational_function

import davies_sym
from davies_sym.topology.symbol_display import mathml_body

from conftest import catalog_path


def _math(text: str) -> list[str]:
    """The inline math of an HTML display, unescaped."""
    found = re.findall(r"\\\((.*?)\\\)", text)
    return [f.replace("&gt;", ">").replace("&lt;", "<").replace("&amp;", "&") for f in found]


def test_train_shows_its_gears_in_latex_and_html() -> None:
    train = davies_sym.load(catalog_path("tuplin"))
    shown = train._repr_latex_()
    assert shown.startswith("$$") and r"\text{A} \to \text{B}" in shown
    for gear in train.gears:
        assert rf"\text{{gear {gear.name}}}" in shown
    assert "<table>" in train._repr_html_()


def test_analysis_html_reads_back_to_its_ratio_and_efficiency() -> None:
    train = davies_sym.load(catalog_path("tuplin"))
    analysis = davies_sym.analyse(train)
    ratio, efficiency = _math(analysis._repr_html_())
    symbols = [*train.symbols.values(), *analysis.sign_symbols.values()]
    assert same_rational_function(read_latex(ratio, symbols), analysis.speed_ratio().to_expr())
    assert same_rational_function(read_latex(efficiency.removeprefix(r"\eta = "), symbols), analysis.efficiency)
    assert analysis._repr_latex_().startswith("$$F_N = 1")


def test_turning_condition_and_variant_show_their_expressions() -> None:
    variants = davies_sym.derive(davies_sym.load(catalog_path("tuplin")))
    symbols = list(variants.train.symbols.values())
    (condition,) = variants.conditions
    shown = condition._repr_latex_()
    assert shown.startswith("$$c_{1} = ")
    r1, r2 = variants.train.symbols["r1"], variants.train.symbols["r2"]
    assert sympy.expand(read_latex(shown[len("$$c_{1} = ") : -2], symbols) - (r2 - r1)) == 0
    assert same_rational_function(read_latex(_math(condition._repr_html_())[0], symbols), r2 - r1)
    for variant in variants.variants:
        where, formula = _math(variant._repr_html_())
        assert "c_{1}" in where
        assert same_rational_function(read_latex(formula.removeprefix(r"\eta = "), symbols), variant.efficiency)
        assert variant._repr_latex_().startswith(rf"$$\eta_{{({variant.number})}} = ")


def test_mathml_power_of_a_subscripted_symbol_is_one_msubsup() -> None:
    r1, x = sympy.symbols("r1 x")
    body = mathml_body(r1**2 + 1 / r1**2 + x**3)
    assert body.count("<msubsup><mi>r</mi><mi>1</mi><mn>2</mn></msubsup>") == 2
    assert "<msup><msub>" not in body and "<msup><mi>x</mi><mn>3</mn></msup>" in body
