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
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.radicals import restore
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.parameter_domain import admissible_facts
from davies_sym.efficiency.variants import VariantSet
from davies_sym.losses.definitions import parameters_of
from davies_sym.network.matrices import FrictionLaw
from davies_sym.topology.couplings import GearMesh
from davies_sym.topology.model import Train
from davies_sym.topology.skew_mesh import SkewMesh


@dataclass(frozen=True)
class Parameter:
    """One parameter: ``low < value <= high`` (``low`` included when ``closed_low``)."""

    name: str
    meaning: str
    unit: str
    low: float
    high: float
    closed_low: bool = False

    @property
    def range_text(self) -> str:
        low = "[" if self.closed_low else "("
        high = "inf)" if math.isinf(self.high) else f"{self.high:g}]"
        return f"{low}{self.low:g}, {high}"


def _gear_meanings(train: Train) -> dict[sympy.Symbol, str]:
    out: dict[sympy.Symbol, str] = {}
    for g in train.gears:
        kind = "internal gear" if g.internal else "gear"
        for s in sorted_symbols(g.radius.free_symbols):
            what = "pitch radius" if g.radius == s else "length in the pitch radius"
            out.setdefault(s, f"{what} of {kind} {g.name} (link {g.link})")
    return out


def _efficiency_meanings(train: Train) -> dict[sympy.Symbol, str]:
    out: dict[sympy.Symbol, str] = {}
    for mesh in train.couplings:
        if not isinstance(mesh, GearMesh) or mesh.efficiencies is None or mesh.gears is None:
            continue
        first, second = mesh.gears
        both = mesh.efficiencies[0] == mesh.efficiencies[1]
        for k, eta in enumerate(mesh.efficiencies):
            driver, driven = (first, second) if k == 0 else (second, first)
            text = (
                f"ordinary efficiency of mesh {mesh.name} (gears {first}, {second}), either gear driving"
                if both
                else f"ordinary efficiency of mesh {mesh.name}, gear {driver} driving gear {driven}"
            )
            for s in sorted_symbols(eta.free_symbols):
                out.setdefault(s, text)
    return out


def _law_meanings(train: Train, laws: Sequence[FrictionLaw]) -> dict[sympy.Symbol, tuple[str, str]]:
    out: dict[sympy.Symbol, tuple[str, str]] = {}
    units = {"coulomb": "length", "linear": "length", "viscous": "torque / angular speed", "drag": "torque"}
    for law in laws:
        for s in sorted_symbols(law.coefficient.free_symbols):
            coupling = train.coupling(law.coupling)
            if isinstance(coupling, SkewMesh):  # mu of a sliding contact: a plain number
                out.setdefault(s, (f"sliding friction coefficient of mesh {law.coupling}", "1"))
                continue
            what = "mesh" if isinstance(coupling, GearMesh) else "coupling"
            out.setdefault(s, (f"{law.law} friction coefficient of {what} {law.coupling}", units.get(law.law, "")))
    return out


def _angle_meanings(train: Train) -> dict[sympy.Symbol, str]:
    """The angles of the meshes (lead, helix, normal pressure angle), in radians
    strictly between 0 and pi/2."""
    out: dict[sympy.Symbol, str] = {}
    for c in train.couplings:
        for angle in c.angles:
            for s in sorted_symbols(angle.angle.free_symbols):
                out.setdefault(s, angle.meaning)
    return out


def _definition_meanings(train: Train) -> dict[sympy.Symbol, tuple[str, str]]:
    """The parameters of the loss models (a flank or journal friction coefficient, a
    journal radius), named by what they define."""
    out: dict[sympy.Symbol, tuple[str, str]] = {}
    gears = _gear_meanings(train)
    for d in train.definitions:
        for s in sorted_symbols(d.expression.free_symbols):
            if s not in gears:
                out.setdefault(s, (f"parameter of the {d.meaning} ({d.source})", d.unit_of(s)))
    return out


def formula_symbols(variants: VariantSet) -> list[sympy.Symbol]:
    """The symbols of the formulas, the conditions and the speed ratio, sorted by name."""
    layout = variants.analysis.network.layout
    ratio = restore(variants.analysis.speed_ratio().to_expr(), layout.radicals)
    return sorted_symbols(parameters_of(set(variants.symbols) | ratio.free_symbols, variants.train.definitions))


def parameter_table(variants: VariantSet) -> tuple[Parameter, ...]:
    """Every symbol of `formula_symbols`, in its order."""
    ports = {
        INPUT_SPEED: Parameter(str(INPUT_SPEED), "input speed (magnitude, at the input port)", "rad/s", 0.0, math.inf),
        INPUT_TORQUE: Parameter(
            str(INPUT_TORQUE), "input torque (magnitude, at the input port)", "torque", 0.0, math.inf
        ),
    }
    return parameters_of_train(variants.train, variants.analysis.network.laws, formula_symbols(variants), ports)


def parameters_of_train(
    train: Train,
    laws: Sequence[FrictionLaw],
    symbols: Sequence[sympy.Symbol],
    operating: Mapping[sympy.Symbol, Parameter],
) -> tuple[Parameter, ...]:
    """The rows of ``symbols`` (in their order): loss-model parameters, ordinary
    efficiencies in (0, 1], lengths and friction coefficients, and the ``operating``
    quantities (speeds and torques at the ports) as given."""
    geometry, etas, law_meanings = _gear_meanings(train), _efficiency_meanings(train), _law_meanings(train, laws)
    defined, angles = _definition_meanings(train), _angle_meanings(train)
    out = []
    for s in symbols:
        if s in operating:
            out.append(operating[s])
        elif s in angles:
            out.append(Parameter(str(s), angles[s], "rad", 0.0, math.pi / 2))
        elif s in defined:
            meaning, unit = defined[s]
            out.append(Parameter(str(s), meaning, unit, 0.0, math.inf))
        elif s in etas:
            out.append(Parameter(str(s), etas[s], "1", 0.0, 1.0))
        elif s in geometry:
            out.append(Parameter(str(s), geometry[s], "length (one unit for all)", 0.0, math.inf))
        elif s in law_meanings:
            meaning, unit = law_meanings[s]
            out.append(Parameter(str(s), meaning, unit, 0.0, math.inf, closed_low=True))
        else:
            out.append(Parameter(str(s), "symbol of the topology file", "", -math.inf, math.inf))
    return tuple(out)


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
    """Expressions positive on every admissible design, in the formulas' symbols (radii
    eliminated by the geometric constraints replaced; bare symbols and sums of positive
    terms are left to the ranges)."""
    layout = variants.analysis.network.layout
    eliminate = eliminated_symbols(variants)
    known = set(variants.symbols)
    out: list[sympy.Expr] = []
    facts = [expr for expr, _ in admissible_facts(variants.train, layout)]
    for expr in facts + _implied_by_excluded(variants):
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
    formulas are written in the efficiencies).  The formula modules of all states of
    one file accept all of them, so design code calls every state alike."""
    replaced: set[sympy.Basic] = set()
    for c in train.couplings:
        if isinstance(c, GearMesh) and c.efficiencies and c.friction.coulomb is not None:
            replaced |= c.friction.coulomb.free_symbols
    return tuple(sorted(name for name, s in train.symbols.items() if s not in replaced))
