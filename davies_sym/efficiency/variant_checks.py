"""The checks of a derived variant: Laus's partial-derivative rule at a sample of its
region (section 3.6.2: with the right driving gear in every mesh the efficiency grows
with each ordinary efficiency), self-locking found by sampling, and the product whose
sign is the efficiency's inside the region."""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import replace

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.light_load import bearings_agree
from davies_sym.efficiency.parameter_domain import Point
from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.efficiency.variant_result import Variant
from davies_sym.network.analysis import Analysis

#: Ordinary efficiency used for the partial-derivative check (Glover's external value).
NOMINAL_EFFICIENCY = sympy.Rational(49, 50)


def _sign_in_region(variant: Variant, conditions: Sequence[TurningCondition], analysis: Analysis) -> sympy.Expr | None:
    """A product with the sign of the efficiency inside the variant's region: factors
    the symbols' assumptions decide, and factors that are a turning condition (whose
    sign the region fixes), are replaced by their signs.  None when always positive."""
    known = {c.simplified: variant.signs[c.name] for c in conditions}
    sign, expression = analysis.oracle.classify(*variant.efficiency_rf.factor_list(), known=known)
    return None if sign == 1 else expression


def _value(rf: RationalFunction, point: Point) -> sympy.Rational:
    """The efficiency at ``point``; 0 where the formula is singular (such a point
    describes no working train)."""
    try:
        return rf.evaluate(point)
    except ZeroDivisionError:
        # A pole of the formula at this sample: 0 lies outside (0, 1], so the point
        # counts as not working, like a self-locking one.
        return sympy.Integer(0)


def _depends_on(rf: RationalFunction, symbol: sympy.Symbol) -> bool:
    index = rf.ring.symbols.index(symbol)
    return rf.num.degrees()[index] > 0 or rf.den.degrees()[index] > 0


def checked_variant(
    variant: Variant,
    region: Sequence[Point],
    etas: Sequence[sympy.Symbol],
    analysis: Analysis,
    conditions: Sequence[TurningCondition],
    rng: random.Random,
) -> Variant:
    """Partial-derivative rule at a region sample; self-locking by sampling."""
    rf = variant.efficiency_rf
    locking_expression = _sign_in_region(variant, conditions, analysis)
    derivative_check = "not checked"
    locked: Point | None = None
    # Laus 3.6.2 applies where the formula describes a working train: check it at a
    # region sample whose efficiency at the nominal mesh efficiencies is in (0, 1].  A
    # case the losses reach (reversed forces) holds at its sample's own efficiencies,
    # not always at the nominal ones: it is checked there.
    reached = bool(variant.reversed_forces)

    def checked_at(point: Point) -> Point:
        if reached and all(e in point for e in etas if _depends_on(rf, e)):
            return point
        return {**point, **{e: NOMINAL_EFFICIENCY for e in etas}}

    region = [p for p in region if bearings_agree(variant.loaded_forces, analysis, checked_at(p))]
    working = [p for p in region[:40] if 0 < _value(rf, checked_at(p)) <= 1]
    if region and not working:
        derivative_check = "not checked: the train self-locks at every sampled point"
    if working:
        nominal = checked_at(working[0])
        failed = [
            str(e) for e in etas if e in rf.ring.symbols and _depends_on(rf, e) and not rf.derivative_at(e, nominal) > 0
        ]
        derivative_check = "positive" if not failed else f"failed: {', '.join(failed)}"
    if region:
        for point in region[:40]:
            values = {**point, **{e: sympy.Rational(rng.randint(50, 99), 100) for e in etas}}
            try:
                value = rf.evaluate(values)
            except ZeroDivisionError:
                continue  # a pole of the formula at this sample: it says nothing of locking
            # Outside (0, 1] the power directions the variant assumes do not hold: the
            # train (or one of its stages, when two locked stages multiply) self-locks.
            if not 0 < value <= 1:
                used = variant.efficiency.free_symbols
                locked = {k: v for k, v in values.items() if k in used}
                break
    return replace(
        variant, derivative_check=derivative_check, self_locking_point=locked, locking_expression=locking_expression
    )
