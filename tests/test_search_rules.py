"""The feasibility rules of ``derive search``, each function on designs whose answer is
worked out here by hand (the rules' tables are one row per design)."""

from __future__ import annotations

import math
from fractions import Fraction as F

import numpy as np
import sympy

from davies_sym.synthesis import rules
from davies_sym.synthesis.exact_values import ExactRational

zs, zr = sympy.symbols("zs zr", positive=True)


def test_a_ratio_exactly_on_the_edge_of_its_window_is_in() -> None:
    """1 + zr/zs at zs = 25, zr = 77 is 102/25 = 4.08 exactly, the upper edge of 4 +- 2 %;
    4.0800000001 would be out.  Floats cannot tell; the integer test does."""
    exact = ExactRational.of(1 + zr / zs, (zs, zr))
    columns = [np.array([25, 25, 20]), np.array([77, 78, 60])]
    window = (F(4) - F(4) * F(2, 100), F(4) + F(4) * F(2, 100))
    assert rules.ratio_within(exact, columns, window).tolist() == [True, False, True]


def test_a_dependent_tooth_number_must_be_whole() -> None:
    """A planet's zp = (zr - zs)/2: whole for zr - zs even only."""
    exact = ExactRational.of((zr - zs) / 2, (zs, zr))
    whole, value = rules.dependent_whole(exact, [np.array([20, 21, 17]), np.array([80, 80, 61])])
    assert whole.tolist() == [True, False, True]
    assert value[whole].tolist() == [30, 22]


def test_every_gear_needs_the_minimum_of_teeth() -> None:
    teeth = {"zs": np.array([17, 16, 30]), "zp": np.array([40, 40, 17])}
    assert rules.enough_teeth(teeth, 17).tolist() == [True, False, True]


def test_tip_clearance_by_hand() -> None:
    """Three planets of 32 teeth, module 2, at a = 57 (zs 25, zp 32): centres 2 a sin 60 deg
    = 98.73 apart against a tip diameter of 68: clear.  Six planets of 30 teeth at a = 34
    (zs 4 + 30 = 34 with module 1, m = 1): 2 a sin 30 deg = 34 against 32: clear; at a =
    32: 32 against 32, touching, which is not clear."""
    assert rules.tips_clear(np.array([57.0]), np.array([68.0]), 3).tolist() == [True]
    assert rules.tips_clear(np.array([34.0, 32.0]), np.array([32.0, 32.0]), 6).tolist() == [True, False]
    assert rules.tips_clear(np.array([1.0]), np.array([100.0]), 1).tolist() == [True]
    assert 2 * 57 * math.sin(math.pi / 3) > 68


def test_a_state_that_self_locks_or_leaves_every_variant_excludes_the_design() -> None:
    """The module gives NaN where the train self-locks or no variant holds; an efficiency
    above 1 cannot come out of a working train."""
    etas = {"low": np.array([0.97, 0.95, np.nan, 0.99]), "high": np.array([0.98, 1.2, 0.9, 1.0])}
    assert rules.runs(etas).tolist() == [True, False, False, True]
