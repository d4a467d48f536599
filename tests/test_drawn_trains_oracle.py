"""Trains drawn by Hypothesis (tests/oracle/strategies.py) through ``derive`` and against
the independent oracle (tests/oracle/balance.py).

* The command line keeps its contract on every drawn train: ``derive FILE`` with plain
  output, ``--json``, ``--state S`` for each state (and ``--latex`` in the slow tier)
  exits 0, or 2 or 3 with every line of standard error a located refusal (``<kind>
  error: FILE``, and ``FILE:LINE: ENTRY:`` for topology, geometry and mobility
  errors); never a traceback, exit 1 or exit 4.
* The engine agrees with the oracle on the drawn trains, as tests/test_seeded_trains_oracle.py
  checks the seeded ones: every state, both input ports, speed ratio and efficiency at
  the drawn (exact, rational) design to a relative 1e-9, self-locking on both sides; and
  ``derive --eval`` prints the same numbers (its exit status 3 where the oracle finds the
  train self-locking).
* The same trains feed ``derive search`` (the drawn design is among the candidates for
  its own speed ratio, with the API's efficiency), ``--emit c`` and ``--emit rust``
  (the code compiles; skipped without a compiler) and ``--python`` (the module gives the
  API's efficiency and speed ratio).

The fast tier draws a handful of examples, the slow tier (``-m slow``) more; each with a
fixed seed and no example database, so every run draws the same examples, as the
derandomized ``davies`` profile does.  DAVIES_SYM_TRAIN_SEED=N draws with seed N
instead (both tiers).  Explicit examples of the fast tier: the stepped planet whose
second module is the dependent symbol (a loop closed by a module, which sympy's
``degree`` once failed on), and, in the contract and oracle checks, the trains written
by hand where drawn ones failed before (strategies.BY_HAND: a Tuplin train with one
annulus by teeth and a module symbol, a stepped planet and a Wolfrom set with module
symbols, each once exit 4; a symbol named ``Some``, whose Rust code once did not
compile, also in the check of the other languages).
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import math
import os
import re
import shutil
import subprocess
import tempfile
import warnings
from collections.abc import Callable, Iterator
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from harness.helpers import Result, run_main
from hypothesis import example, given, seed, settings
from oracle.balance import OracleError, SelfLocking, solve
from oracle.compare import LOCKING, OK, close, compare
from oracle.strategies import (
    BY_HAND,
    FAMILIES,
    QUICK_FAMILIES,
    Drawn,
    planetary_named_after_rust,
    stepped_two_modules,
    trains,
)

import davies_sym

#: DAVIES_SYM_TRAIN_SEED=N: draw with seed N (both tiers) instead of the fixed seeds.
ENV_SEED = os.environ.get("DAVIES_SYM_TRAIN_SEED", "").strip()
#: The fixed seeds of the two tiers: every run draws the same examples (no example
#: database), as the derandomized ``davies`` profile does.
FAST_SEED = 12
SLOW_SEED = 20261129
CC = shutil.which("cc") or shutil.which("gcc")
RUSTC = shutil.which("rustc") or next((p for p in ("/root/.cargo/bin/rustc",) if os.path.exists(p)), None)
#: One derive call that takes longer than this is a hang, not a slow machine.
HANG = 300.0

#: The kinds of refusal (docs/errors.md) and the ones that name the file's line and entry.
KINDS = ("YAML syntax", "topology", "geometry", "mobility", "input", "design")
LOCATED_KINDS = ("topology", "geometry", "mobility")


def fast(examples: int) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """A handful of examples, the same on every run (DAVIES_SYM_TRAIN_SEED draws others)."""

    def wrap(test: Callable[..., Any]) -> Callable[..., Any]:
        chosen = int(ENV_SEED) if ENV_SEED else FAST_SEED
        return seed(chosen)(settings(max_examples=examples, derandomize=False)(test))

    return wrap


def slow(examples: int) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """The slow tier: more examples, the same on every run (DAVIES_SYM_TRAIN_SEED draws others)."""

    def wrap(test: Callable[..., Any]) -> Callable[..., Any]:
        chosen = int(ENV_SEED) if ENV_SEED else SLOW_SEED
        return pytest.mark.slow(seed(chosen)(settings(max_examples=examples, derandomize=False)(test)))

    return wrap


@contextlib.contextmanager
def written(drawn: Drawn) -> Iterator[Path]:
    with tempfile.TemporaryDirectory(prefix="drawn-") as folder:
        path = Path(folder) / "train.yaml"
        path.write_text(drawn.yaml, encoding="utf-8")
        yield path


def derive(*args: object) -> Result:
    return run_main([str(a) for a in args], timeout=HANG)


# -- (a) the command line's contract --------------------------------------------------------


def contract_problems(result: Result, path: Path, call: str) -> list[str]:
    """What in ``result`` breaks the contract of docs/errors.md (empty: nothing)."""
    where = f"{call}: exit {result.returncode}"
    if result.timed_out:
        return [f"{call}: no answer within {HANG:.0f} s"]
    if "Traceback" in result.stderr or result.returncode not in (0, 2, 3):
        return [f"{where}\n{result.stderr[-2000:]}"]
    problems = []
    name = re.escape(str(path))
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    for line in lines:
        if line.startswith("derive: warning: "):
            if not re.match(rf"derive: warning: {name}:\d+: \S", line):
                problems.append(f"{where}: an unlocated warning: {line}")
            continue
        if result.returncode == 0:
            problems.append(f"{where}: a result with a message: {line}")
            continue
        kind = next((k for k in KINDS if line.startswith(f"{k} error: {path}")), None)
        if kind is None:
            problems.append(f"{where}: a refusal line that names no kind and file: {line}")
        elif kind in LOCATED_KINDS and not re.match(rf"{kind} error: {name}:\d+: [^:\s][^:]*: ", line):
            problems.append(f"{where}: a {kind} error without FILE:LINE: ENTRY: {line}")
    if result.returncode == 2 and not lines:
        problems.append(f"{where}: a refusal with nothing on standard error")
    if "--json" in call:
        try:
            answer = json.loads(result.stdout)
        except ValueError:
            problems.append(f"{where}: --json printed no JSON document: {result.stdout[:300]!r}")
        else:
            if result.returncode and answer.get("exit_status") != result.returncode:
                problems.append(f"{where}: --json says {answer.get('status')!r}, {answer.get('exit_status')}")
    return problems


def cli_problems(drawn: Drawn, latex: bool = False) -> list[str]:
    problems = []
    with written(drawn) as path:
        calls = [[], ["--json"], *([["--latex"]] if latex else [])] + [["--state", s] for s in drawn.engine_states()]
        for extra in calls:
            result = derive(path, "--quiet", *extra)
            problems += contract_problems(result, path, "derive FILE " + " ".join(extra))
    return problems


# -- (b) the oracle -----------------------------------------------------------------------------


def value_args(values: dict[str, Fraction]) -> list[str]:
    return [
        f"{k}={v.numerator}" if v.denominator == 1 else f"{k}={v.numerator}/{v.denominator}" for k, v in values.items()
    ]


def oracle_problems(drawn: Drawn) -> list[str]:
    """The engine (through tests/oracle/engine_adapter.py) and ``derive --eval`` against the oracle."""
    problems = [
        f"{o.state} in={o.input} {o.quantity}: {o.kind} {o.detail} engine {o.engine} oracle {o.oracle}"
        for o in compare(drawn.train, drawn.spelling)
        if o.kind not in (OK, LOCKING)
    ]
    if problems:
        return problems
    sp, spec = drawn.spelling, drawn.train.oracle()
    with written(drawn) as path:
        for state in drawn.train.oracle_states():
            engine_state = sp.engine_state(state.name)
            state_args = ["--state", engine_state] if engine_state else []
            for port, other in ((state.input, state.output), (state.output, state.input)):
                call = f"--eval --input {sp.ports[port]} {' '.join(state_args)}"
                result = derive(
                    path, "--quiet", *state_args, "--input", sp.ports[port], "--eval", *value_args(sp.values)
                )
                problems += contract_problems(result, path, call)
                try:
                    expected = solve(spec, port, state)
                    locking = None
                except SelfLocking as exc:
                    expected, locking = None, exc
                except OracleError as exc:
                    problems.append(f"{call}: the oracle fails: {exc}")
                    continue
                lines = result.stdout.splitlines()
                if locking is not None:
                    if result.returncode != 3 or "self-locks" not in result.stdout:
                        problems.append(f"{call}: the oracle finds it self-locking ({locking}), derive: {lines[-1:]}")
                    continue
                assert expected is not None
                if result.returncode != 0:
                    problems.append(
                        f"{call}: exit {result.returncode} where the oracle gives {float(expected.efficiency)}"
                    )
                    continue
                efficiency = float(lines[-1])
                if not close(efficiency, expected.efficiency):
                    problems.append(f"{call}: efficiency {efficiency}, oracle {float(expected.efficiency)}")
                ratio = (
                    solve(spec, port, state, lossless=True).speed_ratio * sp.orientation[port] * sp.orientation[other]
                )
                printed = float(lines[-2].rpartition(": ")[2])
                if not close(printed, ratio):
                    problems.append(f"{call}: speed ratio {printed}, oracle {float(ratio)}")
    return problems


# -- (c) search, other languages, the Python module ---------------------------------------------


def api_efficiency(path: Path, engine_state: str | None, values: dict[str, Fraction], port: str) -> float:
    """The API's efficiency (NaN where it refuses the design as not covered)."""
    train = davies_sym.load(str(path))
    variants = davies_sym.derive(train, state=engine_state) if engine_state else davies_sym.derive(train)
    try:
        return float(variants.evaluate(dict(values), port))
    except davies_sym.NotCoveredError:
        return math.nan


