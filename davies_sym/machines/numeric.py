"""A machine at one position, in floating point (Laus sec. 4.3.3, Algorithm 2).

The geometry's expressions are compiled once; at each position the couplings get
numbers, the network matrices are assembled, the motions are solved from the given
ones (eq. (1)) and the actions from the given loads with the friction constitutive
equations appended (eq. (2)).  Coulomb friction makes those equations depend on the
signs (eqs. (127)-(129)) or directions (eq. (133)) of the loads: they are frozen at the
last solution and the linear system solved again until they stop changing; if that
does not settle, the friction coefficients are raised from zero in steps, each from the
previous solution, as Laus's homotopy continuation does (sec. 4.3.3.4).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import sympy

from davies_sym.errors import DerivationError, MissingValuesError, NotCoveredError, Problem
from davies_sym.machines import passages
from davies_sym.machines.closure import NumericClosure, solve_closure
from davies_sym.machines.joints import FrictionAction
from davies_sym.machines.linear import solve_numeric
from davies_sym.machines.machine_model import Coupling, Friction, Machine
from davies_sym.machines.network import GraphMatrices, Network, build_network, graph_matrices

#: Fixed-point rounds before the friction is continued from zero, and its steps.
ROUNDS = 40
CONTINUATION_STEPS = 20


@dataclass(frozen=True)
class PositionSolution:
    """Motions, actions and powers at one position (powers: positive into the machine)."""

    network: Network
    motions: dict[str, float]
    actions: dict[str, float]
    port_power: dict[str, float]
    friction_power: dict[str, float]
    rounds: int
    #: Signs that change only through a singular position (`passages.signs`).
    orientation: dict[str, float] = field(default_factory=dict)


class NumericMachine:
    """The machine's geometry compiled to floating point."""

    def __init__(self, machine: Machine):
        machine = solve_closure(machine)
        self.machine = machine
        self.graph: GraphMatrices = graph_matrices(machine)
        expressions: list[sympy.Expr] = []
        for c in machine.couplings:
            for vec in (c.at, c.axis, c.normal):
                if vec is not None:
                    expressions.extend(vec)
            if c.friction is not None:
                expressions.append(c.friction.mu)
                expressions.append(c.friction.pin_radius if c.friction.pin_radius is not None else sympy.Integer(0))
                expressions.append(c.friction.height if c.friction.height is not None else sympy.Integer(0))
        for p in machine.ports:
            if p.direction is not None:
                expressions.extend(p.direction)
        margins = [limit.margin for limit in machine.limits]
        self.symbols = tuple(sorted(set().union(*(e.free_symbols for e in [*expressions, *margins])), key=str))
        self._evaluate = sympy.lambdify(self.symbols, expressions, modules="math", cse=True)
        self._margins = sympy.lambdify(self.symbols, margins, modules="math", cse=True)
        self.closure: NumericClosure | None = None
        if machine.unknowns:
            used = set().union(*(e.free_symbols for e in (*machine.closure, *machine.unknowns.values())))
            self.closure = NumericClosure(machine, tuple(sorted(used | set(self.symbols), key=str)))

    def missing(self, values: Mapping[sympy.Symbol, float]) -> list[str]:
        needed = set(self.symbols) | (set(self.closure.parameters) if self.closure else set())
        return sorted(s.name for s in needed if s not in values and s not in self.machine.unknowns)

    def assembled(self, values: Mapping[sympy.Symbol, float]) -> dict[sympy.Symbol, float]:
        """``values`` with the loop closure's unknowns solved (from the last position's)."""
        if self.closure is None:
            return dict(values)
        return {**values, **self.closure.solve(values)}

    def _numbers(self, values: Mapping[sympy.Symbol, float]) -> list[Any]:
        """Every compiled geometry expression at ``values`` (the loop closed once), after
        the workspace limits are checked."""
        missing = self.missing(values)
        if missing:
            raise MissingValuesError(
                [Problem("values", f"give {', '.join(missing)} (in values: of the file, a task's path, or --eval)")],
                self.machine.path,
            )
        values = self.assembled(values)
        args = [float(values[s]) for s in self.symbols]
        try:
            numbers = list(self._evaluate(*args))
            margins = self._margins(*args)
        except (ValueError, ZeroDivisionError) as exc:
            raise NotCoveredError(
                f"the linkage cannot be assembled here ({exc}: a square root of a negative number "
                "or a division by zero in its geometry)"
            ) from None
        for limit, margin in zip(self.machine.limits, margins, strict=True):
            if not float(margin) > 0:
                raise NotCoveredError(
                    f"outside the workspace: the limit {limit.name} ({limit.text}) does not hold here"
                )
        return numbers

    def couplings(self, values: Mapping[sympy.Symbol, float]) -> tuple[Coupling, ...]:
        """The couplings with numbers in place of expressions."""
        return self._couplings(self._numbers(values))

    def _couplings(self, evaluated: list[Any]) -> tuple[Coupling, ...]:
        numbers = iter(evaluated)
        out = []
        for c in self.machine.couplings:
            vecs: list[Any] = [
                (next(numbers), next(numbers), next(numbers)) if v is not None else None
                for v in (c.at, c.axis, c.normal)
            ]
            friction = None
            if c.friction is not None:
                mu, radius, height = next(numbers), next(numbers), next(numbers)
                pin = radius if c.friction.pin_radius is not None else None
                tall = height if c.friction.height is not None else None
                friction = Friction(mu, pin, c.friction.surfaces, c.friction.load, tall)
            out.append(replace(c, at=vecs[0], axis=vecs[1], normal=vecs[2], friction=friction))
        if any(isinstance(x, complex) for c in out for v in (c.at, c.axis, c.normal) if v for x in v):
            raise NotCoveredError("the linkage cannot be assembled here")
        return tuple(out)

    def _ported(self, numbers: list[Any]) -> Machine:
        """The machine with numeric port directions (they follow the couplings' numbers)."""
        k = sum(
            sum(3 for v in (c.at, c.axis, c.normal) if v is not None) + (3 if c.friction else 0)
            for c in self.machine.couplings
        )
        ports = []
        for p in self.machine.ports:
            if p.direction is not None:
                ports.append(replace(p, direction=tuple(numbers[k : k + 3])))
                k += 3
            else:
                ports.append(p)
        return replace(self.machine, ports=tuple(ports))

    def position(self, values: Mapping[sympy.Symbol, float]) -> tuple[tuple[Coupling, ...], Network]:
        """The numeric couplings and the network at ``values``, from one evaluation."""
        numbers = self._numbers(values)
        couplings = self._couplings(numbers)
        return couplings, build_network(self._ported(numbers), couplings, self.graph, numeric=True)

    def network(self, values: Mapping[sympy.Symbol, float]) -> Network:
        return self.position(values)[1]


