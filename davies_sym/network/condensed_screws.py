"""Condensed screws and their pairing: a coupling's motion screw and a sum of action
wrenches with the solved magnitudes, and the power of a wrench on a twist (Laus eqs.
(5), (25)-(31), (59), (65))."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import sympy

from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction


def condensed_screw(
    ring: PolynomialRing,
    order: int,
    magnitudes: Mapping[str, RationalFunction],
    units: Iterable[tuple[str, Sequence[sympy.Expr]]],
) -> list[RationalFunction]:
    """Sum of ``magnitude * unit screw`` over the named ``units``, in the ``order``
    components of the screw system; a magnitude is read only where its unit screw has a
    component (the action magnitudes are formed when first read)."""
    out = [RationalFunction.polynomial(ring, ring.zero) for _ in range(order)]
    for name, unit in units:
        for i in range(order):
            if unit[i] != 0:
                out[i] = out[i] + magnitudes[name] * ring.rational(unit[i])
    return out


def inner_product(
    ring: PolynomialRing, wrench: Sequence[RationalFunction], twist: Sequence[RationalFunction]
) -> RationalFunction:
    """The power of ``wrench`` on ``twist``: the sum of the products of their components."""
    total = RationalFunction.polynomial(ring, ring.zero)
    for a, b in zip(wrench, twist, strict=True):
        if not a.is_zero() and not b.is_zero():
            total = total + a * b
    return total
