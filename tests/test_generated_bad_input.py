"""A generated sweep of bad input: mutated train files and command lines, each answered
by the contract of docs/errors.md.

The generator is deterministic (a fixed seed, a fixed number of cases) and runs ``derive``
in this process (`harness.helpers.run_main`).  It covers each class of bad input whose
regression tests live in the files named after what they check (tests/test_train_entry_checks.py,
test_state_entry_checks.py, test_symbol_name_checks.py, test_option_checks.py,
test_output_targets.py): values of the wrong type, one item where a list is expected,
unknown keys at the top level and in entries, bad operating states, reserved names, YAML
tags a value does not fit, bad option values, outputs that name one file twice or an
input, and targets that cannot be written.

Every case must end cleanly: exit status 0 with an output; or 2 with a message line per
problem, each naming the file and where (``FILE:LINE: ENTRY: ...`` for the file, ``FILE:
OPTION: ...`` for the command line), one line when the mutation is one fault, nothing
written, and a refusal wherever the input has no meaning (an unknown key, a clash of
outputs); or 3 with the reason as the last line.  Never a traceback, never a warning, and
one item alone where a list is expected is answered as the list of that item.
"""

from __future__ import annotations

import copy
import os
import random
import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml
from harness.helpers import CATALOG, DATA, Result, entry_paths, run_main

SEED = 20250611
#: Cases per class: about 250 in all, a minute at most on one core.
PER_CLASS = {
    "wrong_type": 40,
    "one_for_a_list": 20,
    "unknown_key": 25,
    "state": 35,
    "reserved_name": 20,
    "tag": 12,
    "option": 50,
    "clash": 20,
    "unwritable": 20,
}

PAIR = yaml.safe_load((CATALOG / "simple_pair.yaml").read_text(encoding="utf-8"))
STATES = yaml.safe_load((DATA / "two_states.yaml").read_text(encoding="utf-8"))
BASES = {"pair": PAIR, "states": STATES}
PAIR_VALUES = ("r1=20", "r2=50", "eta_C=0.98")

WRONG_VALUES: tuple[Any, ...] = (
    None,
    True,
    [],
    {},
    [1, 2],
    {"a": 1},
    "x y",
    -3,
    0,
    3.5,
    float("inf"),
    "1e400",
    "",
    "nan",
    "r1 +",
    12345678901234567890,
)
#: Mappings whose keys are names the file defines (a new key defines a new entry).
NAME_TABLES = ("links", "gears", "couplings", "states", "values")
UNKNOWN_KEYS = ("gear_ratio", "colour", "brakes", "Input", "ratio", "link", "clutches")
RESERVED = (
    "PORTS",
    "ok",
    "shape",
    "result",
    "float",
    "lambda",
    "np",
    "input",
    "state",
    "CONDITIONS",
    "efficiency",
    "variant",
    "math",
    "None",
    "pi",
    "nan",
    "fn",
    "double",
    "end",
    "k",
)
TAGS = ("!!int abc", "!!float x", "!!bool maybe", "!!int [1]", "!!str {a: 1}", "!!map [1]", "!!seq 3", "!!null [2]")
LANGUAGES = ("c", "julia", "octave", "rust", "modelica")


@dataclass(frozen=True)
class Case:
    """One generated case: the file (``data`` dumped, or ``text`` as written), the command
    line (``{dir}``, ``{top}`` and ``{input}`` stand for a fresh folder, the input's folder
    and the input's path) and what to prepare first (``setup``: a symbolic link, a blocking
    file)."""

    name: str
    data: Any = None
    text: str | None = None
    args: tuple[str, ...] = ()
    setup: tuple[str, ...] = ()
    #: The mutation is one fault: a refusal is one line.
    single: bool = True
    #: Further input files (copies of the first) the command line names.
    extra_files: tuple[str, ...] = ()
    #: The same file written another way, which must get the same answer (one item alone
    #: and the list of that one item).
    twin: Any = None
    #: The answer must be a refusal (exit status 2): the input has no meaning.
    refused: bool = False


# --- the generator -----------------------------------------------------------------------------------------------


def _get(data: Any, path: tuple[Any, ...]) -> Any:
    for key in path:
        data = data[key]
    return data


def _set(data: Any, path: tuple[Any, ...], value: Any) -> Any:
    out = copy.deepcopy(data)
    _get(out, path[:-1])[path[-1]] = value
    return out


def _label(path: tuple[Any, ...]) -> str:
    return ".".join(map(str, path))


def _wrong_type(rng: random.Random, k: int) -> Case:
    base = rng.choice(list(BASES))
    paths = list(entry_paths(BASES[base]))
    path = rng.choice(paths)
    value = rng.choice(WRONG_VALUES)
    # A wrong value may spoil several entries that refer to it (a link's name): a few lines.
    return Case(f"wrong_type-{k:03d}-{base}-{_label(path)}", _set(BASES[base], path, value), single=False)


