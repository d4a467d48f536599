"""Bad input found by a generated sweep (tests/test_bad_input_sweep.py), one regression
test per case: each is refused by the contract of docs/errors.md (exit status 2, one line
``FILE[:LINE]: ENTRY: what is wrong and what to write instead``, no traceback, nothing
written) or, where the input has a meaning, read by it.
"""

from __future__ import annotations

import os

import pytest
from harness.helpers import (
    CATALOG,
    DATA,
    assert_at,
    assert_refused,
    line_of,
    problem_lines,
    replaced,
    run_main,
    write,
)

import davies_sym
from davies_sym.emit.atomic import write_atomic
from davies_sym.topology.yaml_source import MAX_NODES

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
SIMPSON = (CATALOG / "simpson.yaml").read_text(encoding="utf-8")
PAIR_VALUES = ["r2=50", "eta_C=0.98"]

#: A planetary set in two operating states (fast to derive).
STATES = (DATA / "two_states.yaml").read_text(encoding="utf-8")
REDUCTION = "  reduction: {input: A, output: K, brake: [r]}"
#: /proc takes no new files, even from root (who passes every permission check).
NO_NEW_FILES = "/proc"
needs_proc = pytest.mark.skipif(not os.path.isdir(NO_NEW_FILES), reason="needs Linux /proc")


# --- 1. --out into a folder that cannot be made ---------------------------------------------------------------


@needs_proc
def test_out_folder_that_cannot_be_created_is_refused_by_name(tmp_path):
    first, second = write(tmp_path, PAIR, "a.yaml"), write(tmp_path, PAIR, "b.yaml")
    result = run_main([first, second, "--quiet", "--out", "/proc/some-dir"])
    assert_refused(result, first, ("--out",), line=False)
    assert "/proc/some-dir" in result.stderr and "cannot create the folder" in result.stderr, result.describe()


def test_out_folder_below_a_regular_file_is_refused_by_name(tmp_path):
    first, second = write(tmp_path, PAIR, "a.yaml"), write(tmp_path, PAIR, "b.yaml")
    blocker = write(tmp_path, "a file\n", "blocker")
    result = run_main([first, second, "--quiet", "--out", blocker / "derivations"])
    assert_refused(result, first, ("--out",), line=False)
    assert str(blocker / "derivations") in result.stderr, result.describe()
    assert blocker.read_text() == "a file\n"


# --- 2. one item where a list is expected ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("alone", "listed"),
    [
        ("brake: r", "brake: [r]"),
        ("free: p", "free: [p]"),
    ],
)
def test_one_name_where_a_list_is_expected_is_that_list(alone, listed):
    line = "  reduction: {input: A, output: K, %s}"
    one = davies_sym.loads(replaced(STATES, REDUCTION, line % alone), "one.yaml")
    many = davies_sym.loads(replaced(STATES, REDUCTION, line % listed), "many.yaml")
    assert one.states == many.states


def test_one_symbol_where_a_list_of_symbols_is_expected_is_that_list():
    listed = davies_sym.loads(SIMPSON, "listed.yaml")
    alone = davies_sym.loads(replaced(SIMPSON, "independent: [rs, rr1, rr2]", "independent: rs"), "alone.yaml")
    assert alone.independent == ("rs",) and listed.independent == ("rs", "rr1", "rr2")
    fit = PAIR + "calibrate:\n  fit: eta_C\n"
    assert davies_sym.loads(fit, "fit.yaml").calibrate.fit == ("eta_C",)


def test_a_name_alone_as_a_clutch_is_refused_as_the_list_of_it(tmp_path):
    """``clutch: c`` reads as ``clutch: [c]``: both are refused alike (a clutch is a pair)."""
    messages = []
    for written in ("clutch: c", "clutch: [c]"):
        text = replaced(STATES, REDUCTION, f"  reduction: {{input: A, output: K, brake: [r], {written}}}")
        path = write(tmp_path, text)
        result = run_main([path, "--quiet", "--state", "reduction"])
        assert_at(result, path, line_of(text, "reduction:"), "states.reduction.clutch")
        messages.append(result.stderr)
    assert messages[0] == messages[1]
    assert "[[LINK, LINK]]" in messages[0]


