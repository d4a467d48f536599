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

from davies_sym.algebra.exact_sign import UndecidedSign, number_sign
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.design_values import design_values
from davies_sym.efficiency.parameter_ranges import Parameter, parameters_of_train, range_problem
from davies_sym.errors import DerivationError, DesignError, InputError, MissingValuesError, NotCoveredError, Problem
from davies_sym.losses.definitions import completed, parameters_of
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


def _sign(value: sympy.Expr, what: str) -> int:
    """The exact sign of ``value`` (radicals included), never a relational's truth value."""
    try:
        return number_sign(value)
    except UndecidedSign:
        raise NotCoveredError(f"the sign of {what} ({sympy.sstr(value)}) cannot be decided exactly") from None


@dataclass(frozen=True)
class OperatingPoint:
    """The region, port torques and efficiency at given speeds, load and parameters."""

    region: Region
    #: Torque the outside applies at each port.
    torques: Mapping[str, sympy.Expr]
    efficiency: sympy.Expr
    #: Power into the train at each port (negative where the port takes power out).
    powers: Mapping[str, sympy.Expr]

    @property
    def inputs(self) -> tuple[str, ...]:
        return tuple(p for p, v in self.powers.items() if _sign(v, f"the power at {p}") > 0)

    @property
    def outputs(self) -> tuple[str, ...]:
        return tuple(p for p, v in self.powers.items() if _sign(v, f"the power at {p}") < 0)


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
            sign = _sign(_number(c.form, values, f"condition {c.name}"), f"condition {c.name}")
            if sign == 0:
                raise DerivationError(
                    f"the speeds lie on the boundary {c.name}: {sympy.sstr(c.form)} = 0 ({', '.join(c.decides)})"
                )
            signs[c.name] = sign
        candidates = [r for r in self.regions if dict(r.signs) == signs]
        if not candidates:
            raise DerivationError(f"no region has the signs {signs}: no admissible design reaches them")
        holding = []
        for r in candidates:
            forces = {
                c: _sign(_number(f.to_expr(), values, f"the force in {c}"), f"the force in {c}")
                for c, (f, _) in r.loaded_forces.items()
            }
            if all(forces[c] != -assumed for c, (_, assumed) in r.loaded_forces.items()):
                holding.append(r)
        if not holding:
            raise NotCoveredError(
                "no power flow agrees with its own forces at these values (the losses reverse a "
                "tooth force or bearing reaction in a way no region covers)"
            )
        first = _number(holding[0].efficiency, values, "the efficiency")
        if any(
            _sign(_number(r.efficiency, values, "the efficiency") - first, "a difference of efficiencies") != 0
            for r in holding[1:]
        ):
            raise NotCoveredError(
                f"regions {', '.join(f'({r.number})' for r in holding)} all agree with their own "
                "forces at these values and give different efficiencies (a statically "
                "indeterminate friction state)"
            )
        return holding[0]

    def operating_parameters(self) -> dict[sympy.Symbol, Parameter]:
        """The input speeds and the load as rows of the parameter table."""
        ports = self.train.ports
        out = {
            s: Parameter(
                str(s),
                f"speed of input port {p} (signed, along the coupling's positive direction)",
                "rad/s",
                -float("inf"),
                float("inf"),
            )
            for p, s in zip(ports.inputs, self.speeds, strict=True)
        }
        out[LOAD_TORQUE] = Parameter(
            str(LOAD_TORQUE),
            f"load torque at output port {ports.output} (magnitude, resisting its motion)",
            "torque",
            0.0,
            float("inf"),
        )
        return out

    def parameter_table(self, symbols: list[sympy.Symbol] | None = None) -> tuple[Parameter, ...]:
        """Meaning, unit and admissible range of ``symbols`` (default: every one the
        formulas may take): the module's ``PARAMETERS``."""
        if symbols is None:
            train = self.train
            own = set(train.symbols.values())
            symbols = sorted_symbols({*self.speeds, LOAD_TORQUE, *own, *parameters_of(own, train.definitions)})
        return parameters_of_train(self.train, self.analysis.network.laws, symbols, self.operating_parameters())

    def design_point(self, values: Mapping[sympy.Symbol | str, object]) -> OperatingPoint:
        """The region, torques, powers and efficiency at ``values`` (keyed by symbol or
        name, exact when the values are): the one decision the CLI, the API and the
        module share.  Refuses (`InputError`, `DesignError`, `NotCoveredError`) bad or
        missing values, values outside the parameter table, speeds on a region's
        boundary, and a design whose losses exceed the power put in
        (Mantriota and Pennestri 2003, eq. (6) outside (0, 1])."""
        train = self.train
        given = design_values(train, values, "values", (*self.speeds, LOAD_TORQUE))
        by_name = {str(s): v for s, v in given.items()}
        table = self.parameter_table(sorted_symbols(given))
        outside = [why for p in table if (why := range_problem(p, by_name[p.name])) is not None]
        if outside:
            raise DesignError([Problem("values", why) for why in outside], train.path)
        point = completed(given, train.definitions)
        try:
            region = self.region_at(point)
        except DerivationError as exc:
            raise InputError([Problem("values", str(exc))], train.path) from None
        eta = sympy.sympify(region.efficiency.subs(point))
        torques = {p: sympy.sympify(t.to_expr().subs(point)) for p, t in region.torques.items()}
        missing = sorted({str(s) for e in (eta, *torques.values()) for s in e.free_symbols})
        if missing:
            raise MissingValuesError([Problem("values", f"missing values for {', '.join(missing)}")], train.path)
        if _sign(eta, "the efficiency") <= 0 or _sign(eta - 1, "the efficiency less 1") > 0:
            raise NotCoveredError(
                f"region ({region.number}) gives the efficiency {sympy.N(eta, 6)}, outside (0, 1]: "
                "the losses exceed the power put in (the load is too small for the drag, or the "
                "train self-locks)"
            )
        powers = {
            p: sympy.sympify(t * self.port_speeds[p].to_expr().subs(point) * self.pairing[p])
            for p, t in torques.items()
        }
        return OperatingPoint(region, torques, eta, powers)

    def evaluate(self, values: Mapping[sympy.Symbol | str, object]) -> sympy.Expr:
        """The efficiency at ``values``; a design `design_point` refuses is refused here."""
        return self.design_point(values).efficiency