def _one_for_a_list(rng: random.Random, k: int) -> Case:
    base = rng.choice(list(BASES))
    lists = [p for p in entry_paths(BASES[base]) if isinstance(_get(BASES[base], p), list) and _get(BASES[base], p)]
    path = rng.choice(lists)
    first = _get(BASES[base], path)[0]
    state = ("--state", "reduction") if base == "states" and rng.random() < 0.5 else ()
    name = f"one_for_a_list-{k:03d}-{base}-{_label(path)}"
    twin = _set(BASES[base], path, [first])
    return Case(name, _set(BASES[base], path, first), args=state, single=False, twin=twin)


def _unknown_key(rng: random.Random, k: int) -> Case:
    base = rng.choice(list(BASES))
    # Entries of the schema, not the tables of names (a new key there is a new gear or state).
    mappings = [()] + [
        p for p in entry_paths(BASES[base]) if isinstance(_get(BASES[base], p), dict) and p[-1] not in NAME_TABLES
    ]
    path = rng.choice(mappings)
    data = copy.deepcopy(BASES[base])
    _get(data, path)[rng.choice(UNKNOWN_KEYS)] = rng.choice(["x", 3, [1], {"a": 1}])
    return Case(f"unknown_key-{k:03d}-{base}-{_label(path) or 'top'}", data, refused=True)


#: What a state's entry may be changed to (None: the key deleted): the reference link braked,
#: a mesh as a port, the input as the output, members that lock the train or free it, one
#: name for a list, unknown links.
STATE_CHANGES: dict[str, tuple[Any, ...]] = {
    "input": ("B", "K", "M1", "J", "Z", 0, None),
    "output": ("A", "M2", "Z", "B", None),
    "brake": ([0], ["r", "c"], [], "r", "c", ["zz"], ["s"], [["r"]]),
    "clutch": ([["c", "s"]], [["r", "r"]], "c", ["c", "s"], [["p", "c"]], [["zz", "c"]]),
    "free": (["p"], "p", ["s"], ["zz"]),
    "description": (["a", "list"], 3, "a state"),
}


def _state(rng: random.Random, k: int) -> Case:
    """The state ``reduction`` ({input: A, output: K, brake: [r]}) with one or two changes."""
    entry: dict[str, Any] = {"input": "A", "output": "K", "brake": ["r"]}
    for key in rng.sample(sorted(STATE_CHANGES), 1 if rng.random() < 0.7 else 2):
        value = rng.choice(STATE_CHANGES[key])
        if value is None:
            entry.pop(key, None)
        else:
            entry[key] = value
    data = copy.deepcopy(STATES)
    data["states"]["reduction"] = entry
    state = ("--state", "reduction") if rng.random() < 0.7 else ()
    return Case(f"state-{k:03d}", data, args=state, single=False)


def _reserved_name(rng: random.Random, k: int) -> Case:
    name = rng.choice(RESERVED)
    where = rng.choice(["radius", "efficiency", "coulomb"])
    data = copy.deepcopy(PAIR)
    if where == "radius":
        data["gears"][1]["radius"] = name
    elif where == "efficiency":
        data["couplings"]["C"] = {"type": "mesh", "gears": [1, 2], "efficiency": name}
    else:
        data["couplings"]["C"]["friction"]["coulomb"] = name
    output = rng.choice([("--python", "{dir}/m.py"), ("--emit", rng.choice(LANGUAGES)), ()])
    return Case(f"reserved_name-{k:03d}-{name}-{where}", data, args=output)


def _tag(rng: random.Random, k: int) -> Case:
    text = yaml.safe_dump(PAIR, sort_keys=False, width=1000)
    tagged = rng.choice(TAGS)
    old = rng.choice(["radius: r1", "radius: r2", "reference: 0", "degrees_of_freedom: 1", "name: Simple gear pair"])
    key = old.partition(":")[0]
    return Case(f"tag-{k:03d}-{key}", text=text.replace(old, f"{key}: {tagged}", 1), refused=True)


#: Sweep bounds: finite and drawable (kept), or not (refused).
GOOD_BOUNDS = ("10:30", "1/3:1/2")
BAD_BOUNDS = ("10:1e400", "inf:3", "nan:nan", "30:10", "10:10", "a:b", "10", ":", "-1e13:5", "10:10.00000000000001")