def test_one_item_alone_derives_as_the_list(tmp_path):
    alone = write(tmp_path, replaced(STATES, "brake: [r]", "brake: r"), "alone.yaml")
    listed = write(tmp_path, STATES, "listed.yaml")
    results = [run_main([p, "--quiet", "--state", "reduction"]) for p in (alone, listed)]
    assert [r.returncode for r in results] == [0, 0], results[0].describe()
    assert results[0].stdout == results[1].stdout


# --- 3. two outputs naming one file ----------------------------------------------------------------------------


@pytest.mark.parametrize("spelling", ["same", "dotted", "absolute", "symlink"])
def test_two_outputs_naming_one_file_are_refused_before_anything_is_written(tmp_path, monkeypatch, spelling):
    monkeypatch.chdir(tmp_path)
    path = write(tmp_path, PAIR, "pair.yaml")
    (tmp_path / "x").mkdir()
    other = {
        "same": "same.py",
        "dotted": "x/../same.py",
        "absolute": str(tmp_path / "same.py"),
        "symlink": "link.py",
    }[spelling]
    if spelling == "symlink":
        os.symlink(tmp_path / "same.py", tmp_path / "link.py")
    result = run_main([path, "--quiet", "--python", "same.py", "-o", other])
    assert_refused(result, path, ("-o",), line=False)
    assert "both name the file" in result.stderr, result.describe()
    assert not (tmp_path / "same.py").exists(), "an output was written although the call was refused"


def test_emitted_code_and_module_on_one_file_are_refused(tmp_path):
    path = write(tmp_path, PAIR, "pair.yaml")
    target = tmp_path / "code.txt"
    result = run_main([path, "--quiet", "--emit", "c", "--python", target, "-o", target])
    assert_refused(result, path, ("-o",), line=False)
    assert not target.exists()


# --- 4. sweep bounds that are not finite or absurd -------------------------------------------------------------


@pytest.mark.parametrize("bounds", ["10:1e400", "10:inf", "nan:30", "-1e400:30", "10:1e13", "10:10.0000000000001"])
def test_absurd_sweep_bounds_are_refused_naming_plot(tmp_path, bounds):
    path = write(tmp_path, PAIR, "pair.yaml")
    figure = tmp_path / "fig.png"
    result = run_main([path, "--quiet", "--plot", f"r1={bounds}", "--at", *PAIR_VALUES, "-o", figure])
    assert_refused(result, path, ("--plot",), line=False)
    assert "Warning" not in result.stderr, result.describe()
    assert not figure.exists()


# --- 5. one parameter on both axes -----------------------------------------------------------------------------


def test_the_same_parameter_on_both_axes_is_refused(tmp_path):
    path = write(tmp_path, PAIR, "pair.yaml")
    figure = tmp_path / "fig.png"
    result = run_main([path, "--quiet", "--plot", "r1=10:30", "--vs", "r1=5:40", "--at", *PAIR_VALUES, "-o", figure])
    assert_refused(result, path, ("--vs",), line=False)
    assert "r1 is swept by --plot already" in result.stderr, result.describe()
    assert not figure.exists()


# --- 6. --input and --output name ports, with --eval or without ------------------------------------------------


@pytest.mark.parametrize("option", ["--input", "--output"])
def test_an_unknown_port_is_refused_with_or_without_eval(tmp_path, option):
    path = write(tmp_path, PAIR, "pair.yaml")
    alone = run_main([path, "--quiet", option, "Z"])
    evaluated = run_main([path, "--quiet", option, "Z", "--eval", "r1=20", *PAIR_VALUES])
    for result in (alone, evaluated):
        assert_refused(result, path, (option,), line=False)
        assert "'Z' is not a port (ports: A, B)" in result.stderr, result.describe()
    assert alone.stderr == evaluated.stderr


