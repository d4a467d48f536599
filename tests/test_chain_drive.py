"""The chain and the belt (`davies_sym.topology.chain_drive`): two sprockets or pulleys on
two links, turning the same way at equal pitch-line speeds relative to the link holding
both axes, one ordinary efficiency per drive, the centre distance free.

By hand, relative to that link (the frame of a fixed-axis pair): omega_A r_A = omega_B r_B
with the same sign, so the speed ratio omega_A / omega_B = r_B / r_A (= z_B / z_A for
sprockets of one chain pitch); the taut strand's tension U has the moments r_A U about A
and r_B U about B in one sense, and the drive loses the fraction 1 - eta of the power
through it (Laus section 3.1, Tables 5 and 6): eta_AB with A driving, eta_BA with B
driving.  Followed by an external gear pair of radii r3, r4 (speed ratio -r4/r3, its own
efficiency eta_C), the train's speed ratio is -(z2/z1)(r4/r3) and its efficiency
eta_AB eta_C one way, eta_BA eta_C the other.  The free centre distance L_K draws the
strand but enters no formula.
"""

from __future__ import annotations

import contextlib
import io
import random
from pathlib import Path

import pytest
import sympy

import davies_sym
from davies_sym.cli import main
from davies_sym.geometry import train_layout

CHAIN = """
name: chain and gear pair
links: [0, 1, 2, 3]
reference: 0
gears:
  a: {link: 1, teeth: z1, module: p}
  b: {link: 2, teeth: z2, module: p}
  c: {link: 2, radius: r3}
  d: {link: 3, radius: r4}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  D: {type: revolute, links: [0, 3]}
  K: {type: chain, gears: [a, b], efficiency: [eta_1, eta_2]}
  C: {type: mesh, gears: [c, d], efficiency: eta_C}
ports: {input: A, output: D}
"""

#: The belt spelled with pitch radii, one efficiency for both directions, on its own.
BELT = """
name: belt drive
links: [0, 1, 2]
reference: 0
gears:
  a: {link: 1, radius: r1}
  b: {link: 2, radius: r2}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  V: {type: belt, gears: [a, b], efficiency: eta_V}
ports: {input: A, output: B}
"""


def S(name: str) -> sympy.Symbol:
    return sympy.Symbol(name, positive=True)


def _points(names: list[str], count: int = 5, seed: int = 7) -> list[dict[str, sympy.Rational]]:
    """Random rational points: sizes in [1, 200], efficiencies in (1/2, 1)."""
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        point = {}
        for n in names:
            low, high = (50, 99) if n.startswith("eta") else (100, 20000)
            point[n] = sympy.Rational(rng.randint(low, high), 100)
        out.append(point)
    return out


def _efficiency(variants: davies_sym.VariantSet, values: dict[str, sympy.Rational], port: str) -> sympy.Expr:
    return sympy.nsimplify(variants.evaluate({S(k): v for k, v in values.items()}, port))


def test_chain_ratio_and_efficiency_are_the_hand_derivation() -> None:
    variants = davies_sym.derive(davies_sym.loads(CHAIN, "chain.yaml"))
    ratio = variants.analysis.speed_ratio().to_expr()
    z1, z2, r3, r4 = S("z1"), S("z2"), S("r3"), S("r4")
    assert sympy.simplify(ratio - (-(z2 / z1) * (r4 / r3))) == 0
    for values in _points(["z1", "z2", "r3", "r4", "eta_1", "eta_2", "eta_C", "p"]):
        forward = values["eta_1"] * values["eta_C"]
        backward = values["eta_2"] * values["eta_C"]
        assert variants.evaluate({S(k): v for k, v in values.items()}, "A") == pytest.approx(float(forward), rel=1e-12)
        assert variants.evaluate({S(k): v for k, v in values.items()}, "D") == pytest.approx(float(backward), rel=1e-12)
    formulas = [v.efficiency for v in variants.variants]
    assert {sympy.simplify(f) for f in formulas} == {S("eta_1") * S("eta_C"), S("eta_2") * S("eta_C")}


def test_the_free_centre_distance_draws_the_strand_but_enters_no_formula() -> None:
    train = davies_sym.loads(CHAIN, "chain.yaml")
    layout = train_layout(train)
    drawn = set().union(*(sympy.sympify(x).free_symbols for c in layout.gear_centres.values() for x in c))
    assert "L_K" in {str(s) for s in drawn}
    variants = davies_sym.derive(train)
    assert "L_K" not in {str(s) for s in variants.parameters}
    for v in variants.variants:
        assert "L_K" not in {str(s) for s in v.efficiency.free_symbols}
    # The strand is tangent to both pitch circles on one side: r_A from A's axis, r_B from B's.
    point, normal = layout.coupling_points["K"], layout.mesh_normals["K"]
    for gear in ("a", "b"):
        centre = layout.gear_centres[gear]
        distance = sympy.expand(sum((p - c) * n for p, c, n in zip(point, centre, normal, strict=True)))
        assert sympy.simplify(distance - train.gear(gear).radius) == 0


