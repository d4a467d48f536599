"""Values for ``VariantSet.evaluate`` keyed by name as a notebook user writes them
(``{"r1": 40, "eta_C": 0.99}``), read exactly, texts by the expression grammar only."""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy
from harness.helpers import run_main

import davies_sym
from davies_sym.errors import InputError

from conftest import catalog_path

R = sympy.Rational


@pytest.fixture(scope="module")
def tuplin() -> davies_sym.VariantSet:
    return davies_sym.derive(davies_sym.load(catalog_path("tuplin")))


def test_names_numbers_and_texts_give_the_exact_value_of_symbols(tuplin: davies_sym.VariantSet) -> None:
    """Names with ints, floats (taken as written), Fractions and texts equal the value at
    symbol keys with exact rationals."""
    symbols = tuplin.train.symbols
    exact = {
        symbols["r1"]: 40,
        symbols["r2"]: 60,
        symbols["r3"]: 15,
        symbols["eta_C"]: sympy.Rational(99, 100),
        symbols["eta_D"]: sympy.Rational(97, 100),
    }
    want = tuplin.evaluate(exact)
    assert want.is_Rational
    assert tuplin.evaluate({"r1": 40, "r2": 60, "r3": 15, "eta_C": 0.99, "eta_D": 0.97}) == want
    assert tuplin.evaluate({"r1": "40", "r2": 60, "r3": Fraction(15), "eta_C": "99/100", "eta_D": "0.97"}) == want


@pytest.mark.parametrize(
    ("values", "said"),
    [
        ({"r1": 40, "nosuch": 1}, "nosuch"),
        ({"r1": "__import__('os')"}, "r1"),
        ({"r1": [40]}, "not a number"),
    ],
)
def test_bad_names_and_values_are_input_errors(tuplin: davies_sym.VariantSet, values: dict, said: str) -> None:
    with pytest.raises(InputError, match=said):
        tuplin.evaluate(values)


def test_single_state_document_has_the_speed_ratio() -> None:
    """derive --json of the Wolfrom train states the speed ratio (input over output speed);
    at random radii on the geometric constraints it equals the textbook Wolfrom ratio
    i = (1 + r_R1/r_S) / (1 - r_R1 r_P2 / (r_P1 r_R2)), and the text prints it."""
    import json
    import random

    from harness.helpers import run_main

    document = json.loads(run_main([catalog_path("wolfrom"), "--json", "--quiet"]).stdout)
    ratio = document["speed_ratio"]
    assert (ratio["input"], ratio["output"]) == ("A", "B")
    expression = sympy.sympify(ratio["expression"])
    rng = random.Random(5)
    for _ in range(5):
        rs, rp1, rp2 = (sympy.Rational(rng.randint(5, 40), rng.randint(1, 4)) for _ in range(3))
        rr1, rr2 = rs + 2 * rp1, rs + rp1 + rp2
        values = {"rs": rs, "rp1": rp1, "rp2": rp2, "rr1": rr1, "rr2": rr2}
        got = expression.subs({s: values[str(s)] for s in expression.free_symbols})
        assert got == (1 + rr1 / rs) / (1 - rr1 * rp2 / (rp1 * rr2))
    text = run_main([catalog_path("wolfrom"), "--quiet"]).stdout
    assert f"speed ratio (A over B speed) = {ratio['expression']}" in text


def test_notebook_display_shows_every_variant(tuplin: davies_sym.VariantSet) -> None:
    """In a notebook the derived efficiency shows as LaTeX (each variant's formula, read
    back from the text, equals the variant's at a random point) and as an HTML table
    with a row per variant."""
    from hand.latex import read_latex

    latex = tuplin._repr_latex_()
    symbols = list(tuplin.train.symbols.values())
    point = {s: sympy.Rational(k + 3, k + 5) for k, s in enumerate(sorted(symbols, key=str))}
    for v in tuplin.variants:
        body = latex.split(rf"\eta_{{({v.number})}} = ")[1].split(r" \qquad")[0]
        assert read_latex(body, symbols).subs(point) == v.efficiency.subs(point)
    table = tuplin._repr_html_()
    assert table.count("<tr>") == len(tuplin.variants) + 1 and tuplin.train.name in table


