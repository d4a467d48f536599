"""``derive FILE --emit c|julia|octave|rust|modelica``: the formulas as code in other
languages, checked against the generated Python module.

The C is compiled (``cc -O1 -std=c99``) into a shared library and called through ctypes,
the Rust is compiled (``rustc``, skipped when it is missing) into one behind a small
``extern "C"`` wrapper, at random designs of several catalog trains and of a train
written here: designs around the published one (or over wide ranges when the file has
none), chosen so that every variant (every power-flow region) that random designs reach
is covered for both input ports, together with inadmissible designs.  The expected
values come from the Python module ``derive --python`` writes, an independent
implementation of the choice (numpy masks over the region code, the loaded forces and the
admissible parameters; the formulas themselves are shared): the same efficiency to a
relative 1e-12 and NaN at the same points.  Julia and Octave are not installed: their
files are checked for structure (every function, balanced blocks) and their straight-line
functions are read back into Python and evaluated.  The Modelica package is read back by
a tiny reader (``^`` to ``**``, ``if .. then .. else`` to a call, the syntax tree allowed
to hold names, numbers, operators and calls of ``sqrt``, ``abs`` and the package's own
functions only) and every function, the choice included, evaluated.
"""

from __future__ import annotations

import ast
import contextlib
import ctypes
import importlib.util
import inspect
import io
import json
import os
import re
import shutil
import subprocess
import sys
import time
import warnings
import zlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest
import sympy

import davies_sym
from davies_sym.cli import main
from davies_sym.efficiency.parameters import file_parameters
from davies_sym.efficiency.several_inputs import SeveralInputs, derive_several_inputs
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.derived_result import DerivedResult, OneInputResult, SeveralInputResult
from davies_sym.emit.languages import LANGUAGES, emit_code, program_of
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.emit.python_module import python_module
from davies_sym.emit.several_inputs_module import several_inputs_module
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state

ROOT = Path(__file__).resolve().parent.parent
CATALOG = ROOT / "catalog"
CC = shutil.which("cc") or "/usr/bin/cc"
RUSTC = shutil.which("rustc") or next(
    (p for p in (os.path.expanduser("~/.cargo/bin/rustc"), "/root/.cargo/bin/rustc") if os.path.exists(p)), None
)
RTOL = 1e-12

#: A train of our own: a planetary set with the sun held, the ring the input and the
#: carrier the output, Coulomb friction and a drag in the planet bearing and a drag on the
#: carrier, so that at light load the losses reverse tooth forces and the bearing's
#: reaction and light-load variants (with their loaded forces' signs) hold.
OWN_TRAIN = """\
name: planetary with the sun held, ring in, carrier out, at light load (test train)
links: [housing, ring, carrier, planet]
reference: housing
gears:
  S: {link: housing, radius: rs}
  P: {link: planet, radius: rp}
  R: {link: ring, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [housing, ring]}
  B: {type: revolute, links: [housing, carrier], friction: {drag: D_c}}
  E: {type: revolute, links: [carrier, planet], friction: {coulomb: rho_p, drag: D_p}}
  SP: {type: mesh, gears: [S, P]}
  RP: {type: mesh, gears: [R, P]}
ports: {input: A, output: B}
"""
#: A design of OWN_TRAIN to sample around (the catalog trains have their published ones).
OWN_DESIGN = {
    "rs": 20.0,
    "rp": 10.0,
    "eta_SP": 0.98,
    "eta_RP": 0.98,
    "rho_p": 0.5,
    "D_p": 0.3,
    "D_c": 0.3,
    "tau_in": 5.0,
}

#: name -> (catalog file or None for OWN_TRAIN, state)
CASES: dict[str, tuple[str | None, str | None]] = {
    "tuplin": ("tuplin", None),
    "simpson_first": ("simpson", "first"),
    "ravigneaux_second": ("ravigneaux", "second"),
    "humpage": ("humpage", None),
    "litvin_face_drive": ("litvin_face_drive", None),
    "planetary_simple": ("planetary_simple", None),
    "wolfrom": ("wolfrom", None),
    "own_planetary_light_load": (None, None),
    "sr20_differential": ("sr20_differential", None),
}
PER_CLASS = 50  # points per (input port, variant) class
CANDIDATES = 6000


@dataclass(frozen=True)
class Case:
    """A derived train, its Python module and the design points to compare at."""

    name: str
    train: Train
    derived: VariantSet | SeveralInputs
    state: str | None
    module: ModuleType
    parameters: tuple[str, ...]
    ports: tuple[str, ...]  # empty for a train driven at several ports
    points: dict[str, np.ndarray]
    port: np.ndarray  # index of the input port per point (one-input trains)
    expected: np.ndarray  # the Python module's efficiency per point
    classes: int  # (port, variant) classes covered, the not-covered class included

    @property
    def result(self) -> DerivedResult:
        """The derived train as its outputs take it."""
        if isinstance(self.derived, SeveralInputs):
            return SeveralInputResult(self.derived)
        return OneInputResult(self.train, ((self.state or "", self.derived),), self.state)

    @property
    def several(self) -> bool:
        return not self.ports

    def arguments(self, k: int) -> list[float]:
        return [float(self.points[n][k]) for n in self.parameters]


