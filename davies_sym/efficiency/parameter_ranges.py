"""Meaning, unit and admissible range of each parameter of a train's formulas.

One table for every entry point: the formula modules list it (``PARAMETERS``) and give
NaN outside it, ``derive --eval`` and `VariantSet.design_point` refuse a value outside it
(`range_problem`), with the same words.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.exact_sign import UndecidedSign, number_sign
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.network.friction_laws import FrictionLaw
from davies_sym.topology.coupling_kinds import as_skew_mesh, toothed_meshes
from davies_sym.topology.model import Gear, Train


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


#: The unit of every length of a train: radii, modules, journal radii.
LENGTH = "length (one unit for all)"


def _sizes(gear: Gear) -> tuple[tuple[sympy.Expr, str, str], ...]:
    """What sizes ``gear`` as the file writes it: (quantity, what it is, unit)."""
    module = () if gear.module is None else ((gear.module, "module", LENGTH),)
    if gear.teeth is not None:
        return ((sympy.sympify(gear.teeth), "number of teeth", "teeth"), *module)
    return ((gear.written_radius, "pitch radius", LENGTH), *module)


def _gears_text(gears: Sequence[Gear]) -> str:
    """``gear S (link s)``, ``internal gear R (link r)``; several: ``gears S, P, R``."""
    if len(gears) == 1:
        g = gears[0]
        return f"{'internal gear' if g.internal else 'gear'} {g.name} (link {g.link})"
    return "gears " + ", ".join(g.name for g in gears)


def _gear_meanings(train: Train) -> dict[sympy.Symbol, tuple[str, str]]:
    """Meaning and unit of each symbol that sizes a gear, as the file writes it (a tooth
    number, a module, a pitch radius, or a symbol in one), naming every gear it sizes; a
    dependent parameter (solved from a geometric constraint) says so with its relation."""
    roles: dict[sympy.Symbol, dict[tuple[str, str], list[Gear]]] = {}
    for g in train.gears:
        for quantity, what, unit in _sizes(g):
            for s in sorted_symbols(quantity.free_symbols):
                role = (what if quantity == s else f"symbol in the {what}", unit)
                gears = roles.setdefault(s, {}).setdefault(role, [])
                if g not in gears:
                    gears.append(g)
    relations = {r.symbol: r for r in train.dependent or ()}
    out: dict[sympy.Symbol, tuple[str, str]] = {}
    for s, by_role in roles.items():
        meaning = "; ".join(f"{what} of {_gears_text(gears)}" for (what, _), gears in by_role.items())
        if s in relations:
            meaning += f", given by the geometric constraint as {relations[s]}"
        out[s] = (meaning, next(iter(by_role))[1])
    return out


def _efficiency_meanings(train: Train) -> dict[sympy.Symbol, str]:
    out: dict[sympy.Symbol, str] = {}
    for mesh in toothed_meshes(train.couplings):
        if mesh.efficiencies is None:
            continue
        first, second = mesh.sides
        both = mesh.efficiencies[0] == mesh.efficiencies[1]
        for k, eta in enumerate(mesh.efficiencies):
            driver, driven = (first, second) if k == 0 else (second, first)
            text = (
                f"ordinary efficiency of mesh {mesh.name} ({mesh.pair_words}), either {mesh.member_noun} driving"
                if both
                else f"ordinary efficiency of mesh {mesh.name}, {driver} driving {driven}"
            )
            for s in sorted_symbols(eta.free_symbols):
                out.setdefault(s, text)
    return out


def _law_meanings(train: Train, laws: Sequence[FrictionLaw]) -> dict[sympy.Symbol, tuple[str, str]]:
    out: dict[sympy.Symbol, tuple[str, str]] = {}
    for law in laws:
        for s in sorted_symbols(law.coefficient.free_symbols):
            coupling = train.coupling(law.coupling)
            if as_skew_mesh(coupling) is not None:  # mu of a sliding contact: a plain number
                out.setdefault(s, (f"sliding friction coefficient of mesh {law.coupling}", "1"))
                continue
            unit = coupling.load_dependent_unit if law.load_dependent else law.unit
            out.setdefault(s, (f"{law.name} friction coefficient of {coupling.noun} {law.coupling}", unit))
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


def parameters_of_train(
    train: Train,
    laws: Sequence[FrictionLaw],
    symbols: Sequence[sympy.Symbol],
    operating: Mapping[sympy.Symbol, Parameter],
) -> tuple[Parameter, ...]:
    """The rows of ``symbols`` (in their order): loss-model parameters, ordinary
    efficiencies in (0, 1], the gears' sizes (tooth numbers, modules, pitch radii),
    friction coefficients, and the ``operating`` quantities (speeds and torques at the
    ports) as given."""
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
            meaning, unit = geometry[s]
            out.append(Parameter(str(s), meaning, unit, 0.0, math.inf))
        elif s in law_meanings:
            meaning, unit = law_meanings[s]
            out.append(Parameter(str(s), meaning, unit, 0.0, math.inf, closed_low=True))
        else:
            out.append(Parameter(str(s), "symbol of the topology file", "", -math.inf, math.inf))
    return tuple(out)


#: The operating quantities the formulas may take (drag, viscous friction), as parameters.
OPERATING_PARAMETERS: Mapping[sympy.Symbol, Parameter] = {
    INPUT_SPEED: Parameter(str(INPUT_SPEED), "input speed (magnitude, at the input port)", "rad/s", 0.0, math.inf),
    INPUT_TORQUE: Parameter(str(INPUT_TORQUE), "input torque (magnitude, at the input port)", "torque", 0.0, math.inf),
}


def range_problem(parameter: Parameter, value: sympy.Expr) -> str | None:
    """Why ``value`` lies outside ``parameter``'s admissible range (None when inside),
    decided by exact signs: a value exactly on a bound is decided too."""
    try:
        below = number_sign(value - sympy.nsimplify(parameter.low)) if math.isfinite(parameter.low) else 1
        above = number_sign(value - _bound(parameter.high)) if math.isfinite(parameter.high) else -1
    except UndecidedSign:
        return f"{parameter.name} = {sympy.sstr(value)} is not a finite real number"
    if below < 0 or (below == 0 and not parameter.closed_low) or above > 0:
        return (
            f"{parameter.name} = {_shown(value)} is outside the admissible range {parameter.range_text} "
            f"of the {parameter.meaning}"
        )
    return None


def _bound(high: float) -> sympy.Expr:
    """The exact upper bound a float of the table stands for (pi/2 for an angle)."""
    return sympy.pi / 2 if high == math.pi / 2 else sympy.nsimplify(high)


def _shown(value: sympy.Expr) -> str:
    text = sympy.sstr(value)
    return text if len(text) <= 40 else str(sympy.N(value, 6))
