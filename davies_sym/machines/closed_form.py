"""Closed-form efficiency of a one-freedom machine per friction mode (Laus sec. 4.2).

Coulomb friction makes the constitutive equations depend on signs: the friction action
of a freedom is ``-mu sign(motion) sum |load|`` (eq. (98)).  Writing each product
``a = sign(motion) sign(load)`` as a symbol keeps ``D_A`` linear (eq. (107)); every
assignment of the ``a`` is one friction mode, a variant of the efficiency, valid where
the signs it assumed are those of its own solution (Laus eqs. (112)-(114)).  Geometry
enters through abbreviations of the coordinates (``B_x``, ``C_x``, eq. (97)) so the
elimination stays rational; they are substituted back for the output.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import product

import sympy

from davies_sym.errors import NotCoveredError
from davies_sym.machines.closure import solve_closure
from davies_sym.machines.linear import solve_exact
from davies_sym.machines.machine_model import Machine
from davies_sym.machines.network import Network, build_network
from davies_sym.machines.vectors import Vector


@dataclass(frozen=True)
class FrictionMode:
    """One sign product: ``symbol = sign(motion) * sign(load)``; with no motion, the sign
    of the load alone (which face of a slider it presses, Laus Fig. 14)."""

    symbol: sympy.Symbol
    friction: str
    motion: str | None
    load: str


@dataclass(frozen=True)
class ModeVariant:
    """The efficiency under one assignment of the friction modes, and where it holds:
    every condition is an expression that is positive there."""

    signs: tuple[tuple[sympy.Symbol, int], ...]
    efficiency: sympy.Expr
    abbreviated: sympy.Expr
    conditions: tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class DirectionForms:
    """The closed forms with one port as the input (Laus sec. 4.2.4, cases 1 and 2)."""

    input: str
    output: str
    motions: dict[str, sympy.Expr]
    actions: dict[str, sympy.Expr]
    variants: tuple[ModeVariant, ...]


@dataclass(frozen=True)
class ClosedForms:
    machine: Machine
    network: Network
    abbreviations: dict[sympy.Symbol, sympy.Expr]
    modes: tuple[FrictionMode, ...]
    directions: tuple[DirectionForms, ...]

    def direction(self, port: str) -> DirectionForms:
        return next(d for d in self.directions if d.input == port)


def _abbreviate(machine: Machine) -> tuple[Machine, dict[sympy.Symbol, sympy.Expr]]:
    """The machine with every coupling point that is a named vector written in
    coordinate symbols (``B_x``), and those symbols' values."""
    values: dict[sympy.Symbol, sympy.Expr] = {}
    by_value = {vec: name for name, vec in machine.vectors.items()}

    def short(vec: Vector) -> Vector:
        name = by_value.get(vec)
        if name is None:
            return vec
        out = []
        for axis, coordinate in zip("xyz", vec, strict=True):
            if coordinate.is_number:
                out.append(coordinate)
                continue
            symbol = sympy.Symbol(f"{name}_{axis}", real=True)
            values[symbol] = coordinate
            out.append(symbol)
        return (out[0], out[1], out[2])

    couplings = tuple(replace(c, at=short(c.at)) for c in machine.couplings)
    return replace(machine, couplings=couplings), values


def _modes(network: Network) -> tuple[FrictionMode, ...]:
    modes = []
    for f in network.friction:
        if f.resultant:
            raise NotCoveredError(
                f"{f.name}: friction from the resultant load (Laus eq. (133)) has no closed form; "
                "evaluate it at a position (--eval) or along a task (--task)"
            )
        for load, _ in f.load:
            modes.append((f.coupling, f, load))
    per_coupling = {c: sum(1 for m in modes if m[0] == c) for c, _, _ in modes}
    out = []
    for c, f, load in modes:
        suffix = c if per_coupling[c] == 1 else f"{f.name.split('_', 1)[1]}_{load.split('_', 1)[1]}"
        out.append(FrictionMode(sympy.Symbol(f"a_{suffix}", real=True), f.name, f.freedom, load))
        if f.shift is not None:
            out.append(FrictionMode(sympy.Symbol(f"s_{suffix}", real=True), f.name, None, load))
    return tuple(out)