def _import(path: Path, name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _required(function: Callable[..., Any]) -> tuple[str, ...]:
    """The parameters a generated Python entry point needs (no default)."""
    return tuple(n for n, p in inspect.signature(function).parameters.items() if p.default is inspect.Parameter.empty)


def _candidates(
    module: ModuleType, names: tuple[str, ...], published: dict[str, float], rng: np.random.Generator
) -> dict[str, np.ndarray]:
    """Random designs: around the published one where there is one, else over wide
    ranges; efficiencies low enough to self-lock sometimes, lengths far enough from the
    published ones to flip the turning conditions."""
    table = {p["name"]: p for p in module.PARAMETERS}
    out = {}
    for n in names:
        p = table[n]
        if p["unit"] == "1":
            out[n] = rng.uniform(0.4, 1.0, CANDIDATES)
        elif p["low"] == -np.inf:
            out[n] = rng.uniform(-100.0, 100.0, CANDIDATES)
        elif n in published:
            # Lengths near the published ones, losses and loads over decades (light load too).
            spread = 0.8 if p["unit"].startswith("length") else 2.5
            out[n] = published[n] * np.exp(rng.uniform(-spread, spread, CANDIDATES))
        elif p["unit"].startswith("length"):
            out[n] = np.exp(rng.uniform(np.log(5.0), np.log(150.0), CANDIDATES))
        else:
            out[n] = np.exp(rng.uniform(np.log(0.01), np.log(60.0), CANDIDATES))
    # A few inadmissible designs besides those the relations reject: a length below zero,
    # an efficiency above 1.
    bad = rng.choice(CANDIDATES, 40, replace=False)
    for k, index in enumerate(bad):
        n = names[k % len(names)]
        out[n][index] = -out[n][index] if table[n]["low"] >= 0 else out[n][index]
        if table[n]["unit"] == "1":
            out[n][index] = 1.05
    return out


def _pick(numbers: np.ndarray, rng: np.random.Generator) -> list[int]:
    """Up to PER_CLASS candidates of each variant number (0: none holds)."""
    chosen: list[int] = []
    for number in sorted(set(numbers.tolist())):
        where = np.flatnonzero(numbers == number)
        chosen += sorted(rng.choice(where, min(PER_CLASS, len(where)), replace=False).tolist())
    return chosen


def _build(name: str, root: Path) -> Case:
    file, state = CASES[name]
    train = davies_sym.loads(OWN_TRAIN, "own.yaml") if file is None else load(str(CATALOG / f"{file}.yaml"))
    rng = np.random.default_rng(zlib.crc32(name.encode()))
    published = {k: float(sympy.sympify(v)) for k, v in train.published_design(state).items()}
    if file is None:
        published = OWN_DESIGN
    path = root / f"{name}.py"
    if len(train.ports.inputs) > 1:
        derived: VariantSet | SeveralInputs = derive_several_inputs(train)
        path.write_text(several_inputs_module(derived))
        module = _import(path, f"formulas_{name}")
        names = _required(module.efficiency)
        pool = _candidates(module, names, published, rng)
        # Speeds on the condition lines, where no region holds.
        a, b = pool["omega_A"], pool["omega_K"]
        a[0:5] = 0.0
        a[5:10] = b[5:10]
        a[10:15] = -b[10:15]
        b[15:20] = 0.0
        numbers = module.region(**pool)
        picked = _pick(numbers, rng)
        points = {n: v[picked] for n, v in pool.items()}
        expected = module.efficiency(errors="ignore", **points)
        return Case(
            name,
            train,
            derived,
            state,
            module,
            names,
            (),
            points,
            np.zeros(len(picked), dtype=int),
            np.asarray(expected, dtype=float),
            len(set(numbers.tolist())),
        )
    derived = derive_variants(
        train_in_state(train, next(s for s in train.states if s.name == state)) if state else train
    )
    path.write_text(python_module(derived, file_parameters(train)))
    module = _import(path, f"formulas_{name}")
    names = tuple(n for n in _required(module.efficiency) if n not in ("input", "errors"))
    ports = tuple(module.PORTS)
    pool = _candidates(module, names, published, rng)
    rows: list[tuple[int, int]] = []
    classes = 0
    for k, port in enumerate(ports):
        numbers = module.variant(input=port, errors="ignore", **pool)
        classes += len(set(numbers.tolist()))
        rows += [(i, k) for i in _pick(numbers, rng)]
    index = np.array([i for i, _ in rows])
    port_index = np.array([k for _, k in rows])
    points = {n: v[index] for n, v in pool.items()}
    expected = np.full(len(rows), np.nan)
    for k, port in enumerate(ports):
        mask = port_index == k
        expected[mask] = module.efficiency(input=port, errors="ignore", **{n: v[mask] for n, v in points.items()})
    return Case(name, train, derived, state, module, names, ports, points, port_index, expected, classes)


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], Case]:
    root = tmp_path_factory.mktemp("languages")
    cache: dict[str, Case] = {}

    def get(name: str) -> Case:
        if name not in cache:
            cache[name] = _build(name, root)
        return cache[name]

    return get