def search_problems(drawn: Drawn) -> list[str]:
    """``derive search`` for the drawn design's own speed ratios: the drawn tooth numbers
    are a candidate, with the oracle's ratio and the API's efficiency."""
    sp, spec = drawn.spelling, drawn.train.oracle()
    states = drawn.train.oracle_states()
    targets = []
    for state in states:
        ratio = solve(spec, state.input, state, lossless=True).speed_ratio
        ratio *= sp.orientation[state.input] * sp.orientation[state.output]
        text = f"{ratio.numerator}/{ratio.denominator}"
        engine_state = sp.engine_state(state.name)
        targets.append(f"{engine_state}={text}" if engine_state else text)
    free = [t for t in drawn.teeth if t in (drawn.independent or ())]
    bounds = [f"{t}={max(1, drawn.teeth[t] - 2)}:{drawn.teeth[t] + 2}" for t in free]
    problems = []
    with written(drawn) as path:
        # (a negative ratio alone, --target -5/2, once read as an option)
        args = ["search", path, "--target", *targets, "--teeth", *bounds, "--tolerance", "0"]
        args += ["--min-teeth", "1", "--top", "100000", "--json", "--quiet"]
        result = derive(*args)
        call = "derive " + " ".join(map(str, args))
        problems += contract_problems(result, path, call)
        if result.returncode != 0:
            return problems or [f"{call}: exit {result.returncode}: {result.stderr[-500:]}"]
        candidates = json.loads(result.stdout)["candidates"]
        mine = [c for c in candidates if all(c["teeth"].get(t) == drawn.teeth[t] for t in free)]
        locks = False
        for state in states:
            try:
                solve(spec, state.input, state)
            except SelfLocking:
                locks = True
        if locks:
            return problems  # a design that self-locks may well be left out
        if len(mine) != 1:
            return [*problems, f"{call}: the drawn design {drawn.teeth} is {len(mine)} times among the candidates"]
        for state, target in zip(states, targets, strict=True):
            engine_state = sp.engine_state(state.name)
            efficiency, ratio = mine[0]["efficiency"], mine[0]["speed_ratio_exact"]
            if engine_state is not None:
                efficiency, ratio = efficiency[engine_state], ratio[engine_state]
            expected = api_efficiency(path, engine_state, drawn.values, sp.ports[state.input])
            if not close(efficiency, expected):
                problems.append(f"{call}: {engine_state}: search's efficiency {efficiency}, the API's {expected}")
            if Fraction(ratio) != Fraction(target.rpartition("=")[2]):
                problems.append(f"{call}: {engine_state}: ratio {ratio}, oracle {target}")
    return problems


