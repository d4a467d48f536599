"""The operating states of a train file (``states:``): a problem of a state is refused at
the state's own entry (FILE:LINE: states.NAME...), with ``--state NAME`` or without, and
said the way the same problem is said at the top-level ports; one name where a list of
members is expected (``brake: r``) reads as the list of that name.
"""

from __future__ import annotations

import pytest
from harness.helpers import (
    CATALOG,
    DATA,
    assert_at,
    line_of,
    problem_lines,
    replaced,
    run_main,
    write,
)

import davies_sym

SIMPSON = (CATALOG / "simpson.yaml").read_text(encoding="utf-8")
#: A planetary set in two operating states (fast to derive).
STATES = (DATA / "two_states.yaml").read_text(encoding="utf-8")
REDUCTION = "  reduction: {input: A, output: K, brake: [r]}"


# --- one name where a list is expected --------------------------------------------------------------------------------


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


def test_one_item_alone_derives_as_the_list(tmp_path):
    alone = write(tmp_path, replaced(STATES, "brake: [r]", "brake: r"), "alone.yaml")
    listed = write(tmp_path, STATES, "listed.yaml")
    results = [run_main([p, "--quiet", "--state", "reduction"]) for p in (alone, listed)]
    assert [r.returncode for r in results] == [0, 0], results[0].describe()
    assert results[0].stdout == results[1].stdout


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


# --- problems of a state at the state's own entry ---------------------------------------------------------------------


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


def test_a_state_that_cannot_derive_names_itself(tmp_path):
    """The Wolfrom train with its carrier free has no geometry; the message said which
    mesh but not which state."""
    text = replaced(
        (CATALOG / "wolfrom.yaml").read_text(encoding="utf-8"),
        "degrees_of_freedom: 1\n",
        "degrees_of_freedom: 1\nstates:\n  nocar: {input: A, output: B, free: [c]}\n",
    )
    result = run_main([write(tmp_path, text), "--quiet", "--state", "nocar"])
    assert result.returncode == 2 and "(state nocar)" in result.stderr, result.describe()
