"""Admissible parameter points of a train, drawn at random (exact rationals).

Used to tell which turning-condition regions a geometry can reach, to pick an interior
point for the partial-derivative check of a variant (Laus section 3.6.2), and to look
for self-locking.  Lengths are drawn in [1, 100]; each geometric constraint eliminates
one length (r4 = r2 + r3 - r1); a point is kept when every pitch radius and every known
positive fact (annulus larger than its pinion) is positive.  Other coefficients
(bearing friction, viscous) are drawn small.
"""

from __future__ import annotations

import random
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from functools import cached_property

import sympy

from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.geometry.layout import Layout, joint_substitution
from davies_sym.topology.angles import AngleFunctions
from davies_sym.topology.couplings import GearMesh, Revolute
from davies_sym.topology.model import Train

Point = dict[sympy.Symbol, sympy.Rational]


def geometry_symbols(train: Train) -> set[sympy.Symbol]:
    """Symbols of pitch radii, modules and bearing positions."""
    out: set[sympy.Symbol] = set()
    for g in train.gears:
        out |= g.radius.free_symbols
    for c in train.couplings:
        if isinstance(c, Revolute) and c.at is not None:
            out |= c.at.free_symbols
    return out


def efficiency_symbols(train: Train) -> list[sympy.Symbol]:
    """The ordinary-efficiency symbols of the meshes, in coupling order."""
    out: list[sympy.Symbol] = []
    for c in train.couplings:
        if isinstance(c, GearMesh) and c.efficiencies is not None:
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
        checks = [g.radius for g in self.train.gears] + list(self.layout.positive_facts)
        return [self._ring.rational(e) for e in checks]

    def _converted(self, expr: sympy.Expr) -> RationalFunction:
        cache = self._conversions
        if expr not in cache:
            cache[expr] = self._ring.rational(expr)
        return cache[expr]

    @cached_property
    def _conversions(self) -> dict[sympy.Expr, RationalFunction]:
        return {}

    def _admissible(self, point: Point) -> bool:
        if any(point[s] <= 0 for s in self.eliminated):
            return False  # every geometric symbol is positive, eliminated ones too
        args = self._ring.points.args(point)
        return all(e.evaluate(args) > 0 for e in self._positive)

    def value(self, expr: sympy.Expr, point: Point) -> sympy.Rational:
        """Exact value of a rational expression of the train's symbols at ``point``."""
        v = self._converted(sympy.sympify(expr)).evaluate(point)
        return sympy.Rational(int(v.p), int(v.q))

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
            point: Point = {s: sympy.Rational(rng.randint(100, 10000), 100) for s in free}
            for symbol, expr in self.eliminated.items():
                point[symbol] = self.value(expr, point)
            if not self._admissible(point):
                continue
            for s in others:
                point[s] = sympy.Rational(rng.randint(*extra_range), extra_scale)
            for angle in self._angles:
                point.update(angle_point(angle, rng))
            yield point
            produced += 1
            if produced == count or not free:
                return
