"""Security: user text is never evaluated as Python, and generated modules cannot be injected.

Required behaviour (the project's issue on hostile input):

- every expression written by the user (radius, module, efficiency, friction
  coefficients, ``at``, ``axis``, ``placement``, explicit screw coordinates, the
  published values of ``expected``, the values of ``--eval`` and ``--at``, the bounds of
  ``--plot`` and ``--vs``) is read by a small grammar: numbers, names, ``+ - * / **``
  with bounded exponents, parentheses, ``sqrt``, ``sin``, ``cos``, ``tan`` and ``pi``.
  Anything else (attribute access, subscripts, calls of other functions, lambdas,
  conditionals, comprehensions, strings, keyword arguments, dunder names) is refused:
  exit status 2 and one line ``FILE[:LINE]: ENTRY: message`` on stderr, and nothing of it
  runs.  The same holds for names (links, gears, couplings, ports, states), which are
  turned into symbols such as ``eta_<coupling>`` and into Python identifiers;
- names written into a generated formula module (``--python``) are identifiers, or the
  file is refused: a module is never a vehicle for code from the topology file;
- expression bombs (huge powers, very long or very deep expressions) are refused by a bound
  of the grammar (exponent, length) that the message names, never evaluated;
- a state name never makes ``--out DIR`` write outside DIR.

Each attack carries a payload that creates a marker file in the test's tmp_path (or
prints a marker) if it is ever executed; the tests assert the marker never appears.
"""

from __future__ import annotations

import copy
import importlib.util
import inspect
import math
import sys
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from harness.helpers import (
    DATA,
    HANG_GUARD,
    Result,
    assert_not_executed,
    assert_refused,
    catalog,
    dump,
    load_yaml,
    rename_key,
    run_cli,
    run_main,
    skip_slow_unless_full,
)

from davies_sym.topology.expressions import MAX_EXPONENT, MAX_LENGTH

PRINTED_MARKER = "HOSTILE-PRINT-MARKER"
#: The ``print`` payload builds the marker by concatenation: a refusal that quotes the payload
#: never contains the marker, only a payload that runs prints it.
_HALF = len(PRINTED_MARKER) // 2

#: Payloads that create the marker file ``{m}`` (or print PRINTED_MARKER) if Python ever evaluates them.
EXECUTING = {
    "globals_chain": "sqrt.__globals__['__builtins__']['__import__']('os').system('touch {m}')",
    "lambda_call": "(lambda: __import__('os').system('touch {m}'))()",
    "dunder_import": "__import__('os').system('touch {m}')",
    "class_chain": "pi.__class__.__init__.__globals__['__builtins__']['__import__']('os').system('touch {m}')",
    "subscript": "[r1, __import__('os').system('touch {m}')][0]",
    "conditional": "r1 if __import__('os').system('touch {m}') else r2",
    "comprehension": "[__import__('os').system('touch {m}') for k in (1,)][0] + r1",
    "string_open": "open('{m}', 'w') and r1",
    "keyword_arg": "sqrt(r1, evaluate=__import__('os').system('touch {m}'))",
    "exec_string": "exec('import os; os.system(\"touch {m}\")') or r1",
    "getattr": "getattr(__import__('os'), 'system')('touch {m}') + r1",
    "walrus": "(k := __import__('os').system('touch {m}')) + r1",
    "print": f"print('{PRINTED_MARKER[:_HALF]}' + '{PRINTED_MARKER[_HALF:]}') or r1",
    "newline": "r1\n__import__('os').system('touch {m}')",
}

#: The payloads every field gets in the default run (the others: radius and --eval, and the slow run).
CORE = ("globals_chain", "lambda_call", "dunder_import", "conditional")

#: Outside the grammar, harmless if evaluated, and still to be refused.
NOT_GRAMMAR = {
    "if_else": "r1 if r2 else r3",
    "subscript": "r1[0]",
    "string": "'r1'",
    "dunder_name": "__r1__",
    "attribute": "r1.__class__",
    "lambda": "lambda: r1",
    "modulo": "r1 % r2",
    "floor_div": "r1 // r2",
    "comparison": "r1 < r2",
    "bitwise": "r1 & r2",
    "other_function": "exp(r1)",
    "sympy_constructor": "Symbol('r9')",
    "keyword": "sqrt(r1, evaluate=False)",
    "tuple": "r1, r2",
    "set": "{r1}",
    "statement": "r1; r2",
}


