"""Which power-flow regions admissible designs reach, found by sampling.

Speed conditions: for sampled geometries, one direction of the input speeds inside
every sector between the condition lines (two inputs) or random directions (more).
Reversed loaded forces: for those speeds, random losses (ordinary efficiencies in
(1/2, 1), other loss parameters and the load torque spread over decades), and a region
is kept where some sample has every loaded force of the sign the region assumes.  A
region missed here is never a wrong number: where no kept region's forces agree, the
answer is refused.  The same draws (`Draws`) serve the light-load variants of a
train with one input (`davies_sym.efficiency.light_load`).
"""

from __future__ import annotations

import math
import random
from collections.abc import Collection, Mapping, Sequence
from fractions import Fraction
from itertools import pairwise

import numpy as np
import sympy
from flint import fmpz_mpoly

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.parameter_domain import ParameterDomain
from davies_sym.efficiency.power_flow_regions import LOAD_TORQUE, Region
from davies_sym.network.analysis import Analysis
from davies_sym.topology.model import Train

Point = dict[sympy.Symbol, sympy.Expr]


def reached_signs(
    train: Train,
    analysis: Analysis,
    forms: Sequence[sympy.Expr],
    speeds: tuple[sympy.Symbol, ...],
    samples: int,
    seed: int,
) -> dict[tuple[int, ...], list[Point]]:
    """Sign vectors of the speed conditions that admissible designs reach, each with the
    points (geometry and input speeds) that reached it."""
    domain = ParameterDomain.of(train, analysis.network.layout)
    rng = random.Random(seed)
    out: dict[tuple[int, ...], list[Point]] = {}
    for point in domain.samples(samples, seed=seed):
        fixed = [sympy.expand(f.subs(point)) for f in forms]
        directions: list[tuple[Fraction, ...]] = []
        if len(speeds) == 2:
            angles = sorted(
                {
                    math.atan2(-float(f.coeff(speeds[0])), float(f.coeff(speeds[1]))) % math.pi + k * math.pi
                    for f in fixed
                    for k in (0, 1)
                }
            )
            angles.append(angles[0] + 2 * math.pi)
            for a, b in pairwise(angles):
                middle = (a + b) / 2
                directions.append((Fraction(math.cos(middle)), Fraction(math.sin(middle))))
        else:
            directions = [tuple(Fraction(rng.uniform(-1, 1)) for _ in speeds) for _ in range(200)]
        for d in directions:
            values = dict(zip(speeds, (sympy.Rational(x.numerator, x.denominator) for x in d), strict=True))
            signs = [sympy.sign(f.subs(values)) for f in fixed]
            if all(s != 0 for s in signs):
                out.setdefault(tuple(int(s) for s in signs), []).append({**point, **values})
    return dict(sorted(out.items(), reverse=True))


class Draws:
    """Random losses and loads at up to four sampled points, the same for every case asked
    about: each point repeated ``count`` times, ordinary efficiencies in (1/2, 1), the
    ``load`` torque over eight decades and other loss parameters over six; the symbols
    ``drawn`` are drawn even where the points give them."""

    def __init__(
        self,
        points: Sequence[Point],
        efficiencies: Collection[sympy.Symbol],
        load: sympy.Symbol,
        seed: int,
        count: int = 400,
        drawn: Collection[sympy.Symbol] = (),
    ):
        self.points = [{k: v for k, v in p.items() if k not in drawn} for p in points[:4]]
        self.load = load
        self.rows = count * len(self.points)
        self.efficiencies = efficiencies
        self.rng = np.random.default_rng(seed)
        self.columns: dict[sympy.Symbol, np.ndarray] = {}
        #: Each factor's values (by its text) once formed: forces share factors.
        self.factors: dict[str, np.ndarray] = {}
        #: Each drawn value made exact once: the cases of a state read the same rows.
        self._exact: dict[tuple[sympy.Symbol, int], sympy.Rational] = {}

    def column(self, symbol: sympy.Symbol) -> np.ndarray:
        if symbol not in self.columns:
            count = self.rows // len(self.points)
            if symbol in self.points[0]:
                values = np.repeat([_float(p[symbol]) for p in self.points], count)
            elif symbol in self.efficiencies:
                values = self.rng.uniform(0.5, 1.0, self.rows)
            elif symbol == self.load:
                values = 10.0 ** self.rng.uniform(-4, 4, self.rows)
            else:
                values = 10.0 ** self.rng.uniform(-3, 3, self.rows)
            self.columns[symbol] = values
        return self.columns[symbol]

    def point(self, row: int, symbols: Collection[sympy.Symbol]) -> Point:
        """Row ``row`` as exact values (rounded to six significant digits)."""
        out: Point = {}
        for s in symbols:
            exact = self._exact.get((s, row))
            if exact is None:
                value = Fraction(f"{self.column(s)[row]:.6g}")
                exact = self._exact[(s, row)] = sympy.Rational(value.numerator, value.denominator)
            out[s] = exact
        return out


def _float(value: sympy.Expr) -> float:
    """The float nearest ``value`` (a rational's p / q is correctly rounded, as sympy's
    conversion is, without its multiprecision detour)."""
    return value.p / value.q if isinstance(value, sympy.Rational) else float(value)


def needed_signs(
    forces: Mapping[str, tuple[RationalFunction, int]], draws: Draws
) -> tuple[np.ndarray, np.ndarray, list[sympy.Symbol]]:
    """Per draw: whether each force has the sign it needs (rows: draws), whether every
    force is finite, and the symbols drawn."""
    free = sorted({x for f, _ in forces.values() for x in f.free_symbols}, key=str)
    with np.errstate(all="ignore"):
        table = np.array([sign * float_values(f, draws) for f, sign in forces.values()]).T
    return table > 0, np.all(np.isfinite(table), axis=1), free


def float_values(rf: RationalFunction, draws: Draws) -> np.ndarray:
    """``rf`` at every draw in floating point, factor by factor (no compiled function:
    the factors are small, and forming one would print the whole expression)."""
    ring = rf.ring
    (cn, fn), (cd, fd) = rf.factorisation
    out = np.full(draws.rows, float(cn) / float(cd))
    for factors, power in ((fn, 1), (fd, -1)):
        for f, e in factors:
            out *= _factor_values(f, ring.symbols, draws) ** (power * e)
    return out


def _factor_values(f: fmpz_mpoly, symbols: Sequence[sympy.Symbol], draws: Draws) -> np.ndarray:
    """One factor at every draw, formed once per draw table (the columns it reads exist
    once it is formed, so the draws do not depend on what was formed before)."""
    key = str(f)
    if key not in draws.factors:
        value = np.zeros(draws.rows)
        for exponents, coefficient in zip(f.monoms(), f.coeffs(), strict=True):
            term = np.full(draws.rows, float(int(coefficient)))
            for symbol, k in zip(symbols, exponents, strict=True):
                if k:
                    term *= draws.column(symbol) ** int(k)
            value += term
        draws.factors[key] = value
    return draws.factors[key]


def holds_somewhere(
    region: Region, points: Sequence[Point], efficiencies: Sequence[sympy.Symbol], seed: int, count: int = 400
) -> bool:
    """Whether some sampled losses and load at one of ``points`` give every loaded force
    of ``region`` the sign it assumes."""
    if not region.loaded_forces:
        return True
    agree, finite, _ = needed_signs(region.loaded_forces, Draws(points, efficiencies, LOAD_TORQUE, seed, count))
    return bool(np.any(np.all(agree, axis=1) & finite))
