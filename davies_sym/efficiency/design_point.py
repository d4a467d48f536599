"""One design evaluated: the variant that holds, the speed ratio and the efficiency, or
the reason the formulas do not cover it.

`VariantSet.design_point` is the one place where a design is accepted or refused; the
``derive --eval`` answer, `VariantSet.evaluate` and the checks of the formula modules
agree with it.  The refusals:

- values that break a geometric constraint (`DesignError`, exit status 2);
- a port that does not turn (a speed ratio of 0 or infinite, or a vanishing denominator
  of the motions: the train locks), a train that self-locks (an efficiency outside (0, 1],
  Laus section 2.4), an input torque below the load-independent losses
  (`NotCoveredError`, exit status 3).

Every comparison is the exact sign of an exact number (`number_sign`), so a design
exactly on a limit is decided, never rounded.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.algebra.exact_sign import UndecidedSign, is_real_number, number_sign
from davies_sym.efficiency.variant_result import Variant
from davies_sym.errors import DesignError, NotCoveredError, Problem
from davies_sym.geometry.layout import GeometricConstraint

Values = Mapping[sympy.Symbol, sympy.Expr]


@dataclass(frozen=True)
class DesignPoint:
    """The efficiency of one variant at exact values, with ``input`` as the input port."""

    input: str
    output: str
    variant: Variant
    #: Input speed over output speed.
    speed_ratio: sympy.Expr
    efficiency: sympy.Expr


def _sign(value: sympy.Expr, what: str) -> int:
    """The exact sign of ``value``; a value whose sign cannot be decided is not covered."""
    try:
        return number_sign(value)
    except UndecidedSign as exc:
        raise NotCoveredError(f"{what}: {exc}; no efficiency is given where it cannot be decided exactly") from None


def check_constraints(constraints: Iterable[GeometricConstraint], values: Values, path: str | None) -> None:
    """Each geometric constraint (an expression that vanishes) holds at ``values``: those
    no parameter could be solved for (nonlinear ones) are checked here."""
    for c in constraints:
        residual = c.expression.subs(values)
        if residual.is_number and _sign(residual, f"the geometric constraint {c}") != 0:
            raise DesignError(
                [
                    Problem(
                        "values", f"the values break the geometric constraint {c} (difference {sympy.expand(residual)})"
                    )
                ],
                path,
            )


def turning_ratio(ratio: sympy.Expr, values: Values, port: str, other: str, declared: bool) -> sympy.Expr:
    """The speed ratio ``port`` over ``other`` at ``values`` (``ratio``: declared input over
    output; ``declared``: whether ``port`` is the declared input); `NotCoveredError` where
    a port does not turn."""
    value = sympy.sympify(ratio).subs(values)
    value = value if declared else 1 / value
    infinite = value.is_finite is False or value.has(sympy.nan, sympy.zoo)
    if not infinite and _sign(value, f"the speed ratio {port} over {other}") != 0:
        return value
    # An infinite ratio: the other port stands still; a zero one: this port does.
    raise NotCoveredError(
        f"port {other if infinite else port} does not turn at these values (speed ratio {port} over {other} "
        f"{'infinite' if infinite else '0'}): no efficiency"
    )


def check_moving(denominators: Iterable[sympy.Expr], values: Values, input: str) -> None:
    """No denominator of the motions (`davies_sym.network.motion_singularities`) vanishes
    at ``values``; else `NotCoveredError`: the train does not move from its input there,
    however finite the reduced speed ratio stays."""
    for factor in denominators:
        value = sympy.sympify(factor.subs(values))
        if value.is_number and _sign(value, f"the denominator {factor} of the motions") == 0:
            raise NotCoveredError(
                f"port {input} does not turn at these values: the train locks (the denominator "
                f"{sympy.sstr(factor)} of the members' speeds over the input's vanishes), however finite the "
                "reduced speed ratio: no efficiency"
            )


def check_working(value: sympy.Expr, port: str, source: str, operating: bool = False) -> None:
    """The efficiency ``value`` that ``source`` (``variant (3)``, ``the virtual-power
    balance``) gives lies in (0, 1]; else `NotCoveredError` with the reason
    (``operating``: the formula takes the input torque, so a non-positive value means the
    load-independent losses are not overcome)."""
    what = f"the efficiency of {source}"
    positive = value.is_finite is not False and not value.has(sympy.nan, sympy.zoo) and _sign(value, what) > 0
    if not positive and operating:
        raise NotCoveredError(
            f"the input torque does not overcome the load-independent losses (drag, viscous or "
            f"bearing friction) at these values with {port} as input: {source} gives {_shown(value)}; "
            "the output would have to put power in"
        )
    if not positive or _sign(1 - value, what) < 0:
        raise NotCoveredError(
            f"the train self-locks at these values with {port} as input: {source} gives {_shown(value)}, outside (0, 1]"
        )


def _shown(value: sympy.Expr) -> str:
    """``value`` for a message: 6 digits, or ``0 exactly`` on the limit itself."""
    if not is_real_number(value):
        return str(sympy.sstr(value))
    return "0 exactly (the limit itself)" if number_sign(value) == 0 else str(sympy.N(value, 6))