def first_state(drawn: Drawn) -> tuple[list[str], str | None]:
    engine_state = drawn.spelling.engine_state(drawn.train.oracle_states()[0].name)
    return (["--state", engine_state] if engine_state else []), engine_state


def emit_problems(drawn: Drawn, language: str) -> list[str]:
    """``--emit LANG`` exits 0 and the code compiles, or it refuses a name with a located message."""
    compiler = {"c": CC, "rust": RUSTC}[language]
    if compiler is None:
        pytest.skip(f"no compiler for {language}")
    state_args, _ = first_state(drawn)
    with written(drawn) as path:
        target = path.with_suffix(".c" if language == "c" else ".rs")
        result = derive(path, "--quiet", *state_args, "--emit", language, "-o", target)
        call = f"derive FILE --emit {language} {' '.join(state_args)}"
        problems = contract_problems(result, path, call)
        if result.returncode != 0:
            if result.returncode == 2 and "cannot be a name in the generated" not in result.stderr:
                problems.append(f"{call}: refused: {result.stderr.strip()[:500]}")
            return problems
        if language == "c":
            command = [compiler, "-std=c99", "-fsyntax-only", str(target)]
        else:
            command = [
                compiler,
                "--crate-type",
                "lib",
                "--emit",
                "metadata",
                "-o",
                str(target.with_suffix(".rmeta")),
                str(target),
            ]
        compiled = subprocess.run(command, capture_output=True, text=True, timeout=300, check=False)
        if compiled.returncode != 0:
            problems.append(f"{call}: the {language} code does not compile:\n{compiled.stderr[-2500:]}")
    return problems


