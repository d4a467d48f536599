"""Admissible parameter points of a train, drawn at random (exact rationals).

Used to tell which turning-condition regions a geometry can reach, to pick an interior
point for the partial-derivative check of a variant (Laus section 3.6.2), and to look
for self-locking.  Lengths are drawn in [1, 100]; each geometric constraint eliminates
one length (r4 = r2 + r3 - r1); a point is kept when every pitch radius and every known
positive fact (annulus larger than its pinion) is positive.  Other coefficients
(bearing friction, viscous) are drawn small.
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import cache, cached_property
from typing import cast

import sympy
from flint import fmpq, fmpz_mpoly

from davies_sym.algebra.point_values import Args
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.caches import IdentityCache
from davies_sym.geometry.layout import Layout, joint_substitution
from davies_sym.topology.angles import AngleFunctions
from davies_sym.topology.coupling_kinds import bearings, toothed_meshes
from davies_sym.topology.model import Train

Point = dict[sympy.Symbol, sympy.Rational]


@cache
def _hundredths(value: int) -> sympy.Rational:
    """``value / 100`` (a drawn length): the few thousand values recur in every point
    drawn, and sympy's constructor costs more than the rest of the draw."""
    return sympy.Rational(value, 100)


@dataclass(frozen=True)
class FloatPolynomial:
    """An integer polynomial evaluated in floating point, with the sign only where the
    value exceeds a bound on its rounding error."""

    terms: tuple[tuple[float, tuple[tuple[sympy.Symbol, int], ...]], ...]

    @classmethod
    def of(cls, p: fmpz_mpoly, symbols: Sequence[sympy.Symbol]) -> FloatPolynomial:
        return cls(
            tuple(
                (float(int(c)), tuple((x, int(k)) for x, k in zip(symbols, m, strict=True) if k))
                for m, c in zip(p.monoms(), p.coeffs(), strict=True)
            )
        )

    def _parts(self, values: Mapping[sympy.Symbol, float]) -> tuple[float, float]:
        """The value and the sum of the terms' sizes (nan where a symbol has no value)."""
        total, size = 0.0, 0.0
        for c, powers in self.terms:
            term = c
            for x, k in powers:
                term *= values.get(x, math.nan) ** k
            total += term
            size += abs(term)
        return total, size

    def value(self, values: Mapping[sympy.Symbol, float]) -> float:
        return self._parts(values)[0]

    def sign(self, values: Mapping[sympy.Symbol, float]) -> int | None:
        """+1 or -1, or None (zero, or too close to it to tell in floating point)."""
        total, size = self._parts(values)
        if not abs(total) > 1e-9 * size:  # also nan
            return None
        return 1 if total > 0 else -1


def _positive_in(p: fmpz_mpoly, symbols: Sequence[sympy.Symbol], drawn: set[sympy.Symbol]) -> bool:
    """Whether ``p`` is positive wherever the ``drawn`` symbols are: a non-zero polynomial
    in them alone with positive coefficients."""
    used = {x for x, d in zip(symbols, p.degrees(), strict=False) if d > 0}  # no symbols: one dummy generator
    return not p.is_zero() and used <= drawn and all(int(c) > 0 for c in p.coeffs())


def admissible_facts(train: Train, layout: Layout) -> list[tuple[sympy.Expr, str]]:
    """Expressions positive on every admissible design, each with what it is: every pitch
    radius (``pitch radius of S1``) and every fact of the layout (an annulus larger than
    its pinion, a placement's triangle that closes; described by the expression alone)."""
    radii = [(sympy.sympify(g.radius), f"pitch radius of {g.name}") for g in train.gears]
    return radii + [(sympy.sympify(f), "") for f in layout.positive_facts]


def geometry_symbols(train: Train) -> set[sympy.Symbol]:
    """Symbols of pitch radii, modules and bearing positions, and those a dependent one is
    given in (a module solved from the constraints, m2 = 2 (r1 - r3 + 40) / z2, leaves z2 in
    no radius but in the fact m2 > 0)."""
    out: set[sympy.Symbol] = set()
    for g in train.gears:
        out |= g.radius.free_symbols
    for c in bearings(train.couplings):
        if c.at is not None:
            out |= c.at.free_symbols
    for relation in train.dependent or ():
        out |= relation.expression.free_symbols
    return out - {relation.symbol for relation in train.dependent or ()}


def efficiency_symbols(train: Train) -> list[sympy.Symbol]:
    """The ordinary-efficiency symbols of the meshes, in coupling order."""
    out: list[sympy.Symbol] = []
    for c in toothed_meshes(train.couplings):
        if c.efficiencies is not None:
            for e in c.efficiencies:
                for s in sorted_symbols(e.free_symbols):
                    if s not in out:
                        out.append(s)
    return out


