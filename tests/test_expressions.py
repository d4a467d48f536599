"""The expression grammar: user text is read, never evaluated as Python.

Every attack here would run code (create the marker file) if the text reached
``eval``, ``sympify`` or ``parse_expr``; each must be refused with a message instead.
"""

from __future__ import annotations

import sys
import tracemalloc
from pathlib import Path

import pytest
import sympy

import davies_sym
from davies_sym.cli import main
from davies_sym.topology.expressions import MAX_EXPONENT, ExpressionError, check_name, parse_expression

ROOT = Path(__file__).resolve().parent.parent


def _symbol(name: str) -> sympy.Symbol:
    return sympy.Symbol(name, positive=True)


def _attacks(marker: Path) -> list[str]:
    touch = f"__import__('pathlib').Path('{marker}').touch()"
    return [
        f"sqrt.__globals__['__builtins__']['__import__']('pathlib').Path('{marker}').touch()",
        f"(lambda: {touch})()",
        touch,
        f"r1 + [{touch} for _ in (1,)][0]",
        f"r1 if {touch} else r2",
        f"sqrt({touch})",
        f"sqrt(x=({touch}))",
        "().__class__.__base__.__subclasses__()",
        f"{{{touch}: 1}}",
        f"r1[{touch}]",
        f"f'{{{touch}}}'",
    ]


def test_attacks_are_refused_and_never_run(tmp_path: Path) -> None:
    marker = tmp_path / "ran"
    for text in _attacks(marker):
        with pytest.raises(ExpressionError):
            parse_expression(text, _symbol)
        assert not marker.exists(), text


@pytest.mark.parametrize(
    "text",
    [
        "9**9**9",
        "r1**100000",
        "2**10**10",
        "(r1**60)**60",
        "((2**60)**60)**60",
        "1e999999999",
        "9" * 2000,
        "+".join(["r1"] * 3000),
        "(" * 10000 + "1" + ")" * 10000,
        "-" * 5000 + "1",
    ],
)
def test_bombs_are_refused_at_once(text: str) -> None:
    """Refused before any real work, measured in work (Python calls made and memory
    allocated, the same on every machine), not in seconds: a few thousand calls and well
    under a megabyte (the refusals take 2-1,000 calls and 3-65 kB)."""
    calls = 0

    def count(frame: object, event: str, arg: object) -> None:
        nonlocal calls
        calls += event == "call"

    tracemalloc.start()
    sys.setprofile(count)
    try:
        with pytest.raises(ExpressionError):
            parse_expression(text, _symbol)
    finally:
        sys.setprofile(None)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    assert calls < 5_000, f"{calls} calls before the refusal"
    assert peak < 1_000_000, f"{peak} bytes allocated before the refusal"


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("0.99", sympy.Rational(99, 100)),
        ("1-(1/16-1/34)/5", 1 - (sympy.Rational(1, 16) - sympy.Rational(1, 34)) / 5),
        ("sqrt(2)*10", 10 * sympy.sqrt(2)),
        ("2**0.5", sympy.sqrt(2)),
        ("1e-3", sympy.Rational(1, 1000)),
        ("2.5e2", sympy.Integer(250)),
        ("pi/4", sympy.pi / 4),
        ("cos(pi/3)", sympy.Rational(1, 2)),
        ("-(-3)", sympy.Integer(3)),
        (f"2**{MAX_EXPONENT}", sympy.Integer(2) ** MAX_EXPONENT),
    ],
)
def test_numbers_are_exact(text: str, value: sympy.Expr) -> None:
    assert parse_expression(text) == value


def test_names_become_the_callers_symbols() -> None:
    made: list[str] = []

    def symbol(name: str) -> sympy.Symbol:
        made.append(name)
        return _symbol(name)

    expr = parse_expression("m*z1/2 + E*N - S", symbol)
    assert sorted(made) == ["E", "N", "S", "m", "z1"]
    assert expr == _symbol("m") * _symbol("z1") / 2 + _symbol("E") * _symbol("N") - _symbol("S")
    assert expr.has(_symbol("E")) and not expr.has(sympy.E)


