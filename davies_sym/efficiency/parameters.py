"""What each parameter of a train's formulas is: meaning, unit and admissible range.

The generated formula modules and the documentation list them (``PARAMETERS``), and the
admissible design is stated as relations that must be positive (``RELATIONS``): every
pitch radius and every known fact of the layout (an annulus larger than its pinion, a
radicand of a bevel geometry), written in the symbols left after the geometric
constraints eliminated some radii, and the sign of a turning condition the facts are
proved to imply (`davies_sym.efficiency.empty_regions`).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence

import sympy

from davies_sym.algebra.radicals import Radical, restore
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameter_domain import admissible_facts
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.power_flow_regions import SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.losses.definitions import parameters_of, substituted
from davies_sym.topology.coupling_kinds import toothed_meshes
from davies_sym.topology.model import Train


def formula_symbols(variants: VariantSet) -> list[sympy.Symbol]:
    """The symbols of the formulas, the conditions and the speed ratio, sorted by name."""
    return variants.parameters


def given_parameters(variants: VariantSet) -> dict[str, sympy.Symbol]:
    """The parameters the user gives, by name in sorted order: the formulas' symbols with
    every symbol a loss model or an angle defines replaced by its definition's parameters."""
    return {str(s): s for s in sorted_symbols(parameters_of(variants.symbols, variants.train.definitions))}


def given_form(expr: sympy.Expr, train: Train, radicals: Sequence[Radical]) -> sympy.Expr:
    """``expr`` in the parameters the user gives: the layout's square roots written as
    roots, every defined symbol replaced by its definition."""
    return substituted(restore(expr, radicals), train.definitions)


def given_forms(derived: VariantSet | SeveralInputs) -> Callable[[sympy.Expr], sympy.Expr]:
    """`given_form` for the formulas of ``derived`` (the variants of a train driven at
    one port, or the regions of one driven at several)."""
    train, radicals = derived.train, derived.analysis.network.layout.radicals
    return lambda expr: given_form(expr, train, radicals)


def parameter_table(variants: VariantSet) -> tuple[Parameter, ...]:
    """Every symbol of `formula_symbols`, in its order."""
    return variants.parameter_table


def eliminated_symbols(variants: VariantSet) -> dict[sympy.Symbol, sympy.Expr]:
    """Parameters the geometric constraints determine, in the independent ones (Tuplin:
    r4 = r2 + r3 - r1); the formulas do not use them."""
    return {r.symbol: r.expression for r in variants.train.dependent or ()}


def _obviously_positive(expr: sympy.Expr) -> bool:
    """A sum of positive terms in positive symbols."""
    return all(c > 0 for c in sympy.Poly(expr, *sorted_symbols(expr.free_symbols)).coeffs()) and all(
        s.is_positive for s in expr.free_symbols
    )


def admissible_relations(variants: VariantSet) -> tuple[sympy.Expr, ...]:
    """Expressions positive on every admissible design, in the symbols of the formulas and
    the speed ratio, which a formula module takes alike (radii eliminated by the geometric
    constraints replaced; bare symbols and sums of positive terms are left to the
    ranges): a module checks each where it is given every symbol, as the engine does."""
    layout = variants.analysis.network.layout
    eliminate = eliminated_symbols(variants)
    ratio = restore(variants.analysis.speed_ratio().to_expr(), layout.radicals)
    known = set(variants.symbols) | ratio.free_symbols
    out: list[sympy.Expr] = []
    facts = [expr for expr, _ in admissible_facts(variants.train, layout)]
    for expr in facts + list(layout.side_facts) + _implied_by_excluded(variants):
        relation = sympy.expand(restore(expr.subs(eliminate), layout.radicals))
        if relation.is_Symbol or relation.is_number or not relation.free_symbols <= known:
            continue
        if not relation.is_polynomial() or _obviously_positive(relation):
            continue
        if relation not in out:
            out.append(relation)
    return tuple(out)


def _implied_by_excluded(variants: VariantSet) -> list[sympy.Expr]:
    """-c of each turning condition c whose whole positive side (c >= 0, with every sign
    of the others) is proved to hold no admissible design: the facts imply c < 0, in
    the formulas' symbols even where a fact needs others (Ravigneaux 2nd gear: the
    planets' triangle, with the short planet's radius, implies rs1 < rr)."""
    empty = {tuple(v.signs[c.name] for c in variants.conditions) for v in variants.excluded}
    out = []
    for k, c in enumerate(variants.conditions):
        side = [combo for combo in itertools.product((1, -1), repeat=len(variants.conditions)) if combo[k] > 0]
        if all(combo in empty for combo in side):
            out.append(-c.expression)
    return out


def file_parameters(train: Train) -> tuple[str, ...]:
    """Every parameter any state of ``train`` may take, sorted: the symbols of the file
    except the friction coefficients of meshes that give ordinary efficiencies (the
    formulas are written in the efficiencies) and the free lengths of the layout (a
    chain's centre distance).  The formula modules of all states of one file accept all
    of them, so design code calls every state alike."""
    replaced: set[sympy.Basic] = set()
    for c in toothed_meshes(train.couplings):
        if c.efficiencies and c.friction.coulomb is not None:
            replaced |= c.friction.coulomb.free_symbols
    replaced |= {s for c in train.couplings for s in c.free_lengths}
    return tuple(sorted(name for name, s in train.symbols.items() if s not in replaced))