def test_a_port_of_any_state_is_a_port_without_state(tmp_path):
    path = write(tmp_path, STATES)
    result = run_main([path, "--quiet", "--input", "Z"])
    assert_refused(result, path, ("--input",), line=False)
    assert "(ports: A, B, K)" in result.stderr, result.describe()
    assert run_main([path, "--quiet", "--output", "K"]).returncode == 0


def test_an_unknown_port_of_a_machine_is_refused_without_eval():
    result = run_main([CATALOG / "three_upu.yaml", "--quiet", "--input", "Z"])
    assert_refused(result, CATALOG / "three_upu.yaml", ("--input",), line=False)


# --- 7. a tag its value does not fit ---------------------------------------------------------------------------


@pytest.mark.parametrize("tagged", ["!!int abc", "!!float abc", "!!bool maybe", "!!int [1, 2]", "!!map [1]"])
def test_a_tag_its_value_does_not_fit_is_refused_at_its_line(tmp_path, tagged):
    text = replaced(PAIR, "  1: {link: 1, radius: r1}", f"  1: {{link: 1, radius: {tagged}}}")
    path = write(tmp_path, text)
    assert_at(run_main([path, "--quiet"]), path, line_of(text, "radius: !!"), "gears.1.radius")


def test_a_tagged_key_its_value_does_not_fit_is_refused_at_its_line(tmp_path):
    text = PAIR + "!!int abc: 3\n"
    path = write(tmp_path, text)
    assert_at(run_main([path, "--quiet"]), path, line_of(text, "!!int abc"), "abc")


# --- 8. a long list is not an alias bomb -----------------------------------------------------------------------


@pytest.mark.slow
def test_a_long_plain_list_is_refused_as_too_many_items_at_its_line(tmp_path):
    text = PAIR + "notes_list:\n" + "  - x\n" * MAX_NODES
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, "notes_list:"), "notes_list")
    assert "too many items" in result.stderr and "bomb" not in result.stderr, result.describe()


def test_an_alias_bomb_is_still_refused_as_a_bomb(tmp_path):
    lines = ['a0: &a0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 10)]
    path = write(tmp_path, PAIR + "bomb:\n  " + "\n  ".join(lines) + "\n")
    result = run_main([path, "--quiet"])
    assert_refused(result, path, ("bomb.a1",))
    assert "alias bomb" in result.stderr, result.describe()


# --- 9. an unknown top-level key -------------------------------------------------------------------------------


def test_an_unknown_top_level_key_is_reported_at_its_own_line(tmp_path):
    text = PAIR + "gear_ratio: 3\n"
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, "gear_ratio"), "gear_ratio")
    assert ".gear_ratio" not in result.stderr
    assert "known: calibrate, couplings, degrees_of_freedom" in result.stderr, result.describe()


# --- 10. and 11. problems of a state at the state's own entry --------------------------------------------------


@pytest.mark.parametrize(
    ("written", "entry", "words"),
    [
        ("{input: A, output: K, brake: [0]}", "states.reduction.brake[0]", "is the reference link"),
        ("{input: A, output: K}", "states.reduction", "2 degrees of freedom"),
        ("{input: A, output: A, brake: [r]}", "states.reduction.output", "every port must be a different coupling"),
        ("{input: M1, output: K, brake: [r]}", "states.reduction.input", "is a gear mesh"),
    ],
    ids=["brake_on_the_reference", "two_freedoms", "input_is_output", "input_is_a_mesh"],
)
@pytest.mark.parametrize("chosen", [True, False], ids=["with_state", "every_state"])
def test_a_problem_of_a_state_is_at_the_state_entry(tmp_path, written, entry, words, chosen):
    text = replaced(STATES, REDUCTION, f"  reduction: {written}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet", *(["--state", "reduction"] if chosen else [])])
    assert_at(result, path, line_of(text, "reduction:"), entry)
    assert words in result.stderr and "ports" not in result.stderr.split(f"{entry}:")[0], result.describe()