def test_print_payload_prints_the_marker_only_when_run(capsys):
    """The check of the ``print`` payload can fail: run as Python it prints the marker,
    while its text does not contain it."""
    payload = EXECUTING["print"]
    assert PRINTED_MARKER not in payload
    eval(payload, {"r1": 1})  # the payload is a fixed string of this file
    assert PRINTED_MARKER in capsys.readouterr().out


def marker_of(tmp_path: Path) -> Path:
    return tmp_path / f"MARKER-{uuid.uuid4().hex[:8]}"


@pytest.fixture(autouse=True)
def _extended_cases_on_request(request: pytest.FixtureRequest) -> None:
    skip_slow_unless_full(request)


# --- where a payload goes ----------------------------------------------------------------------------------

# Each field: (catalog or data file, function placing the payload, entries the message may name, extra args).
Setter = Callable[[dict[str, Any], str], dict[str, Any]]


def _gear1(**entry: Any) -> Setter:
    def put(d: dict[str, Any], p: str) -> dict[str, Any]:
        d["gears"][1] = {"link": 1, **{k: (p if v is None else v) for k, v in entry.items()}}
        return d

    return put


def _set(*keys: Any, wrap: Callable[[str], Any] = lambda p: p) -> Setter:
    def put(d: dict[str, Any], p: str) -> dict[str, Any]:
        target = d
        for k in keys[:-1]:
            target = target[k]
        target[keys[-1]] = wrap(p)
        return d

    return put


def _mesh_efficiency(value: Callable[[str], Any]) -> Setter:
    def put(d: dict[str, Any], p: str) -> dict[str, Any]:
        d["couplings"]["C"] = {"type": "mesh", "gears": [1, 2], "efficiency": value(p)}
        return d

    return put


def _rename_coupling(old: str, port: str | None = None) -> Setter:
    def put(d: dict[str, Any], p: str) -> dict[str, Any]:
        d["couplings"] = rename_key(d["couplings"], old, p)
        if port:
            d["ports"][port] = p
        return d

    return put


def _rename_link_2(d: dict[str, Any], p: str) -> dict[str, Any]:
    d["links"] = rename_key(d["links"], 2, p)
    d["gears"][2]["link"] = p
    d["couplings"]["B"]["links"] = [0, p]
    return d


def _rename_gear_2(d: dict[str, Any], p: str) -> dict[str, Any]:
    d["gears"] = rename_key(d["gears"], 2, p)
    d["couplings"]["C"]["gears"] = [1, p]
    return d


def _state(d: dict[str, Any], p: str) -> dict[str, Any]:
    d["states"] = {p: {"input": "A", "output": "B"}}
    return d


def _screw_magnitude(d: dict[str, Any], p: str) -> dict[str, Any]:
    d["couplings"]["C"]["motions"] = {p: {"t": 1, "u": "r1"}}
    return d


def _expected_value(d: dict[str, Any], p: str) -> dict[str, Any]:
    d["expected"][0]["values"]["r1"] = p
    return d


