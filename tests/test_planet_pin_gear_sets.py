"""A gear set on a planet's own pin: a second planet (the star) carried by the planet
(the pin) meshes a gear fixed to the arm about the pin's axis and an annulus turning
about the same axis in a bearing on the pin.  The carrier of the star's meshes is the
pin, which holds the star's axis and the annulus's alike, whatever the links are
called (atlas7_r11_d2 is such a train: its meshes were given the arm as carrier when
the annulus's name sorted before the star's, which placed the star on the main axis).

Checks that share no code with the package: Willis' relation in the pin's frame
(the annulus turns against the arm's gear by -ra / rw there) and, the branch carrying
no power, the efficiency of the plain planetary (sun in, arm out, ring held), eta =
(1 + k eta_0) / (1 + k) with k = rr / rs and eta_0 = eta_M1 eta_M2 (Mueller, Epicyclic
Drive Trains, 1982)."""

from __future__ import annotations

import random

import pytest
import sympy

import davies_sym
from davies_sym.network.analysis import analyse

BRANCH = """\
format: 1
name: planetary with a gear set on the planet's pin
links:
  housing: {description: frame}
  sun: {description: input}
  arm: {description: 'carrier on the main axis: output'}
  pin: {description: planet turning on the arm}
  ANNULUS: {description: 'turns about the pin axis in a bearing on the pin'}
  STAR: {description: planet of the pin}
reference: housing
gears:
  S: {link: sun, radius: rs}
  R: {link: housing, radius: rr, internal: true}
  P: {link: pin, radius: rp}
  A: {link: arm, radius: ra, about: pin}
  I: {link: STAR, radius: ri}
  W: {link: ANNULUS, radius: rw, internal: true}
couplings:
  Bs: {type: revolute, links: [housing, sun], axis: housing}
  Ba: {type: revolute, links: [housing, arm], axis: housing}
  Jp: {type: revolute, links: [arm, pin]}
  Jw: {type: revolute, links: [pin, ANNULUS], axis: pin}
  Ji: {type: revolute, links: [pin, STAR]}
  M1: {type: mesh, gears: [S, P]}
  M2: {type: mesh, gears: [P, R]}
  M3: {type: mesh, gears: [A, I]}
  M4: {type: mesh, gears: [W, I]}
ports: {input: Bs, output: Ba}
"""

#: The annulus's and the star's names: sorted either way (the first is the order that
#: named the arm as carrier), and the meshes' gears in the other order.
SPELLINGS = [
    BRANCH.replace("ANNULUS", "annulus").replace("STAR", "star"),
    BRANCH.replace("ANNULUS", "wheel").replace("STAR", "idler"),
    BRANCH.replace("ANNULUS", "annulus")
    .replace("STAR", "star")
    .replace("gears: [A, I]", "gears: [I, A]")
    .replace("gears: [W, I]", "gears: [I, W]"),
]

ra, ri = sympy.symbols("ra ri", positive=True)


@pytest.mark.parametrize("text", SPELLINGS, ids=["annulus-star", "wheel-idler", "gears-swapped"])
def test_the_star_turns_in_the_pin_as_willis_says(text: str) -> None:
    """(w_annulus - w_pin) / (w_arm - w_pin) = -ra / rw with rw = ra + 2 ri, the pin's
    frame being the carrier of both meshes of the star; the ring and the annulus are
    sized by their loops (rr = rs + 2 rp, rw = ra + 2 ri)."""
    train = davies_sym.loads(text)
    annulus = "annulus" if "annulus" in text else "wheel"
    analysis = analyse(train)
    speeds = {k: analysis.motion_magnitudes[f"t_{k}"].to_expr() for k in ("Jp", "Jw")}
    # Jp: the pin in the arm; Jw: the annulus in the pin.
    ratio = sympy.cancel(speeds["Jw"] / -speeds["Jp"])
    assert sympy.cancel(ratio + ra / (ra + 2 * ri)) == 0, (annulus, ratio)


@pytest.mark.parametrize("text", SPELLINGS, ids=["annulus-star", "wheel-idler", "gears-swapped"])
def test_the_idle_branch_leaves_the_planetary_efficiency(text: str) -> None:
    """Sun in, arm out: eta = (1 + k eta_M1 eta_M2) / (1 + k), k = rr / rs, at random
    rational designs; the star's meshes carry no power (their loss is none)."""
    variants = davies_sym.derive(davies_sym.loads(text))
    rng = random.Random(11)
    for _ in range(5):
        values = {
            "rs": sympy.Rational(rng.randint(10, 60)),
            "rp": sympy.Rational(rng.randint(10, 40)),
            "ra": sympy.Rational(rng.randint(10, 40)),
            "ri": sympy.Rational(rng.randint(8, 30)),
            **{f"eta_M{k}": sympy.Rational(rng.randint(900, 999), 1000) for k in range(1, 5)},
        }
        k = (values["rs"] + 2 * values["rp"]) / values["rs"]
        expected = (1 + k * values["eta_M1"] * values["eta_M2"]) / (1 + k)
        assert variants.evaluate(values, "Bs") == expected
