"""Every file ``derive FILE --emit LANG`` writes compiles, or parses where no compiler is
installed, for every gear train of the catalog: each file, each state of a file with
states (``--state NAME``), a train driven at several ports as its regions.  The machine
files (``machine:``) have no ``--emit``: the command refuses them (exit 2), and that is
checked too.  Beside the catalog, a program written here holds the constants and
functions the printers write differently (pi and its fractions, e, Euler's gamma, the
golden ratio, sqrt(2), log(2), a number's sine, rational powers, ``!=`` ...), and a rack at
a 45-degree pressure angle brings sqrt(2) and pi/4 into a derived train.

- C: one ``cc -std=c99 -pedantic -Wall -Wextra -Werror -fsyntax-only`` over every file
  (strict C99's math.h has no ``M_PI``, ``M_SQRT2``, ``M_E`` ...); the program of constants
  is also built and called through ctypes, against sympy's values.
- Rust: one crate whose modules are the files, ``rustc --emit metadata -D warnings``
  (type-checked, so a name not in scope or a method on an untyped number fails).
- Julia: tree-sitter-julia; Octave: tree-sitter-matlab (the syntax MATLAB shares with
  Octave, so ``!=`` is an error there); Modelica: modelicalang (the Modelica 3.5 grammar,
  a PEG parser).  A tree-sitter tree must hold no ERROR or MISSING node; modelicalang
  raises on the first error.  Each parser must also refuse a broken file.
- Names: a parser does not resolve names, so in the Julia, Octave and Modelica files every
  name a function uses must be one of its arguments, a local it assigns or declares, a
  function of the file, or a keyword or function of the language (listed below): a
  constant the language does not have (Modelica has no ``pi``), or a statement it does
  not take inside a function (Julia's ``const``), fails.

A missing compiler or parser is a skip.  The Modelica parser, pure Python, takes ten
seconds over the catalog: that test is in the slow tier.  The deeper checks, each function against the
Python module at random designs, are tests/test_other_languages.py's (slow).
"""

from __future__ import annotations

import contextlib
import ctypes
import io
import os
import re
import shutil
import subprocess
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import sympy

from davies_sym.cli import main
from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.derived_result import DerivedResult, OneInputResult, SeveralInputResult
from davies_sym.emit.languages import LANGUAGES, TARGETS, emit_code
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.printers import rust_printer
from davies_sym.emit.languages.program import Argument, Kind, Program, Routine, Step
from davies_sym.topology.loader import load, loads
from davies_sym.topology.states import train_in_state

from conftest import MACHINE_FILES, TRAIN_FILES

ROOT = Path(__file__).resolve().parent.parent
CC = shutil.which("cc")
RUSTC = shutil.which("rustc") or next(
    (p for p in (os.path.expanduser("~/.cargo/bin/rustc"), "/root/.cargo/bin/rustc") if os.path.exists(p)), None
)
SUFFIX = {"c": ".c", "rust": ".rs", "julia": ".jl", "octave": ".m", "modelica": ".mo"}

# --------------------------------------------------------------------------- what is emitted


def _rack_at_45_degrees() -> str:
    text = (ROOT / "catalog" / "rack_pinion.yaml").read_text(encoding="utf-8")
    assert "pressure_angle: 20," in text
    return text.replace("pressure_angle: 20,", "pressure_angle: 45,")


x = sympy.Symbol("x")
#: name -> a real expression in x, each a constant or function the printers treat apart.
CONSTANT_FORMULAS: dict[str, sympy.Expr] = {
    "pi_alone": sympy.pi + x,
    "pi_half": sympy.pi / 2 + x,
    "one_over_pi": x / sympy.pi,
    "two_over_sqrt_pi": 2 / sympy.sqrt(sympy.pi) + x,
    "cos_pi_quarter_plus_x": sympy.cos(sympy.pi / 4 + x),
    "sqrt_two": sympy.sqrt(2) * x,
    "sqrt_half": x / sympy.sqrt(2),
    "log_two": sympy.log(2) * x,
    "e_times_x": sympy.E * x,
    "euler_gamma": sympy.EulerGamma * x,
    "golden_ratio": sympy.GoldenRatio + x,
    "sin_one": sympy.sin(1) * x,
    "sin_fifth": sympy.sin(sympy.Rational(1, 5)) + x,
    "thirds": sympy.Rational(1, 3) * x + x / 7 + 2 / x,
    "rational_power": sympy.Abs(x) ** sympy.Rational(2, 3),
    "half_to_the_x": sympy.Rational(1, 2) ** x,
    "pi_to_the_x": sympy.pi**x,
}