FIELDS: dict[str, tuple[str, Setter, tuple[str, ...], tuple[str, ...]]] = {
    "radius": ("simple_pair", _set("gears", 1, "radius"), ("gears.1.radius",), ()),
    "module": ("simple_pair", _gear1(teeth=20, module=None), ("gears.1.module",), ()),
    "teeth": ("simple_pair", _gear1(teeth=None, module=2), ("gears.1.teeth",), ()),
    "efficiency": ("simple_pair", _mesh_efficiency(lambda p: p), ("couplings.C.efficiency",), ()),
    "efficiency_pair": ("simple_pair", _mesh_efficiency(lambda p: [0.98, p]), ("couplings.C.efficiency",), ()),
    "friction_coulomb": (
        "simple_pair",
        _set("couplings", "C", "friction", "coulomb"),
        ("couplings.C.friction.coulomb",),
        (),
    ),
    "friction_linear": (
        "simple_pair",
        _set("couplings", "C", "friction", wrap=lambda p: {"linear": p}),
        ("couplings.C.friction.linear",),
        (),
    ),
    "friction_viscous": (
        "simple_pair",
        _set("couplings", "A", "friction", wrap=lambda p: {"viscous": p}),
        ("couplings.A.friction.viscous",),
        (),
    ),
    "at": ("planetary_simple", _set("couplings", "O", "at"), ("couplings.O.at",), ()),
    "axis_text": ("litvin_face_drive", _set("gears", "2", "axis"), ("gears.2.axis",), ()),
    "axis_vector": ("litvin_face_drive", _set("gears", "2", "axis", wrap=lambda p: [0, p, 0]), ("gears.2.axis",), ()),
    "placement_vector": ("simple_pair", _set("placement", wrap=lambda p: [1, p]), ("placement",), ()),
    "placement_angle": ("simple_pair", _set("placement"), ("placement",), ()),
    "prismatic_direction": (
        "planetary_simple",
        _set("couplings", "K", "direction", wrap=lambda p: [p, 0, 0]),
        ("couplings.K.direction",),
        (),
    ),
    "screw_coordinate": (
        "data:tuplin_screws",
        _set("couplings", "C", "motions", "t_C", "u"),
        ("couplings.C.motions",),
        (),
    ),
    "screw_magnitude_name": ("data:tuplin_screws", _screw_magnitude, ("couplings.C.motions",), ()),
    "mesh_name": ("simple_pair", _rename_coupling("C"), ("couplings",), ()),
    "port_name": ("simple_pair", _rename_coupling("A", "input"), ("couplings", "ports"), ()),
    "link_name": ("simple_pair", _rename_link_2, ("links", "gears.2.link", "couplings.B"), ()),
    "gear_name": ("simple_pair", _rename_gear_2, ("gears", "couplings.C.gears"), ()),
    "state_name": ("simple_pair", _state, ("states",), ()),
    "expected_values": ("simple_pair", _expected_value, ("expected",), ("--plot", "r2=30:60", "-o", "{fig}")),
}


def _base(source: str) -> dict[str, Any]:
    if source.startswith("data:"):
        return load_yaml(DATA / f"{source[5:]}.yaml")
    return catalog(source)


def _attack_file(tmp_path: Path, field: str, payload: str) -> tuple[Path, tuple[str, ...], list[str]]:
    source, put, entries, extra = FIELDS[field]
    data = put(copy.deepcopy(_base(source)), payload)
    path = dump(data, tmp_path / f"{field}.yaml")
    args = [a.replace("{fig}", str(tmp_path / "fig.png")) for a in extra]
    return path, entries, args


def _check(
    result: Result,
    path: Path | None,
    entries: tuple[str, ...],
    marker: Path,
    *,
    line: bool = True,
    max_lines: int | None = 1,
) -> None:
    assert_not_executed(marker, result=result)
    assert PRINTED_MARKER not in result.stdout + result.stderr, f"PAYLOAD EXECUTED (printed):\n{result.describe()}"
    assert_refused(result, path, entries, line=line, max_lines=max_lines)


def _is_name_field(field: str) -> bool:
    return field.endswith("_name")


def _field_cases(payloads: tuple[str, ...]) -> list[Any]:
    """Every field with every payload; the default run: the radius with all, the other fields with ``payloads``."""
    cases = []
    for field in FIELDS:
        for name in EXECUTING:
            slow = name not in payloads and field != "radius"
            marks = [pytest.mark.slow] if slow else []
            cases.append(pytest.param(field, name, id=f"{field}-{name}", marks=marks))
    return cases


@pytest.mark.parametrize(("field", "attack"), _field_cases(CORE))
def test_payload_in_topology_field_is_refused_and_never_runs(tmp_path, field, attack):
    """A payload in any field of the file: exit 2, one line naming the file, line and entry; nothing runs."""
    marker = marker_of(tmp_path)
    payload = EXECUTING[attack].format(m=marker)
    path, entries, extra = _attack_file(tmp_path, field, payload)
    result = run_main([str(path), "--quiet", *extra])
    # A name may be referred to in several places: one line per place is fine.
    _check(result, path, entries, marker, max_lines=None if _is_name_field(field) else 1)


FRESH = ("globals_chain", "lambda_call", "exec_string")


@pytest.mark.parametrize("attack", [pytest.param(a, marks=[] if a in FRESH else [pytest.mark.slow]) for a in EXECUTING])
def test_every_payload_as_a_radius_in_a_fresh_process(tmp_path, attack):
    """The same attacks in a fresh interpreter (nothing imported or cached by the test process)."""
    marker = marker_of(tmp_path)
    path, entries, _ = _attack_file(tmp_path, "radius", EXECUTING[attack].format(m=marker))
    _check(run_cli([str(path), "--quiet"]), path, entries, marker)