def python_problems(drawn: Drawn) -> list[str]:
    """``--python``: the module's efficiency (both ports) and speed ratio at the drawn design
    are the API's."""
    state_args, engine_state = first_state(drawn)
    sp = drawn.spelling
    state = drawn.train.oracle_states()[0]
    with written(drawn) as path:
        target = path.with_name("drawn_module.py")
        result = derive(path, "--quiet", *state_args, "--python", target)
        call = f"derive FILE --python {' '.join(state_args)}"
        problems = contract_problems(result, path, call)
        if result.returncode != 0:
            if result.returncode == 2 and "cannot be a name" not in result.stderr:
                problems.append(f"{call}: refused: {result.stderr.strip()[:500]}")
            return problems
        spec = importlib.util.spec_from_file_location(f"drawn_module_{abs(hash(drawn.yaml))}", target)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        import inspect

        parameters = inspect.signature(module.efficiency).parameters
        values = {k: float(v) for k, v in sp.values.items() if k in parameters}
        for port in (state.input, state.output):
            expected = api_efficiency(path, engine_state, sp.values, sp.ports[port])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                got = float(module.efficiency(input=sp.ports[port], **values))
            if not ((math.isnan(got) and math.isnan(expected)) or close(got, expected)):
                problems.append(f"{call}: efficiency(input={sp.ports[port]!r}) = {got}, the API gives {expected}")
        geometry = {k: v for k, v in values.items() if k in inspect.signature(module.speed_ratio).parameters}
        ratio = solve(drawn.train.oracle(), state.input, state, lossless=True).speed_ratio
        ratio *= sp.orientation[state.input] * sp.orientation[state.output]
        got = float(module.speed_ratio(**geometry))
        if not close(got, ratio):
            problems.append(f"{call}: speed_ratio = {got}, the oracle gives {float(ratio)}")
    return problems


def check(problems: list[str], drawn: Drawn) -> None:
    assert not problems, "\n".join(problems) + f"\n--- the train ---\n{drawn!r}"


# -- the tests ----------------------------------------------------------------------------------


def by_hand(test: Callable[..., Any]) -> Callable[..., Any]:
    """``test`` with every train of strategies.BY_HAND as an explicit example."""
    for build in BY_HAND:
        test = example(drawn=build())(test)
    return test


STEPPED = stepped_two_modules()
STEPPED_Z4 = stepped_two_modules("[z1, z2, z3, m1, m2]")
STEPPED_SEARCH = stepped_two_modules(numeric_efficiency=True)


@fast(6)
@given(drawn=trains(QUICK_FAMILIES))
@example(drawn=STEPPED)
@by_hand
def test_drawn_trains_keep_the_command_line_contract(drawn: Drawn) -> None:
    check(cli_problems(drawn), drawn)


@slow(30)
@given(trains(FAMILIES))
def test_drawn_trains_keep_the_command_line_contract_many(drawn: Drawn) -> None:
    check(cli_problems(drawn, latex=True), drawn)


@fast(6)
@given(drawn=trains(QUICK_FAMILIES))
@example(drawn=STEPPED)
@example(drawn=STEPPED_Z4)
@by_hand
def test_drawn_trains_agree_with_the_oracle(drawn: Drawn) -> None:
    check(oracle_problems(drawn), drawn)


@slow(40)
@given(trains(FAMILIES))
def test_drawn_trains_agree_with_the_oracle_many(drawn: Drawn) -> None:
    check(oracle_problems(drawn), drawn)


@fast(2)
@given(trains(QUICK_FAMILIES, search=True).filter(lambda d: d.searchable))
@example(STEPPED_SEARCH)
def test_search_finds_the_drawn_design(drawn: Drawn) -> None:
    check(search_problems(drawn), drawn)


@slow(20)
@given(trains(QUICK_FAMILIES, search=True).filter(lambda d: d.searchable))
def test_search_finds_the_drawn_design_many(drawn: Drawn) -> None:
    check(search_problems(drawn), drawn)


@pytest.mark.parametrize("language", ["c", "rust"])
@fast(2)
@given(drawn=trains(QUICK_FAMILIES))
@example(drawn=STEPPED)
@example(drawn=planetary_named_after_rust())
def test_emitted_code_of_drawn_trains_compiles(language: str, drawn: Drawn) -> None:
    check(emit_problems(drawn, language), drawn)


@pytest.mark.parametrize("language", ["c", "rust"])
@slow(15)
@given(drawn=trains(FAMILIES))
def test_emitted_code_of_drawn_trains_compiles_many(language: str, drawn: Drawn) -> None:
    check(emit_problems(drawn, language), drawn)


@fast(3)
@given(drawn=trains(QUICK_FAMILIES))
@example(drawn=STEPPED)
def test_python_module_of_drawn_trains(drawn: Drawn) -> None:
    check(python_problems(drawn), drawn)


@slow(20)
@given(trains(FAMILIES))
def test_python_module_of_drawn_trains_many(drawn: Drawn) -> None:
    check(python_problems(drawn), drawn)
