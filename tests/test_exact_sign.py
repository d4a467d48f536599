"""The exact sign of closed forms at a limit (`davies_sym.algebra.exact_sign`): a design
exactly on a self-locking limit is decided, never rounded (a float cannot tell 0 from
1e-40 there)."""

from __future__ import annotations

import pytest
import sympy
from harness.helpers import CATALOG, run_main

from davies_sym.algebra.exact_sign import UndecidedSign, number_sign

S = sympy.Rational


@pytest.mark.parametrize(
    ("value", "sign"),
    [
        # The triple-angle identity sin 3t = 3 sin t - 4 sin^3 t at t = 1/10 rad: exactly 0.
        (sympy.sin(S(3, 10)) - 3 * sympy.sin(S(1, 10)) + 4 * sympy.sin(S(1, 10)) ** 3, 0),
        # cos^2 + sin^2 = 1 through a tangent: tan t cos t - sin t = 0 at t = 2/7.
        (sympy.tan(S(2, 7)) * sympy.cos(S(2, 7)) - sympy.sin(S(2, 7)), 0),
        # A hair off the identity: decided by guaranteed-accuracy evaluation.
        (sympy.sin(S(3, 10)) - 3 * sympy.sin(S(1, 10)) + 4 * sympy.sin(S(1, 10)) ** 3 + S(1, 10**40), 1),
        (sympy.sin(S(3, 10)) - 3 * sympy.sin(S(1, 10)) + 4 * sympy.sin(S(1, 10)) ** 3 - S(1, 10**40), -1),
        # Radicals and rational multiples of pi keep their minimal-polynomial route.
        (sympy.sqrt(2) * sympy.sqrt(3) - sympy.sqrt(6), 0),
        (sympy.cos(sympy.pi / 5) - (1 + sympy.sqrt(5)) / 4, 0),
    ],
    ids=["triple-angle", "tangent", "just-above", "just-below", "radicals", "cos-pi-5"],
)
def test_an_exact_number_has_its_exact_sign(value, sign):
    assert number_sign(value) == sign


def test_a_transcendental_constant_that_cancels_is_undecided_not_guessed():
    """log 6 - log 2 - log 3 cannot be separated from zero by evaluation and is not
    algebraic: refused, never rounded to 0."""
    with pytest.raises(UndecidedSign):
        number_sign(sympy.log(6) - sympy.log(2) - sympy.log(3))


@pytest.mark.parametrize(
    ("mu", "port", "variant"),
    [("cos(3/10)*tan(1/10)", "B", 2), ("cos(3/10)/tan(1/10)", "A", 1)],
)
def test_a_worm_exactly_at_its_self_locking_limit_in_radians_is_decided(mu, port, variant):
    """The worm's efficiency with the wheel (B) driving is proportional to
    cos(alpha_n) sin(gamma) - mu cos(gamma): at mu = cos(alpha_n) tan(gamma) it is 0 exactly
    (lead angle 0.1 rad, pressure angle 0.3 rad), which was refused as undecidable."""
    result = run_main(
        [CATALOG / "worm_drive.yaml", "--quiet", "--eval", "gamma=1/10", "alpha_n=3/10", f"mu={mu}", "--input", port]
    )
    assert result.returncode == 3, result.describe()
    assert f"variant ({variant}) gives 0 exactly (the limit itself)" in result.stdout, result.describe()