@pytest.mark.parametrize("expression", list(NOT_GRAMMAR.values()), ids=list(NOT_GRAMMAR))
@pytest.mark.parametrize(
    "field",
    [
        "radius",
        pytest.param("efficiency", marks=pytest.mark.slow),
        pytest.param("friction_coulomb", marks=pytest.mark.slow),
    ],
)
def test_expression_outside_the_grammar_is_refused(tmp_path, field, expression):
    marker = marker_of(tmp_path)
    path, entries, extra = _attack_file(tmp_path, field, expression)
    _check(run_main([str(path), "--quiet", *extra]), path, entries, marker)


@pytest.mark.parametrize("expression", ["r1 + r2/3", "(r1 + 1)**2", "3*r2 - r1", "1/3", "0.5*r1", "r1**2/r2"])
def test_grammar_still_reads_ordinary_expressions(tmp_path, expression):
    """The grammar is not a refusal of everything: what the docs promise still loads and derives."""
    data = catalog("simple_pair")
    data["gears"][1]["radius"] = expression
    path = dump(data, tmp_path / "ok.yaml")
    result = run_main([str(path), "--quiet"])
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode == 0, result.describe()


@pytest.mark.parametrize("expression", ["2*sqrt(r1)", "r1*cos(pi/6)", "sin(pi/4)*r1", "tan(pi/8) + r1", "sqrt(2)*r1"])
def test_grammar_functions_are_read_then_derived_or_refused_cleanly(tmp_path, expression):
    """``sqrt``, ``sin``, ``cos``, ``tan`` and ``pi`` belong to the grammar: the radius is read, then the
    train is derived (exit 0) or refused with one clear line naming the radius (exit 2), never a crash."""
    data = catalog("simple_pair")
    data["gears"][1]["radius"] = expression
    path = dump(data, tmp_path / "ok.yaml")
    result = run_main([str(path), "--quiet"])
    assert "Traceback" not in result.stderr, result.describe()
    if result.returncode != 0:
        assert_refused(result, path, ("gears.1.radius",))


# --- command-line values ------------------------------------------------------------------------------------

SIMPLE_VALUES = ["r2=50", "eta_C=0.98"]


def _cli_args(option: str, payload: str, fig: Path) -> tuple[list[str], tuple[str, ...]]:
    if option == "--eval value":
        return ["--eval", f"r1={payload}", *SIMPLE_VALUES], ("--eval",)
    if option == "--eval name":
        return ["--eval", f"{payload}=3", "r1=20", *SIMPLE_VALUES], ("--eval",)
    if option == "--at value":
        return ["--plot", "r1=10:30", "-o", str(fig), "--at", f"r2={payload}", "eta_C=0.98"], ("--at",)
    if option == "--plot start":
        return ["--plot", f"r1={payload}:30", "-o", str(fig), "--at", *SIMPLE_VALUES], ("--plot",)
    if option == "--plot stop":
        return ["--plot", f"r1=10:{payload}", "-o", str(fig), "--at", *SIMPLE_VALUES], ("--plot",)
    if option == "--vs bounds":
        return ["--plot", "r1=10:30", "--vs", f"r2=30:{payload}", "-o", str(fig), "--at", "eta_C=0.98"], ("--vs",)
    if option == "--input":
        return ["--input", payload, "--eval", "r1=20", *SIMPLE_VALUES], ("--input",)
    if option == "--state":
        return ["--state", payload], ("--state",)
    raise AssertionError(option)


CLI_OPTIONS = [
    "--eval value",
    "--eval name",
    "--at value",
    "--plot start",
    "--plot stop",
    "--vs bounds",
    "--input",
    "--state",
]


def _cli_cases() -> list[Any]:
    cases = []
    for option in CLI_OPTIONS:
        for name in EXECUTING:
            every = option == "--eval value"
            marks = [] if every or name in CORE else [pytest.mark.slow]
            cases.append(pytest.param(option, name, id=f"{option.replace(' ', '_')}-{name}", marks=marks))
    return cases


@pytest.mark.parametrize(("option", "attack"), _cli_cases())
def test_payload_on_the_command_line_is_refused_and_never_runs(tmp_path, option, attack):
    """``--eval``/``--at`` values, ``--plot``/``--vs`` bounds, names of symbols, ports and states."""
    marker = marker_of(tmp_path)
    fig = tmp_path / "fig.png"
    args, entries = _cli_args(option, EXECUTING[attack].format(m=marker), fig)
    path = dump(catalog("simple_pair"), tmp_path / "pair.yaml")
    result = run_main([str(path), "--quiet", *args])
    _check(result, path, entries, marker, line=False)
    assert not fig.exists(), "a figure was written although an option was refused"