def angle_point(angle: AngleFunctions, rng: random.Random) -> Point:
    """cos and sin of ``angle`` at a rational point of the unit circle: t = tan(angle / 2)
    drawn in [1/100, 3/5] (an angle given as a number: t a close rational), cos =
    (1 - t^2) / (1 + t^2), sin = 2 t / (1 + t^2), so that cos^2 + sin^2 = 1 holds exactly."""
    if angle.angle.free_symbols:
        t = sympy.Rational(rng.randint(1, 60), 100)
    else:
        t = sympy.Rational(str(sympy.tan(angle.angle / 2).evalf(20))).limit_denominator(10**9)
    return {angle.cos: (1 - t**2) / (1 + t**2), angle.sin: 2 * t / (1 + t**2)}


@dataclass(frozen=True, eq=False)
class ParameterDomain:
    """Where the symbols of a train may lie."""

    train: Train
    layout: Layout
    #: Symbols eliminated by the geometric constraints, with their expressions.
    eliminated: Mapping[sympy.Symbol, sympy.Expr]

    @classmethod
    def of(cls, train: Train, layout: Layout) -> ParameterDomain:
        return cls(train, layout, joint_substitution(layout.constraints))

    @cached_property
    def _angles(self) -> list[AngleFunctions]:
        """The angles of the meshes (helix, lead, pressure), whose cos and sin are drawn together."""
        out = {a.cos: a for c in self.train.couplings for a in c.angles}
        return [out[k] for k in sorted_symbols(out)]

    @cached_property
    def _ring(self) -> PolynomialRing:
        return PolynomialRing(self.train.symbols.values())

    @cached_property
    def _positive(self) -> list[RationalFunction]:
        return [self._ring.rational(e) for e, _ in admissible_facts(self.train, self.layout)]

    def _converted(self, expr: sympy.Expr) -> RationalFunction:
        cache = self._conversions
        if expr not in cache:
            cache[expr] = self._ring.rational(expr)
        return cache[expr]

    @cached_property
    def _conversions(self) -> dict[sympy.Expr, RationalFunction]:
        return {}

    @cached_property
    def _float_checks(
        self,
    ) -> tuple[list[tuple[sympy.Symbol, FloatPolynomial, FloatPolynomial]], list[FloatPolynomial]]:
        """The eliminated symbols and the positive facts as float evaluations (numerator
        and denominator of each, with a bound on their rounding error): a quick first
        look at a drawn point, decided exactly only where it is not clear."""
        ring = self._ring
        eliminated = []
        for symbol, expr in self.eliminated.items():
            rf = self._converted(sympy.sympify(expr))
            eliminated.append(
                (symbol, FloatPolynomial.of(rf.num, ring.symbols), FloatPolynomial.of(rf.den, ring.symbols))
            )
        # A fact in the drawn symbols with positive terms only (a pitch radius) is positive
        # at every drawn point: it has nothing to tell.
        facts = [FloatPolynomial.of(p, ring.symbols) for rf in self._undecided for p in (rf.num, rf.den)]
        return eliminated, facts

    def _float_verdict(self, point: Mapping[sympy.Symbol, int]) -> bool | None:
        """Whether floating point shows ``point`` (drawn integers over 100) inside the
        domain (True) or outside it (False) beyond its rounding error: an eliminated symbol
        not positive, or a fact's numerator and denominator of opposite signs.  None where
        a sign is too close to zero to tell: the exact test decides."""
        eliminated, facts = self._float_checks
        values = {s: v / 100 for s, v in point.items()}
        clear = True
        for symbol, num, den in eliminated:
            n, d = num.sign(values), den.sign(values)
            if n is None or d is None:
                return None  # its value feeds the facts: nothing after it is clear
            if n * d < 0:
                return False
            values[symbol] = num.value(values) / den.value(values)
        for k in range(0, len(facts), 2):
            n, d = facts[k].sign(values), facts[k + 1].sign(values)
            if n is None or d is None:
                clear = False
            elif n * d < 0:
                return False
        return True if clear else None

    def _admissible(self, args: Args) -> bool:
        """Whether the symbols' values ``args`` (`args`) are an admissible design: every
        eliminated symbol and every fact positive (a fact with positive terms only is,
        where every drawn length is)."""
        index = self.symbol_index
        if any(cast(fmpq, args[index[s]]) <= 0 for s in self.eliminated):
            return False  # every geometric symbol is positive, eliminated ones too
        drawn = [args[index[s]] for s in self._drawn]
        facts = self._undecided if all(v is not None and v > 0 for v in drawn) else self._positive
        try:
            return all(e.evaluate(args) > 0 for e in facts)
        except ZeroDivisionError:  # a fact undefined here (a dependent module's pole): no design
            return False

    def value(self, expr: sympy.Expr, point: Point) -> sympy.Rational:
        """Exact value of a rational expression of the train's symbols at ``point``."""
        v = self._converted(sympy.sympify(expr)).evaluate(point)
        return sympy.Rational(int(v.p), int(v.q))

    def args(self, point: Point) -> Args:
        """``point`` read once as the values of the train's symbols (`value_at`)."""
        return self._ring.points.args(point)

    def signs_at(self, expressions: Iterable[sympy.Expr], args: Args) -> tuple[int, ...]:
        """The sign of each expression at ``args`` (`args`), 0 counted as positive: the
        region of a point among the turning conditions."""
        return tuple(1 if self.value_at(e, args) >= 0 else -1 for e in expressions)

    def value_at(self, expr: sympy.Expr, args: Args) -> fmpq:
        """Exact value of a rational expression of the train's symbols at ``args``
        (`args`): many expressions at one point without reading it again."""
        return self._converted(expr).evaluate(args)

    def completed(self, free: list[fmpq | None]) -> Args | None:
        """The symbols' values ``free`` (indexed as the train's symbols) with the
        eliminated ones filled in place: the values of the admissible design, or None
        where it is none."""
        index = self.symbol_index
        for symbol in self.eliminated:
            free[index[symbol]] = None  # given by the free symbols alone
        try:
            for symbol, expr in self.eliminated.items():
                free[index[symbol]] = self._converted(sympy.sympify(expr)).evaluate(tuple(free))
        except ZeroDivisionError:
            return None
        args = tuple(free)
        return args if self._admissible(args) else None

    @cached_property
    def _drawn(self) -> list[sympy.Symbol]:
        """The symbols a design draws or computes: lengths, all positive on a design."""
        return sorted_symbols((geometry_symbols(self.train) & set(self.symbol_index)) | set(self.eliminated))

    @cached_property
    def _undecided(self) -> list[RationalFunction]:
        """The positive facts not positive by their terms alone (`_positive_in`)."""
        drawn, symbols = set(self._drawn), self._ring.symbols
        return [rf for rf in self._positive if not all(_positive_in(p, symbols, drawn) for p in (rf.num, rf.den))]

    @cached_property
    def symbol_index(self) -> dict[sympy.Symbol, int]:
        """The place of each of the train's symbols in `args`."""
        return {s: k for k, s in enumerate(self._ring.symbols)}

    def point_of(self, args: Args, keys: Iterable[sympy.Symbol], given: Point) -> Point:
        """The design of ``args`` as a point with the ``keys`` in order: a symbol of the
        train from ``args``, any other from ``given``."""
        index = self.symbol_index
        out: Point = {}
        for key in keys:
            if key in index:
                v = cast(fmpq, args[index[key]])
                out[key] = sympy.Rational(int(v.p), int(v.q))
            else:
                out[key] = given[key]
        return out

    def drawn_samples(self, count: int, seed: int, extra: Sequence[sympy.Symbol]) -> list[Point]:
        """The points of `samples` as a list, each a new dict: drawn once for the states
        of one whole train whose domains agree (their symbols, constraints, facts and
        angles: the draw reads nothing else)."""
        whole = self.train.whole
        if whole is None:
            return list(self.samples(count, seed=seed, extra=extra))
        key = (
            tuple(sorted_symbols(self.train.symbols.values())),
            tuple(sorted_symbols(geometry_symbols(self.train))),
            tuple(self.eliminated.items()),
            tuple(e for e, _ in admissible_facts(self.train, self.layout)),
            tuple((a.angle, a.cos, a.sin) for a in self._angles),
            count,
            seed,
            tuple(extra),
        )
        drawn = _SAMPLES.get(whole, lambda: list(self.samples(count, seed=seed, extra=extra)), key)
        return [dict(point) for point in drawn]

    def samples(
        self,
        count: int,
        seed: int = 0,
        extra: Iterable[sympy.Symbol] = (),
        extra_range: tuple[int, int] = (1, 10),
        extra_scale: int = 1000,
        attempts: int = 50,
    ) -> Iterator[Point]:
        """Up to ``count`` admissible points; ``extra`` symbols drawn in
        ``extra_range / extra_scale``."""
        rng = random.Random(seed)
        free = sorted_symbols(geometry_symbols(self.train) - set(self.eliminated))
        others = sorted_symbols(set(extra) - geometry_symbols(self.train))
        produced = 0
        for _ in range(count * attempts):
            drawn = {s: rng.randint(100, 10000) for s in free}
            verdict = self._float_verdict(drawn)
            if verdict is False:
                continue
            point: Point = {s: _hundredths(v) for s, v in drawn.items()}
            try:
                for symbol, expr in self.eliminated.items():
                    point[symbol] = self.value(expr, point)
            except ZeroDivisionError:  # on the pole of an eliminated symbol: no design
                continue
            if verdict is None and not self._admissible(self.args(point)):
                continue
            for s in others:
                point[s] = sympy.Rational(rng.randint(*extra_range), extra_scale)
            for angle in self._angles:
                point.update(angle_point(angle, rng))
            yield point
            produced += 1
            if produced == count or not free:
                return


#: The points drawn for the states of each whole train, by what the draw reads.
_SAMPLES: IdentityCache[Train, list[Point]] = IdentityCache()
