"""Hostile and broken input: YAML attacks, bad numbers, output safety, exit statuses.

Required behaviour (the project's issue on hostile input):

- a topology file that YAML cannot safely read (unknown or Python tags, merge keys,
  alias bombs, 10,000 levels of nesting, 50 MB, a 2 MB single entry, bytes that are not
  UTF-8, a byte-order mark, nothing, a list or a scalar instead of a mapping, a key given
  twice) gives exit status 2 while the file is read, never after a derivation (the message
  names the bound that was hit: the file's size, its nesting depth, its number of
  entries), one short message naming the file (and the line where one is meaningful),
  never a traceback and never the huge value echoed back;
- numbers a train cannot have (a radius of -40, 0, oo, nan, inf, .nan, .inf, 1e400, an
  annulus smaller than its planet; ``--eval`` efficiencies outside (0, 1], a negative or
  non-finite radius) give exit status 2 with a message naming the entry;
- output never destroys input: ``-o`` into a missing or unwritable folder is a clear
  refusal; ``-o``/``--python`` onto the input file (by any path) is refused and the input
  keeps its bytes; ``--out DIR`` never overwrites an input that lives in DIR; a refused
  ``--eval`` leaves an existing ``--python`` target untouched (refusals come before any
  write);
- exit statuses: 0 a result, 2 bad input, 3 a valid design the formulas do not cover
  (a self-locking train: the last line is a one-line reason, never a number and never an
  efficiency outside (0, 1]).
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest
from harness.helpers import (
    CATALOG,
    HANG_GUARD,
    Result,
    assert_not_executed,
    assert_refused,
    run_cli,
    run_main,
    skip_slow_unless_full,
)

from davies_sym.topology.documents import MAX_FILE_BYTES
from davies_sym.topology.yaml_source import MAX_DEPTH, MAX_NODES

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
TUPLIN = (CATALOG / "tuplin.yaml").read_text(encoding="utf-8")
RADIUS_LINE = "  1: {link: 1, radius: r1}"  # line 11 of simple_pair.yaml

#: A hang guard only, never a claim about speed: a run still going after this long is killed
#: (and fails); how little work a refusal takes is asserted as the bound it names (`READ_BOUNDS`).
KILL_AFTER = HANG_GUARD
#: The attacks in a fresh process run with this address-space limit: one that expanded the
#: document in memory would fail in its own process instead of starving the machine.
ATTACK_MEMORY = 2 * 1024**3
#: The refusal happens while the file is read: the message begins with the reading stage's kind.
READING_STAGE = re.compile(r"^(YAML syntax error|topology error): ")


def simple_pair_with(old: str, new: str) -> str:
    assert old in SIMPLE_PAIR, old
    return SIMPLE_PAIR.replace(old, new, 1)


def write(tmp_path: Path, name: str, content: str | bytes) -> Path:
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return path


@pytest.fixture(autouse=True)
def _extended_cases_on_request(request: pytest.FixtureRequest) -> None:
    skip_slow_unless_full(request)


# --- YAML attacks -------------------------------------------------------------------------------------------


def _alias_bomb() -> str:
    lines = ['a0: &a0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for i in range(1, 10):
        lines.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]")
    return SIMPLE_PAIR + "notes_bomb:\n  " + "\n  ".join(lines) + "\n"


def _fifty_megabytes() -> bytes:
    padding = ("# " + "x" * 98 + "\n").encode() * (50 * 1024 * 1024 // 100)
    return SIMPLE_PAIR.encode() + padding


# name -> (content, line of the problem where one is meaningful or None, needs a fresh process)
YAML_ATTACKS: dict[str, tuple[object, int | None, bool]] = {
    "python_object_apply_tag": (
        simple_pair_with(RADIUS_LINE, '  1: {link: 1, radius: !!python/object/apply:os.system ["touch {m}"]}'),
        11,
        False,
    ),
    "python_name_tag": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: !!python/name:os.system }"), 11, False),
    "unknown_local_tag": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: !gear r1}"), 11, False),
    "merge_key": (simple_pair_with("  2: {link: 2, radius: r2}", "  2: {<<: {link: 2}, radius: r2}"), 12, False),
    "merge_key_with_anchor": (
        simple_pair_with(
            "  1: {link: 1, radius: r1}\n  2: {link: 2, radius: r2}",
            "  1: &g {link: 1, radius: r1}\n  2:\n    <<: *g\n    link: 2",
        ),
        13,
        False,
    ),
    "alias_bomb": (_alias_bomb(), None, True),
    "deep_nesting": (SIMPLE_PAIR + "notes: " + "[" * 10000 + "]" * 10000 + "\n", 27, True),
    "fifty_megabytes": (_fifty_megabytes(), None, True),
    "two_megabyte_entry": (simple_pair_with("name: Simple gear pair", "name: " + "x" * (2 * 1024 * 1024)), None, True),
    "two_megabyte_number": (
        simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: " + "7" * (2 * 1024 * 1024) + "}"),
        None,
        True,
    ),
    "not_utf8": (
        simple_pair_with("name: Simple gear pair", "name: Simple gear pair caf\udce9").encode(
            "utf-8", errors="surrogateescape"
        ),
        None,
        False,
    ),
    "byte_order_mark": (b"\xef\xbb\xbf" + SIMPLE_PAIR.encode(), None, False),
    "utf16": (SIMPLE_PAIR.encode("utf-16"), None, False),
    "empty": (b"", None, False),
    "comments_only": (b"# nothing here\n\n", None, False),
    "list": ("- format: 1\n- name: x\n", None, False),
    "scalar": ("just some text\n", None, False),
    "null_document": ("~\n", None, False),
    "two_documents": (SIMPLE_PAIR + "---\n" + SIMPLE_PAIR, 27, False),
    "duplicate_top_level_key": (simple_pair_with("source:", "name: Another name\nsource:"), 4, False),
    "duplicate_gear": (
        simple_pair_with("  2: {link: 2, radius: r2}", "  2: {link: 2, radius: r2}\n  2: {link: 2, radius: r3}"),
        13,
        False,
    ),
    "duplicate_key_in_entry": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: r1, radius: r9}"), 11, False),
    "control_character": (simple_pair_with("name: Simple gear pair", "name: Simple \x07 gear pair"), 3, False),
}


#: The bound each large attack hits, as its message names it: the work done is bounded by it,
#: whatever the machine's load (the file read at most to its size limit, the document
#: converted at most to its depth and entry limits).
READ_BOUNDS = {
    "alias_bomb": f"more than {MAX_NODES} entries through aliases",
    "deep_nesting": f"nests deeper than {MAX_DEPTH} levels",
    "fifty_megabytes": f"larger than {MAX_FILE_BYTES // 1000} kB",
    "two_megabyte_entry": f"larger than {MAX_FILE_BYTES // 1000} kB",
    "two_megabyte_number": f"larger than {MAX_FILE_BYTES // 1000} kB",
}


@pytest.mark.parametrize("attack", list(YAML_ATTACKS))
def test_yaml_attack_gives_one_short_clear_refusal(tmp_path, attack):
    content, line, fresh = YAML_ATTACKS[attack]
    marker = tmp_path / "MARKER"
    if isinstance(content, str):
        content = content.replace("{m}", str(marker))
    path = write(tmp_path, f"{attack}.yaml", content)  # type: ignore[arg-type]
    args = [str(path), "--quiet"]
    result = run_cli(args, timeout=KILL_AFTER, memory=ATTACK_MEMORY) if fresh else run_main(args, timeout=KILL_AFTER)
    assert_not_executed(marker, result=result)
    assert_refused(result, path, line=line is not None, max_lines=None)
    assert READING_STAGE.match(result.stderr), f"not refused while reading the file:\n{result.describe()}"
    if attack in READ_BOUNDS:
        assert READ_BOUNDS[attack] in result.stderr, f"the message names no bound:\n{result.describe()}"
    if line is not None:
        assert re.search(re.escape(str(path)) + f":{line}:", result.stderr), (
            f"the message does not give line {line}:\n{result.describe()}"
        )


# --- bad numbers --------------------------------------------------------------------------------------------

BAD_RADII = [
    "-40",
    "0",
    "oo",
    "-oo",
    "zoo",
    "nan",
    "inf",
    ".nan",
    ".inf",
    "-.inf",
    "1e400",
    "1.0e+400",
    "1/0",
    "-r1",
    "0*r1",
    "r1 - r1",
]


@pytest.mark.parametrize("radius", BAD_RADII)
def test_impossible_radius_is_refused_with_the_entry(tmp_path, radius):
    path = write(tmp_path, "pair.yaml", simple_pair_with(RADIUS_LINE, f"  1: {{link: 1, radius: {radius}}}"))
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1.radius",))
    assert ":11:" in result.stderr, result.describe()


@pytest.mark.parametrize(
    ("entry", "old", "new"),
    [
        ("gears.1.module", RADIUS_LINE, "  1: {link: 1, teeth: 20, module: -2}"),
        ("gears.1.module", RADIUS_LINE, "  1: {link: 1, teeth: 20, module: .nan}"),
        ("gears.1.teeth", RADIUS_LINE, "  1: {link: 1, teeth: 0, module: 2}"),
        ("couplings.C.friction.coulomb", "friction: {coulomb: zeta_C}", "friction: {coulomb: -1}"),
        ("couplings.C.friction.coulomb", "friction: {coulomb: zeta_C}", "friction: {coulomb: .inf}"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: 0"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: -0.5"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: .nan"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: [0.98, 1.5]"),
    ],
    ids=[
        "module_negative",
        "module_nan",
        "teeth_zero",
        "coulomb_negative",
        "coulomb_inf",
        "efficiency_zero",
        "efficiency_negative",
        "efficiency_nan",
        "efficiency_pair_above_one",
    ],
)
def test_impossible_coefficient_is_refused_with_the_entry(tmp_path, entry, old, new):
    path = write(tmp_path, "pair.yaml", simple_pair_with(old, new))
    assert_refused(run_main([str(path), "--quiet"]), path, (entry,))


def test_annulus_smaller_than_its_planet_is_refused(tmp_path):
    text = TUPLIN.replace("1: {link: 1, radius: r1, internal: true}", "1: {link: 1, radius: 10, internal: true}")
    text = text.replace("3: {link: 3/4, radius: r3}", "3: {link: 3/4, radius: 15}")
    path = write(tmp_path, "tuplin.yaml", text)
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1", "gears.3", "couplings.C"), max_lines=None)


@pytest.mark.parametrize(
    "value",
    [
        "eta_C=1.5",
        "eta_C=0",
        "eta_C=-0.5",
        "eta_C=nan",
        "r1=-3",
        "r1=0",
        "r1=nan",
        "r1=oo",
        "r1=inf",
        "r1=zoo",
        "r1=1/0",
        "r1=-oo",
    ],
)
def test_impossible_eval_value_is_refused_with_the_name(tmp_path, value):
    path = write(tmp_path, "pair.yaml", SIMPLE_PAIR)
    name = value.partition("=")[0]
    others = [v for v in ("r1=20", "r2=50", "eta_C=0.98") if not v.startswith(name + "=")]
    result = run_main([str(path), "--quiet", "--eval", value, *others])
    assert_refused(result, path, ("--eval",), line=False)
    assert name in result.stderr, result.describe()
    assert result.stdout == "", "a number was printed although a value was refused"


# --- output safety ------------------------------------------------------------------------------------------


def _input(tmp_path: Path, name: str = "pair.yaml") -> tuple[Path, bytes]:
    path = write(tmp_path, name, SIMPLE_PAIR)
    return path, path.read_bytes()


def _assert_clean_refusal(result: Result, *words: str) -> None:
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode == 2, result.describe()
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected one line:\n{result.describe()}"
    if words:
        assert any(w in result.stderr for w in words), f"the message names none of {words}:\n{result.describe()}"


@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_into_a_missing_folder_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    target = tmp_path / "missing" / "deeper" / "out.py"
    result = run_main([str(path), "--quiet", option, str(target)])
    _assert_clean_refusal(result, str(target.parent), str(target))
    assert not target.parent.exists()


@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_below_a_regular_file_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    blocker = write(tmp_path, "blocker", "not a folder\n")
    result = run_main([str(path), "--quiet", option, str(blocker / "out.py")])
    _assert_clean_refusal(result, str(blocker))
    assert blocker.read_text() == "not a folder\n"


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root ignores folder permissions")
@pytest.mark.parametrize("option", ["-o", "--python", "--out"])
def test_output_into_a_read_only_folder_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        target = folder if option == "--out" else folder / "out.py"
        result = run_main([str(path), "--quiet", option, str(target)])
        _assert_clean_refusal(result, str(folder))
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(0o755)


@pytest.mark.parametrize("how", ["same_path", "relative", "dot_segments", "symlink", "hard_link"])
@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_onto_the_input_is_refused_and_the_input_keeps_its_bytes(tmp_path, monkeypatch, option, how):
    path, before = _input(tmp_path)
    monkeypatch.chdir(tmp_path)
    target = {
        "same_path": str(path),
        "relative": "pair.yaml",
        "dot_segments": str(tmp_path / "." / "x" / ".." / "pair.yaml"),
        "symlink": str(tmp_path / "link.yaml"),
        "hard_link": str(tmp_path / "hard.yaml"),
    }[how]
    (tmp_path / "x").mkdir()
    if how == "symlink":
        os.symlink(path, target)
    if how == "hard_link":
        os.link(path, target)
    result = run_main([str(path), "--quiet", "--json", option, target])
    assert path.read_bytes() == before, "the input file was overwritten"
    _assert_clean_refusal(result, str(path), target)


@pytest.mark.parametrize("name", ["pair.py", "pair.tex"])
def test_out_dir_never_overwrites_an_input_in_that_folder(tmp_path, name):
    """``derive d/pair.py --out d`` would write d/pair.tex and d/pair.py: the input must survive."""
    folder = tmp_path / "d"
    folder.mkdir()
    path, before = _input(folder, name)
    result = run_cli([str(path), "--quiet", "--out", str(folder)], timeout=KILL_AFTER)
    assert path.read_bytes() == before, f"--out overwrote its own input {path}:\n{result.describe()}"
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode in (0, 2), result.describe()


def test_out_dir_with_two_inputs_of_one_name_does_not_overwrite_an_input(tmp_path):
    """Two inputs ``a/pair.py`` and ``b/pair.yaml`` with ``--out a``: the module of b must not replace a's input."""
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first, before = _input(tmp_path / "a", "pair.py")
    second, _ = _input(tmp_path / "b", "pair.yaml")
    result = run_cli([str(first), str(second), "--quiet", "--out", str(tmp_path / "a")], timeout=KILL_AFTER)
    assert first.read_bytes() == before, f"an input was overwritten:\n{result.describe()}"
    assert "Traceback" not in result.stderr, result.describe()