def _option(rng: random.Random, k: int) -> Case:
    """A command line with an option of the pair's train, good or bad (a bad one must be refused)."""
    kind = rng.choice(["plot", "plot", "vs", "eval", "eval", "port", "state", "emit", "at"])
    fig = rng.choice(["{dir}/fig.png", "{dir}/fig.png", "{dir}/fig.txt"])
    held = rng.choice(["eta_C=0.98", "eta_C=0.98", "eta_C=1.5", "eta_C=nan", "zz=3"])
    bounds = rng.choice(GOOD_BOUNDS + BAD_BOUNDS)
    good = bounds in GOOD_BOUNDS and fig.endswith(".png")
    if kind == "plot":
        name = rng.choice(["r1", "r1", "r2", "zz", ""])
        args: tuple[str, ...] = ("--plot", f"{name}={bounds}", "--at", "r2=50", held, "-o", fig)
        good = good and name in ("r1", "r2") and held == "eta_C=0.98"
    elif kind == "vs":
        other = rng.choice(["r1", "r2", "eta_C"])
        args = ("--plot", "r1=10:30", "--vs", f"{other}={bounds}", "--at", "eta_C=0.98", "-o", fig)
        good = good and other != "r1" and not (other == "eta_C" and bounds == "10:30")
    elif kind == "eval":
        value = rng.choice(["r1=nan", "r1=-1", "r1=1e400", "r1=abc", "r1", "eta_C=2", "zz=1", "r1=1/0", "r1=20"])
        args = ("--eval", value, *[v for v in PAIR_VALUES if not v.startswith(value.partition("=")[0] + "=")])
        good = value == "r1=20"
    elif kind == "port":
        option = rng.choice(["--input", "--output"])
        port = rng.choice(["A", "B", "Z", "C", "a b", ""])
        args = (option, port, *(("--eval", *PAIR_VALUES) if rng.random() < 0.5 else ()))
        good = port in ("A", "B")
    elif kind == "state":
        args, good = ("--state", rng.choice(["reduction", "nosuch", ""])), False  # the pair has no states
    elif kind == "emit":
        args, good = ("--emit", rng.choice(LANGUAGES), rng.choice(["--json", "--latex", "--eval"])), False
    else:
        args, good = ("--vs" if rng.random() < 0.5 else "--at", "r1=3"), False  # only with --plot
    return Case(f"option-{k:03d}-{kind}", copy.deepcopy(PAIR), args=args, refused=not good)


def _clash(rng: random.Random, k: int) -> Case:
    spelling = rng.choice(["same", "dotted", "double_slash", "symlink", "input", "input_dotted"])
    first = rng.choice(["--python", "-o"])
    second = "-o" if first == "--python" else "--python"
    target = {
        "same": "{dir}/out.py",
        "dotted": "{dir}/x/../out.py",
        "double_slash": "{dir}//out.py",
        "symlink": "{dir}/link.py",
        "input": "{input}",
        "input_dotted": "{top}/x/../train.yaml",
    }[spelling]
    args = (first, "{dir}/out.py", second, target) if not spelling.startswith("input") else (first, target)
    setup = ("symlink",) if spelling == "symlink" else ()
    return Case(f"clash-{k:03d}-{spelling}", copy.deepcopy(PAIR), args=args, setup=setup, refused=True)


def _unwritable(rng: random.Random, k: int) -> Case:
    where = rng.choice(["proc", "missing", "below_a_file", "folder", "out_proc", "out_below_a_file"])
    option = rng.choice(["-o", "--python"])
    target = {
        "proc": "/proc/out.txt",
        "missing": "{dir}/missing/deeper/out.txt",
        "below_a_file": "{dir}/blocker/out.txt",
        "folder": "{dir}",
    }.get(where)
    if where.startswith("out_"):
        folder = "/proc/some-dir" if where == "out_proc" else "{dir}/blocker/derivations"
        name, args, extra = f"unwritable-{k:03d}-{where}", ("--out", folder), ("second.yaml",)
        return Case(name, copy.deepcopy(PAIR), args=args, setup=("blocker",), extra_files=extra, refused=True)
    # `-o DIR` with one file writes its derivations into DIR (as --out DIR does): not a refusal.
    refused = not (where == "folder" and option == "-o")
    args = (option, str(target))
    return Case(f"unwritable-{k:03d}-{where}", copy.deepcopy(PAIR), args=args, setup=("blocker",), refused=refused)


GENERATORS: dict[str, Callable[[random.Random, int], Case]] = {
    "wrong_type": _wrong_type,
    "one_for_a_list": _one_for_a_list,
    "unknown_key": _unknown_key,
    "state": _state,
    "reserved_name": _reserved_name,
    "tag": _tag,
    "option": _option,
    "clash": _clash,
    "unwritable": _unwritable,
}


def generated() -> list[Case]:
    """The cases, the same on every run."""
    rng = random.Random(SEED)
    return [GENERATORS[kind](rng, k) for kind, count in PER_CLASS.items() for k in range(count)]


CASES = generated()


# --- running a case and checking its answer ----------------------------------------------------------------------


def _dump(data: Any) -> str:
    """``data`` as a train file, its innermost entries in flow style as the catalog writes them."""
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=1000, default_flow_style=None)