@pytest.mark.parametrize("expression", list(NOT_GRAMMAR.values()), ids=list(NOT_GRAMMAR))
@pytest.mark.parametrize("option", ["--eval value", "--at value"])
def test_command_line_value_outside_the_grammar_is_refused(tmp_path, option, expression):
    fig = tmp_path / "fig.png"
    args, entries = _cli_args(option, expression, fig)
    path = dump(catalog("simple_pair"), tmp_path / "pair.yaml")
    _check(run_main([str(path), "--quiet", *args]), path, entries, marker_of(tmp_path), line=False)


# --- names in generated formula modules ---------------------------------------------------------------------

#: Names that are not Python identifiers, or are but must not reach the module as code.
HOSTILE_NAMES = {
    "triple_quote": 'A"""\n__import__(\'os\').system(\'touch {m}\')\n"""',
    "quote": "A'\n__import__('os').system('touch {m}')#",
    "newline": "A\nimport os; os.system('touch {m}')\n",
    "dunder_import": "__import__('os').system('touch {m}')",
    "keyword_lambda": "lambda",
    "keyword_class": "class",
    "keyword_none": "None",
    "integer": "7",
    "non_ascii": "Ä",
    "greek": "ζ",
    "space": "A B",
}


def _named(data: dict[str, Any], role: str, name: str) -> dict[str, Any]:
    if role == "input_port":
        return _rename_coupling("A", "input")(data, name)
    if role == "output_port":
        return _rename_coupling("B", "output")(data, name)
    if role == "mesh":
        return _rename_coupling("C")(data, name)
    if role == "link":
        return _rename_link_2(data, name)
    raise AssertionError(role)


ROLE_ENTRIES = {
    "input_port": ("couplings", "ports"),
    "output_port": ("couplings", "ports"),
    "mesh": ("couplings",),
    "link": ("links", "gears.2.link", "couplings.B"),
}


def _value_for(parameter: str) -> float:
    if parameter == "r1":
        return 20.0
    if parameter == "r2":
        return 50.0
    return 0.98


@pytest.mark.parametrize("name", list(HOSTILE_NAMES), ids=list(HOSTILE_NAMES))
@pytest.mark.parametrize("role", list(ROLE_ENTRIES))
def test_names_in_a_generated_module_are_refused_or_inert(tmp_path, monkeypatch, role, name):
    """``--python``: a hostile name is refused (exit 2, the entry named, no module written) or
    gives a module that compiles, imports and evaluates without running anything injected."""
    marker = marker_of(tmp_path)
    hostile = HOSTILE_NAMES[name].format(m=marker)
    path = dump(_named(catalog("simple_pair"), role, hostile), tmp_path / "named.yaml")
    module_path = tmp_path / "formulas.py"
    monkeypatch.chdir(tmp_path)
    result = run_main([str(path), "--quiet", "--python", str(module_path)])
    assert_not_executed(marker, result=result)
    assert "Traceback" not in result.stderr, result.describe()
    if result.returncode != 0:
        assert_refused(result, path, ROLE_ENTRIES[role], max_lines=None)
        assert not module_path.exists(), "a module was written although the file was refused"
        return
    source = module_path.read_text(encoding="utf-8")
    compile(source, str(module_path), "exec")  # a SyntaxError here is an injection that only failed by luck
    spec = importlib.util.spec_from_file_location(f"hostile_module_{uuid.uuid4().hex}", module_path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
        assert_not_executed(marker)
        accepted = [
            n
            for n, p in inspect.signature(module.efficiency).parameters.items()
            if p.kind is inspect.Parameter.KEYWORD_ONLY and n not in ("input", "errors")
        ]
        value = float(module.efficiency(**{n: _value_for(n) for n in accepted}))
    finally:
        sys.modules.pop(spec.name, None)
    assert_not_executed(marker)
    assert math.isfinite(value) and 0 < value <= 1, value
    assert value == pytest.approx(0.98, abs=1e-9)


# --- state names and --out DIR ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "state",
    [
        "/../../escaped",
        pytest.param("../escaped", marks=pytest.mark.slow),
        pytest.param("a/b", marks=pytest.mark.slow),
        "/tmp/escaped-abs",
        pytest.param("x\x00y", marks=pytest.mark.slow),
    ],
)
def test_state_name_never_writes_outside_the_output_folder(tmp_path, state):
    """``--out DIR`` names a module ``<train>_<state>.py``: a state name with a path in it is
    refused (exit 2, the state named) and nothing is written outside DIR."""
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "pair_").mkdir()  # makes "pair_/../../escaped.py" resolve outside the folder
    data = catalog("simple_pair")
    data["states"] = {state: {"input": "A", "output": "B"}}
    path = dump(data, tmp_path / "pair.yaml")
    before = {p for p in tmp_path.rglob("*")}
    result = run_cli([str(path), "--quiet", "--out", str(folder)])
    created = {p for p in tmp_path.rglob("*")} - before
    outside = [p for p in created if folder not in p.parents]
    assert not outside, f"files written outside {folder}: {outside}\n{result.describe()}"
    assert not Path("/tmp/escaped-abs.py").exists()
    assert_refused(result, path, ("states",), max_lines=None)


