"""Geometric constraints applied: each solved for one parameter, substituted into the gears.

Where the loops of meshes over-determine the radii (r1 - r3 = r2 - r4 for Tuplin's
train, Laus section 3.4.1.6; r_R = r_S + 2 r_P for a simple planetary set), every
formula must hold on the constraint, not for radii that break it.  Each constraint is
solved exactly (it is linear in the parameter chosen) for one parameter, which the
train then gives by the others: speed ratios, efficiencies and generated modules are
written in the independent parameters, and a value given for a dependent one is checked
against the relation (`check_values`), never used as another train.

The choice: the symbols of ``independent:`` in the file stay free; otherwise the
annulus radius when the constraint makes it a sum of the others, then a radius of the
mesh that closes the loop (its planet's gear first), then the first by name.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

import sympy

from davies_sym.algebra.signs import without_positive_factors
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.caches import IdentityCache
from davies_sym.errors import DesignError, GeometryError, Problem
from davies_sym.geometry import train_layout
from davies_sym.geometry.layout import Layout, linear_roots, polynomial_part, tidy_quotient
from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.gear import Gear
from davies_sym.topology.model import Relation, Train


def resolved_train(train: Train) -> Train:
    """``train`` with every geometric constraint solved for one parameter and substituted
    into the gear radii (a state: the constraints of its whole train)."""
    if train.dependent is not None:
        return train
    return _RESOLVED.get(train, lambda: _resolved(train))


#: The resolved form of each train, derived once while the train lives.
_RESOLVED: IdentityCache[Train, Train] = IdentityCache()


def _resolved(train: Train) -> Train:
    if train.whole is not None:
        whole = resolved_train(train.whole)
        # A state's gear is its whole's (on a renamed link): its radius resolved there.
        done = {(g.name, g.radius): r for g, r in zip(train.whole.gears, whole.gears, strict=True)}
        return _substituted(replace(train, whole=whole), whole.dependent or (), done)
    return _substituted(train, _solve(train, train_layout(train)))


def _substituted(
    train: Train, relations: tuple[Relation, ...], done: Mapping[tuple[str, sympy.Expr], Gear] | None = None
) -> Train:
    """``train`` with ``relations`` substituted into its radii; a gear found in ``done``
    (by its name and radius as written: the whole train's, resolved) takes its radius."""
    values = {r.symbol: r.expression for r in relations}

    def resolved(g: Gear) -> Gear:
        if not values:
            return g
        known = (done or {}).get((g.name, g.radius))
        if known is not None:
            return replace(g, radius=known.radius, written=known.written)
        return replace(g, radius=sympy.expand(g.radius.subs(values)), written=g.written_radius)

    return replace(train, gears=tuple(resolved(g) for g in train.gears), dependent=relations)


def _solve(train: Train, layout: Layout) -> tuple[Relation, ...]:
    """One parameter per constraint, solved in order, each substituted into the next."""
    independent = set(train.independent or ())
    preferred = _preferred(train, layout.planet_second)
    relations: list[Relation] = []
    problems: list[Problem] = []
    for c in layout.constraints:
        values = {r.symbol: r.expression for r in relations}
        # A module solved before makes the radii quotients: solve on the numerator.
        expr = without_positive_factors(polynomial_part(sympy.expand(c.expression.subs(values))))
        if expr == 0:
            continue  # implied by the constraints solved already
        roots = linear_roots(expr, independent)
        if not roots:
            problems.append(
                Problem(
                    "independent" if independent else f"couplings.{c.coupling}",
                    f"the geometric constraint {c} leaves no parameter to solve for"
                    + (
                        f": `independent` lists all of {', '.join(sorted(map(str, expr.free_symbols)))}; leave one out"
                        if independent
                        else ""
                    ),
                )
            )
            continue
        symbol = min(roots, key=lambda s: _rank(s, roots[s], c.coupling, preferred))
        solution = tidy_quotient(roots[symbol])
        relations = [
            Relation(r.symbol, tidy_quotient(r.expression.subs(symbol, solution)), r.constraint) for r in relations
        ]
        relations.append(Relation(symbol, solution, str(c)))
    if problems:
        raise GeometryError(problems, train.file_lines)
    return tuple(relations)


def _preferred(train: Train, planet_second: frozenset[str]) -> dict[str, list[sympy.Symbol]]:
    """Mesh -> the radius symbols of its gears, the planet's gear first."""
    gears = {g.name: g for g in train.gears}
    out: dict[str, list[sympy.Symbol]] = {}
    for c in gear_meshes(train.couplings):
        order = c.gears[::-1] if c.name in planet_second else c.gears
        out[c.name] = [s for g in order for s in sorted_symbols(gears[g].radius.free_symbols)]
    return out


def _rank(
    symbol: sympy.Symbol, solution: sympy.Expr, coupling: str, preferred: Mapping[str, list[sympy.Symbol]]
) -> tuple[int, int, str]:
    """How much ``symbol`` (whose root is ``solution``) is preferred as the parameter a
    constraint closed by ``coupling`` gives: a positive sum first, then the closing
    mesh's radii in ``preferred`` order, then by name (lowest first)."""
    positive_sum = solution.is_Add and all(t.as_coeff_Mul()[0] > 0 for t in solution.args)
    closing = preferred.get(coupling, [])
    return (0 if positive_sum else 1, closing.index(symbol) if symbol in closing else len(closing), str(symbol))


def check_values(train: Train, values: Mapping[sympy.Symbol, sympy.Expr]) -> dict[sympy.Symbol, sympy.Expr]:
    """``values`` without the dependent parameters, each checked against its relation:
    a value that breaks it is refused (`DesignError`) with the relation, both values
    and their difference."""
    relations = {r.symbol: r for r in resolved_train(train).dependent or ()}
    problems = []
    out = {}
    for symbol, value in values.items():
        relation = relations.get(symbol)
        if relation is None:
            out[symbol] = value
            continue
        implied = sympy.expand(relation.expression.subs(values))
        if implied.free_symbols:
            continue  # the relation cannot be checked without the other values
        difference = sympy.expand(value - implied)
        if difference != 0:
            problems.append(
                Problem(
                    "values",
                    f"{symbol} = {value} breaks the relation {relation} (from the "
                    f"geometric constraint {relation.constraint}), which gives {implied}; the "
                    f"difference is {difference}",
                )
            )
    if problems:
        raise DesignError(problems, train.file_lines)
    return out


def with_dependent(train: Train, values: Mapping[sympy.Symbol, sympy.Expr]) -> dict[sympy.Symbol, sympy.Expr]:
    """`check_values`, then each dependent parameter the given values determine added
    with its value (a loss model may be written in it: the tooth-contact efficiency of a
    planet's mesh takes the planet's teeth)."""
    out = check_values(train, values)
    for r in resolved_train(train).dependent or ():
        implied = sympy.expand(r.expression.subs(out))
        if not implied.free_symbols:
            out.setdefault(r.symbol, implied)
    return out