def test_an_immobile_state_is_one_problem_at_the_state_entry(tmp_path):
    old = "second: {description: second gear, input: A, output: B, brake: [s]}"
    text = replaced(SIMPSON, old, "second: {description: second gear, input: A, output: B, brake: [s, c2]}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet", "--state", "second"])
    assert_at(result, path, line_of(text, "second:"), "states.second")
    assert "no degree of freedom" in result.stderr, result.describe()


def test_a_mesh_as_a_port_reads_the_same_in_a_state_and_at_the_top(tmp_path):
    top = write(tmp_path, replaced(STATES, "ports: {input: A, output: B}", "ports: {input: M1, output: B}"), "top.yaml")
    state = write(tmp_path, replaced(STATES, REDUCTION, "  reduction: {input: M1, output: K}"), "state.yaml")
    said = [problem_lines(run_main([p, "--quiet"]))[0].partition(".input: ")[2] for p in (top, state)]
    assert said[0] == said[1] and "a port sits on a revolute" in said[0], said


# --- 12. names a generated module cannot hold ------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "output"),
    [
        *((name, option) for name in ("PORTS", "values", "float") for option in ("--python", "")),
        ("fn", "--emit rust"),  # a keyword of the language
        ("efficiency", "--emit c"),  # the name of a generated function
    ],
)
def test_a_reserved_symbol_is_refused_at_its_line_and_entry(tmp_path, name, output):
    """A symbol the generated code cannot take is refused where the file writes it, as
    ``float`` (refused on load) is."""
    old = "C: {type: mesh, gears: [1, 2], friction: {coulomb: zeta_C}}"
    # Without the published check, whose eta_C the renamed efficiency no longer is.
    unchecked = PAIR.partition("expected:")[0]
    text = replaced(unchecked, old, f"C: {{type: mesh, gears: [1, 2], efficiency: {name}}}")
    path = write(tmp_path, text)
    option, _, language = output.partition(" ")
    asked = [option, language or tmp_path / "m.py"] if option else []  # a name the module binds is refused on load
    result = run_main([path, "--quiet", *asked])
    assert_at(result, path, line_of(text, f"efficiency: {name}"), "couplings.C.efficiency")
    assert repr(name) in result.stderr, result.describe()
    assert not (tmp_path / "m.py").exists()


# --- 13. a write the system refuses names the target -----------------------------------------------------------


@needs_proc
@pytest.mark.parametrize("option", ["-o", "--python"])
def test_a_refused_write_names_the_target(tmp_path, option):
    path = write(tmp_path, PAIR, "pair.yaml")
    target = f"{NO_NEW_FILES}/out.txt"
    result = run_main([path, "--quiet", option, target])
    assert_refused(result, path, (option,), line=False)
    assert f"cannot write {target}" in result.stderr and ".tmp" not in result.stderr, result.describe()


@needs_proc
def test_write_atomic_names_the_target_it_could_not_write():
    with pytest.raises(OSError) as raised:
        write_atomic(f"{NO_NEW_FILES}/out.txt", "text")
    assert raised.value.filename == f"{NO_NEW_FILES}/out.txt"


# --- 14. types a fresh sweep of bad files found accepted ----------------------------------------------------


@pytest.mark.parametrize(
    ("old", "new", "entry", "words"),
    [
        ("format: 1", "format: true", "format", "unsupported topology language version true"),
        ("name: Simple gear pair", 'name: ""', "name", "the train needs a name"),
        ("  0: {description: frame}", "  0: {description: [frame]}", "links.0.description", "expected text"),
        (
            "  1: {link: 1, radius: r1}",
            "  1: {link: 1, teeth: 1" + "0" * 400 + ", module: 2}",
            "gears.1.teeth",
            "from 1 to",
        ),
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: NaN}", "gears.1.radius", "not finite"),
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: Infinity}", "gears.1.radius", "not finite"),
        ("degrees_of_freedom: 1", "degrees_of_freedom: 1\nindependent: 5", "independent", "is not a symbol"),
    ],
    ids=[
        "format-true",
        "empty-name",
        "description-list",
        "teeth-huge",
        "radius-NaN",
        "radius-Infinity",
        "independent-5",
    ],
)
def test_a_value_of_the_wrong_kind_is_refused_at_its_line(tmp_path, old, new, entry, words):
    text = replaced(PAIR, old, new)
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, new.splitlines()[-1][:24]), entry)
    assert words in result.stderr, result.describe()


