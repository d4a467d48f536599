"""The results of a train driven on several shafts: speed conditions, power-flow regions
and their closed forms, and the choice of the region that holds at given values.

A region is one sign of every speed condition (which gear drives in each mesh and which
way each shaft turns, without losses) and one choice of the couplings whose loaded force
the losses reverse (a mesh whose tooth force the drag reverses swaps its driving gear, a
bearing whose reaction reverses swaps the sense of its Coulomb moment).  Its formulas
hold where every loaded force has the sign the region assumes: at light load, drag and
viscous losses can reverse them (Laus Tables 5 and 6 separate variants the same way).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.errors import DerivationError, NotCoveredError
from davies_sym.network.analysis import Analysis
from davies_sym.topology.model import Train

#: The magnitude of the torque the load puts on the output (it resists the output's motion).
LOAD_TORQUE = sympy.Symbol("tau_out", positive=True)


def speed_symbol(port: str) -> sympy.Symbol:
    """The speed of an input port (signed, along the coupling's positive direction); no
    coupling's magnitude is named so (those are t_<coupling>, w_<coupling>, ...)."""
    return sympy.Symbol(f"omega_{port}", real=True)


@dataclass(frozen=True)
class SpeedCondition:
    """The sign of a linear form in the input speeds: ``form`` > 0 or < 0."""

    name: str
    form: sympy.Expr
    #: What the sign decides (an input's direction, a mesh's driver, a dragging coupling).
    decides: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class Region:
    """One power-flow region and its closed forms."""

    number: int
    signs: Mapping[str, int]
    #: Mesh -> True when its first gear drives.
    first_drives: Mapping[str, bool]
    #: Ports that put power in and ports that take it out, without losses.
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    #: Torque the outside applies at each port, in the load torque and the input speeds.
    torques: Mapping[str, RationalFunction] = field(repr=False)
    efficiency_rf: RationalFunction = field(repr=False)
    #: The tooth force of each mesh and the reaction loading each bearing's Coulomb law,
    #: with the sign the region assumes for it (the formulas hold where all agree).
    loaded_forces: Mapping[str, tuple[RationalFunction, int]] = field(default_factory=dict, repr=False)
    #: Couplings whose loaded force the losses reverse against the lossless direction.
    reversed: frozenset[str] = frozenset()

    @property
    def efficiency(self) -> sympy.Expr:
        return self.efficiency_rf.to_expr()


def _number(expr: sympy.Expr, values: Mapping[sympy.Symbol, sympy.Expr], what: str) -> sympy.Expr:
    value = sympy.sympify(expr.subs(values))
    if not value.is_number:
        raise DerivationError(f"missing values for {', '.join(sorted(map(str, value.free_symbols)))} ({what})")
    return value


@dataclass(frozen=True, eq=False)
class SeveralInputs:
    """Every power-flow region of a train driven on several shafts."""

    train: Train
    analysis: Analysis = field(repr=False)
    speeds: tuple[sympy.Symbol, ...]
    #: Speed of every port (the output's included) in the input speeds.
    port_speeds: Mapping[str, RationalFunction] = field(repr=False)
    conditions: tuple[SpeedCondition, ...]
    regions: tuple[Region, ...]
    #: +1 where a port's torque and speed of one sign put power in.
    pairing: Mapping[str, int] = field(default_factory=dict)

    def region_at(self, values: Mapping[sympy.Symbol, sympy.Expr]) -> Region:
        """The region that holds at ``values``: its speed conditions hold and every loaded
        force has its assumed sign.  Raises `NotCoveredError` where no region's
        forces agree (the losses exceed what the load can carry) or two disagree."""
        signs = {}
        for c in self.conditions:
            value = _number(c.form, values, f"condition {c.name}")
            if value == 0:
                raise DerivationError(
                    f"the speeds lie on the boundary {c.name}: {sympy.sstr(c.form)} = 0 ({', '.join(c.decides)})"
                )
            signs[c.name] = 1 if value > 0 else -1
        candidates = [r for r in self.regions if dict(r.signs) == signs]
        if not candidates:
            raise DerivationError(f"no region has the signs {signs}: no admissible design reaches them")
        holding = []
        for r in candidates:
            forces = {c: _number(f.to_expr(), values, f"the force in {c}") for c, (f, _) in r.loaded_forces.items()}
            if all(sympy.sign(forces[c]) != -assumed for c, (_, assumed) in r.loaded_forces.items()):
                holding.append(r)
        if not holding:
            raise NotCoveredError(
                "no power flow agrees with its own forces at these values (the losses reverse a "
                "tooth force or bearing reaction in a way no region covers)"
            )
        first = _number(holding[0].efficiency, values, "the efficiency")
        if any(_number(r.efficiency, values, "the efficiency") != first for r in holding[1:]):
            raise NotCoveredError(
                f"regions {', '.join(f'({r.number})' for r in holding)} all agree with their own "
                "forces at these values and give different efficiencies (a statically "
                "indeterminate friction state)"
            )
        return holding[0]