def _constants_program() -> Program:
    """A program of one routine per `CONSTANT_FORMULAS` entry, a test of ``!=`` and a
    choice whose branches hold pi and e."""
    arg = (Argument("x", Kind.REAL),)
    routines = [
        Routine(name, f"the constant {name}", arg, Kind.REAL, (), value) for name, value in CONSTANT_FORMULAS.items()
    ]
    routines.append(Routine("nonzero", "whether x is not 0", arg, Kind.BOOL, (), sympy.Ne(x, 0)))
    chosen = sympy.Piecewise((sympy.pi * x, sympy.Ne(x, 1)), (sympy.E, True))
    step = Step("chosen", Kind.REAL, chosen)
    routines.append(Routine("choice", "pi x, or e at x = 1", arg, Kind.REAL, (step,), sympy.Symbol("chosen") + 1))
    return Program("Constants", ("Constants and functions",), tuple(routines), "choice", ("x",), ())


def _derived() -> Iterator[tuple[str, DerivedResult]]:
    """(id, derived train) of every catalog gear train as ``derive FILE --emit LANG``
    writes it: a file with states once per ``--state NAME``."""
    for path in TRAIN_FILES:
        train = load(path)
        stem = Path(path).stem
        if len(train.ports.inputs) > 1:
            yield stem, SeveralInputResult(derive_several_inputs(train))
        elif (train.degrees_of_freedom or 1) > 1:
            continue  # no --emit for a train of several freedoms driven at one port (refused)
        elif train.states:
            for st in train.states:
                derived = derive_variants(train_in_state(train, st))
                yield f"{stem}[{st.name}]", OneInputResult(train, ((st.name, derived),), st.name)
        else:
            yield stem, OneInputResult(train, (("", derive_variants(train)),), None)
    rack = loads(_rack_at_45_degrees(), "rack_45.yaml")
    yield "rack_45_degrees", OneInputResult(rack, (("", derive_variants(rack)),), None)


@dataclass(frozen=True)
class Emitted:
    """The derived trains and a folder to write their code in."""

    derived: tuple[tuple[str, DerivedResult], ...]
    folder: Path

    def write(self, language: str) -> list[tuple[str, Path]]:
        """Every train's file in ``language`` and the program of constants: (id, path)."""
        folder = self.folder / language
        folder.mkdir(exist_ok=True)
        out = []
        texts = [(name, emit_code(d, language)) for name, d in self.derived]
        texts.append(("constants", TARGETS[language].write(_constants_program())))
        for k, (name, text) in enumerate(texts):
            stem = re.sub(r"\W", "_", name)
            path = folder / f"m{k:02d}_{stem}{SUFFIX[language]}"
            path.write_text(text, encoding="utf-8")
            out.append((name, path))
        return out


@pytest.fixture(scope="module")
def emitted(tmp_path_factory: pytest.TempPathFactory) -> Emitted:
    return Emitted(tuple(_derived()), tmp_path_factory.mktemp("emitted"))


def test_every_catalog_train_is_covered(emitted: Emitted) -> None:
    names = {name for name, _ in emitted.derived}
    for path in TRAIN_FILES:
        stem = Path(path).stem
        assert stem in names or any(n.startswith(f"{stem}[") for n in names), stem
    assert {"simpson[reverse]", "ravigneaux[first]", "sr20_differential", "worm_drive"} <= names


# --------------------------------------------------------------------------- C and Rust


def _fail(result: subprocess.CompletedProcess[str], what: str) -> str:
    return f"{what} failed (exit {result.returncode}):\n{(result.stderr + result.stdout)[-6000:]}"


@pytest.mark.skipif(CC is None, reason="no C compiler (cc)")
def test_c_compiles_as_strict_c99(emitted: Emitted, tmp_path: Path) -> None:
    assert CC is not None
    files = emitted.write("c")
    flags = ["-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror"]
    result = subprocess.run(
        [CC, *flags, "-fsyntax-only", *(str(p) for _, p in files)], capture_output=True, text=True, check=False
    )
    assert result.returncode == 0, _fail(result, "cc")
    # The constants have their values.
    constants = next(p for name, p in files if name == "constants")
    library = tmp_path / "constants.so"
    build = [CC, *flags, "-O1", "-shared", "-fPIC", "-o", str(library), str(constants), "-lm"]
    result = subprocess.run(build, capture_output=True, text=True, check=False)
    assert result.returncode == 0, _fail(result, "cc -shared")
    compiled = ctypes.CDLL(str(library))
    for name, value in [*CONSTANT_FORMULAS.items(), ("choice", sympy.pi * x + 1)]:
        function = getattr(compiled, name)
        function.argtypes, function.restype = [ctypes.c_double], ctypes.c_double
        for point in (0.7, 2.5):
            expected = float(value.subs(x, point).evalf(30))
            assert function(point) == pytest.approx(expected, rel=1e-15), name
    assert compiled.choice(1.0) == pytest.approx(float(sympy.E) + 1, rel=1e-15)


