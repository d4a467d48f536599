"""Which power-flow regions admissible designs reach, found by sampling.

Speed conditions: for sampled geometries, one direction of the input speeds inside
every sector between the condition lines (two inputs) or random directions (more).
Reversed loaded forces: for those speeds, random losses (ordinary efficiencies in
(1/2, 1), other loss parameters and the load torque spread over decades), and a region
is kept where some sample has every loaded force of the sign the region assumes.  A
region missed here is never a wrong number: where no kept region's forces agree, the
answer is refused.
"""

from __future__ import annotations

import math
import random
from collections.abc import Sequence
from fractions import Fraction
from itertools import pairwise

import numpy as np
import sympy

from davies_sym.efficiency.parameter_domain import ParameterDomain
from davies_sym.efficiency.power_flow_regions import LOAD_TORQUE, Region
from davies_sym.network.analysis import Analysis
from davies_sym.topology.model import Train

Point = dict[sympy.Symbol, sympy.Expr]


def reached_signs(train: Train, analysis: Analysis, forms: Sequence[sympy.Expr], speeds: tuple[sympy.Symbol, ...],
                  samples: int, seed: int) -> dict[tuple[int, ...], list[Point]]:
    """Sign vectors of the speed conditions that admissible designs reach, each with the
    points (geometry and input speeds) that reached it."""
    domain = ParameterDomain.of(train, analysis.network.layout)
    rng = random.Random(seed)
    out: dict[tuple[int, ...], list[Point]] = {}
    for point in domain.samples(samples, seed=seed):
        fixed = [sympy.expand(f.subs(point)) for f in forms]
        directions: list[tuple[Fraction, ...]] = []
        if len(speeds) == 2:
            angles = sorted({math.atan2(-float(f.coeff(speeds[0])), float(f.coeff(speeds[1]))) % math.pi + k * math.pi
                             for f in fixed for k in (0, 1)})
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


def holds_somewhere(region: Region, points: Sequence[Point], efficiencies: Sequence[sympy.Symbol],
                    seed: int, count: int = 400) -> bool:
    """Whether some sampled losses and load at one of ``points`` give every loaded force
    of ``region`` the sign it assumes."""
    signed = [f.to_expr() * assumed for f, assumed in region.loaded_forces.values()]
    if not signed:
        return True
    rng = np.random.default_rng(seed)
    for point in points[:4]:
        fixed = [sympy.sympify(f.subs(point)) for f in signed]
        free = sorted({s for f in fixed for s in f.free_symbols}, key=str)
        columns = []
        for s in free:
            if s in efficiencies:
                columns.append(rng.uniform(0.5, 1.0, count))
            elif s == LOAD_TORQUE:
                columns.append(10.0 ** rng.uniform(-4, 4, count))
            else:
                columns.append(10.0 ** rng.uniform(-3, 3, count))
        function = sympy.lambdify(free, fixed, "numpy")
        with np.errstate(all="ignore"):
            values = [np.broadcast_to(np.asarray(v, dtype=float), (count,)) for v in function(*columns)]
        if np.any(np.all(np.array(values) > 0, axis=0)):
            return True
    return False
