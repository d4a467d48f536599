"""The plain data of a machine file, as frozen dataclasses (read by `machine_loader`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy

from davies_sym.machines.vectors import Vector

#: The time of a task, the variable of its path and loads.
TIME = sympy.Symbol("t", real=True)
#: The most time samples a task may take (the numeric route solves every one).
MAX_STEPS = 100_000


@dataclass(frozen=True)
class Friction:
    """Coulomb friction of a coupling (Laus eqs. (98), (127)-(129), (133) and App. D).

    ``load`` says how the normal load is formed from the transmitted forces: ``sum`` of
    their magnitudes (eqs. (127)-(129)) or their ``resultant`` (eq. (133)).  ``surfaces``
    picks the multipliers of App. D for pins: ``worn`` (cosine law, 4/pi on a half
    cylinder, eq. (146) on a flat face), ``new`` (uniform law, pi/2 and eq. (145)) or
    ``clearance`` (line contact, 1).
    """

    mu: sympy.Expr
    pin_radius: sympy.Expr | None = None
    surfaces: str = "worn"
    load: str = "sum"
    #: A slider's height: its friction forces act on the pressed faces, not on the axis.
    height: sympy.Expr | None = None


@dataclass(frozen=True)
class Coupling:
    """One joint: its kind, the links it connects (tail -> head), where, along what."""

    name: str
    kind: str
    links: tuple[str, str]
    at: Vector
    axis: Vector | None = None
    normal: Vector | None = None
    friction: Friction | None = None
    line: int | None = None


@dataclass(frozen=True)
class Port:
    """Where power enters or leaves: along a coupling's freedom, or a force or torque
    along a direction on a (free) coupling."""

    name: str
    coupling: str
    action: str = "freedom"  # freedom | force | torque
    direction: Vector | None = None


@dataclass(frozen=True)
class Task:
    """A prescribed motion over time (Laus sec. 4.3.4): the position variables as
    functions of ``t``, the coupling whose point they move, and the port loads."""

    name: str
    start: sympy.Expr
    stop: sympy.Expr
    step: sympy.Expr
    path: dict[sympy.Symbol, sympy.Expr]
    drive: str
    loads: dict[str, sympy.Expr]


@dataclass(frozen=True)
class Cycle:
    """One cycle of a one-freedom machine: the position variable runs from ``start`` to
    ``stop`` while the ``steady`` port's power stays constant (Laus eqs. (118)-(123))."""

    variable: sympy.Symbol
    start: sympy.Expr
    stop: sympy.Expr
    steady: str


@dataclass(frozen=True)
class Expected:
    """A published number the machine must reproduce (regression-checked)."""

    quantity: str
    value: float
    tolerance: float
    source: str
    values: dict[str, sympy.Expr] = field(default_factory=dict)
    input: str | None = None
    task: str | None = None


@dataclass(frozen=True)
class Limit:
    """A bound of the workspace: ``margin`` > 0 wherever the machine is assembled as
    modelled (a slider's stroke, a joint's range).  Outside it the network's equations
    may still have a solution, but not one of this machine."""

    name: str
    text: str
    margin: sympy.Expr


@dataclass(frozen=True)
class Machine:
    """A machine file, read: links, couplings, ports and what to derive."""

    name: str
    source: str
    links: tuple[str, ...]
    reference: str
    position: tuple[sympy.Symbol, ...]
    values: dict[sympy.Symbol, sympy.Expr]
    couplings: tuple[Coupling, ...]
    ports: tuple[Port, ...]
    input: str
    tasks: dict[str, Task]
    cycle: Cycle | None
    expected: tuple[Expected, ...]
    vectors: dict[str, Vector] = field(default_factory=dict)
    #: Joint coordinates left unknown, with a guess (which assembly branch), and the
    #: loop-closure equations (expressions equal to zero) that fix them.
    unknowns: dict[sympy.Symbol, sympy.Expr] = field(default_factory=dict)
    closure: tuple[sympy.Expr, ...] = ()
    limits: tuple[Limit, ...] = ()
    path: str | None = None

    def symbols(self) -> dict[str, sympy.Symbol]:
        """Every name the machine's expressions use, by name."""
        found: set[sympy.Symbol] = set(self.values) | set(self.position)
        for c in self.couplings:
            for vec in (c.at, c.axis, c.normal):
                if vec is not None:
                    found |= set().union(*(e.free_symbols for e in vec))
            if c.friction is not None:
                for value in (c.friction.mu, c.friction.pin_radius, c.friction.height):
                    if value is not None:
                        found |= value.free_symbols
        for e in (*self.closure, *self.unknowns.values()):
            found |= e.free_symbols
        return {s.name: s for s in found if s not in self.unknowns}

    def sample(self) -> dict[sympy.Symbol, sympy.Expr]:
        """Values at which the friction modes' regions over a cycle are found: the file's
        values, completed by its first published check's."""
        named = self.symbols()
        out = dict(self.values)
        if self.expected:
            out.update({named[k]: v for k, v in self.expected[0].values.items() if k in named})
        return out

    def coupling(self, name: str) -> Coupling:
        return next(c for c in self.couplings if c.name == name)

    def port(self, name: str) -> Port:
        return next(p for p in self.ports if p.name == name)
