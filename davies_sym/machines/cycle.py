"""Efficiency over one cycle of a one-freedom machine (Laus eqs. (118)-(123)).

With the ``steady`` port's power constant while the position variable runs over the
cycle, the work ratio is an integral of the per-position efficiency over the regions
of its friction modes: the mean of eta when the steady port is the input (eq. (120)),
the cycle length over the integral of 1/eta when it is the output (eq. (123)).  A term
``sin(theta) g(cos(theta))`` is integrated by ``u = cos(theta)``; what has no closed
form is integrated numerically (and said so).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise

import mpmath
import sympy
from sympy.integrals.manualintegrate import manualintegrate

from davies_sym.errors import MissingValuesError, NotCoveredError, Problem
from davies_sym.machines.closed_form import DirectionForms, ModeVariant
from davies_sym.machines.machine_model import Cycle, Machine
from davies_sym.machines.numeric import NumericMachine

#: Positions of a cycle at which the linkage must assemble before its efficiency is given.
ASSEMBLY_SAMPLES = 721


@dataclass(frozen=True)
class CycleEfficiency:
    """The cycle efficiency with one port as the input: closed, or ``None`` with the
    integrand pieces for numerical evaluation."""

    input: str
    steady: str
    variable: sympy.Symbol
    closed: sympy.Expr | None
    pieces: tuple[tuple[sympy.Expr, sympy.Interval], ...]
    length: sympy.Expr
    steady_is_input: bool

    @property
    def equation(self) -> str:
        """The thesis's equation for this cycle efficiency: the mean of eta with a steady
        input, the length over the integral of 1/eta with a steady output."""
        return "Laus eq. (120)" if self.steady_is_input else "Laus eq. (123)"

    def evaluate(self, values: dict[sympy.Symbol, sympy.Expr]) -> float:
        if self.closed is not None:
            value = sympy.N(self.closed.subs(values), 30)
            if not (value.is_real and value.is_finite):
                raise NotCoveredError(
                    f"the cycle efficiency is not a finite real number here ({value}): "
                    "the cycle passes through a singular position"
                )
            return float(value)
        total = mpmath.mpf(0)
        for integrand, interval in self.pieces:
            f = sympy.lambdify(self.variable, integrand.subs(values), "mpmath")
            lo, hi = (float(sympy.N(e.subs(values))) for e in (interval.start, interval.end))
            total += mpmath.quad(f, [lo, hi])
        length = float(sympy.N(self.length.subs(values)))
        return float(total / length if self.steady_is_input else length / total)


def check_assembles(machine: Machine, cycle: Cycle, values: dict[sympy.Symbol, sympy.Expr]) -> None:
    """Refuse a cycle the linkage cannot run through: it must assemble, within its
    limits, at every sampled position (a crank longer than its rod has no full turn)."""
    numeric = NumericMachine(machine)
    floats = {s: float(sympy.N(v)) for s, v in values.items() if s != cycle.variable}
    lo, hi = (float(sympy.N(e.subs(values))) for e in (cycle.start, cycle.stop))
    for k in range(ASSEMBLY_SAMPLES):
        at = lo + (hi - lo) * k / (ASSEMBLY_SAMPLES - 1)
        try:
            numeric.couplings({**floats, cycle.variable: at})
        except NotCoveredError as exc:
            raise NotCoveredError(f"no cycle efficiency: at {cycle.variable} = {at:.6g} {exc}") from None


def _boundaries(variant: ModeVariant, cycle: Cycle, sample: dict[sympy.Symbol, sympy.Expr]) -> list[sympy.Expr]:
    """Exact positions where a condition of ``variant`` can change sign: the zeros of
    its factors that solveset finds; a factor without exact zeros must keep its sign
    over the cycle at the sample point (else the region has no closed form)."""
    x, points = cycle.variable, [cycle.start, cycle.stop]
    domain = sympy.Interval(cycle.start, cycle.stop)
    for condition in variant.conditions:
        numerator, denominator = sympy.fraction(sympy.factor(condition))
        for factor in sympy.Mul.make_args(numerator) + sympy.Mul.make_args(denominator):
            if not factor.has(x):
                continue
            at_sample = factor.subs(sample)
            if at_sample.free_symbols - {x}:
                names = ", ".join(sorted(s.name for s in at_sample.free_symbols - {x}))
                raise MissingValuesError(
                    [
                        Problem(
                            "values", f"give {names} in values: to find where the friction modes hold over the cycle"
                        )
                    ],
                    None,
                )
            f = sympy.lambdify(x, at_sample, "mpmath")
            lo, hi = float(cycle.start.subs(sample)), float(cycle.stop.subs(sample))
            grid = [f(lo + (hi - lo) * (k + 0.5) / 400) for k in range(400)]
            if min(grid) > 0 or max(grid) < 0:
                continue  # one sign over the whole cycle
            zeros = sympy.solveset(sympy.Eq(factor, 0), x, domain)
            if not isinstance(zeros, sympy.FiniteSet):
                raise NotCoveredError(f"where {factor} changes sign has no closed form")
            points.extend(zeros)
    return sorted(set(points), key=lambda p: float(p))


def _region(variant: ModeVariant, cycle: Cycle, sample: dict[sympy.Symbol, sympy.Expr]) -> list[sympy.Interval]:
    """The intervals of the cycle where every condition of ``variant`` holds, judged
    between consecutive exact boundaries at the sample point."""
    points = _boundaries(variant, cycle, sample)
    out = []
    for lo, hi in pairwise(points):
        middle = {**sample, cycle.variable: (lo + hi) / 2}
        if all(sympy.N(c.subs(middle)) > 0 for c in variant.conditions):
            out.append(sympy.Interval(lo, hi))
    return out


def _branch(expr: sympy.Expr, sample: dict[sympy.Symbol, sympy.Expr]) -> sympy.Expr:
    """``expr`` with every Piecewise replaced by its branch that holds at ``sample``."""

    def pick(*pairs: tuple[sympy.Expr, sympy.Basic]) -> sympy.Expr:
        for value, condition in pairs:
            if condition is sympy.true or bool(condition.subs(sample)):
                return value
        raise NotCoveredError("no branch of the antiderivative holds at the sample values")

    return expr.replace(lambda e: isinstance(e, sympy.Piecewise), lambda e: pick(*e.args))


def _antiderivative(g: sympy.Expr, u: sympy.Symbol, sample: dict[sympy.Symbol, sympy.Expr]) -> sympy.Expr | None:
    value = manualintegrate(g, u)
    return None if value.has(sympy.Integral) else _branch(value, sample)


def _integrate_term(
    term: sympy.Expr, x: sympy.Symbol, lo: sympy.Expr, hi: sympy.Expr, sample: dict[sympy.Symbol, sympy.Expr]
) -> sympy.Expr | None:
    """Closed integral of one term over [lo, hi], or None."""
    if not term.has(x):
        return term * (hi - lo)
    h = sympy.cancel(term / sympy.sin(x))
    if sympy.expand(h.subs(x, -x) - h) == 0:
        u = sympy.Dummy("u", real=True)
        g = h.subs(sympy.sin(x) ** 2, 1 - sympy.cos(x) ** 2).subs(sympy.cos(x), u)
        if not g.has(x) and (found := _antiderivative(g, u, sample)) is not None:
            return found.subs(u, sympy.cos(lo)) - found.subs(u, sympy.cos(hi))
    found = _antiderivative(term, x, sample)
    return None if found is None else found.subs(x, hi) - found.subs(x, lo)


def cycle_efficiency(
    direction: DirectionForms, cycle: Cycle, sample: dict[sympy.Symbol, sympy.Expr]
) -> CycleEfficiency:
    """Laus eq. (120) (steady input) or (123) (steady output) for ``direction``; the
    variants' regions are found at the parameter values ``sample``."""
    steady_is_input = cycle.steady == direction.input
    pieces = []
    for variant in direction.variants:
        integrand = variant.efficiency if steady_is_input else sympy.cancel(1 / variant.efficiency)
        for interval in _region(variant, cycle, sample):
            pieces.append((integrand, interval))
    length = cycle.stop - cycle.start
    total: sympy.Expr | None = sympy.Integer(0)
    for integrand, interval in pieces:
        for term in sympy.Add.make_args(sympy.expand(integrand)):
            value = _integrate_term(term, cycle.variable, interval.start, interval.end, sample)
            if value is None or total is None:
                total = None
                break
            total += value
    closed = None
    if total is not None:
        closed = sympy.expand(total / length) if steady_is_input else length / sympy.expand(total)
    return CycleEfficiency(
        direction.input, cycle.steady, cycle.variable, closed, tuple(pieces), length, steady_is_input
    )
