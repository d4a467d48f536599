"""`derive FILE --eval ...` alone derives only the variants of its input port: the
variant it names (its number as in the whole document) and the efficiency are those of
the full derivation, on the catalog's published designs for both inputs and on a
planetary whose drag reverses a tooth force at light load (where the other input's
light-load variants are numbered first, so the whole set is derived)."""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path

import pytest
import sympy
from harness.helpers import run_main

import davies_sym
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.variants import derive_variants

from conftest import TRAIN_FILES


def _cases():
    for path in TRAIN_FILES:
        train = davies_sym.load(path)
        if (train.degrees_of_freedom or 1) > 1:
            continue
        for i, check in enumerate(train.expected):
            if check.state is None and not train.states:
                # Humpage's full derivation takes tens of seconds: the slow tier.
                slow = [pytest.mark.slow] if Path(path).stem == "humpage" else []
                yield pytest.param(path, i, id=f"{Path(path).stem}[{i}]", marks=slow)


@pytest.mark.parametrize(("path", "index"), list(_cases()))
def test_evaluation_alone_names_the_full_derivations_variant_and_value(path, index, tmp_path):
    train = davies_sym.load(path)
    check = train.expected[index]
    pairs = [f"{k}={v}" for k, v in check.values.items()]
    for port in (train.ports.input, train.ports.output):
        alone = run_main([path, "--quiet", "--json", "--input", port, "--eval", *pairs], timeout=120)
        whole = run_main([path, "--quiet", "--json", "--input", port, "-o", tmp_path / "doc.json", "--eval", *pairs])
        assert (alone.returncode, alone.stdout) == (whole.returncode, whole.stdout), (
            alone.describe(),
            whole.describe(),
        )


PLANETARY = """\
name: planetary with planet drag
links: [0, s, c, p]
reference: 0
gears:
  S: {link: s, radius: rs}
  P: {link: p, radius: rp}
  R: {link: 0, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  E: {type: revolute, links: [c, p], friction: {drag: D_p}}
  SP: {type: mesh, gears: [S, P]}
  RP: {type: mesh, gears: [R, P]}
ports: {input: A, output: B}
"""


def test_only_the_asked_inputs_variants_keep_their_numbers():
    """Sun input A has a light-load variant (the drag reverses mesh RP), numbered after
    both base variants; carrier input B has none."""
    train = davies_sym.loads(PLANETARY, "planetary.yaml")
    whole = derive_variants(train)
    assert [(v.number, v.input, sorted(v.reversed_forces)) for v in whole.variants] == [
        (1, "A", []),
        (2, "B", []),
        (3, "A", ["RP"]),
    ]
    for port in ("A", "B"):
        alone = derive_variants(train, inputs=[port])
        expected = [(v.number, v.signs, v.efficiency) for v in whole.variants if v.input == port]
        assert [(v.number, v.signs, v.efficiency) for v in alone.variants] == expected


def test_light_load_variants_after_a_skipped_input_derive_the_whole_set():
    """With the carrier declared the input, the sun's light-load variant is numbered after
    the carrier's variants: asking for the sun alone derives everything."""
    train = davies_sym.loads(PLANETARY.replace("{input: A, output: B}", "{input: B, output: A}"), "swapped.yaml")
    whole = derive_variants(train)
    assert any(v.input == "A" and v.reversed_forces for v in whole.variants)
    alone = derive_variants(train, inputs=["A"])
    assert [(v.number, v.input, v.efficiency) for v in alone.variants] == [
        (v.number, v.input, v.efficiency) for v in whole.variants
    ]


@pytest.mark.parametrize("load", [F(1, 10), F(1, 2), F(5), F(100)])
@pytest.mark.parametrize("port", ["A", "B"])
def test_light_load_evaluation_alone_equals_the_full_set(port, load):
    """Drag 5 in the planet bearing: at light load the drag reverses a tooth force and a
    light-load variant holds (stop notes: 128 points against the torque oracle)."""
    train = davies_sym.loads(PLANETARY, "planetary.yaml")
    s = train.symbols
    point = {
        s["rs"]: 20,
        s["rp"]: 20,
        s["rr"]: 60,
        s["D_p"]: 5,
        s["eta_SP"]: sympy.Rational(97, 100),
        s["eta_RP"]: sympy.Rational(98, 100),
        INPUT_TORQUE: sympy.Rational(load.numerator, load.denominator),
        INPUT_SPEED: 50,
    }
    whole = derive_variants(train)
    alone = derive_variants(train, inputs=[port])
    try:
        expected = (whole.variant_for(point, port).number, whole.evaluate(point, port))
    except davies_sym.DaviesError as exc:
        with pytest.raises(type(exc)):
            alone.evaluate(point, port)
        return
    assert (alone.variant_for(point, port).number, alone.evaluate(point, port)) == expected


def test_json_of_an_evaluation_is_one_object():
    path = next(p for p in TRAIN_FILES if Path(p).stem == "tuplin")
    result = run_main([path, "--quiet", "--json", "--eval", "r1=40", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"])
    assert result.returncode == 0, result.describe()
    assert json.loads(result.stdout)["variant"]["number"] == 1
