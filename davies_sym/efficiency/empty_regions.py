"""Turning-condition regions no admissible geometry reaches, proved before their
variants are built.

A variant holds where its turning conditions have their signs (Laus Tables 5 and 6,
eqs. (86)-(88)); the admissible geometry is every pitch radius and every fact of the
layout positive (an annulus larger than its pinion, a placement's triangle that
closes), each positive symbol positive.  Where sampling finds no point of a region,
`davies_sym.algebra.linear_regions` looks for a proof that there is none; a proved
region's variants are listed without a formula (`ExcludedVariant`), an unproved one is
derived as any other and reported as not reached by the samples.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy

from davies_sym.algebra.exact_sign import UndecidedSign, number_sign
from davies_sym.algebra.linear_regions import Requirement, empty_region
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameter_domain import admissible_facts
from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.errors import DesignError, Problem
from davies_sym.geometry.layout import Layout
from davies_sym.topology.model import Train

#: Labels of the requirements: a turning condition's, a fact's of the geometry.
CONDITION, FACT = "condition", "fact"


def geometry_facts(train: Train, layout: Layout, conditions: Sequence[TurningCondition]) -> list[Requirement]:
    """What every admissible design satisfies: each pitch radius and layout fact positive,
    each side of a triangle the drawing closes shorter than the other two, and each
    symbol the file declares positive that they or the conditions use."""
    facts = admissible_facts(train, layout)
    used: set[sympy.Symbol] = set()
    for expr in [*(f for f, _ in facts), *(c.expression for c in conditions)]:
        used |= expr.free_symbols
    out = [Requirement(s, ">", FACT) for s in sorted_symbols(used) if s.is_positive]
    seen: set[sympy.Expr] = {s for s in used if s.is_positive}
    sides = [(sympy.sympify(f), "a triangle of the drawing that closes") for f in layout.side_facts]
    for expr, description in [*facts, *sides]:
        if expr not in seen and not expr.is_number:
            seen.add(expr)
            out.append(Requirement(expr, ">", FACT, description))
    return out


def region_requirements(conditions: Sequence[TurningCondition], signs: Mapping[str, int]) -> list[Requirement]:
    """The region of ``signs``: a condition is at least zero where its sign is +1 (a point
    on the boundary counts as positive, as where a variant is chosen) and below zero
    where it is -1."""
    return [Requirement(c.expression, ">=" if signs[c.name] > 0 else "<", CONDITION) for c in conditions]


def emptiness_proof(
    facts: Sequence[Requirement], conditions: Sequence[TurningCondition], signs: Mapping[str, int]
) -> tuple[tuple[Requirement, ...], tuple[Requirement, ...]] | None:
    """The conditions and facts a proof that the region of ``signs`` is empty needs;
    None when no proof is found (or the facts alone are contradictory, which is not this
    region's doing)."""
    proof = empty_region([*region_requirements(conditions, signs), *facts])
    if proof is None:
        return None
    used = tuple(r for r in proof.core if r.label == CONDITION)
    if not used:
        return None
    return used, tuple(r for r in proof.core if r.label == FACT)


def broken_facts(facts: Sequence[Requirement], values: Mapping[sympy.Symbol, sympy.Expr]) -> list[str]:
    """Each fact of the admissible geometry the ``values`` break, with its value there
    (a fact whose symbols are not all given is left to the evaluation's own message).
    Decided by exact signs: a fact that is 0 exactly is broken."""
    out = []
    for fact in facts:
        value = sympy.sympify(fact.expression).subs(values)
        if not value.is_number:
            continue
        try:
            broken = number_sign(value) <= 0
        except UndecidedSign:
            broken = value.is_extended_real is False
        if broken:
            out.append(f"{fact}, which is {sympy.sstr(value)} here")
    return out


def check_facts(facts: Sequence[Requirement], values: Mapping[sympy.Symbol, sympy.Expr], path: str | None) -> None:
    """Refuse (`DesignError`) ``values`` that break a fact of the admissible geometry:
    the one check of it that every entry point makes."""
    broken = broken_facts(facts, values)
    if broken:
        raise DesignError(
            [
                Problem(
                    "values",
                    f"the values break {'; '.join(broken)}: no admissible design has them "
                    "(every pitch radius and every fact of the layout is positive)",
                )
            ],
            path,
        )