KNOWN_MODULE = "# written by the user before the run\nKNOWN = 1\n"


@pytest.mark.parametrize(
    "bad",
    [
        ["--eval", "nosuch=3", "r1=20", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=abc", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=-3", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=20", "r2=50"],
        ["--eval", "r1", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=20", "r2=50", "eta_C=0.98", "--input", "Z"],
    ],
    ids=["unknown_name", "not_a_number", "negative_radius", "missing_value", "no_equals", "bad_port"],
)
def test_refused_eval_leaves_an_existing_module_untouched(tmp_path, bad):
    path, _ = _input(tmp_path)
    module = write(tmp_path, "m.py", KNOWN_MODULE)
    result = run_main([str(path), "--quiet", "--python", str(module), *bad])
    assert module.read_text(encoding="utf-8") == KNOWN_MODULE, f"m.py was rewritten:\n{result.describe()}"
    assert_refused(result, path, ("--eval", "--input"), line=False)


def test_refused_plot_writes_no_figure_and_keeps_an_existing_one(tmp_path):
    path, _ = _input(tmp_path)
    figure = write(tmp_path, "fig.png", b"not really a png")
    result = run_main([str(path), "--quiet", "--plot", "r1=10:30", "--at", "r2=-50", "eta_C=0.98", "-o", str(figure)])
    assert figure.read_bytes() == b"not really a png"
    assert_refused(result, path, ("--at",), line=False)


def test_no_temporary_files_are_left_behind_by_a_refusal(tmp_path):
    path, _ = _input(tmp_path)
    run_main([str(path), "--quiet", "--json", "-o", str(tmp_path / "missing" / "out.json")])
    run_main([str(path), "--quiet", "--python", str(tmp_path / "m.py"), "--eval", "r1=oops()"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.yaml"]


# --- exit statuses ------------------------------------------------------------------------------------------

SELF_LOCKING = ["--eval", "r1=40", "r2=60", "r3=15", "r4=35", "eta_C=0.7", "eta_D=0.7"]
FLOAT = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?(nan|inf|oo|zoo)$", re.IGNORECASE)


def _numbers(text: str) -> list[float]:
    """Every stdout line that is a bare number."""
    return [
        float(line.strip().replace("zoo", "nan").replace("oo", "inf"))
        for line in text.splitlines()
        if FLOAT.match(line.strip())
    ]


@pytest.mark.parametrize("ports", [["--input", "B"], ["--output", "A"]], ids=["input_B", "output_A"])
def test_self_locking_design_exits_3_with_a_reason(tmp_path, ports):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", *ports, *SELF_LOCKING])
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode == 3, f"a self-locking design must exit 3:\n{result.describe()}"
    lines = [line for line in result.stdout.splitlines() if line.strip()]
    assert lines, result.describe()
    last = lines[-1].strip()
    assert not FLOAT.match(last), f"the last line is a number, not a reason: {last!r}"
    assert re.search(r"self-lock", last, re.IGNORECASE), f"the last line does not say why: {last!r}"
    outside = [v for v in _numbers(result.stdout) if not 0 < v <= 1]
    assert not outside, f"an efficiency outside (0, 1] was printed: {outside}"


def test_admissible_design_exits_0_with_the_efficiency_last(tmp_path):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", "--eval", "r1=40", "r2=60", "r3=15", "r4=35", "eta_C=0.99", "eta_D=0.99"])
    assert result.returncode == 0, result.describe()
    value = float(result.stdout.splitlines()[-1])
    assert value == pytest.approx(0.9462, abs=5e-5)


def test_bad_input_exits_2_and_prints_nothing_on_stdout(tmp_path):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", "--eval", "r9=40"])
    assert_refused(result, path, ("--eval",), line=False)
    assert result.stdout == ""


def test_several_problems_give_one_line_each(tmp_path):
    text = simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: -40}")
    text = text.replace("  2: {link: 2, radius: r2}", "  2: {link: 2, radius: 0}")
    path = write(tmp_path, "pair.yaml", text)
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1.radius",), max_lines=2)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 2, result.describe()
    assert re.search(re.escape(str(path)) + r":11: gears\.1\.radius: ", lines[0]), result.describe()
    assert re.search(re.escape(str(path)) + r":12: gears\.2\.radius: ", lines[1]), result.describe()


def test_fresh_process_refusal_has_the_same_shape(tmp_path):
    """The contract holds for the real command (exit status of the process, not of ``main``)."""
    path = write(tmp_path, "pair.yaml", simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: -40}"))
    result = run_cli([str(path), "--quiet"], timeout=KILL_AFTER)
    assert_refused(result, path, ("gears.1.radius",))


def test_catalog_copy_is_untouched_by_every_run(tmp_path):
    """Sanity for the tests above: the catalog itself is never written by them."""
    before = {p.name: p.read_bytes() for p in CATALOG.glob("*.yaml")}
    path = tmp_path / "copy.yaml"
    shutil.copy(CATALOG / "simple_pair.yaml", path)
    run_main([str(path), "--quiet", "--json", "-o", str(path)])
    assert {p.name: p.read_bytes() for p in CATALOG.glob("*.yaml")} == before
