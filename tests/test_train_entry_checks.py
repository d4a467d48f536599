"""The entries of a gear-train file, checked where they are written: a value of the wrong
kind or out of its role, a YAML tag its value does not fit, an unknown or null key, a list
too long, a published check or a calibration entry that cannot hold, a mistake of a
link, a bearing or a worm, each refused by the contract of docs/errors.md (exit status 2,
one line ``FILE:LINE: ENTRY: what is wrong and what to write instead``, no traceback); and
what has a meaning is read by it (one symbol where a list of symbols is expected, a
coefficient finer than a double).
"""

from __future__ import annotations

import pytest
from harness.helpers import (
    CATALOG,
    assert_at,
    assert_edit_refused,
    assert_refused,
    line_of,
    problem_lines,
    replaced,
    run_main,
    write,
)

import davies_sym
from davies_sym.topology.yaml_source import MAX_NODES

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
SIMPSON = (CATALOG / "simpson.yaml").read_text(encoding="utf-8")
SR20 = (CATALOG / "sr20_differential.yaml").read_text(encoding="utf-8")
WORM = (CATALOG / "worm_drive.yaml").read_text(encoding="utf-8")
TUPLIN = (CATALOG / "tuplin.yaml").read_text(encoding="utf-8")


# --- values of the wrong kind or out of their role --------------------------------------------------------------------


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


@pytest.mark.parametrize(
    ("source", "old", "new", "at", "entry", "words"),
    [
        (PAIR, "    value: 0.98\n", "    value: 1.5\n", "value: 1.5", "expected[0].value", "lies in (0, 1]"),
        (PAIR, "    value: 0.98\n", "    value: -0.2\n", "value: -0.2", "expected[0].value", "lies in (0, 1]"),
        (
            TUPLIN,
            "degrees_of_freedom: 1\n",
            "degrees_of_freedom: 1\nindependent: [r1, r1, r2]\n",
            "independent:",
            "independent[1]",
            "written twice",
        ),
        (
            TUPLIN,
            "degrees_of_freedom: 1\n",
            "degrees_of_freedom: 1\nindependent: [r1, r2, eta_C]\n",
            "independent:",
            "independent[2]",
            "no size of the geometry",
        ),
        (SR20, "D_P: 0.1}", "D_P: 1e400}", "start:", "calibrate.start.D_P", "expected a positive number"),
    ],
    ids=["check-above-one", "check-negative", "independent-twice", "independent-efficiency", "start-infinite"],
)
def test_a_train_file_value_out_of_its_role_is_refused_at_its_entry(tmp_path, source, old, new, at, entry, words):
    """Accepted before: a published efficiency of 1.5 or -0.2, a symbol listed twice or a
    mesh efficiency among the independent sizes, a calibration start of 1e400."""
    assert_edit_refused(tmp_path, source, old, new, at, entry, words)


def test_a_calibration_start_above_one_for_an_efficiency_is_refused_at_its_line(tmp_path):
    old, new = "start: {eta_M: 0.95", "start: {eta_M: 1.95"
    assert_edit_refused(tmp_path, SR20, old, new, "start:", "calibrate.start.eta_M", "eta_M is an efficiency")


def test_a_bearing_coefficient_beyond_a_double_still_gives_a_module(tmp_path):
    """coulomb: 1e-300 made the module writer recurse without end on a 301-digit number;
    the module now gives the efficiency, which tends to eta_C as the loss vanishes."""
    text = replaced(
        PAIR,
        "  A: {type: revolute, links: [0, 1]}",
        "  A: {type: revolute, links: [0, 1], friction: {coulomb: 1e-300}}",
    )
    path = write(tmp_path, text)
    module = tmp_path / "m.py"
    result = run_main([path, "--quiet", "--python", module])
    assert result.returncode == 0, result.describe()
    namespace: dict[str, object] = {}
    exec(compile(module.read_text(encoding="utf-8"), str(module), "exec"), namespace)
    value = namespace["efficiency"](r1=20.0, r2=50.0, eta_C=0.98)  # type: ignore[operator]
    assert abs(float(value) - 0.98) < 1e-12