def _agree(actual: np.ndarray, expected: np.ndarray, atol: float = 0.0) -> tuple[int, float]:
    """Assert NaN at the same points and a relative difference <= RTOL elsewhere (or an
    absolute one <= ``atol``); return the number of finite values compared and the largest
    relative difference."""
    nan_a, nan_e = np.isnan(actual), np.isnan(expected)
    assert np.array_equal(nan_a, nan_e), (
        f"NaN at {np.flatnonzero(nan_a != nan_e)[:10]}: got "
        f"{actual[nan_a != nan_e][:5]}, expected {expected[nan_a != nan_e][:5]}"
    )
    finite = ~nan_e
    if not finite.any():
        return 0, 0.0
    same = actual[finite] == expected[finite]  # infinities included
    with np.errstate(all="ignore"):
        rel = np.where(same, 0.0, np.abs(actual[finite] - expected[finite]) / np.abs(expected[finite]))
        rel = np.where(np.abs(actual[finite] - expected[finite]) <= atol, 0.0, rel)
    worst = float(np.max(rel))
    assert worst <= RTOL, f"relative difference {worst:.3g} at {np.argmax(rel)}"
    return int(finite.sum()), worst


#: A variant's formula evaluated outside its own region can cancel to a small value (an
#: "efficiency" of 1e-4 where another variant holds): there the raw formulas are compared
#: to an absolute 1e-12 as well; the choice itself is compared to the relative RTOL only.
RAW_ATOL = 1e-12


def _report(label: str, **numbers: object) -> None:
    print(f"\n[{label}] " + ", ".join(f"{k}={v}" for k, v in numbers.items()))


# --------------------------------------------------------------------------- C and Rust


def _library(path: Path, program: Program, kind: str) -> ctypes.CDLL:
    """The compiled functions with their ctypes signatures (doubles, the port an int)."""
    library = ctypes.CDLL(str(path))
    for routine in program.routines:
        if not routine.exported:
            continue
        symbol = routine.name if kind == "c" else f"x_{routine.name}"
        function = getattr(library, symbol)
        function.argtypes = [ctypes.c_int if a.kind is Kind.PORT else ctypes.c_double for a in routine.arguments]
        function.restype = ctypes.c_double
    return library


#: The reasons of the Python module's DesignError, in the order of its message, and the
#: number the other languages' ``reason`` gives each (a train driven at one port; at several).
_REASON_WORDS = (
    ("design point(s) outside the admissible parameters", 1),
    ("where a port does not turn", 4),
    ("where no variant's power flow agrees", 2),
    ("where the train self-locks", 3),
)
_SEVERAL_REASON_WORDS = (
    ("point(s) outside the parameters' ranges", 1),
    ("on a speed-condition line", 4),
    ("where no region's loaded forces agree", 2),
    ("with an efficiency outside (0, 1]", 3),
)


def _python_reasons(case: Case) -> np.ndarray:
    """Per point, why the Python module (``errors="raise"``) gives no efficiency: the
    reason whose count its message gives as 1, numbered as ``REASONS`` of the other
    languages (0 where it gives an efficiency)."""
    out = np.zeros(len(case.expected))
    for k in range(len(case.expected)):
        point = {n: case.points[n][k] for n in case.parameters}
        port = {} if case.several else {"input": case.ports[int(case.port[k])]}
        words = _SEVERAL_REASON_WORDS if case.several else _REASON_WORDS
        try:
            case.module.efficiency(errors="raise", **port, **point)
        except case.module.DesignError as exc:
            found = [re.search(rf"(\d+) {re.escape(said)}", str(exc)) for said, _ in words]
            counts = [int(m.group(1)) if m else -1 for m in found]
            assert sorted(counts) == [0, 0, 0, 1], str(exc)
            out[k] = words[counts.index(1)][1]
    return out


def _by_port(
    case: Case, routine: Routine, python: Callable[..., Any], function: Callable[..., float]
) -> tuple[np.ndarray, np.ndarray]:
    """A routine taking the input port, against the Python function of the same name with
    ``input=`` that port, at every point (the port each point was drawn for)."""
    expected, actual = [], []
    for k in range(len(case.expected)):
        port = int(case.port[k])
        point = {a.name: float(case.points[a.name][k]) for a in routine.arguments if a.kind is not Kind.PORT}
        expected.append(float(python(input=case.ports[port], errors="ignore", **point)))
        actual.append(function(*(port if a.kind is Kind.PORT else point[a.name] for a in routine.arguments)))
    return np.array(expected), np.array(actual)


