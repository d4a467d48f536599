"""The layout of generated modules (davies_sym.emit.code_layout): any data and any text,
however hostile, becomes a module that parses back to the same tree, runs without
executing anything but the assignment, keeps every line within 120 columns (except a
single unbreakable token), and gives the data back."""

from __future__ import annotations

import ast

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from davies_sym.emit.code_layout import WIDTH, LayoutError, docstring, literal, module_source

TEXT = st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=400)
HOSTILE = st.sampled_from(
    [
        '"""',
        "'''",
        "\\",
        "\n",
        "\r",
        "\x00",
        "\\N{BULLET}",
        "{x}",
        "# noqa",
        "\u2028",
        "__import__('os').system('false')",
        "a\\\n",
    ]
)
STRINGS = st.one_of(TEXT, st.lists(st.one_of(TEXT, HOSTILE), max_size=8).map("".join))
NUMBERS = st.one_of(st.integers(-(10**30), 10**30), st.floats(allow_nan=False), st.booleans(), st.none())
DATA = st.recursive(
    st.one_of(STRINGS, NUMBERS),
    lambda inner: st.one_of(st.lists(inner, max_size=5).map(tuple), st.dictionaries(STRINGS, inner, max_size=4)),
    max_leaves=20,
)


def _run(source: str) -> dict[str, object]:
    namespace: dict[str, object] = {}
    exec(compile(source, "<generated>", "exec"), namespace)
    return namespace


@settings(max_examples=150, deadline=None, derandomize=True)
@given(value=DATA, doc=STRINGS)
def test_any_data_and_docstring_round_trip(value, doc):
    assignment = ast.Assign([ast.Name("VALUE", ast.Store())], literal(value))
    source = module_source([(0, docstring(doc or "x", "")), (2, assignment)])
    namespace = _run(source)
    assert namespace["VALUE"] == value
    for line in source.splitlines():
        assert len(line) <= WIDTH or " " not in line.strip() or line.endswith("# noqa: E501"), line


@pytest.mark.parametrize("text", ['a """ b', 'ends with a quote"', "back\\slash", "new\nline", "\x00nul"])
def test_docstrings_keep_their_text(text):
    function = ast.parse("def f() -> None:\n    pass").body[0]
    assert isinstance(function, ast.FunctionDef)
    function.body = [docstring(text, "    "), ast.Return(None)]
    namespace = _run(module_source([(0, function)]))
    got = namespace["f"].__doc__
    assert " ".join(got.split()) == " ".join("".join(c if c.isprintable() else " " for c in text).split())


def test_text_that_is_not_the_tree_is_refused():
    """Verbatim source that does not parse to statements is an error, never written."""
    with pytest.raises(SyntaxError):
        module_source([(0, "def broken(:\n")])
    with pytest.raises(LayoutError):
        module_source([(0, ast.Assign([ast.Name("X", ast.Store())], ast.Constant(float("nan"))))])