def test_belt_spelled_with_radii_turns_the_same_way() -> None:
    variants = davies_sym.derive(davies_sym.loads(BELT, "belt.yaml"))
    r1, r2 = S("r1"), S("r2")
    assert sympy.simplify(variants.analysis.speed_ratio().to_expr() - r2 / r1) == 0
    for values in _points(["r1", "r2", "eta_V"]):
        for port in ("A", "B"):
            assert _efficiency(variants, values, port) == values["eta_V"]


def test_equal_pulleys_still_lose_their_efficiency() -> None:
    """On equal pulleys the two members do not turn relative to each other: the loss is
    the strand's, not a relative rotation's."""
    text = BELT.replace("radius: r2", "radius: r1")
    variants = davies_sym.derive(davies_sym.loads(text, "equal.yaml"))
    assert variants.analysis.speed_ratio().to_expr() == 1
    for port in ("A", "B"):
        assert _efficiency(variants, {"r1": sympy.Integer(30), "eta_V": sympy.Rational(9, 10)}, port) == sympy.Rational(
            9, 10
        )


def test_lossless_drive_is_lossless() -> None:
    variants = davies_sym.derive(davies_sym.loads(CHAIN, "chain.yaml"))
    for values in _points(["z1", "z2", "r3", "r4", "p"]):
        lossless = values | {"eta_1": 1, "eta_2": 1, "eta_C": 1}
        for port in ("A", "D"):
            assert _efficiency(variants, lossless, port) == 1


def _refused(tmp_path: Path, text: str, entry: str, words: str) -> None:
    """``derive`` refuses ``text``: exit status 2, the file and line, the entry and ``words``."""
    path = tmp_path / "train.yaml"
    path.write_text(text, encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(path), "--quiet"])
    message = err.getvalue()
    assert code == 2, message
    assert f"{path}:" in message and entry in message and words in message, message
    line = message.split(f"{path}:")[1].split(":")[0]
    assert line.isdigit(), message


@pytest.mark.parametrize(
    ("edit", "entry", "words"),
    [
        # Two members on one axis: a revolute between the sprockets' links makes them coaxial.
        (
            (
                "  B: {type: revolute, links: [0, 2]}",
                "  B: {type: revolute, links: [0, 2]}\n  X: {type: revolute, links: [1, 2]}",
            ),
            "couplings.",
            "cannot be joined by a belt drive",
        ),
        # No link holds both axes: a second belt between two links no bearing holds (sliders).
        (
            (
                "links: [0, 1, 2]",
                "links: [0, 1, 2, 3, 4]",
                "  b: {link: 2, radius: r2}",
                "  b: {link: 2, radius: r2}\n  e: {link: 3, radius: r5}\n  f: {link: 4, radius: r6}",
                "ports:",
                "  W: {type: belt, gears: [e, f]}\n  G: {type: prismatic, links: [0, 3], direction: x}\n"
                "  H: {type: prismatic, links: [0, 4], direction: x}\nports:",
            ),
            "couplings.W",
            "no link holds both gear axes of this belt drive",
        ),
        (
            ("b: {link: 2, radius: r2}", "b: {link: 2, radius: r2, internal: true}"),
            "couplings.V.gears",
            "remove `internal: true`",
        ),
        (
            ("b: {link: 2, radius: r2}", "b: {link: 1, radius: r2}"),
            "couplings.V.gears",
            "a belt must join gears on different links",
        ),
        (("gears: [a, b]", "gears: [a, q]"), "couplings.V.gears", "q"),
        (("efficiency: eta_V", "efficiency: 1.5"), "couplings.V.efficiency", "(0, 1]"),
        # The free centre distance's symbol written as something else.
        (("radius: r1}", "radius: L_V}"), "gears.a", "L_V is the name of the free centre distance of belt drive V"),
        # Both axes placed by the bearings: the belt would close a loop.
        (
            ("links: [0, 1]}", "links: [0, 1], at: 0}", "links: [0, 2]}", "links: [0, 2], at: 30}"),
            "couplings.V",
            "closes a loop",
        ),
        # Intersecting axes: a belt joins parallel axes only.
        (
            (
                "a: {link: 1, radius: r1}",
                "a: {link: 1, radius: r1, axis: z}",
                "b: {link: 2, radius: r2}",
                "b: {link: 2, radius: r2, axis: x}",
            ),
            "couplings.V",
            "joins parallel axes only",
        ),
    ],
)
def test_bad_drives_are_refused_at_their_entry(tmp_path: Path, edit: tuple[str, ...], entry: str, words: str) -> None:
    text = BELT
    for old, new in zip(edit[::2], edit[1::2], strict=True):
        assert old in text, old
        text = text.replace(old, new, 1)
    _refused(tmp_path, text, entry, words)