def _compare_compiled(case: Case, library: ctypes.CDLL, program: Program, prefix: str) -> dict[str, object]:
    """The choice and every variant (region) and condition function against the Python module."""
    n = len(case.expected)
    entry = getattr(library, prefix + program.entry)
    if case.several:
        got = np.array([entry(*case.arguments(k)) for k in range(n)])
    else:
        got = np.array([entry(*case.arguments(k), int(case.port[k])) for k in range(n)])
        # Any other port value: no efficiency.
        assert all(np.isnan(entry(*case.arguments(k), 2)) for k in range(min(n, 20)))
    compared, worst = _agree(got, case.expected)
    assert compared >= len(case.expected) // 4, "too few points where the efficiency is defined"
    # Why there is no efficiency: the reason the Python module's DesignError gives.
    reason = getattr(library, prefix + "reason")
    ports = [[] if case.several else [int(case.port[k])] for k in range(n)]
    said = np.array([reason(*case.arguments(k), *ports[k]) for k in range(n)])
    expected_reasons = _python_reasons(case)
    differ = said != expected_reasons
    assert not differ.any(), (
        f"reasons differ at {np.flatnonzero(differ)[:10]}: got {said[differ][:10]}, "
        f"the Python module says {expected_reasons[differ][:10]}"
    )
    assert set(expected_reasons.tolist()) >= {0.0, 1.0}, "the points reach no refusal"
    formulas = 0
    for routine in program.routines:
        python = getattr(case.module, routine.name, None)
        if (
            not routine.exported
            or routine.returns is not Kind.REAL
            or routine.name == program.entry
            or python is None
            or routine.name.startswith("efficiency_from_")
        ):
            continue
        function = getattr(library, prefix + routine.name)
        if any(a.kind is Kind.PORT for a in routine.arguments):
            # variant(..., input_port): the Python module's variant(input=PORT), point by point.
            expected, actual = _by_port(case, routine, python, function)
            differ = np.flatnonzero(actual != expected)[:10]
            assert not differ.size, f"{routine.name} differs at {differ}: {actual[differ]} vs {expected[differ]}"
            formulas += 1
            continue
        values = {a: case.points[a] for a in routine.argument_names}
        with np.errstate(all="ignore"), warnings.catch_warnings():
            # speed_ratio says where it gives NaN; the NaN itself is compared.
            warnings.simplefilter("ignore", case.module.DesignWarning)
            expected = np.broadcast_to(np.asarray(python(**values), dtype=float), (n,))
        actual = np.array([function(*(float(values[a][k]) for a in routine.argument_names)) for k in range(n)])
        # The raw formulas agree wherever they are defined (NaN where numpy's is).
        _agree(actual, expected, RAW_ATOL)
        formulas += 1
    return {
        "points": n,
        "finite": compared,
        "max_rel_diff": f"{worst:.2e}",
        "functions": formulas,
        "classes": case.classes,
    }


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_c_matches_the_python_module(built: Callable[[str], Case], name: str, tmp_path: Path) -> None:
    case = built(name)
    program = program_of(case.result, "c")
    assert program.parameters == case.parameters  # the choice takes the Python module's parameters, in its order
    source = tmp_path / f"{name}.c"
    source.write_text(emit_code(case.result, "c"))
    started = time.perf_counter()
    subprocess.run(
        [
            CC,
            "-O1",
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-shared",
            "-fPIC",
            str(source),
            "-o",
            str(tmp_path / "lib.so"),
            "-lm",
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    seconds = time.perf_counter() - started
    numbers = _compare_compiled(case, _library(tmp_path / "lib.so", program, "c"), program, "")
    _report(f"C {name}", compile_s=f"{seconds:.2f}", **numbers)


def _rust_wrapper(program: Program, generated: Path) -> str:
    """A crate exporting every public function of the generated module to C callers."""
    lines = [f'#[path = "{generated}"]', "mod generated;"]
    types = {Kind.REAL: "f64", Kind.BOOL: "bool", Kind.PORT: "i32"}
    for routine in program.routines:
        if not routine.exported:
            continue
        args = ", ".join(f"{a.name}: {types[a.kind]}" for a in routine.arguments)
        call = ", ".join(routine.argument_names)
        lines += [
            "#[no_mangle]",
            f'pub extern "C" fn x_{routine.name}({args}) -> {types[routine.returns]} {{',
            f"    generated::{routine.name}({call})",
            "}",
        ]
    return "#![allow(non_snake_case)]\n" + "\n".join(lines) + "\n"


@pytest.mark.slow
@pytest.mark.skipif(RUSTC is None, reason="rustc is not installed")
@pytest.mark.parametrize("name", sorted(CASES))
def test_rust_matches_the_python_module(built: Callable[[str], Case], name: str, tmp_path: Path) -> None:
    assert RUSTC is not None
    case = built(name)
    program = program_of(case.result, "rust")
    generated = tmp_path / f"{name}.rs"
    generated.write_text(emit_code(case.result, "rust"))
    wrapper = tmp_path / "wrapper.rs"
    wrapper.write_text(_rust_wrapper(program, generated))
    started = time.perf_counter()
    result = subprocess.run(
        [
            RUSTC,
            "--edition",
            "2021",
            "--crate-type",
            "cdylib",
            "-C",
            "opt-level=1",
            "-o",
            str(tmp_path / "lib.so"),
            str(wrapper),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    seconds = time.perf_counter() - started
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr, result.stderr  # the generated module compiles cleanly
    numbers = _compare_compiled(case, _library(tmp_path / "lib.so", program, "rust"), program, "x_")
    _report(f"Rust {name}", compile_s=f"{seconds:.2f}", **numbers)


# --------------------------------------------------------------------------- Modelica


@dataclass(frozen=True)
class ModelicaFunction:
    name: str
    inputs: tuple[tuple[str, str], ...]  # (type, name)
    output: str
    statements: tuple[tuple[str, ast.Expression], ...]


_TOKEN = re.compile(r"\s*(\d+\.\d*(?:[eE][+-]?\d+)?|\d+(?:[eE][+-]?\d+)?|[A-Za-z_]\w*|<=|>=|<>|==|[-+*/^(),<>])")
_NODES = (
    ast.Expression,
    ast.BoolOp,
    ast.And,
    ast.Or,
    ast.UnaryOp,
    ast.Not,
    ast.USub,
    ast.UAdd,
    ast.BinOp,
    ast.Add,
    ast.Sub,
    ast.Mult,
    ast.Div,
    ast.Pow,
    ast.Compare,
    ast.Lt,
    ast.LtE,
    ast.Gt,
    ast.GtE,
    ast.Eq,
    ast.NotEq,
    ast.Call,
    ast.Name,
    ast.Load,
    ast.Constant,
    ast.Lambda,
    ast.arguments,
)


def _tokens(text: str) -> Iterator[str]:
    position = 0
    text = text.rstrip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        assert match, f"cannot read {text[position : position + 30]!r}"
        yield match.group(1)
        position = match.end()


def _python_expression(text: str, callable_names: set[str]) -> ast.Expression:
    """A Modelica expression as a Python one: ``^`` is ``**``, ``<>`` is ``!=``,
    ``(if c then a elseif d then b else e)`` is ``_ite(c, lambda: a, d, lambda: b, lambda: e)``;
    only names, numbers, operators and calls of ``callable_names`` may appear."""
    words = {
        "^": "**",
        "<>": "!=",
        "true": "True",
        "false": "False",
        "then": ", lambda:",
        "elseif": ",",
        "else": ", lambda:",
        "and": "and",
        "or": "or",
        "not": "not",
    }
    out: list[str] = []
    for token in _tokens(text):
        if token == "if":
            assert out and out[-1] == "(", "an if-expression is written in parentheses"
            out[-1] = "_ite("
        else:
            out.append(words.get(token, token))
    tree = ast.parse(" ".join(out), mode="eval")
    for node in ast.walk(tree):
        assert isinstance(node, _NODES), f"unexpected {type(node).__name__} in {text}"
        if isinstance(node, ast.Call):
            assert isinstance(node.func, ast.Name) and node.func.id in callable_names, ast.unparse(node)
        if isinstance(node, ast.Constant):
            assert isinstance(node.value, (int, float, bool))
    return tree


def _read_modelica(text: str) -> tuple[str, dict[str, ModelicaFunction]]:
    """The package name and its functions, each as inputs, output and statements."""
    code = [line for line in text.split("\n") if line and not line.startswith("//")]
    opening = re.fullmatch(r'package (\w+) ".*"', code[0])
    assert opening, code[0]
    package = opening.group(1)
    assert code[-1] == f"end {package};"
    names = set(re.findall(r"^  function (\w+) ", text, flags=re.M))
    functions: dict[str, ModelicaFunction] = {}
    k = 1
    while k < len(code) - 1:
        model = re.fullmatch(r'  model (\w+) ".*"', code[k])
        if model:  # the flanged model: tests/test_modelica_flanges.py reads it
            k = code.index(f"  end {model.group(1)};", k) + 1
            continue
        head = re.fullmatch(r'  function (\w+) "(?:[^"\\]|\\.)*"', code[k])
        assert head, code[k]
        name = head.group(1)
        inputs, output, statements = [], "", []
        section = "public"
        k += 1
        while code[k] != f"  end {name};":
            line = code[k].strip()
            if line in ("protected", "algorithm"):
                section = line
            elif section == "algorithm":
                target, expression = re.fullmatch(r"(\w+) := (.*);", line).groups()  # type: ignore[union-attr]
                allowed = {"sqrt", "abs", "_ite"} | names
                statements.append((target, _python_expression(expression, allowed)))
            else:
                match = re.fullmatch(r"(input |output )?(Real|Integer|Boolean) (\w+);", line)
                assert match, line
                if match.group(1) == "input ":
                    inputs.append((match.group(2), match.group(3)))
                elif match.group(1) == "output ":
                    output = match.group(3)
            k += 1
        functions[name] = ModelicaFunction(name, tuple(inputs), output, tuple(statements))
        k += 1
    return package, functions


def _ite(*parts: Any) -> Any:
    """``_ite(c1, f1, c2, f2, ..., f_else)``: the branch of the first true condition."""
    for condition, branch in zip(parts[:-1:2], parts[1:-1:2], strict=True):
        if condition:
            return branch()
    return parts[-1]()


def _modelica_functions(functions: dict[str, ModelicaFunction]) -> dict[str, Callable[..., Any]]:
    table: dict[str, Callable[..., Any]] = {}

    def make(f: ModelicaFunction) -> Callable[..., Any]:
        compiled = [(target, compile(tree, f"<{f.name}>", "eval")) for target, tree in f.statements]

        def run(*args: Any) -> Any:
            # One dictionary as the globals: the branches (lambdas) see the steps before them.
            scope: dict[str, Any] = {"__builtins__": {}, "sqrt": np.sqrt, "abs": np.abs, "_ite": _ite, **table}
            scope.update({n: (int(v) if t == "Integer" else v) for (t, n), v in zip(f.inputs, args, strict=True)})
            for target, code in compiled:
                scope[target] = eval(code, scope)
            return scope[f.output]

        return run

    for f in functions.values():
        table[f.name] = make(f)
    return table


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_modelica_package_reads_back(built: Callable[[str], Case], name: str) -> None:
    case = built(name)
    program = program_of(case.result, "modelica")
    text = emit_code(case.result, "modelica")
    assert not re.search(r"[*/^]\s*-", text.split("\npackage ")[1]), "Modelica allows unary minus only first"
    package, functions = _read_modelica(text)
    assert package == program.module
    assert list(functions) == [r.name for r in program.routines]
    for routine in program.routines:
        f = functions[routine.name]
        assert tuple(n for _, n in f.inputs) == routine.argument_names
    run = _modelica_functions(functions)
    count = min(len(case.expected), 150)
    picked = np.linspace(0, len(case.expected) - 1, count).astype(int)
    got = np.empty(count)
    with np.errstate(all="ignore"):
        for j, k in enumerate(picked):
            args = [np.float64(v) for v in case.arguments(int(k))]
            got[j] = run[program.entry](*args) if case.several else run[program.entry](*args, int(case.port[k]))
    # Modelica has no NaN: 0 stands for it.
    expected = np.nan_to_num(case.expected[picked], nan=0.0)
    _agree(got, expected)
    # Every variant (region) function and condition against the Python module.
    for routine in program.routines:
        python = getattr(case.module, routine.name, None)
        if (
            routine.returns is not Kind.REAL
            or python is None
            or routine.name == program.entry
            or routine.name.startswith("efficiency_from_")
            or any(a.kind is Kind.PORT for a in routine.arguments)  # compared in C and Rust
        ):
            continue
        for k in picked[:40]:
            values = {a: np.float64(case.points[a][k]) for a in routine.argument_names}
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", case.module.DesignWarning)
                _agree(
                    np.array([run[routine.name](*values.values())], dtype=float),
                    np.nan_to_num(np.array([np.asarray(python(**values), dtype=float)]).reshape(1), nan=0.0),
                    RAW_ATOL,
                )
    _report(f"Modelica {name}", points=count, functions=len(functions))


# --------------------------------------------------------------------------- Julia and Octave


def _blocks_balance(lines: list[str], openers: tuple[str, ...]) -> bool:
    depth = 0
    for line in lines:
        word = line.strip().split("(")[0].split(" ")[0]
        if word in openers:
            depth += 1
        elif word == "end":
            depth -= 1
            if depth < 0:
                return False
    return depth == 0


def _straight_line(text: str, language: str) -> dict[str, tuple[tuple[str, ...], list[tuple[str, str]], str]]:
    """The functions without choices: name -> (arguments, assignments, returned expression)."""
    out = {}
    head = r"^function (\w+)\(([^)]*)\)$" if language == "julia" else r"^function (\w+) = (\w+)\(([^)]*)\)$"
    lines = text.split("\n")
    for k, line in enumerate(lines):
        match = re.match(head, line)
        if not match:
            continue
        name, args = (match.group(1), match.group(2)) if language == "julia" else (match.group(2), match.group(3))
        output = None if language == "julia" else match.group(1)
        body = []
        j = k + 1
        while lines[j] != "end":
            body.append(lines[j].strip())
            j += 1
        if any(b.startswith("if ") or "::" in args for b in body):
            continue
        steps = [tuple(s.rstrip(";").split(" = ", 1)) for s in body if not s.startswith("return ")]
        if language == "julia":
            result = body[-1].removeprefix("return ")
        else:
            result = dict(steps).pop(output)  # type: ignore[arg-type]
            steps = [s for s in steps if s[0] != output]
        out[name] = (tuple(a.strip() for a in args.split(",") if a.strip()), steps, result)  # type: ignore[misc]
    return out


def _as_python(expression: str) -> str:
    """Julia's or Octave's elementwise operators as Python's (the arguments are scalars)."""
    for old, new in ((".^", "**"), (".*", "*"), ("./", "/"), ("//", "/"), ("^", "**")):
        expression = expression.replace(old, new)
    return expression


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_julia_and_octave_files_hold_every_function(built: Callable[[str], Case], name: str) -> None:
    case = built(name)
    for language, openers in (("julia", ("function", "if", "module")), ("octave", ("function", "if"))):
        program = program_of(case.result, language)
        text = emit_code(case.result, language)
        code = [line for line in text.split("\n") if not line.startswith(("#", "%"))]
        assert _blocks_balance(code, openers), f"unbalanced blocks in the {language} file"
        defined = re.findall(r"^function (?:\w+ = )?(\w+)\(", text, flags=re.M)
        assert defined == [r.name for r in program.routines]
        if language == "julia":
            assert f"module {program.module}" in code and code[-2] == f"end  # module {program.module}"
        else:
            assert code[1] == "1;  % a script file: the functions below are defined when it is run"
        # The functions without choices, read back and evaluated.
        checked = 0
        for fname, (args, steps, result) in _straight_line(text, language).items():
            python = getattr(case.module, fname, None)
            if python is None or fname not in {r.name for r in program.routines if r.returns is Kind.REAL}:
                continue
            for k in range(0, len(case.expected), max(1, len(case.expected) // 10)):
                scope: dict[str, Any] = {"sqrt": np.sqrt, "abs": np.abs}
                scope.update({a: np.float64(case.points[a][k]) for a in args})
                with np.errstate(all="ignore"):
                    for target, expression in steps:
                        scope[target] = eval(_as_python(expression), {"__builtins__": {}}, scope)
                    value = eval(_as_python(result), {"__builtins__": {}}, scope)
                    expected = np.asarray(python(**{a: scope[a] for a in args}), dtype=float).reshape(1)
                _agree(np.array([value], dtype=float), expected, RAW_ATOL)
            checked += 1
        assert checked >= 1
        _report(f"{language} {name}", functions=len(defined), evaluated=checked)


# --------------------------------------------------------------------------- the command line


def _run(*args: str) -> tuple[int, str, str]:
    """``derive`` in this process: status, standard output, standard error."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main([*args, "--quiet"])
    return status, out.getvalue(), err.getvalue()


@pytest.mark.slow
def test_the_command_writes_the_same_bytes_as_the_library(built: Callable[[str], Case], tmp_path: Path) -> None:
    case = built("tuplin")
    path = str(CATALOG / "tuplin.yaml")
    for language in LANGUAGES:
        target = tmp_path / f"tuplin.{language}"
        status, out, err = _run(path, "--emit", language, "-o", str(target))
        assert status == 0 and out == "" and err == "", err
        assert target.read_text() == emit_code(case.result, language)
    status, out, _ = _run(path, "--emit", "c")
    assert status == 0 and out == emit_code(case.result, "c")
    # --python beside --emit: both files.
    status, _, err = _run(path, "--emit", "julia", "-o", str(tmp_path / "t.jl"), "--python", str(tmp_path / "t.py"))
    assert status == 0, err
    assert (tmp_path / "t.py").read_text() == python_module(case.derived, file_parameters(case.train))


@pytest.mark.slow
def test_the_same_train_gives_the_same_bytes_in_a_fresh_process(tmp_path: Path) -> None:
    outputs = []
    for seed in ("1", "2"):
        result = subprocess.run(
            [sys.executable, "-m", "davies_sym.cli", str(CATALOG / "tuplin.yaml"), "--emit", "modelica", "--quiet"],
            capture_output=True,
            text=True,
            check=True,
            env={**os.environ, "PYTHONHASHSEED": seed},
        )
        outputs.append(result.stdout)
    assert outputs[0] == outputs[1] and outputs[0].startswith("// Efficiency of")


@pytest.mark.slow
def test_a_state_is_needed_and_named(tmp_path: Path) -> None:
    status, out, err = _run(str(CATALOG / "simpson.yaml"), "--emit", "c")
    assert status == 2 and out == "" and "--state" in err and "first" in err and "Traceback" not in err
    status, out, err = _run(str(CATALOG / "simpson.yaml"), "--emit", "octave", "--state", "reverse")
    assert status == 0, err
    assert "state reverse" in out and "function result = efficiency(" in out


@pytest.mark.parametrize("other", [["--json"], ["--latex"], ["--eval", "r1=40"], ["--plot", "r1=30:50"]])
def test_emit_refuses_a_document_option(other: list[str]) -> None:
    status, out, err = _run(str(CATALOG / "tuplin.yaml"), "--emit", "c", *other)
    assert status == 2 and "Traceback" not in err
    # No code; with --json the refusal as JSON, as for every refusal.
    assert (json.loads(out)["exit_status"] == 2) if other == ["--json"] else out == ""
    assert err.count("\n") == 1 and "--emit" in err and other[0] in err


def test_emit_refuses_several_files_and_an_unknown_language(tmp_path: Path) -> None:
    status, _, err = _run(
        str(CATALOG / "tuplin.yaml"), str(CATALOG / "wolfrom.yaml"), "--emit", "c", "--out", str(tmp_path)
    )
    assert status == 2 and "--emit" in err
    with pytest.raises(SystemExit) as exit_info:
        _run(str(CATALOG / "tuplin.yaml"), "--emit", "fortran")
    assert exit_info.value.code == 2


@pytest.mark.slow
@pytest.mark.parametrize(
    ("language", "word"),
    [("c", "double"), ("julia", "end"), ("octave", "end"), ("rust", "fn"), ("rust", "Some"), ("modelica", "algorithm")],
)
def test_a_keyword_symbol_is_refused_by_name(language: str, word: str, tmp_path: Path) -> None:
    text = (CATALOG / "planetary_simple.yaml").read_text().replace("rA", word)
    path = tmp_path / "keyword.yaml"
    path.write_text(text)
    status, out, err = _run(str(path), "--emit", language)
    assert status == 2 and out == "" and "Traceback" not in err
    assert f"symbol '{word}'" in err and err.count("\n") == 1
    # Another language takes it.
    assert _run(str(path), "--emit", "octave" if language == "c" else "c")[0] == 0


@pytest.mark.slow
def test_a_train_driven_at_several_ports_has_its_region_choice(built: Callable[[str], Case]) -> None:
    case = built("sr20_differential")
    text = emit_code(case.result, "c")
    assert "double efficiency(double D_P, double eta_M, double omega_A, double omega_K, double tau_out)" in text
    assert all(f"double region_{r.number}(" in text for r in case.derived.regions)  # type: ignore[union-attr]
    assert case.classes >= 4  # regions reached by the random speeds, and none on the lines


# --------------------------------------------------------------------------- shell completion


def test_bash_completion_is_valid_and_knows_the_options(tmp_path: Path) -> None:
    status, script, err = _run("--completion", "bash")
    assert status == 0 and err == ""
    path = tmp_path / "derive.bash"
    path.write_text(script)
    assert subprocess.run(["bash", "-n", str(path)], capture_output=True, check=False).returncode == 0
    for option in ("--emit", "--python", "--state", "--catalog", "--completion", "--eval", "--latex"):
        assert option in script
    assert "tuplin" in script and "'!*.yaml'" in script

    def complete(*words: str) -> list[str]:
        line = " ".join(["derive", *words])
        program = (
            f"source {path}; COMP_WORDS=(derive {' '.join(words)}); COMP_CWORD={len(words)}; "
            f"COMP_LINE='{line}'; COMP_POINT={len(line)}; _shtab_derive; printf '%s\\n' \"${{COMPREPLY[@]}}\""
        )
        result = subprocess.run(["bash", "-c", program], capture_output=True, text=True, check=False, cwd=tmp_path)
        return result.stdout.split()

    assert "--emit" in complete("--em")
    assert set(complete("--emit", "")) == {*LANGUAGES, "fmu"}
    assert complete("--catalog", "tup") == ["tuplin"]
    (tmp_path / "train.yaml").write_text("")
    (tmp_path / "notes.txt").write_text("")
    offered = complete("")
    assert "train.yaml" in offered and "notes.txt" not in offered


@pytest.mark.parametrize("shell", ["zsh", "tcsh"])
def test_zsh_and_tcsh_completion(shell: str) -> None:
    status, script, _ = _run("--completion", shell)
    assert status == 0 and "--emit" in script and "tuplin" in script and "yaml" in script


def test_completion_knows_the_other_commands(tmp_path: Path) -> None:
    """`derive calibrate` and `derive search` complete as subcommands, with their own options
    and their topology file as a `.yaml` file."""
    status, script, _ = _run("--completion", "bash")
    assert status == 0
    path = tmp_path / "derive.bash"
    path.write_text(script)

    def complete(*words: str) -> list[str]:
        line = " ".join(["derive", *words])
        program = (
            f"source {path}; COMP_WORDS=(derive {' '.join(words)}); COMP_CWORD={len(words)}; "
            f"COMP_LINE='{line}'; COMP_POINT={len(line)}; _shtab_derive; printf '%s\\n' \"${{COMPREPLY[@]}}\""
        )
        result = subprocess.run(["bash", "-c", program], capture_output=True, text=True, check=False, cwd=tmp_path)
        return result.stdout.split()

    assert {"calibrate", "search"} <= set(complete("ca")) | set(complete("se")) | set(complete(""))
    assert "--fit" in complete("calibrate", "--f")
    assert complete("calibrate", "--catalog", "sr2") == ["sr20_differential"]
    assert "--target" in complete("search", "--ta")
    (tmp_path / "rig.yaml").write_text("")
    assert "rig.yaml" in complete("calibrate", "")
    status, zsh, _ = _run("--completion", "zsh")
    assert status == 0 and "calibrate" in zsh and "--target" in zsh
