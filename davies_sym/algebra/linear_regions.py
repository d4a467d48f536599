"""Exact proofs that a region of sign conditions is empty.

A region is a conjunction of requirements ``p > 0``, ``p >= 0`` or ``p < 0`` on
rational expressions.  Each expression is factored (flint); a product's sign is a
disjunction over the signs of its factors.  Where the factors are linear (radii, sums
and differences of radii, the factors of a placement's triangle), every branch is a
system of linear inequalities, decided exactly by Fourier-Motzkin elimination over the
rationals.  A requirement with a factor of higher degree is left out: dropping
requirements only enlarges the region, so emptiness proved without it still holds.
Nothing here guesses: the answer is a proof of emptiness, or no answer.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import product

import sympy

from davies_sym.algebra.flint_conversion import factor_expression

#: Relations a requirement may state of its expression.
RELATIONS = (">", ">=", "<")

#: Most eliminations (of a sign pattern of the factors, whole or partial) one search
#: may run, and most inequalities one elimination may hold; beyond either, no answer.
MAX_BRANCHES = 512
MAX_INEQUALITIES = 4000


@dataclass(frozen=True)
class Requirement:
    """``expression relation 0``, with a label saying which kind it is and a
    description saying what it is (``pitch radius of PL``)."""

    expression: sympy.Expr
    relation: str
    label: str = ""
    description: str = ""

    def __post_init__(self) -> None:
        if self.relation not in RELATIONS:
            raise ValueError(f"relation must be one of {RELATIONS}")

    def factored(self) -> sympy.Expr:
        """The expression as the product of its irreducible factors (unevaluated)."""
        sign, factors = factor_expression(self.expression)
        if len(factors) < 2:
            return self.expression
        product = sympy.Mul(*(f**e for f, e in factors), evaluate=False)
        return sympy.Mul(-1, product, evaluate=False) if sign < 0 else product

    def __str__(self) -> str:
        shown = f"{sympy.sstr(self.factored())} {self.relation} 0"
        return f"{shown} ({self.description})" if self.description else shown


@dataclass(frozen=True)
class Inequality:
    """``sum(coefficients[x] x) + constant > 0`` (strict) or ``>= 0``."""

    coefficients: tuple[tuple[sympy.Symbol, Fraction], ...]
    constant: Fraction
    strict: bool


Branch = tuple[Inequality, ...]
_Form = tuple[tuple[tuple[sympy.Symbol, Fraction], ...], Fraction]


def _linear(factor: sympy.Expr) -> _Form | None:
    """The coefficients and constant of a polynomial of degree one, else None."""
    poly = sympy.Poly(factor, *sorted(factor.free_symbols, key=str))
    if poly.total_degree() > 1:
        return None
    coefficients, constant = [], Fraction(0)
    for monom, coeff in poly.terms():
        value = Fraction(int(coeff.p), int(coeff.q))
        if not any(monom):
            constant = value
        else:
            coefficients.append((poly.gens[monom.index(1)], value))
    return tuple(coefficients), constant


def _inequality(form: _Form, sign: int, strict: bool) -> Inequality:
    """``sign * form > 0`` (strict) or ``>= 0``."""
    coefficients, constant = form
    return Inequality(tuple((x, sign * a) for x, a in coefficients), sign * constant, strict)


def branches(requirement: Requirement) -> list[Branch] | None:
    """The linear systems one of which must hold where ``requirement`` does (a product
    is positive where an even number of its odd-power factors is negative; ``>= 0`` also
    where a factor is zero); None when a factor is not linear."""
    sign, factors = factor_expression(requirement.expression)
    if sign == 0:  # the expression is zero
        return [()] if requirement.relation == ">=" else []
    forms = []
    for base, exponent in factors:
        form = _linear(base)
        if form is None:
            return None
        forms.append((form, abs(exponent)))
    odd = [form for form, e in forms if e % 2]
    even = [form for form, e in forms if not e % 2]
    wanted = -1 if requirement.relation == "<" else 1
    out: list[Branch] = []
    for signs in product((1, -1), repeat=len(odd)):
        if sign * math.prod(signs) != wanted:
            continue
        system = [_inequality(f, s, True) for f, s in zip(odd, signs, strict=True)]
        # An even power is positive where it is not zero; zero is not > 0 nor < 0.
        nonzero = [[_inequality(f, s, True) for s in (1, -1)] for f in even]
        for choice in product(*nonzero):
            out.append((*system, *choice))
    if requirement.relation == ">=":
        for form, _ in forms:  # the product is zero where one factor is
            out.append((_inequality(form, 1, False), _inequality(form, -1, False)))
    return out


def feasible(system: Sequence[Inequality]) -> bool | None:
    """Whether the linear system has a real solution, by Fourier-Motzkin elimination in
    exact rationals; None when it grows beyond `MAX_INEQUALITIES`."""
    rows = _normalised(system)
    while rows is not None:
        if not rows:
            return True
        counts: dict[sympy.Symbol, list[int]] = {}
        for coefficients, _, _ in rows:
            for x, a in coefficients.items():
                counts.setdefault(x, [0, 0])[0 if a > 0 else 1] += 1
        # A variable of one sign only can be taken large enough: its rows always hold.
        one_sided = next((x for x, (p, n) in counts.items() if p == 0 or n == 0), None)
        if one_sided is not None:
            rows = [r for r in rows if one_sided not in r[0]]
            continue
        x = min(counts, key=lambda s: (counts[s][0] * counts[s][1], str(s)))
        upper = [r for r in rows if r[0].get(x, 0) < 0]
        lower = [r for r in rows if r[0].get(x, 0) > 0]
        combined = [r for r in rows if x not in r[0]]
        if len(combined) + len(upper) * len(lower) > MAX_INEQUALITIES:
            return None
        for (cu, ku, su), (cl, kl, sl) in product(upper, lower):
            a, b = -cu[x], cl[x]  # both positive: b * upper + a * lower frees x
            coefficients = {y: b * cu.get(y, 0) + a * cl.get(y, 0) for y in {*cu, *cl} - {x}}
            combined.append((coefficients, b * ku + a * kl, su or sl))
        rows = _reduced(combined)
    return False


_Row = tuple[dict[sympy.Symbol, Fraction], Fraction, bool]


def _normalised(system: Sequence[Inequality]) -> list[_Row] | None:
    return _reduced([(dict(i.coefficients), i.constant, i.strict) for i in system])


def _reduced(rows: Sequence[_Row]) -> list[_Row] | None:
    """``rows`` without zero coefficients, each scaled so its largest coefficient is one,
    the tightest of parallel rows kept; None when a row without variables fails."""
    best: dict[tuple[tuple[str, sympy.Symbol, Fraction], ...], tuple[Fraction, bool]] = {}
    for coefficients, constant, strict in rows:
        coefficients = {x: a for x, a in coefficients.items() if a != 0}
        if not coefficients:
            if constant < 0 or (strict and constant == 0):
                return None
            continue
        scale = max(abs(a) for a in coefficients.values())
        key = tuple(sorted(((str(x), x, a / scale) for x, a in coefficients.items()), key=lambda t: t[0]))
        bound = (constant / scale, strict)
        known = best.get(key)
        if known is None or bound[0] < known[0] or (bound[0] == known[0] and strict):
            best[key] = bound
    return [({x: a for _, x, a in key}, constant, strict) for key, (constant, strict) in best.items()]


@dataclass(frozen=True)
class Emptiness:
    """A proof that no point satisfies every requirement: the requirements it needs."""

    core: tuple[Requirement, ...]


def empty_region(requirements: Sequence[Requirement]) -> Emptiness | None:
    """A proof that the requirements have no common real solution, with a core of them
    that alone has none; None when none is found (the region may be empty all the same)."""
    usable = [(r, b) for r in requirements if (b := branches(r)) is not None]
    if _empty([b for _, b in usable]) is not True:
        return None
    core = list(usable)
    for item in list(core):  # drop what the proof does not need, one at a time
        trial = [other for other in core if other is not item]
        if _empty([b for _, b in trial]) is True:
            core = trial
    return Emptiness(tuple(r for r, _ in core))


def _empty(alternatives: Sequence[list[Branch]]) -> bool | None:
    """Whether every combination of one branch per requirement is infeasible; None when
    one is feasible, or the search needs more than `MAX_BRANCHES` eliminations."""
    budget = [MAX_BRANCHES]
    for system in _systems(sorted(alternatives, key=len), (), budget):
        answer = _checked(system, budget)
        if answer is not False:
            return None if answer is None else False
    return None if budget[0] < 0 else True


def _checked(system: Branch, budget: list[int]) -> bool | None:
    """`feasible`, counted against ``budget`` (None once it is spent)."""
    budget[0] -= 1
    return None if budget[0] < 0 else feasible(system)


def _systems(alternatives: Sequence[list[Branch]], base: Branch, budget: list[int]) -> Iterator[Branch]:
    """Every combination of one branch per requirement, a partial one cut off as soon as
    it is infeasible on its own (depth first: the single-branch requirements come first);
    the search stops when ``budget`` is spent."""
    if not alternatives:
        yield base
        return
    first, rest = alternatives[0], alternatives[1:]
    for branch in first:
        if budget[0] < 0:
            return
        system = (*base, *branch)
        if rest and _checked(system, budget) is False:
            continue
        yield from _systems(rest, system, budget)