def test_one_symbol_where_a_list_of_symbols_is_expected_is_that_list():
    listed = davies_sym.loads(SIMPSON, "listed.yaml")
    alone = davies_sym.loads(replaced(SIMPSON, "independent: [rs, rr1, rr2]", "independent: rs"), "alone.yaml")
    assert alone.independent == ("rs",) and listed.independent == ("rs", "rr1", "rr2")
    fit = PAIR + "calibrate:\n  fit: eta_C\n"
    assert davies_sym.loads(fit, "fit.yaml").calibrate.fit == ("eta_C",)


# --- YAML tags, keys and sizes ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("tagged", ["!!int abc", "!!float abc", "!!bool maybe", "!!int [1, 2]", "!!map [1]"])
def test_a_tag_its_value_does_not_fit_is_refused_at_its_line(tmp_path, tagged):
    text = replaced(PAIR, "  1: {link: 1, radius: r1}", f"  1: {{link: 1, radius: {tagged}}}")
    path = write(tmp_path, text)
    assert_at(run_main([path, "--quiet"]), path, line_of(text, "radius: !!"), "gears.1.radius")


def test_a_tagged_key_its_value_does_not_fit_is_refused_at_its_line(tmp_path):
    text = PAIR + "!!int abc: 3\n"
    path = write(tmp_path, text)
    assert_at(run_main([path, "--quiet"]), path, line_of(text, "!!int abc"), "abc")


def test_an_unknown_top_level_key_is_reported_at_its_own_line(tmp_path):
    text = PAIR + "gear_ratio: 3\n"
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, "gear_ratio"), "gear_ratio")
    assert ".gear_ratio" not in result.stderr
    assert "known: calibrate, couplings, degrees_of_freedom" in result.stderr, result.describe()


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


# --- published checks -------------------------------------------------------------------------------------------------


def test_a_check_that_leaves_a_parameter_out_is_said_at_its_line(tmp_path):
    """A published check without r2 can never be evaluated: said on standard error with
    its line (it was accepted silently); the derivation itself stands."""
    text = replaced(PAIR, "values: {r1: 20, r2: 50, eta_C: 0.98}", "values: {r1: 20, eta_C: 0.98}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert result.returncode == 0 and "eta = eta_C" in result.stdout, result.describe()
    said = f"derive: warning: {path}:{line_of(text, 'values:')}: expected[0].values: the check gives no value for r2"
    assert said in result.stderr, result.describe()


def test_a_check_whose_input_is_a_mesh_is_refused_at_its_line(tmp_path):
    old, new = "    value: 0.98\n", "    value: 0.98\n    input: C\n"
    assert_edit_refused(tmp_path, PAIR, old, new, "input: C", "expected[0].input", "is a gear mesh")


# --- links, bearings and worms ----------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("source", "old", "new", "at", "entry", "words"),
    [
        (PAIR, "radius: r2}", "radius: r2#big}", "r2#big", "gears.2.radius", "'#' is not part"),
        (
            PAIR,
            "  2: {description: gear 2}\n",
            "  2: {description: gear 2}\n  3: {description: spare}\n",
            "spare",
            "links.3",
            "no coupling joins link '3'",
        ),
        (
            PAIR,
            "  C: {type: mesh",
            "  D: {type: revolute, links: [0, 1]}\n  C: {type: mesh",
            "D: {type",
            "couplings.D",
            "U_D stay free",
        ),
        (WORM, "lead_angle: gamma", "lead_angle: -gamma", "-gamma", "couplings.W.lead_angle", "is negative"),
        (
            WORM,
            "{link: 1, radius: 1}",
            "{link: 1, radius: 1, internal: true}",
            "internal: true",
            "gears.worm.internal",
            "skew axes",
        ),
    ],
    ids=[
        "hash-in-a-radius",
        "lone-link",
        "twin-bearing",
        "negative-lead-angle",
        "internal-worm",
    ],
)
def test_a_second_sweep_of_file_mistakes_is_refused_at_the_entry_written(tmp_path, source, old, new, at, entry, words):
    """`r2#big` read as r2 (Python's parser dropped a comment) and a negative symbolic lead
    angle were accepted; a lone link, a second bearing and an
    internal worm were refused at the wrong entry."""
    assert_edit_refused(tmp_path, source, old, new, at, entry, words)
