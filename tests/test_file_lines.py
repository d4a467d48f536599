"""A problem found after loading names its entry; the error raised with the file's lines
(`FileLines`) puts it where the file writes that entry."""

from __future__ import annotations

from types import MappingProxyType

from davies_sym.errors import FileLines, GeometryError, Problem
from davies_sym.topology.loader import loads

PLANETARY = """\
name: ring held
links: [frame, sun, planet, carrier]
gears:
  S: {link: sun, radius: rs}
  P: {link: planet, radius: rp}
  R: {link: frame, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [frame, sun]}
  B: {type: revolute, links: [frame, carrier]}
  C: {type: revolute, links: [carrier, planet]}
  M1: {type: mesh, gears: [S, P]}
  M2: {type: mesh, gears: [P, R]}
ports: {input: A, output: B}
"""


def test_a_stage_problem_gets_the_line_of_its_entry_or_the_nearest_enclosing_one() -> None:
    train = loads(PLANETARY, "ring.yaml")
    error = GeometryError(
        [Problem("couplings.M2", "the loop cannot close"), Problem("couplings.M2.gears.0", "deeper")],
        train.file_lines,
    )
    assert [(p.entry, p.line) for p in error.problems] == [("couplings.M2", 12), ("couplings.M2.gears.0", 12)]
    assert error.report().splitlines()[0] == "geometry error: ring.yaml:12: couplings.M2: the loop cannot close"


def test_an_option_and_a_located_problem_are_kept_as_they_are() -> None:
    lines = FileLines("f.yaml", MappingProxyType({"": 1, "ports": 4}), MappingProxyType({}))
    assert lines.locate(Problem("--eval", "missing values for r1")) == Problem("--eval", "missing values for r1")
    assert lines.locate(Problem("ports", "kept", 9)) == Problem("ports", "kept", 9)


def test_a_state_entry_is_renamed_to_where_the_file_writes_it() -> None:
    lines = FileLines(
        "f.yaml",
        MappingProxyType({"": 1, "states.low": 20, "states.low.input": 21}),
        MappingProxyType({"ports": "states.low", "ports.input": "states.low.input"}),
    )
    assert lines.locate(Problem("ports.input", "cannot move")) == Problem("states.low.input", "cannot move", 21)
    assert lines.locate(Problem("ports", "locked")) == Problem("states.low", "locked", 20)
    # Located once, a problem is not renamed again.
    once = lines.locate(Problem("ports.input", "x"))
    assert lines.locate(once) == once