def _friction_rows(
    network: Network, motions: Mapping[str, float], guess: Mapping[str, float], scale: float, weight: float
) -> np.ndarray:
    """Laus eqs. (127)-(129) (sums) or (133) (resultants) with the loads' signs or
    directions frozen at ``guess``."""
    rows = np.zeros((len(network.friction), len(network.actions)))
    motion_scale = max((abs(v) for v in motions.values()), default=0.0)
    for r, f in enumerate(network.friction):
        rows[r, network.action_index(f.name)] = 1.0
        speed = motions[f.freedom]
        sense = 0.0 if abs(speed) <= 1e-12 * motion_scale else float(np.sign(speed))
        loads = [(name, float(w), guess.get(name, 0.0)) for name, w in f.load]
        if f.resultant:
            size = float(np.sqrt(sum((w * q) ** 2 for _, w, q in loads)))
            parts = [(name, w * w * q / size if size > 0 else 0.0) for name, w, q in loads]
        else:
            parts = [(name, w * _load_sign(q, scale)) for name, w, q in loads]
        for name, part in parts:
            rows[r, network.action_index(name)] += weight * float(f.coefficient) * sense * part
    return rows


def _load_sign(value: float, scale: float) -> float:
    """sign(load) as the friction rows take it: 0 for a load negligible beside ``scale``."""
    return 0.0 if abs(value) <= 1e-12 * scale else float(np.sign(value))


def _face_sign(f: FrictionAction, guess: Mapping[str, float], scale: float) -> float:
    """sign(load) of a slider face's friction: which face the one load presses."""
    return _load_sign(guess.get(f.load[0][0], 0.0), scale)