def test_latex_prose_has_no_program_syntax(tuplin: davies_sym.VariantSet) -> None:
    """The LaTeX notes write their expressions as mathematics: no ``**``, no ``<=`` (which
    prints as an inverted exclamation mark in text), the self-locking sign as ``\\le 0``."""
    from davies_sym.emit.latex import latex_document

    text = latex_document(tuplin)
    assert "**" not in text and "<=" not in text
    if any(v.locking_expression is not None for v in tuplin.variants):
        assert r"$\le 0$" in text


def test_a_train_with_states_is_derived_in_a_state_named_as_the_cli_names_it() -> None:
    """`derive(train, state=NAME)`, `analyse(train, state=NAME)` and `train_in_state(train,
    NAME)` take the state by name; without one, a train with states is refused with their
    names (it has several degrees of freedom until a state's brakes hold them).  Simpson
    first gear by the textbook: speed ratio (R1 + R2 + S) / R1, second 1 + S / R1."""
    train = davies_sym.load(catalog_path("simpson"))
    with pytest.raises(InputError, match=r"states: the train has operating states \(first, second, third, reverse\)"):
        davies_sym.derive(train)
    with pytest.raises(InputError, match=r"state: unknown state 'fourth' \(states: first, second, third, reverse\)"):
        davies_sym.derive(train, state="fourth")
    assert (
        davies_sym.train_in_state(train, "first").ports == davies_sym.train_in_state(train, train.state("first")).ports
    )
    values = {"rs": 30, "rr1": 70, "rr2": 80}
    first = davies_sym.derive(train, state="first")
    assert first.design_point({**values, "eta_C": 1, "eta_D": 1, "eta_E": 1, "eta_F": 1}, "A").speed_ratio == R(180, 70)
    ratio = davies_sym.analyse(train, state="second").speed_ratio().to_expr()
    assert ratio.subs({train.symbols[k]: v for k, v in values.items()}) == R(100, 70)
    pair = davies_sym.load(catalog_path("simple_pair"))
    with pytest.raises(InputError, match="the train has no states"):
        davies_sym.derive(pair, state="first")


def test_refusals_of_the_api_name_its_values_not_an_option() -> None:
    """The API's refusals speak of its `values`; the command line files the same reasons
    under --eval.  The list of names to give holds the train's parameters only (not the
    input torque and speed every train accepts, nor the coefficients its efficiencies give)."""
    variants = davies_sym.derive(davies_sym.load(catalog_path("simple_pair")))
    with pytest.raises(InputError) as missing:
        variants.evaluate({"r1": 20}, "A")
    assert ": values: missing values for " in str(missing.value) and "--eval" not in str(missing.value)
    with pytest.raises(InputError) as unknown:
        variants.evaluate({"r1": 20, "r2": 50, "eta_C": "0.98", "foo": 1}, "A")
    said = str(unknown.value)
    assert ": values: unknown symbol 'foo' (the train has: eta_C, r1, r2)" in said, said
    result = run_main([catalog_path("simple_pair"), "--eval", "r1=20", "--quiet"])
    assert result.returncode == 2 and ": --eval: missing values for eta_C, r2" in result.stderr, result.describe()


def test_a_variant_set_prints_as_one_line_per_variant(tuplin: davies_sym.VariantSet) -> None:
    """`print(variants)` shows what a reader looks for (ports, where, the formula), not the
    whole record with its exact algebra."""
    shown = repr(tuplin)
    lines = shown.splitlines()
    assert len(lines) == 1 + len(tuplin.variants) and len(shown) < 400 * len(lines)
    for line, v in zip(lines[1:], tuplin.variants, strict=True):
        assert line.strip().startswith(f"<Variant ({v.number}): input {v.input}, output {v.output}, where ")
        assert str(v.efficiency) in line