def _prepare(case: Case, tmp_path: Path) -> tuple[Path, list[str]]:
    """The file and the command line of ``case`` in ``tmp_path``."""
    path = tmp_path / "train.yaml"
    path.write_text(case.text if case.text is not None else _dump(case.data), encoding="utf-8")
    work = tmp_path / "work"
    (work / "x").mkdir(parents=True)
    (tmp_path / "x").mkdir()
    if "symlink" in case.setup:
        os.symlink(work / "out.py", work / "link.py")
    if "blocker" in case.setup:
        (work / "blocker").write_text("a file\n", encoding="utf-8")
    files = [str(path)]
    for extra in case.extra_files:
        (tmp_path / extra).write_bytes(path.read_bytes())
        files.append(str(tmp_path / extra))
    places = {"{dir}": str(work), "{top}": str(tmp_path), "{input}": str(path)}
    args = [re.sub(r"\{\w+\}", lambda m: places[m.group()], a) for a in case.args]
    return path, [*files, "--quiet", *args]


def _problem(result: Result, path: Path, case: Case, caught: list[warnings.WarningMessage]) -> str | None:
    """What is unclean about ``result`` (None: clean); ``caught``: the warnings it gave."""
    # The answer's own warnings (numpy's invalid values, matplotlib's), not a library's deprecations.
    shown = [w for w in caught if issubclass(w.category, (RuntimeWarning, UserWarning))]
    if result.timed_out:
        return "no answer (hang)"
    if "Traceback" in result.stderr:
        return "a traceback"
    if shown or "Warning" in result.stderr:
        return f"a warning: {shown[0].message if shown else result.stderr}"
    if case.refused and result.returncode != 2:
        return f"exit status {result.returncode} for input that has no meaning (expected a refusal, exit 2)"
    name = re.escape(str(path))
    # A problem of the file has its line and entry; one of the command line names its option.
    located = re.compile(rf"^([a-zA-Z ]+: )?{name}(:\d+: [^.\s-]|: --?[a-z][a-z-]*: )")
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    if result.returncode == 0:
        written = any(a in ("-o", "--python", "--out") for a in case.args)
        return None if result.stdout.strip() or written else "exit 0 and no output"
    if result.returncode == 2:
        if not lines:
            return "exit 2 and no message"
        unlocated = [line for line in lines if not located.match(line)]
        if unlocated:
            return f"a message line without FILE:LINE: ENTRY: (or FILE: OPTION:): {unlocated[0]!r}"
        if case.name.startswith("state") and any(re.search(rf"{name}:\d+: ports\b", line) for line in lines):
            return "a problem of a state at the top-level ports, not at the state's own entry"
        if case.single and len(lines) > 1:
            return f"{len(lines)} lines for one fault"
        return None
    if result.returncode == 3:
        last = (result.stdout.strip().splitlines() or [""])[-1]
        return None if re.match(rf"^derive: {name}: ", last) else f"exit 3 without a reason as the last line: {last!r}"
    return f"exit status {result.returncode}"


def _run(args: list[str]) -> tuple[Result, list[warnings.WarningMessage]]:
    """``derive ARGS`` in this process, every warning it gives recorded."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = run_main(args)
    return result, list(caught)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_generated_bad_input_is_answered_cleanly(tmp_path, case):
    path, args = _prepare(case, tmp_path)
    before = path.read_bytes()
    result, caught = _run(args)
    why = _problem(result, path, case, caught)
    assert why is None, f"{why}:\nderive {' '.join(args)}\n{result.describe()}"
    assert path.read_bytes() == before, "the input file was changed"
    if result.returncode == 2 and not case.name.startswith("state"):
        written = sorted(p.name for p in (tmp_path / "work").iterdir() if p.name not in ("x", "blocker", "link.py"))
        assert not written, f"files written although refused: {written}\n{result.describe()}"
    if case.twin is not None:
        other = tmp_path / "twin"
        other.mkdir()
        _, twin_args = _prepare(Case(case.name, case.twin, args=case.args), other)
        twin, _ = _run(twin_args)
        # The two files are laid out alike but not line for line: the answers are compared without lines.
        answers = [
            (r.returncode, r.stdout, re.sub(r":\d+: ", ": ", r.stderr.replace(str(d), "DIR")))
            for r, d in ((result, tmp_path), (twin, other))
        ]
        assert answers[0] == answers[1], f"one item alone is not its list:\n{result.describe()}\n{twin.describe()}"


def test_the_sweep_is_deterministic_and_covers_every_class():
    assert [c.name for c in generated()] == [c.name for c in CASES]
    assert len(CASES) == sum(PER_CLASS.values())
    assert {c.name.partition("-")[0] for c in CASES} == set(PER_CLASS)