@pytest.mark.skipif(RUSTC is None, reason="rustc is not installed")
def test_rust_compiles(emitted: Emitted) -> None:
    assert RUSTC is not None
    files = emitted.write("rust")
    crate = files[0][1].parent / "lib.rs"
    crate.write_text("".join(f"pub mod {p.stem};\n" for _, p in files), encoding="utf-8")
    command = [RUSTC, "--edition", "2021", "--crate-type", "lib", "--crate-name", "emitted", "--emit", "metadata"]
    command += ["-D", "warnings", "--out-dir", str(crate.parent), str(crate)]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    assert result.returncode == 0, _fail(result, "rustc")


def test_rust_computes_roots_and_logarithms_of_numbers_exactly() -> None:
    """sqrt(2) is the method call on the typed number, not sympy's 15-digit Float
    (1.4142135623731); a number's method is called on an ``f64``: ``2.0.ln()`` does not
    compile (E0689), a rational receiver is parenthesised."""
    printer = rust_printer()
    assert printer.doprint(sympy.sqrt(2)) == "2_f64.sqrt()"
    assert printer.doprint(sympy.log(2)) == "2_f64.ln()"
    assert printer.doprint(sympy.sin(sympy.Rational(1, 5))) == "(1_f64/5.0).sin()"
    assert printer.doprint(sympy.pi) == "std::f64::consts::PI"


# --------------------------------------------------------------------------- Julia, Octave and Modelica


def _tree_errors(grammar: str) -> Callable[[str], list[str]]:
    """The ERROR and MISSING nodes of a text's tree-sitter parse with ``grammar``
    (``julia``, ``matlab``): where and what."""
    tree_sitter = pytest.importorskip("tree_sitter")
    module = pytest.importorskip(f"tree_sitter_{grammar}")
    parser = tree_sitter.Parser(tree_sitter.Language(module.language()))

    def errors(text: str) -> list[str]:
        source = text.encode("utf-8")
        found, stack = [], [parser.parse(source).root_node]
        while stack:
            node = stack.pop()
            if node.is_error or node.is_missing:
                row, column = node.start_point
                what = f"{'MISSING' if node.is_missing else 'ERROR'} {node.type}"
                found.append(f"{row + 1}:{column + 1} {what} {source[node.start_byte : node.end_byte][:60]!r}")
            elif node.has_error:
                stack.extend(node.children)
        return found

    return errors


def _modelica_errors() -> Callable[[str], list[str]]:
    """The syntax error of a Modelica text, as modelicalang's parser says it (none: [])."""
    arpeggio = pytest.importorskip("arpeggio")
    syntax = pytest.importorskip("modelicalang").latest.Syntax
    with syntax:  # modelicalang's grammar functions are read inside this block only

        def whole_file() -> Any:  # a rule's name must differ from the grammar's (arpeggio resolves by name)
            return syntax.stored_definition, arpeggio.EOF

        parser = arpeggio.ParserPython(whole_file, comment_def=syntax.COMMENT)

    def errors(text: str) -> list[str]:
        try:
            parser.parse(text)
        except arpeggio.NoMatch as exc:
            return [str(exc)]
        return []

    return errors