def test_a_null_key_is_not_the_name_none(tmp_path):
    """``~:`` (YAML's null) as a gear's key would have been a gear called 'None'."""
    text = replaced(PAIR, "  2: {link: 2, radius: r2}", "  2: {link: 2, radius: r2}\n  ~: {link: 2, radius: r3}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert result.returncode == 2 and f"{path}:{line_of(text, '~:')}: gears:" in result.stderr, result.describe()


def test_a_machine_key_in_a_gear_train_is_one_problem_at_that_key(tmp_path):
    """``machine:`` makes a file a general machine (Laus ch. 4); in a gear train it used to
    turn every train entry into a problem of its own."""
    text = PAIR + "machine: x\n"
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, "machine: x"), "machine")
    assert len(problem_lines(result)) == 1 and "gears" in result.stderr, result.describe()


@pytest.mark.parametrize("args", [["--completion", "bash"], [str(CATALOG / "tuplin.yaml"), "--latex", "--quiet"]])
def test_a_reader_that_stops_early_gets_no_traceback(args):
    """``derive ... | head -1``: the pipe is closed before the command writes (here before it
    has even started: the reader is gone); it stops quietly instead of a BrokenPipeError."""
    import subprocess
    import sys

    process = subprocess.Popen(
        [sys.executable, "-m", "davies_sym.cli", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    assert process.stdout is not None and process.stderr is not None
    process.stdout.close()
    stderr = process.stderr.read().decode()
    assert process.wait() == 0, stderr
    assert "Traceback" not in stderr and "BrokenPipe" not in stderr, stderr


@pytest.mark.parametrize(
    ("old", "new", "entry", "words"),
    [
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: eta_C}", "gears.1.radius", "eta_C is the name of"),
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: tau_in}", "gears.1.radius", "input torque"),
        ("friction: {coulomb: zeta_C}}", "efficiency: r1}", "couplings.C.efficiency", "one symbol has one meaning"),
    ],
    ids=["radius-is-the-mesh-efficiency", "radius-is-the-input-torque", "efficiency-is-a-radius"],
)
def test_one_symbol_in_two_roles_is_refused_where_the_second_is_written(tmp_path, old, new, entry, words):
    """A radius called eta_C (the name of mesh C's ordinary efficiency), a radius called
    tau_in (the formulas' input torque), a mesh efficiency written as the radius r1: each
    was derived as if the two meanings were one."""
    text = replaced(PAIR, old, new)
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, new.strip()[:20]), entry)
    assert words in result.stderr, result.describe()


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="making a device node needs root")
def test_output_to_a_device_writes_to_it_and_keeps_it(tmp_path):
    """``-o /dev/null`` as root: renaming a file over the device would have replaced it."""
    import stat

    device = tmp_path / "nulldev"
    os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    result = run_main([CATALOG / "simple_pair.yaml", "--quiet", "-o", device])
    assert result.returncode == 0, result.describe()
    assert stat.S_ISCHR(os.stat(device).st_mode)


@needs_proc
def test_calibration_figure_that_cannot_be_written_is_refused_by_name(tmp_path):
    data = CATALOG / "data" / "sr20_table1.csv"
    result = run_main(["calibrate", CATALOG / "sr20_differential.yaml", data, "--quiet", "-o", "/proc/fit.png"])
    assert result.returncode == 2 and "Traceback" not in result.stderr, result.describe()
    assert "cannot write /proc/fit.png" in result.stderr, result.describe()