@pytest.mark.parametrize("text", ["r1", "pi", "sqrt(2)"])
def test_numbers_only_where_no_symbols_are_wanted(text: str) -> None:
    if text == "r1":
        with pytest.raises(ExpressionError, match="not a number"):
            parse_expression(text)
    else:
        assert parse_expression(text).is_number


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("1/0", "divides by zero"),
        ("1/(2-2)", "divides by zero"),
        ("0**-1", "divides by zero"),
        ("sqrt(-1)", "not a real"),
        ("x^2", r"write \*\* for a power"),
        ("lambda", "keyword"),
        ("True", "constant"),
        ("'a'", "constant"),
        ("1j", "constant"),
        ("r1**r2", "rational number"),
        ("", "empty"),
        ("a.b", "attribute"),
    ],
)
def test_refusals_say_why(text: str, why: str) -> None:
    with pytest.raises(ExpressionError, match=why):
        parse_expression(text, _symbol)


@pytest.mark.parametrize(
    "name", ["lambda", "class", "np", "input", "errors", "sqrt", "pi", "print", "_x", "η", "a-b", "1r"]
)
def test_reserved_and_malformed_names(name: str) -> None:
    assert check_name(name) is not None


def test_long_values_are_shortened_in_messages() -> None:
    with pytest.raises(ExpressionError) as info:
        parse_expression("r1+" * 200_000 + "r1", _symbol)
    assert len(str(info.value)) < 200


def _simple_pair(radius: str) -> str:
    return (ROOT / "catalog" / "simple_pair.yaml").read_text().replace("radius: r1", f"radius: {radius}")


def test_attack_in_a_topology_file_is_reported_with_its_line(tmp_path: Path) -> None:
    marker = tmp_path / "ran"
    for text in _attacks(marker):
        quoted = '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
        with pytest.raises(davies_sym.TopologyError) as info:
            davies_sym.loads(_simple_pair(quoted), "pair.yaml")
        assert "pair.yaml:" in str(info.value) and ".radius:" in str(info.value)
        assert not marker.exists(), text


def test_attack_in_eval_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    marker = tmp_path / "ran"
    pair = str(ROOT / "catalog" / "simple_pair.yaml")
    for text in _attacks(marker):
        assert main([pair, "--quiet", "--eval", f"r1={text}", "r2=2", "zeta_C=1/10"]) == 2
        err = capsys.readouterr().err
        assert "--eval" in err and "Traceback" not in err
        assert not marker.exists(), text


@pytest.mark.parametrize(
    ("key", "name", "why"),
    [
        ("couplings", 'C"""', "not a valid coupling name"),
        ("couplings", "C-1", "not a valid coupling name"),
        ("couplings", "Ĉ", "not a valid coupling name"),
        ("links", "a;b", "not a valid link name"),
        ("links", " a", "not a valid link name"),
    ],
)
def test_names_that_would_break_outputs_are_refused(key: str, name: str, why: str) -> None:
    text = (ROOT / "catalog" / "simple_pair.yaml").read_text()
    old = "  C:" if key == "couplings" else "  1:"
    assert old in text
    text = text.replace(old, f"  {name!r}:".replace("'", '"') if '"' not in name else f"  '{name}':", 1)
    with pytest.raises(davies_sym.TopologyError, match=why):
        davies_sym.loads(text, "pair.yaml")


def test_a_numbered_port_gives_a_module_that_compiles(tmp_path: Path) -> None:
    """Ports named by numbers: the variant functions still have identifier names."""
    text = (ROOT / "catalog" / "simple_pair.yaml").read_text()
    for old, new in (("  A:", "  1:"), ("  B:", "  2:"), ("input: A", "input: 1"), ("output: B", "output: 2")):
        assert old in text
        text = text.replace(old, new)
    (tmp_path / "pair.yaml").write_text(text)
    out = tmp_path / "pair_module.py"
    assert main([str(tmp_path / "pair.yaml"), "--quiet", "--python", str(out)]) == 0
    namespace: dict[str, object] = {}
    exec(compile(out.read_text(), str(out), "exec"), namespace)  # the test's own generated file
    assert "from_1_to_2" in namespace