#: What a function may use besides its arguments, its locals and the file's functions.
LANGUAGE_NAMES = {
    "julia": {"if", "elseif", "else", "end", "return", "true", "false", "NaN", "Inf", "pi"},
    "octave": {"if", "elseif", "else", "end", "true", "false", "NaN", "Inf", "inf", "pi"},
    "modelica": {"if", "then", "elseif", "else", "and", "or", "not", "true", "false"},
}
FUNCTIONS = {"abs", "sqrt", "exp", "log", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh"}
#: A function's head and its last line, per language (groups: name, arguments).
HEADS = {
    "julia": (r"^function (\w+)\(([^)]*)\)$", r"^end$"),
    "octave": (r"^function \w+ = (\w+)\(([^)]*)\)$", r"^end$"),
    "modelica": (r'^  function (\w+) ".*"$', r"^  end {name};$"),
}
COMMENT = {"julia": "#", "octave": "%", "modelica": "//"}
_NAME = re.compile(r"(?<![\w.])[A-Za-z_]\w*")


def _unresolved(text: str, language: str) -> list[str]:
    """Names a function of the file uses that it does not have (see the module's docstring)."""
    lines = text.split("\n")
    head, last = HEADS[language]
    functions = {m.group(1) for line in lines if (m := re.match(head, line))}
    known = LANGUAGE_NAMES[language] | FUNCTIONS | functions
    wrong = []
    k = 0
    while k < len(lines):
        match = re.match(head, lines[k])
        k += 1
        if not match:
            continue
        name = match.group(1)
        own = set() if language == "modelica" else set(_NAME.findall(match.group(2).replace("::Integer", "")))
        body = []
        while not re.match(last.format(name=name), lines[k]):
            line = lines[k].split(COMMENT[language])[0].strip()
            k += 1
            if language == "modelica":
                declared = re.fullmatch(r"(?:input |output )?(?:Real|Integer|Boolean) (\w+);", line)
                if declared:
                    own.add(declared.group(1))
                    continue
                if line in ("protected", "algorithm"):
                    continue
            else:
                assigned = re.match(r"(\w+) = ", line)
                own |= {assigned.group(1)} if assigned else set()
            body.append(line)
        used = {n for line in body for n in _NAME.findall(line)}
        wrong += [f"{name}: {n}" for n in sorted(used - own - known)]
    return wrong


def _unresolved_in(language: str) -> Callable[[str], list[str]]:
    return lambda text: _unresolved(text, language)


def _check_parsed(language: str, files: list[tuple[str, Path]], errors: Callable[[str], list[str]]) -> None:
    failures = []
    for name, path in files:
        text = path.read_text(encoding="utf-8")
        found = [f"syntax: {e}" for e in errors(text)] + [f"name: {e}" for e in _unresolved(text, language)]
        failures += [f"{name} ({path.name}) {e}" for e in found[:5]]
    assert not failures, f"{len(failures)} faults in the {language} files:\n" + "\n".join(failures)


#: Per language, a text of the file of constants and that text broken: each parser must
#: refuse the syntax break, the name check the names (the faults these files once had:
#: Julia's ``const pi = ...`` in a function, Octave's ``!=``, Modelica's ``pi``).
SYNTAX_BREAKS = {
    "julia": ("    return ", "    return )"),
    "octave": (" ~= ", " != "),
    "modelica": (" := ", " = "),
}
NAME_BREAKS = {
    "julia": ("    return ", "    const pi = 3.1415926535897932\n    return "),
    "octave": ("  result = ", "  result = undefined_name + "),
    "modelica": (" := ", " := pi + "),
}


@pytest.mark.parametrize("language", ["julia", "octave", pytest.param("modelica", marks=pytest.mark.slow)])
def test_files_parse_and_every_name_resolves(emitted: Emitted, language: str) -> None:
    errors = _modelica_errors() if language == "modelica" else _tree_errors(language.replace("octave", "matlab"))
    files = emitted.write(language)
    _check_parsed(language, files, errors)
    text = next(p for name, p in files if name == "constants").read_text(encoding="utf-8")
    for (good, bad), check in ((SYNTAX_BREAKS[language], errors), (NAME_BREAKS[language], _unresolved_in(language))):
        assert good in text and check(text.replace(good, bad, 1)), (language, bad)


# --------------------------------------------------------------------------- names


def _program_with_parameter(name: str, value: sympy.Expr) -> Program:
    arg = (Argument(name, Kind.REAL),)
    return Program("Named", ("named",), (Routine("value", "a value", arg, Kind.REAL, (), value),), "value", (name,), ())


@pytest.mark.parametrize("language", ["julia", "octave"])
def test_a_parameter_may_take_the_name_of_a_function_the_file_does_not_call(language: str) -> None:
    """A helix angle ``beta``, a lead angle ``gamma`` (catalog/worm_drive.yaml): the
    printer writes functions of those names, but the file calls none; a parameter named
    ``log`` where the file calls log is refused."""
    for name in ("beta", "gamma"):
        symbol = sympy.Symbol(name)
        text = TARGETS[language].write(_program_with_parameter(name, 2 * sympy.cos(symbol)))
        assert f"value({name})" in text
    log = sympy.Symbol("log")
    with pytest.raises(RefusedName, match="'log'"):
        TARGETS[language].write(_program_with_parameter("log", sympy.log(log + 1)))


# --------------------------------------------------------------------------- the command line


def _run(*args: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main([*args, "--quiet"])
    return status, out.getvalue(), err.getvalue()


def test_the_command_writes_what_is_checked(emitted: Emitted) -> None:
    """``derive FILE --emit LANG --state NAME`` writes the text the tests above check."""
    derived = dict(emitted.derived)
    for name, language in (("simpson[reverse]", "octave"), ("worm_drive", "julia"), ("sr20_differential", "rust")):
        stem, _, state = name.partition("[")
        path = str(ROOT / "catalog" / f"{stem}.yaml")
        status, out, err = _run(path, "--emit", language, *(("--state", state.rstrip("]")) if state else ()))
        assert status == 0, err
        assert out == emit_code(derived[name], language)


@pytest.mark.parametrize("path", MACHINE_FILES, ids=lambda p: Path(p).stem)
def test_a_machine_file_has_no_emit(path: str) -> None:
    for language in LANGUAGES:
        status, out, err = _run(path, "--emit", language)
        assert status == 2 and out == "" and "--emit is for gear trains" in err and "Traceback" not in err
