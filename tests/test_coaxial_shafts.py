"""Two shafts on one axis, each in a bearing of the frame: a revolute's `axis:` naming a
third link (the reverted two-stage reducer, input and output coaxial). Checked against
the hand formulas of the fixed-axis train: Willis' ratio (r2 / r1)(r4 / r3), the
coaxial condition r1 + r2 = r3 + r4, the efficiency eta_A eta_B either way."""

from __future__ import annotations

import random
import re

import pytest
import sympy
from harness.helpers import run_main_in

import davies_sym
from davies_sym.geometry import train_layout

REVERTED = """\
format: 1
name: reverted two-stage reducer
links:
  case: {description: gearbox housing}
  input: {description: input shaft}
  lay: {description: countershaft}
  output: {description: 'output shaft, coaxial with the input'}
reference: case
gears:
  G1: {link: input, radius: r1}
  G2: {link: lay, radius: r2}
  G3: {link: lay, radius: r3}
  G4: {link: output, radius: r4}
couplings:
  Bi: {type: revolute, links: [case, input], axis: case}
  Bl: {type: revolute, links: [case, lay]}
  Bo: {type: revolute, links: [case, output], axis: input}
  A: {type: mesh, gears: [G1, G2]}
  B: {type: mesh, gears: [G3, G4]}
ports: {input: Bi, output: Bo}
"""

#: The same train spelled otherwise: the output bearing's links reversed, entries in
#: another order, block-style mappings.
RESPELLED = """\
format: 1
name: reverted two-stage reducer, respelled
reference: case
links:
  output: {}
  lay: {}
  input: {}
  case: {}
couplings:
  B:
    type: mesh
    gears: [G3, G4]
  Bo:
    type: revolute
    links: [output, case]
    axis: input
  A: {type: mesh, gears: [G1, G2]}
  Bl: {type: revolute, links: [lay, case]}
  Bi: {type: revolute, links: [case, input], axis: case}
gears:
  G4: {link: output, radius: r4}
  G3: {link: lay, radius: r3}
  G2: {link: lay, radius: r2}
  G1: {link: input, radius: r1}
ports: {output: Bo, input: Bi}
"""


@pytest.mark.parametrize("text", [REVERTED, RESPELLED])
def test_the_output_shaft_turns_on_the_input_axis(text: str) -> None:
    """The layout puts G4 on the input's axis and closes the second mesh with the
    coaxial condition; without `axis:` the output shaft lies beyond the countershaft
    and no condition follows."""
    layout = train_layout(davies_sym.loads(text))
    r1, r2, r3, r4 = sympy.symbols("r1 r2 r3 r4", positive=True)
    (constraint,) = layout.constraints
    assert sympy.expand(constraint.expression - (r1 + r2 - r3 - r4)) in (0, sympy.expand(2 * (r1 + r2 - r3 - r4)))
    assert layout.gear_centres["G4"] == layout.gear_centres["G1"]
    free = train_layout(davies_sym.loads(REVERTED.replace(", axis: input}", "}")))
    assert not free.constraints
    assert free.gear_centres["G4"] != free.gear_centres["G1"]


@pytest.mark.parametrize(("text", "sign"), [(REVERTED, 1), (RESPELLED, -1)])
def test_ratio_and_efficiency_are_the_hand_formulas(text: str, sign: int) -> None:
    """At random rational points on the coaxial condition: the speed ratio is Willis'
    (r2 / r1)(r4 / r3) with r3 = r1 + r2 - r4 (two external meshes: the output turns
    with the input; a port reads its second link relative to its first, so the output
    bearing written [output, case] reads the opposite sign), and the efficiency is
    eta_A eta_B with either shaft driving."""
    variants = davies_sym.derive(davies_sym.loads(text))
    chooser = random.Random(4)
    for _ in range(5):
        r1, r2, r4 = (sympy.Rational(chooser.randint(10, 60)) for _ in range(3))
        r4 = min(r4, r1 + r2 - 1)
        r3 = r1 + r2 - r4
        eta_a, eta_b = sympy.Rational(chooser.randint(90, 99), 100), sympy.Rational(chooser.randint(90, 99), 100)
        values = {"r1": r1, "r2": r2, "r4": r4, "eta_A": eta_a, "eta_B": eta_b}
        point = variants.design_point(values)
        assert point.speed_ratio == sign * (r2 / r1) * (r4 / r3)
        assert point.efficiency == eta_a * eta_b
        assert variants.evaluate(values, "Bo") == eta_a * eta_b


def test_an_axis_naming_no_link_is_refused_at_its_entry(tmp_path) -> None:
    """Exit status 2, the file, line and entry, the name that is not a link."""
    path = tmp_path / "typo.yaml"
    path.write_text(REVERTED.replace("axis: input", "axis: inptu"))
    result = run_main_in(tmp_path, [str(path)], timeout=600)
    assert result.returncode == 2
    assert re.search(r"typo\.yaml:17: couplings\.Bo\.axis: unknown link 'inptu'", result.stderr), result.stderr
    assert "Traceback" not in result.stderr
