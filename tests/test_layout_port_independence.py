"""A layout follows the file's own statements (`at:` values, the reference, the meshes),
never the choice of the input port: the same train written with its ports swapped, with
an `at:` moved to another member or left out, derives and gives the same exact efficiency."""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy

import davies_sym

from conftest import catalog_path, read_text

#: Two gears on fixed axes in a frame that carries no gear (the reference H).
PAIR = """\
format: 1
name: Fixed-axis pair on a gearless frame
links: [H, A, B]
reference: H
gears:
  GA: {link: A, radius: ra}
  GB: {link: B, radius: rb}
couplings:
  JA: {type: revolute, links: [H, A]BEARING_A}
  JB: {type: revolute, links: [H, B], axis: BBEARING_B}
  M: {type: mesh, gears: [GA, GB]}
ports: {input: INPUT, output: OUTPUT}
PLACEMENT"""

PAIR_DESIGN = {"ra": 20, "rb": 50, "eta_M": sympy.Rational(49, 50)}

#: Where the bearings' `at:` values are written: none, one on either member, or both.
PAIR_POSITIONS = {
    "no at": ("", ""),
    "at: 0 on A": (", at: 0", ""),
    "at: 0 on B": ("", ", at: 0"),
    "A at 0, B at ra + rb": (", at: 0", ", at: ra + rb"),
    "A at rb, B at -ra": (", at: rb", ", at: -ra"),
}


def pair_text(bearing_a: str, bearing_b: str, ports: tuple[str, str], placement: str = "") -> str:
    return (
        PAIR.replace("BEARING_A", bearing_a)
        .replace("BEARING_B", bearing_b)
        .replace("INPUT", ports[0])
        .replace("OUTPUT", ports[1])
        .replace("PLACEMENT", placement)
    )


def hand_power_balance(r_driver: Fraction, r_driven: Fraction, eta: Fraction) -> Fraction:
    """Output over input power of an external pair by hand: the driver's torque T gives
    the tooth force T / r_driver; the driven gear turns at w r_driver / r_driven and
    receives eta of the power the mesh passes on (eta: the ordinary mesh efficiency)."""
    torque, speed = Fraction(7), Fraction(3)
    force = torque / r_driver
    driven_speed = speed * r_driver / r_driven
    delivered = eta * force * r_driven * driven_speed
    return delivered / (torque * speed)


@pytest.mark.parametrize("placement", ["", "placement: [0, 1]\n"], ids=["line", "plane"])
@pytest.mark.parametrize("ports", [("JA", "JB"), ("JB", "JA")], ids=["A in", "B in"])
@pytest.mark.parametrize("where", list(PAIR_POSITIONS))
def test_pair_on_a_gearless_frame_derives_with_either_input(where: str, ports: tuple[str, str], placement: str) -> None:
    """`input: JB` with `at: 0` on JA used to put both axes at 0 (the input member was
    drawn at the origin whatever `at` said) and the derivation refused the mesh."""
    text = pair_text(*PAIR_POSITIONS[where], ports, placement)
    variants = davies_sym.derive(davies_sym.loads(text, "pair.yaml"))
    radii = (Fraction(PAIR_DESIGN["ra"]), Fraction(PAIR_DESIGN["rb"]))
    driver, driven = radii if ports[0] == "JA" else radii[::-1]
    expected = hand_power_balance(driver, driven, Fraction(49, 50))
    assert expected == Fraction(49, 50)  # an external pair passes the mesh efficiency on, driven by either gear
    assert variants.evaluate(PAIR_DESIGN, ports[0]) == sympy.Rational(expected.numerator, expected.denominator)


def test_pair_layout_keeps_every_at_as_written() -> None:
    """The axes stay where the file's `at:` values put them, for either input port."""
    from davies_sym.geometry import train_layout

    for ports in (("JA", "JB"), ("JB", "JA")):
        layout = train_layout(davies_sym.loads(pair_text(", at: rb", ", at: -ra", ports), "pair.yaml"))
        ra, rb = sympy.Symbol("ra", positive=True), sympy.Symbol("rb", positive=True)
        centres = {name: sympy.simplify(point[1]) for name, point in layout.gear_centres.items()}
        assert {k: str(v) for k, v in centres.items()} == {"GA": str(rb), "GB": str(-ra)}, ports


def test_pair_without_at_is_drawn_alike_for_either_input() -> None:
    """No `at:` and a gearless reference: the first geared link is drawn at the origin,
    whichever port is the input."""
    from davies_sym.geometry import train_layout

    layouts = [
        train_layout(davies_sym.loads(pair_text("", "", ports), "pair.yaml")) for ports in (("JA", "JB"), ("JB", "JA"))
    ]
    assert layouts[0].gear_centres == layouts[1].gear_centres
    assert layouts[0].coupling_points == layouts[1].coupling_points


PLANETARY_DESIGN = {"rA": 40, "rB": 20, "eta_G": sympy.Rational(49, 50)}


def planetary_spelling(moves: list[tuple[str, str]], swap: bool) -> str:
    """catalog/planetary_simple.yaml with its `at:` moved (``moves``: line replacements)
    and, with ``swap``, input and output exchanged."""
    text = read_text(catalog_path("planetary_simple"))
    for old, new in moves:
        assert old in text
        text = text.replace(old, new)
    if swap:
        ports = "ports:\n  input: I\n  output: O\n"
        assert ports in text
        text = text.replace(ports, "ports:\n  input: O\n  output: I\n")
    return text


O_PLAIN = ("O: {type: revolute, links: [1, 4], at: 0}", "O: {type: revolute, links: [1, 4]}")
PLANETARY_MOVES = {
    "as in the catalog": [],
    "at on the arm": [O_PLAIN, ("I: {type: revolute, links: [1, 3]}", "I: {type: revolute, links: [1, 3], at: 0}")],
    "at on the planet pin": [
        O_PLAIN,
        ("P: {type: revolute, links: [3, 2]}", "P: {type: revolute, links: [3, 2], at: rA + rB}"),
    ],
    "no at": [O_PLAIN],
}


@pytest.fixture(scope="module")
def catalog_planetary() -> davies_sym.VariantSet:
    return davies_sym.derive(davies_sym.load(catalog_path("planetary_simple")))


@pytest.mark.parametrize("swap", [False, True], ids=["arm in", "output shaft in"])
@pytest.mark.parametrize("where", list(PLANETARY_MOVES))
def test_planetary_spellings_give_the_catalog_efficiency(where: str, swap: bool, catalog_planetary) -> None:
    """Chen's planetary pair with its `at:` on another member, or none, and with the ports
    swapped: the catalog's own efficiency for that input, exactly."""
    train = davies_sym.loads(planetary_spelling(PLANETARY_MOVES[where], swap), "planetary.yaml")
    value = davies_sym.derive(train).evaluate(PLANETARY_DESIGN)
    assert value == catalog_planetary.evaluate(PLANETARY_DESIGN, "O" if swap else "I")
    if not swap:
        # Chen 2006, after eq. (4.10): (gamma + 1)(1 - lambda)/(gamma + 1 - lambda), gamma = 2, lambda = 1/50.
        assert value == sympy.Rational(3 * 49, 50) / (3 - sympy.Rational(1, 50))