def constitutive_rows(network: Network, modes: tuple[FrictionMode, ...]) -> sympy.Matrix:
    """One row per friction action: ``Psi_f + c sum_k w_k a_k Psi_k = 0`` (Laus eq. (107))."""
    rows = sympy.zeros(len(network.friction), len(network.actions))
    for r, f in enumerate(network.friction):
        rows[r, network.action_index(f.name)] = 1
        for load, weight in f.load:
            mode = next(m for m in modes if m.friction == f.name and m.load == load and m.motion is not None)
            rows[r, network.action_index(load)] += f.coefficient * weight * mode.symbol
    return rows


def shifted_actions(network: Network, modes: tuple[FrictionMode, ...]) -> sympy.Matrix:
    """A_N with each slider face's friction on the face its load's sign presses."""
    matrix = network.action_matrix.copy()
    for f in network.friction:
        if f.name in network.shifts:
            face = next(m for m in modes if m.friction == f.name and m.motion is None)
            matrix[:, network.action_index(f.name)] += face.symbol * network.shifts[f.name]
    return matrix


def sign_free(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` without the factors whose sign is known positive (declared positive
    symbols, square roots, even powers, positive numbers): a condition ``expr > 0``
    reads as simply as the thesis writes it (eq. (114))."""
    expr = sympy.factor(sympy.cancel(expr))
    sign, kept = 1, []
    for factor in sympy.Mul.make_args(expr):
        if factor.is_number:
            sign *= 1 if factor > 0 else -1
        elif factor.is_positive or (
            isinstance(factor, sympy.Pow) and factor.exp.is_Rational and (factor.exp.q == 2 or factor.exp.p % 2 == 0)
        ):
            continue
        else:
            kept.append(factor)
    return sign * sympy.Mul(*kept)


def derive_closed_forms(machine: Machine) -> ClosedForms:
    """Every friction mode's efficiency, each port taken as the input in turn."""
    machine = solve_closure(machine)
    if machine.unknowns:
        names = ", ".join(u.name for u in machine.unknowns)
        raise NotCoveredError(
            f"the loop closure for {names} has no closed form here; evaluate at a position (--eval) or a task"
        )
    short, abbreviations = _abbreviate(machine)
    network = build_network(short)
    if len(machine.ports) != 2:
        raise NotCoveredError("a closed form is derived for machines with two ports (an input and an output)")
    modes = _modes(network)
    d_a = shifted_actions(network, modes).col_join(constitutive_rows(network, modes))
    directions = []
    for port in machine.ports:
        other = next(p for p in machine.ports if p.name != port.name)
        into, out = network.ports[port.name], network.ports[other.name]
        motion_primary = into.power_terms[0][1]
        motions = solve_exact(
            network.motion_matrix, network.motions, {motion_primary: sympy.Symbol(motion_primary, real=True)}, "motions"
        )
        actions = solve_exact(d_a, network.actions, {into.action: sympy.Symbol(into.action, real=True)}, "actions")
        unit = {sympy.Symbol(motion_primary, real=True): 1, sympy.Symbol(into.action, real=True): 1}
        p_in = sum(c * motions[m] for c, m in into.power_terms) * actions[into.action]
        p_out = sum(c * motions[m] for c, m in out.power_terms) * actions[out.action]
        eta = sympy.cancel((-p_out / p_in).subs(unit))
        variants = []
        for signs in product((1, -1), repeat=len(modes)):
            chosen = {m.symbol: s for m, s in zip(modes, signs, strict=True)}
            conditions = tuple(
                sign_free(
                    (s * (motions[m.motion] if m.motion is not None else 1) * actions[m.load])
                    .subs(unit)
                    .subs(chosen)
                    .subs(abbreviations)
                )
                for m, s in zip(modes, signs, strict=True)
            )
            if any(c.is_number and c <= 0 for c in conditions):
                continue
            abbreviated = sympy.cancel(eta.subs(chosen))
            full = sympy.cancel(abbreviated.subs(abbreviations))
            variants.append(
                ModeVariant(tuple(chosen.items()), full, abbreviated, tuple(c for c in conditions if not c.is_number))
            )
        directions.append(DirectionForms(port.name, other.name, motions, actions, tuple(variants)))
    return ClosedForms(machine, network, abbreviations, modes, tuple(directions))
