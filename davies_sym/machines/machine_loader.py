"""Read a machine file (YAML) into a `Machine`; every problem is reported with its line.

A machine file is told from a gear-train file by its ``machine:`` entry (the name).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import sympy

from davies_sym.algebra.screws import cross
from davies_sym.errors import Problem, TopologyError
from davies_sym.machines import entry_checks
from davies_sym.machines.joints import JOINT_KINDS
from davies_sym.machines.machine_model import Coupling, Cycle, Expected, Friction, Limit, Machine, Port, Task
from davies_sym.machines.vectors import AXES, Vector, parse_scalar, parse_vector
from davies_sym.topology.expressions import ExpressionError
from davies_sym.topology.yaml_source import SourceDocument

_TOP = {
    "format",
    "machine",
    "source",
    "links",
    "reference",
    "position",
    "values",
    "vectors",
    "couplings",
    "ports",
    "input",
    "cycle",
    "tasks",
    "expected",
    "positive",
    "unknowns",
    "closure",
    "limits",
}
_COUPLING_KEYS = {"type", "links", "at", "axis", "normal", "axes", "friction"}
_NEEDS_AXIS = {"revolute", "prismatic", "cylindrical", "square_annulus", "round_annulus"}


def is_machine(data: object) -> bool:
    """Whether a parsed YAML document describes a general machine."""
    return isinstance(data, dict) and "machine" in data


class _Reader:
    def __init__(self, doc: SourceDocument):
        self.doc = doc
        self.problems: list[Problem] = []
        self.symbols: dict[str, sympy.Symbol] = {}
        self.vectors: dict[str, Vector] = {}

    def symbol(self, name: str) -> sympy.Symbol:
        return self.symbols.setdefault(name, sympy.Symbol(name, real=True))

    def declare_positive(self, names: list[str]) -> None:
        """Lengths and coefficients the user declares positive (they let conditions and
        cycle integrals drop factors of known sign)."""
        for name in names:
            self.symbols[name] = sympy.Symbol(name, positive=True)

    def problem(self, entry: str, message: str) -> None:
        self.problems.append(Problem(entry, message, self.doc.line(entry)))

    def said(self, problems: list[tuple[str, str]]) -> None:
        for entry, message in problems:
            self.problem(entry, message)

    def guarded(self, entry: str, read: Callable[[], Any]) -> Any:
        try:
            return read()
        except ExpressionError as exc:
            self.problem(entry, str(exc))
            return None

    def scalar(self, entry: str, written: object) -> sympy.Expr | None:
        return self.guarded(entry, lambda: parse_scalar(written, self.vectors, self.symbol))

    def vector(self, entry: str, written: object) -> Vector | None:
        found: Vector | None = self.guarded(entry, lambda: parse_vector(written, self.vectors, self.symbol))
        return found

    def mapping(self, entry: str, value: object) -> dict[str, Any]:
        if value is None:
            return {}
        if not isinstance(value, dict):
            self.problem(entry, f"expected a mapping (name: value, ...), got {type(value).__name__}")
            return {}
        return {str(k): v for k, v in value.items()}

    def names(self, entry: str, value: object) -> list[str]:
        if isinstance(value, str):
            return [value]
        if not isinstance(value, list) or not all(isinstance(v, (str, int)) for v in value):
            self.problem(entry, "expected a list of names")
            return []
        return [str(v) for v in value]


def build_machine(doc: SourceDocument) -> Machine:
    """Validate the document of a machine file; raises `TopologyError` with every problem."""
    r = _Reader(doc)
    data = r.mapping("", doc.data)
    _check_top_entries(r, data, doc.name)
    r.declare_positive(r.names("positive", data.get("positive", [])))
    links = r.names("links", data.get("links"))
    r.said(entry_checks.repeated(links, "links"))
    reference = str(data.get("reference", links[0] if links else ""))
    if links and reference not in links:
        r.problem("reference", f"the reference link {reference!r} is not among the links {links}")
    position_names = r.names("position", data.get("position", []))
    r.said(entry_checks.repeated(position_names, "position"))
    position = tuple(dict.fromkeys(r.symbol(n) for n in position_names))
    values = _scalars(r, "values", data)
    _read_vectors(r, data)
    unknowns = _scalars(r, "unknowns", data)
    closure = _closure(r, data.get("closure"), unknowns)
    limits = _limits(r, data.get("limits"))
    couplings = tuple(
        c
        for name, written in r.mapping("couplings", data.get("couplings")).items()
        if (c := _coupling(r, name, written, links))
    )
    names = {c.name for c in couplings}
    ports = tuple(
        p for name, written in r.mapping("ports", data.get("ports")).items() if (p := _port(r, name, written, names))
    )
    port_names = [p.name for p in ports]
    chosen = str(data.get("input", port_names[0] if port_names else ""))
    if port_names and chosen not in port_names:
        r.problem("input", f"the input {chosen!r} is not a port; write one of {', '.join(port_names)}")
    tasks = {n: t for n, written in r.mapping("tasks", data.get("tasks")).items() if (t := _task(r, n, written, ports))}
    cycle = _cycle(r, data.get("cycle"), port_names) if "cycle" in data else None
    expected = tuple(e for i, written in enumerate(data.get("expected") or []) if (e := _expected(r, i, written)))
    machine = Machine(
        name=str(data.get("machine")),
        source=str(data.get("source", "")),
        links=tuple(links),
        reference=reference,
        position=position,
        values=values,
        couplings=couplings,
        ports=ports,
        input=chosen,
        tasks=tasks,
        cycle=cycle,
        expected=expected,
        vectors=dict(r.vectors),
        unknowns=unknowns,
        closure=closure,
        limits=limits,
        path=doc.name,
    )
    _check_together(r, machine)
    if r.problems:
        raise TopologyError(r.problems, doc.name)
    return machine


def _check_top_entries(r: _Reader, data: dict[str, Any], path: str | None) -> None:
    """The file's top-level entries: a gear train's entries refused at once (one mistake,
    said once), unknown entries and formats noted."""
    train_only = sorted(k for k in ("gears", "states", "degrees_of_freedom", "independent") if k in data)
    if train_only:
        r.problem(
            "machine",
            f"machine: makes this a machine file (Laus ch. 4), but it has {', '.join(train_only)} of a gear "
            "train: take machine: out for a gear train, or write the machine's vectors and couplings",
        )
        raise TopologyError(r.problems, path)
    for key in data:
        if key not in _TOP:
            r.problem(key, f"unknown entry {key!r} (a machine file has {', '.join(sorted(_TOP))})")
    if data.get("format", 1) != 1:
        r.problem("format", "only format 1 is known; write format: 1")


def _scalars(r: _Reader, entry: str, data: dict[str, Any]) -> dict[sympy.Symbol, sympy.Expr]:
    """``values:`` or ``unknowns:`` (a guess each): scalars by symbol."""
    out: dict[sympy.Symbol, sympy.Expr] = {}
    for name, written in r.mapping(entry, data.get(entry)).items():
        value = r.scalar(f"{entry}.{name}", written)
        if value is not None:
            out[r.symbol(name)] = value
    return out


def _read_vectors(r: _Reader, data: dict[str, Any]) -> None:
    """``vectors:`` into the reader (couplings and closure equations name them)."""
    for name, written in r.mapping("vectors", data.get("vectors")).items():
        if name in AXES:
            r.problem(f"vectors.{name}", f"{name!r} is the coordinate axis; name the vector otherwise")
            continue
        vec = r.vector(f"vectors.{name}", written)
        if vec is not None:
            r.vectors[name] = vec


def _check_together(r: _Reader, m: Machine) -> None:
    """What the entries must agree on: values against friction coefficients, tasks
    against the position and couplings, a position that moves something, the cycle
    and the published checks."""
    coefficients = {s for c in m.couplings if c.friction is not None for s in c.friction.mu.free_symbols}
    r.said(entry_checks.value_problems(m.values, coefficients))
    kinds = {c.name: c.kind for c in m.couplings}
    for task in m.tasks.values():
        r.said(entry_checks.task_problems(task, m.position, m.values, kinds))
    written = {s for v in r.vectors.values() for x in v for s in x.free_symbols}
    written |= {s for c in m.couplings for x in c.at for s in x.free_symbols}
    unused = [s.name for s in m.position if s not in written]
    if m.couplings and unused:
        r.problem("position", f"{', '.join(unused)} moves nothing: no vector or coupling is written in it")
    if m.cycle is not None:
        r.said(entry_checks.cycle_problems(m.cycle, m.position, m.values))
    for i, check in enumerate(m.expected):
        r.said(entry_checks.expected_problems(check, i, m.tasks))
    if not m.couplings and not r.problems:
        r.problem("couplings", "a machine needs couplings")


def _closure(r: _Reader, written: object, unknowns: dict[sympy.Symbol, sympy.Expr]) -> tuple[sympy.Expr, ...]:
    """``closure:``: equations ``LHS = RHS`` of scalars (``norm(C - B) = a2``), one per unknown."""
    if written is None:
        if unknowns:
            r.problem("unknowns", "unknowns need closure: equations that fix them (e.g. - norm(C - B) = a2)")
        return ()
    if not isinstance(written, list):
        r.problem("closure", "write a list of equations, e.g. - norm(C - B) = a2")
        return ()
    out = []
    for i, text in enumerate(written):
        left, sep, right = str(text).partition("=")
        if not sep or "=" in right:
            r.problem(f"closure.{i}", f"write one equation LEFT = RIGHT, got {str(text)[:60]!r}")
            continue
        a, b = r.scalar(f"closure.{i}", left), r.scalar(f"closure.{i}", right)
        if a is not None and b is not None:
            out.append(a - b)
    if len(out) == len(written) and len(out) != len(unknowns):
        r.problem("closure", f"{len(out)} closure equations for {len(unknowns)} unknowns: give one per unknown")
    return tuple(out)


def _limits(r: _Reader, written: object) -> tuple[Limit, ...]:
    """``limits:``: named inequalities ``LEFT < RIGHT`` (or ``>``) of scalars that hold
    wherever the machine is assembled as modelled (``stroke: norm(d1) < l_B + l_C``)."""
    out = []
    for name, text in r.mapping("limits", written).items():
        entry = f"limits.{name}"
        parts = re.split(r"(<=|>=|<|>)", str(text))
        if len(parts) != 3:
            r.problem(entry, f"write one inequality LEFT < RIGHT or LEFT > RIGHT, got {str(text)[:60]!r}")
            continue
        left, sign, right = parts
        a, b = r.scalar(entry, left), r.scalar(entry, right)
        if a is not None and b is not None:
            out.append(Limit(name, " ".join(str(text).split()), b - a if sign in ("<", "<=") else a - b))
    return tuple(out)


def _coupling(r: _Reader, name: str, written: object, links: list[str]) -> Coupling | None:
    entry = f"couplings.{name}"
    spec = r.mapping(entry, written)
    for key in spec:
        if key not in _COUPLING_KEYS:
            r.problem(f"{entry}.{key}", f"unknown entry {key!r} (write {', '.join(sorted(_COUPLING_KEYS))})")
    kind = spec.get("type")
    if not isinstance(kind, str) or kind not in JOINT_KINDS:
        r.problem(f"{entry}.type", f"unknown coupling type {kind!r}; write one of {', '.join(JOINT_KINDS)}")
        return None
    ends = r.names(f"{entry}.links", spec.get("links"))
    if len(ends) != 2 or ends[0] == ends[1] or any(e not in links for e in ends):
        r.problem(f"{entry}.links", f"write the two different links it connects, among {links}")
        return None
    at = r.vector(f"{entry}.at", spec.get("at", [0, 0, 0]))
    axis = normal = None
    if "axes" in spec:
        pair = spec["axes"]
        if kind != "universal" or not isinstance(pair, list) or len(pair) != 2:
            r.problem(f"{entry}.axes", "axes: [first, second] is for a universal joint (its two pin axes)")
            return None
        axis, normal = r.vector(f"{entry}.axes", pair[0]), r.vector(f"{entry}.axes", pair[1])
    else:
        if "axis" in spec:
            axis = r.vector(f"{entry}.axis", spec["axis"])
        elif kind in _NEEDS_AXIS:
            r.problem(entry, f"a {kind} coupling needs axis: (a direction, e.g. z or [0, 0, 1])")
        if "normal" in spec:
            normal = r.vector(f"{entry}.normal", spec["normal"])
    for what, direction in (("axis", axis), ("normal", normal)):
        if direction is not None and all(x == 0 for x in direction):
            r.problem(f"{entry}.{what}", f"the {what} must not be the zero vector")
    if axis is not None and normal is not None and all(sympy.expand(x) == 0 for x in cross(axis, normal)):
        r.problem(f"{entry}.normal", "the normal must not be parallel to the axis: give a direction across it")
    if kind == "universal" and "axes" not in spec:
        r.problem(entry, "a universal joint needs axes: [first, second] (its two pin axes)")
    friction = _friction(r, f"{entry}.friction", spec["friction"], kind) if "friction" in spec else None
    if at is None:
        return None
    return Coupling(name, str(kind), (ends[0], ends[1]), at, axis, normal, friction, r.doc.line(entry))


def _friction(r: _Reader, entry: str, written: object, kind: str) -> Friction | None:
    spec = r.mapping(entry, written)
    if "mu" not in spec:
        r.problem(entry, "friction needs mu: (the Coulomb coefficient)")
        return None
    if kind in ("spherical", "free"):
        r.problem(entry, f"friction of a {kind} coupling is not modelled; leave it out")
        return None
    mu = r.scalar(f"{entry}.mu", spec["mu"])
    radius = r.scalar(f"{entry}.pin_radius", spec["pin_radius"]) if "pin_radius" in spec else None
    height = r.scalar(f"{entry}.height", spec["height"]) if "height" in spec else None
    if height is not None and kind in ("revolute", "universal"):
        r.problem(f"{entry}.height", "height: is a slider's (prismatic, cylindrical, annulus); a pin has pin_radius:")
    for key in spec:
        if key not in ("mu", "pin_radius", "surfaces", "load", "height"):
            r.problem(f"{entry}.{key}", f"unknown entry {key!r} (write mu, pin_radius, surfaces, load, height)")
    if kind in ("revolute", "universal") and radius is None:
        r.problem(entry, f"a {kind} joint's friction needs pin_radius: (the Coulomb moment arm, Laus App. D)")
    surfaces, load = str(spec.get("surfaces", "worn")), str(spec.get("load", "sum"))
    if surfaces not in ("worn", "new", "clearance"):
        r.problem(
            f"{entry}.surfaces",
            "write worn (cosine pressure law) or new (uniform law), Laus App. D, or clearance (line contact)",
        )
    if load not in ("sum", "resultant"):
        r.problem(f"{entry}.load", "write sum (Laus eqs. (127)-(129)) or resultant (eq. (133))")
    if height is not None and load == "resultant":
        r.problem(f"{entry}.height", "a slider's height places one friction force per pressed face: use load: sum")
    return Friction(mu, radius, surfaces, load, height) if mu is not None else None


def _port(r: _Reader, name: str, written: object, couplings: set[str]) -> Port | None:
    entry = f"ports.{name}"
    spec = r.mapping(entry, written)
    r.said(entry_checks.unknown_keys(spec, entry_checks.PORT_KEYS, entry))
    coupling = str(spec.get("coupling", ""))
    if coupling not in couplings:
        r.problem(f"{entry}.coupling", f"name the coupling of the port, one of {', '.join(sorted(couplings))}")
        return None
    for action in ("force", "torque"):
        if action in spec:
            direction = r.vector(f"{entry}.{action}", spec[action])
            return Port(name, coupling, action, direction) if direction is not None else None
    return Port(name, coupling)


def _task(r: _Reader, name: str, written: object, ports: tuple[Port, ...]) -> Task | None:
    entry = f"tasks.{name}"
    spec = r.mapping(entry, written)
    r.said(entry_checks.unknown_keys(spec, entry_checks.TASK_KEYS, entry))
    time = spec.get("time")
    if not isinstance(time, list) or len(time) != 2:
        r.problem(f"{entry}.time", "write time: [start, stop] in seconds")
        return None
    start, stop = r.scalar(f"{entry}.time", time[0]), r.scalar(f"{entry}.time", time[1])
    step = r.scalar(f"{entry}.step", spec.get("step", "0.005"))
    path = {
        r.symbol(k): v
        for k, w in r.mapping(f"{entry}.path", spec.get("path")).items()
        if (v := r.scalar(f"{entry}.path.{k}", w)) is not None
    }
    loads = {
        k: v
        for k, w in r.mapping(f"{entry}.loads", spec.get("loads")).items()
        if (v := r.scalar(f"{entry}.loads.{k}", w)) is not None
    }
    for port in loads:
        if port not in {p.name for p in ports}:
            r.problem(f"{entry}.loads.{port}", f"{port!r} is not a port")
    if None in (start, stop, step):
        return None
    return Task(name, start, stop, step, path, str(spec.get("drive", "")), loads)


def _cycle(r: _Reader, written: object, ports: list[str]) -> Cycle | None:
    spec = r.mapping("cycle", written)
    r.said(entry_checks.unknown_keys(spec, entry_checks.CYCLE_KEYS, "cycle"))
    variable = r.symbol(str(spec.get("variable", "theta")))
    start, stop = r.scalar("cycle.from", spec.get("from", "-pi")), r.scalar("cycle.to", spec.get("to", "pi"))
    steady = str(spec.get("steady", ""))
    if steady not in ports:
        r.problem("cycle.steady", f"name the port whose power stays constant over the cycle, one of {ports}")
    if start is None or stop is None:
        return None
    return Cycle(variable, start, stop, steady)


def _expected(r: _Reader, index: int, written: object) -> Expected | None:
    entry = f"expected[{index}]"
    spec = r.mapping(entry, written)
    r.said(entry_checks.unknown_keys(spec, entry_checks.EXPECTED_KEYS, entry))
    try:
        return Expected(
            quantity=str(spec["quantity"]),
            value=float(spec["value"]),
            tolerance=float(spec.get("tolerance", 1e-12)),
            source=str(spec.get("source", "")),
            values={
                k: v
                for k, w in r.mapping(f"{entry}.values", spec.get("values")).items()
                if (v := r.scalar(f"{entry}.values.{k}", w)) is not None
            },
            input=spec.get("input"),
            task=spec.get("task"),
        )
    except (KeyError, TypeError, ValueError):
        r.problem(entry, "an expected number needs quantity:, value: (a number) and source:")
        return None
