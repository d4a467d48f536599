"""The validated, immutable model of a train (what `davies_sym.load` returns).

`Gear` lives in `.gear` (couplings read gears too) and is named here as part
of the model."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType

import sympy

from davies_sym.errors import FileLines, InputError, Problem
from davies_sym.losses.definitions import Definition
from davies_sym.topology.calibration_entry import CalibrationDefaults
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.gear import Gear as Gear  # named here as part of the model
from davies_sym.topology.symbol_display import latex
from davies_sym.topology.train_display import train_html, train_latex


@dataclass(frozen=True)
class Link:
    """A member of the machine (a node of the coupling graph)."""

    name: str
    description: str = ""


@dataclass(frozen=True)
class Ports:
    """The couplings that carry the input and the output action (Laus section 2.3)."""

    input: str
    output: str
    #: Further inputs of a train with several degrees of freedom (a differential driven on
    #: two shafts, Mantriota and Pennestri 2003).
    others: tuple[str, ...] = ()

    @property
    def inputs(self) -> tuple[str, ...]:
        return (self.input, *self.others)

    @property
    def every(self) -> tuple[str, ...]:
        """Every port: the inputs, then the output."""
        return (*self.inputs, self.output)

    def swapped(self) -> Ports:
        return Ports(self.output, self.input)


@dataclass(frozen=True)
class State:
    """An operating state of a multi-speed set: its ports, the members braked to the
    housing, the members clutched together and the members running free (unloaded)."""

    name: str
    input: str
    output: str
    brake: tuple[str, ...] = ()
    clutch: tuple[tuple[str, str], ...] = ()
    free: tuple[str, ...] = ()
    description: str = ""


@dataclass(frozen=True)
class Relation:
    """A parameter the geometry determines from the others: ``symbol = expression``,
    from the geometric constraint ``constraint`` (e.g. r4 = r2 + r3 - r1 from
    r1 - r3 = r2 - r4, Laus section 3.4.1.6)."""

    symbol: sympy.Symbol
    expression: sympy.Expr
    constraint: str

    def __str__(self) -> str:
        return f"{self.symbol} = {sympy.sstr(self.expression)}"


@dataclass(frozen=True)
class Expected:
    """A number to reproduce: parameter values, expected value, tolerance.

    ``published`` is False for a regression value of the file's own geometry (not a
    number from the literature); ``differs`` explains a published number that the file's
    geometry does not reproduce (the check then asserts that it differs)."""

    quantity: str
    values: Mapping[str, str]
    value: float
    tolerance: float
    source: str
    input: str | None = None
    state: str | None = None
    published: bool = True
    differs: str | None = None


@dataclass(frozen=True)
class Train:
    """A gear train (or machine) as written in a topology file, validated."""

    name: str
    links: tuple[Link, ...]
    gears: tuple[Gear, ...]
    couplings: tuple[Coupling, ...]
    ports: Ports
    reference: str
    symbols: Mapping[str, sympy.Symbol] = field(default_factory=lambda: MappingProxyType({}))
    source: str = ""
    degrees_of_freedom: int | None = None
    expected: tuple[Expected, ...] = ()
    path: str | None = None
    #: Line of each entry path of the source file (``couplings.C.gears`` -> 12).
    locations: Mapping[str, int] = field(default_factory=lambda: MappingProxyType({}))
    states: tuple[State, ...] = ()
    #: Placement direction (x, y) of a planar train drawn in 2-D; None: drawn on a line.
    placement: tuple[sympy.Expr, sympy.Expr] | None = None
    #: For a train in one operating state: the train with every member, whose geometry
    #: the state keeps (a brake or a clutch joins members, it does not move their axes).
    whole: Train | None = field(default=None, repr=False, compare=False)
    #: Symbols the user declares independent (``independent:``); None: the default choice.
    independent: tuple[str, ...] | None = None
    #: Parameters solved from the geometric constraints and substituted into the gears;
    #: None until the geometry has been solved (`davies_sym.geometry.dependent.resolved_train`).
    dependent: tuple[Relation, ...] | None = None
    #: What ``derive calibrate`` fits by default (the ``calibrate`` entry).
    calibrate: CalibrationDefaults | None = None
    #: The entry where each symbol is first written (``r1`` -> ``gears.1.radius``), for a
    #: problem with a symbol found after loading (a name a generated module cannot hold).
    written: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    #: Entries the later stages name that the file writes elsewhere: the train of an
    #: operating state has its ports at ``states.NAME`` (``ports.input`` ->
    #: ``states.NAME.input``), so a problem with them points at the state's own entry.
    renamed: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))

    @property
    def definitions(self) -> tuple[Definition, ...]:
        """Symbols that loss models define in other parameters (Laus App. A, App. D)."""
        return tuple(d for c in self.couplings for d in c.definitions)

    def _repr_html_(self) -> str:
        summary = f"input {', '.join(self.ports.inputs)}, output {self.ports.output}; reference link {self.reference}"
        if (self.degrees_of_freedom or 1) > 1:
            summary += f"; {self.degrees_of_freedom} degrees of freedom"
        return train_html(
            self.name,
            self.source,
            summary,
            [(k.name, k.description) for k in self.links],
            [(c.name, type(c).__name__, " \u2014 ".join(c.links)) for c in self.couplings],
        )

    def _repr_latex_(self) -> str:
        gears = [(g.name, latex(g.radius), g.link) for g in self.gears]
        return train_latex(self.name, (", ".join(self.ports.inputs), self.ports.output), gears)

    @property
    def file_lines(self) -> FileLines:
        """Where the file writes each entry: an error raised with these puts its problems
        at their lines (`davies_sym.errors.FileLines`)."""
        return FileLines(self.path, self.locations, self.renamed)

    def problem(self, entry: str, message: str) -> Problem:
        """A `Problem` at ``entry`` (where the file writes it, see ``renamed``) with the
        line it has in the source file."""
        return self.file_lines.locate(Problem(entry, message))

    def symbol_problem(self, name: str, message: str) -> Problem:
        """A `Problem` with the symbol ``name``, at the entry where the file first writes it."""
        return self.problem(self.written.get(name, ""), message)

    def coupling(self, name: str) -> Coupling:
        for c in self.couplings:
            if c.name == name:
                return c
        raise KeyError(name)

    def gear(self, name: str) -> Gear:
        for g in self.gears:
            if g.name == name:
                return g
        raise KeyError(name)

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.links)

    def state(self, name: str, entry: str = "--state") -> State:
        """The operating state ``name``; an unknown one is refused at ``entry`` (the option
        or argument that named it) with the known names."""
        for st in self.states:
            if st.name == name:
                return st
        known = ", ".join(st.name for st in self.states) or "none"
        raise InputError([Problem(entry, f"unknown state {name!r} (states: {known})")], self.path)

    def published_design(self, state: str | None = None) -> Mapping[str, str]:
        """Parameter values of the first published check of ``state`` (or of a check
        given for the whole train); empty when there is none."""
        for check in self.expected:
            if check.state in (None, state):
                return check.values
        return {}

    def with_ports(self, ports: Ports) -> Train:
        """The same train with other input/output ports."""
        return replace(self, ports=ports)
