"""Exact values of a ring's polynomials at rational points (sampling, checks, choices).

A point is read once into the generators' values (`PointValues.args`; a radical gets a
value where its radicand is a rational square), and each polynomial is then evaluated
as an ``fmpq_mpoly`` at those values.  Symbols the point does not give are 0 where the
polynomial does not use them, and a ``KeyError`` naming the first one where it does.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from functools import cached_property
from math import isqrt
from typing import Protocol, cast

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx, fmpz_mpoly, fmpz_mpoly_ctx

Args = tuple[fmpq | None, ...]
_ZERO = fmpq(0)


class Evaluable(Protocol):
    def evaluate(self, point: Args) -> fmpq: ...


class PointValues:
    """Rational points of one ring: its context, its generators (``symbols``) and its
    radicals' radicands (generator index, radicand), formed when first needed."""

    def __init__(
        self,
        ctx: fmpz_mpoly_ctx,
        symbols: tuple[sympy.Symbol, ...],
        radicands: Callable[[], Sequence[tuple[int, Evaluable]]],
    ):
        self.ctx, self.symbols, self._radicand_forms = ctx, symbols, radicands
        #: The last point evaluated: (args, values with 0 for None, mask of the None).
        self._filled: tuple[Args | None, tuple[fmpq, ...], int] = (None, (), 0)

    @cached_property
    def _radicands(self) -> Sequence[tuple[int, Evaluable]]:
        return self._radicand_forms()

    def args(self, point: Mapping[sympy.Symbol, object]) -> Args:
        """The generators' values at ``point`` (absent symbols: None), for `evaluate`."""
        out: list[fmpq | None] = []
        for symbol in self.symbols:
            value = point.get(symbol)
            if value is None:
                out.append(None)
            elif isinstance(value, (sympy.Rational, int)):  # the common case, without sympy's constructor
                out.append(fmpq(int(value.p), int(value.q)) if isinstance(value, sympy.Rational) else fmpq(value))
            else:
                r = sympy.Rational(value)
                out.append(fmpq(int(r.p), int(r.q)))
        for index, radicand in self._radicands:
            # A radical has a rational value only where its radicand is a square.
            if out[index] is None:
                try:  # KeyError: the point does not give the radicand
                    square = radicand.evaluate(tuple(out))
                except (KeyError, ZeroDivisionError):
                    continue
                n, d = int(square.p), int(square.q)
                if n >= 0 and isqrt(n) ** 2 == n and isqrt(d) ** 2 == d:
                    out[index] = fmpq(isqrt(n), isqrt(d))
        return tuple(out)

    def evaluate(self, p: fmpz_mpoly, args: Args, rational: fmpq_mpoly | None = None, used: int | None = None) -> fmpq:
        """Exact value of ``p`` at ``args`` (from `args`); KeyError names a symbol ``p``
        needs that has no value.  ``rational`` is ``p`` as an fmpq_mpoly (`rational_form`),
        ``used`` its generators (`used`), when known."""
        if not self.symbols:
            return fmpq(int(p.leading_coefficient())) if not p.is_zero() else fmpq(0)
        filled, values, missing = self._filled
        if args is not filled:  # one point is evaluated in many polynomials
            missing = sum(1 << i for i, v in enumerate(args) if v is None)
            values = tuple(_ZERO if v is None else v for v in args) if missing else cast(tuple[fmpq, ...], args)
            self._filled = (args, values, missing)
        # Absent symbols: 0 where p does not use them.
        if missing and (absent := (self.used(p) if used is None else used) & missing):
            raise KeyError(self.symbols[(absent & -absent).bit_length() - 1])
        return (rational if rational is not None else self.rational_form(p))(*values)

    def used(self, p: fmpz_mpoly) -> int:
        """The generators ``p`` depends on, as a bit mask."""
        return sum(1 << i for i, d in enumerate(p.degrees()) if d > 0)  # the zero polynomial has -1

    def rational_form(self, p: fmpz_mpoly) -> fmpq_mpoly:
        """``p`` as an ``fmpq_mpoly`` (for evaluation at rational points)."""
        return fmpq_mpoly_ctx.get(self.ctx.names(), "degrevlex").from_dict(p.to_dict())
