"""The 3-UPU as Laus varies it (2011, sec. 4.3.4.4 and 4.3.5), from the catalog file:

- each limb's two annuli replaced by one prismatic coupling whose friction comes from the
  transmitted forces alone (its torque disregarded): "eta = 0.9904, regardless of the
  location of the prismatic joint" (either end or the middle of the limb);
- the round annuli's and the universal joints' friction from the resultant of the normal
  forces (eq. (133)) instead of the sum of their magnitudes: "no significant impact on
  the overall efficiency".
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from davies_sym.machines.machine_loader import build_machine
from davies_sym.machines.task import run_task
from davies_sym.topology.yaml_source import parse_yaml

from conftest import CATALOG

THREE_UPU = Path(CATALOG) / "three_upu.yaml"
LIMBS = {1: ("A", "B", "C", "D", "s1", "n1"), 2: ("E", "F", "G", "H", "s2", "n2"), 3: ("I", "J", "K", "L", "s3", "n3")}


def _machine(text: str, name: str):
    return build_machine(parse_yaml(text, name))


def _single_prismatic(where: str) -> str:
    """One prismatic coupling per limb at its base joint, its middle or its platform joint."""
    text = re.sub(r"limits:\n(  .*\n)+", "", THREE_UPU.read_text(encoding="utf-8"))
    for limb, (a, b, c, d, axis, normal) in LIMBS.items():
        text = re.sub(rf"  {b}: {{type: square_annulus.*\n", "", text)
        point = {"base": a, "middle": f"({a} + {d})/2", "platform": d}[where]
        text = re.sub(
            rf"  {c}: {{type: round_annulus.*\n",
            f"  {c}: {{type: prismatic, links: [tube{limb}, rod{limb}], at: {point}, axis: {axis}, normal: {normal}, "
            "friction: {mu: mu}}\n",
            text,
        )
    return text


@pytest.fixture(scope="module")
def single():
    return {w: run_task(_machine(_single_prismatic(w), f"{w}.yaml"), "lift") for w in ("base", "middle", "platform")}


def test_one_prismatic_coupling_per_limb_is_independent_of_its_location(single):
    """Laus sec. 4.3.4.4: "the transmitted force has the same value for different joint
    locations", so the efficiency is the same in all three."""
    values = [r.efficiency for r in single.values()]
    assert max(values) - min(values) < 1e-12
    assert all(r.lost.keys() == single["base"].lost.keys() for r in single.values())


def test_one_prismatic_coupling_per_limb_against_laus_0_9904(single):
    """Laus sec. 4.3.4.4: eta = 0.9904 (here 0.99195: the universal joints lose the same
    26.0 J as in the catalog model, where the thesis's figures imply about 1.2 times as
    much, see tests/test_machines.py); the annuli's moment-driven losses are what
    brings the full model down to 0.65."""
    eta = single["middle"].efficiency
    assert abs(eta - 0.9904) < 0.002
    assert eta > 0.99


def test_resultant_laws_have_no_significant_impact():
    """Laus sec. 4.3.5: friction of the round annuli and the universal joints from the
    resultant of their normal forces (eq. (133)) leaves the lift's efficiency within a
    fraction of a per cent of the sum law's (0.6549 against 0.6533 here)."""
    text = THREE_UPU.read_text(encoding="utf-8")
    resultant = re.sub(r"(type: round_annulus.*friction: \{mu: mu)\}", r"\1, load: resultant}", text)
    resultant = resultant.replace("pin_radius: r_pin}", "pin_radius: r_pin, load: resultant}")
    assert resultant.count("load: resultant") == 9
    plain = run_task(_machine(text, "sum.yaml"), "lift").efficiency
    changed = run_task(_machine(resultant, "resultant.yaml"), "lift").efficiency
    assert changed != plain and abs(changed - plain) / plain < 0.005