def _shifted(network: Network, guess: Mapping[str, float], scale: float) -> np.ndarray:
    """A_N with each slider face's friction on the face its load presses at ``guess``."""
    if not network.shifts:
        return np.asarray(network.action_matrix)
    matrix = np.array(network.action_matrix, dtype=float)
    for f in network.friction:
        if f.name in network.shifts:
            column = network.action_index(f.name)
            matrix[:, column] += _face_sign(f, guess, scale) * np.asarray(network.shifts[f.name])[:, 0]
    return matrix


def _settled(network: Network, old: Mapping[str, float], new: Mapping[str, float], scale: float) -> bool:
    for f in network.friction:
        for name, _ in f.load:
            a, b = old.get(name, 0.0), new[name]
            if f.resultant:
                if abs(a - b) > 1e-11 * scale:
                    return False
            elif abs(b) > 1e-12 * scale and _load_sign(a, scale) != np.sign(b):
                # The rows took a negligible guess as no load (sign 0): a load that is not
                # negligible now must be taken again with its sign, whatever the guess's.
                return False
    return True


def _actions(
    network: Network,
    motions: Mapping[str, float],
    known: Mapping[str, float],
    start: Mapping[str, float] | None,
    frictionless_system: np.ndarray,
) -> tuple[dict[str, float], int]:
    scale = max(1.0, *(abs(v) for v in known.values()))

    def settle(guess: Mapping[str, float], weight: float) -> tuple[dict[str, float] | None, int]:
        for round_ in range(1, ROUNDS + 1):
            rows = _friction_rows(network, motions, guess, scale, weight)
            matrix = np.vstack([_shifted(network, guess, scale), rows])
            solution = solve_numeric(matrix, network.actions, known, "actions")
            if _settled(network, guess, solution, scale):
                return solution, round_
            guess = solution
        return None, ROUNDS

    frictionless = solve_numeric(frictionless_system, network.actions, known, "actions")
    solution, rounds = settle(start or frictionless, 1.0)
    if solution is not None:
        return solution, rounds
    guess, total = frictionless, rounds
    for step in range(1, CONTINUATION_STEPS + 1):
        reached, rounds = settle(guess, step / CONTINUATION_STEPS)
        total += rounds
        if reached is None:
            raise NotCoveredError(
                "the friction signs do not settle here (a load passes through zero, or the machine locks)"
            )
        guess = reached
    return guess, total


def solve_position(
    numeric: NumericMachine,
    values: Mapping[sympy.Symbol, float],
    known_motions: Mapping[str, float],
    known_actions: Mapping[str, float],
    start: Mapping[str, float] | None = None,
) -> PositionSolution:
    """Motions and actions at one position; ``start``: the actions of a neighbouring
    position, the known problem the continuation starts from."""
    couplings, network = numeric.position(values)
    motions = solve_numeric(network.motion_matrix, network.motions, known_motions, "motions")
    # The friction rows at weight 0 only pin each friction action to zero.
    frictionless = np.vstack([network.action_matrix, _friction_rows(network, motions, {}, 1.0, 0.0)])
    actions, rounds = _actions(network, motions, known_actions, start, frictionless)
    port_power = {
        name: actions[port.action] * sum(float(c) * motions[m] for c, m in port.power_terms)
        for name, port in network.ports.items()
    }
    friction_power: dict[str, float] = {}
    for joint in network.joints:
        for f in (f for f in network.friction if f.coupling == joint.coupling):
            power = actions[f.name] * sum(float(np.dot(f.screw, twist)) * motions[m] for m, twist in joint.freedoms)
            friction_power[joint.coupling] = friction_power.get(joint.coupling, 0.0) + power
    _check_balance(port_power, friction_power)
    orientation = passages.signs(network, couplings, frictionless, known_motions, known_actions)
    return PositionSolution(network, motions, actions, port_power, friction_power, rounds, orientation)


def _check_balance(port_power: Mapping[str, float], friction_power: Mapping[str, float]) -> None:
    """Tellegen's theorem on the network: the powers of all couplings add up to zero;
    friction powers are never positive."""
    total = sum(port_power.values()) + sum(friction_power.values())
    scale = max([1e-300, *(abs(v) for v in port_power.values())])
    if abs(total) > 1e-8 * scale or any(v > 1e-9 * scale for v in friction_power.values()):
        raise DerivationError(f"the power balance fails ({total:.3g} W left over): please report this machine")