# --- expression bombs ---------------------------------------------------------------------------------------

BOMBS = {
    "power_tower": "9**9**9",
    "huge_exponent": "r1**100000",
    "power_of_power": "2**10**10",
    "sum_3000_terms": " + ".join(["r1"] * 3000),
    "nested_10000": "(" * 10000 + "r1" + ")" * 10000,
}

#: A hang guard only, never a claim about speed (a busy machine may be slow): a bomb still
#: computing after this long is killed and fails.  That a bomb is not evaluated is asserted by
#: the bound its refusal names (`BOMB_BOUNDS`) and by the memory limit below.
BOMB_KILL_AFTER = HANG_GUARD
#: The bombs run with an address-space limit, so that a bomb that allocates (2**10**10 wants
#: more than a gigabyte) fails in its own process instead of starving the machine.
BOMB_MEMORY = 2 * 1024**3
_EXPONENT = f"is too large (at most {MAX_EXPONENT})"
_LENGTH = f"is too long for an expression (at most {MAX_LENGTH} characters)"
#: The bound of the grammar each bomb hits, as its refusal names it (the work is bounded by it).
BOMB_BOUNDS = {
    "power_tower": _EXPONENT,
    "huge_exponent": _EXPONENT,
    "power_of_power": _EXPONENT,
    "sum_3000_terms": _LENGTH,
    "nested_10000": _LENGTH,
}
#: ``--eval`` takes a number: a value naming a symbol is refused for that before any bound.
EVAL_REFUSALS = {**BOMB_BOUNDS, "huge_exponent": "is not a number (it names 'r1')"}


def _run_bomb(args: list[str]) -> Result:
    return run_cli(args, timeout=BOMB_KILL_AFTER, memory=BOMB_MEMORY)


def _bomb_check(result: Result, path: Path, entries: tuple[str, ...], line: bool, bound: str) -> None:
    assert not result.timed_out, f"still computing after {BOMB_KILL_AFTER} s (killed)"
    assert_refused(result, path, entries, line=line)
    assert bound in result.stderr, f"the refusal does not name the bound {bound!r}:\n{result.describe()}"


@pytest.mark.parametrize("bomb", list(BOMBS), ids=list(BOMBS))
def test_expression_bomb_as_radius_is_refused_by_a_bound(tmp_path, bomb):
    data = catalog("simple_pair")
    data["gears"][1]["radius"] = BOMBS[bomb]
    path = dump(data, tmp_path / "bomb.yaml")
    _bomb_check(_run_bomb([str(path), "--quiet"]), path, ("gears.1.radius",), line=True, bound=BOMB_BOUNDS[bomb])


EVAL_BOMBS = ("power_tower", "nested_10000")


@pytest.mark.parametrize("bomb", [pytest.param(b, marks=[] if b in EVAL_BOMBS else [pytest.mark.slow]) for b in BOMBS])
def test_expression_bomb_as_eval_value_is_refused_by_a_bound(tmp_path, bomb):
    path = dump(catalog("simple_pair"), tmp_path / "pair.yaml")
    result = _run_bomb([str(path), "--quiet", "--eval", f"r1={BOMBS[bomb]}", *SIMPLE_VALUES])
    _bomb_check(result, path, ("--eval",), line=False, bound=EVAL_REFUSALS[bomb])
