"""How the program of a train driven at one port picks its variant, as the Python module
(`davies_sym.emit.formula_runtime`) does: the steps that decide which variant of an input
port holds, the choice ``efficiency_from_<port>`` that screens it for self-locking,
``reason_from_<port>`` that says why there is no efficiency, and the routine that picks
a port's routine by the port's number."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.languages.program import NOT_COVERED, UPPER, Argument, Kind, Routine, Step
from davies_sym.emit.languages.routines import call, fresh, relation
from davies_sym.emit.languages.text import identifier_part


@dataclass(frozen=True)
class Choice:
    """The steps that pick the variant of one input port: ``ok`` (the design is
    admissible), ``turns`` (both ports turn: the speed ratio is finite and not 0),
    ``chosen`` (the first variant whose conditions hold and whose loaded forces agree, NaN
    where none does); ``held``: the conditions under which one does, in order;
    ``regions``: each variant with the conditions of its region alone (loaded forces
    aside)."""

    steps: tuple[Step, ...]
    ok: sympy.Symbol
    turns: sympy.Symbol
    chosen: sympy.Symbol
    held: tuple[sympy.Basic, ...]
    regions: tuple[tuple[sympy.Expr, sympy.Basic], ...]
    local: Callable[[str], str]
    #: The variant of each branch of ``held``, in order.
    order: tuple[str, ...] = ()


@dataclass(frozen=True)
class ChoiceRoutines:
    """The routines a port's choice calls: every routine by name (each condition's as
    ``condition_<name>``, each variant's as its name), the loaded-force checks by variant,
    ``admissible``, ``turning``, the raw speed ratio (None where the ratio has
    parameters the routines do not take), and ``moving``, whether no denominator of the
    motions vanishes (None where none can)."""

    by_name: Mapping[str, Routine]
    forces: Mapping[str, Routine]
    admissible: Routine
    turning: Routine | None
    moving: Routine | None = None


@dataclass(frozen=True)
class PortSignature:
    """What the routines picked by the input port share: the parameter ``names``, the
    argument ``port_argument`` that numbers the input port, the two ``ports``, and what
    the language returns where there is no efficiency (``not_covered``)."""

    names: tuple[str, ...]
    port_argument: str
    ports: tuple[str, str]
    not_covered: str


def choice_steps(variants: VariantSet, port: str, names: tuple[str, ...], called: ChoiceRoutines) -> Choice:
    """The steps that pick the variant of input ``port`` (see `Choice`), with local names
    clear of the parameter ``names``."""
    local = _local_names(names)
    steps, ok, turns = _screen_steps(local, called)
    negative: dict[str, sympy.Symbol] = {}
    for c in variants.conditions:
        name = local(f"negative_{c.name}")
        negative[c.name] = sympy.Symbol(name)
        condition = call(called.by_name[f"condition_{c.name}"])
        steps.append(Step(name, Kind.BOOL, relation(condition, "<", sympy.Integer(0))))
    mine = [v for v in variants.variants if v.input == port]
    agrees: dict[str, sympy.Symbol] = {}
    for v in mine:
        if v.name in called.forces:
            name = local(f"agrees_{v.number}")
            agrees[v.name] = sympy.Symbol(name)
            steps.append(Step(name, Kind.BOOL, call(called.forces[v.name])))
    branches, regions = [], []
    for v in mine:
        signs = [negative[c] if s < 0 else sympy.Not(negative[c]) for c, s in v.signs.items()]
        holds = sympy.And(sympy.Symbol(ok), *signs, *([agrees[v.name]] if v.name in agrees else []))
        branches.append((call(called.by_name[v.name]), holds))
        regions.append((call(called.by_name[v.name]), sympy.And(sympy.Symbol(ok), *signs)))
    # Where the losses move a turning point past its lossless boundary, the variant of
    # another region whose loaded forces all agree holds.
    branches += [
        (call(called.by_name[v.name]), sympy.And(sympy.Symbol(ok), agrees[v.name])) for v in mine if v.name in agrees
    ]
    order = [v.name for v in mine] + [v.name for v in mine if v.name in agrees]
    chosen = local("chosen")
    steps.append(Step(chosen, Kind.REAL, sympy.Piecewise(*branches, (NOT_COVERED, True), evaluate=False)))
    return Choice(
        tuple(steps),
        sympy.Symbol(ok),
        sympy.Symbol(turns),
        sympy.Symbol(chosen),
        tuple(condition for _, condition in branches),
        tuple(regions),
        local,
        tuple(order),
    )


def _local_names(names: tuple[str, ...]) -> Callable[[str], str]:
    """A source of local names: each new, none among ``names`` or those it gave before."""
    taken = set(names)

    def local(base: str) -> str:
        name = fresh(base, taken)
        taken.add(name)
        return name

    return local


def _screen_steps(local: Callable[[str], str], called: ChoiceRoutines) -> tuple[list[Step], str, str]:
    """The first steps of a choice and the names they set: ``ok`` (the design is
    admissible) and ``turns`` (both ports turn: the speed ratio is finite and not 0, and
    no denominator of the motions vanishes)."""
    steps: list[Step] = []
    ok = local("ok")
    steps.append(Step(ok, Kind.BOOL, call(called.admissible)))
    turns = local("turns")
    # Where a denominator of the motions vanishes the train locks, however finite the ratio.
    moving = []
    if called.moving is not None:
        moves = local("moves")
        steps.append(Step(moves, Kind.BOOL, call(called.moving)))
        moving.append(sympy.Symbol(moves))
    if called.turning is None:
        steps.append(Step(turns, Kind.BOOL, sympy.And(*moving)))
    else:
        ratio = local("ratio")
        steps.append(Step(ratio, Kind.REAL, call(called.turning)))
        finite = relation(sympy.Abs(sympy.Symbol(ratio)), "<", LARGEST)
        nonzero = relation(sympy.Symbol(ratio), "!=", sympy.Integer(0))
        steps.append(Step(turns, Kind.BOOL, sympy.And(finite, nonzero, *moving)))
    return steps, ok, turns


def working(value: sympy.Symbol) -> sympy.Basic:
    """``0 < value <= 1`` (to rounding): the train runs; else it self-locks."""
    return sympy.And(relation(value, ">", sympy.Integer(0)), relation(value, "<=", UPPER))


def port_choice(variants: VariantSet, port: str, names: tuple[str, ...], choice: Choice, not_covered: str) -> Routine:
    """``efficiency_from_<port>(...)``: the first variant of ``port`` whose turning
    conditions hold and whose loaded forces agree, screened for self-locking."""
    eta = choice.local("eta")
    chosen = choice.chosen
    picked = sympy.Piecewise(
        (chosen, sympy.And(choice.ok, choice.turns, working(chosen))), (NOT_COVERED, True), evaluate=False
    )
    other = variants.train.ports.output if port == variants.train.ports.input else variants.train.ports.input
    return Routine(
        f"efficiency_from_{identifier_part(port)}",
        f"the efficiency with {port} as the input port ({other} the output): the first of its variants "
        f"whose turning conditions hold (and loaded forces agree); {not_covered} outside the admissible "
        "parameters, where none holds, or where the efficiency is outside (0, 1] (self-locking)",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(eta, Kind.REAL, picked)),
        sympy.Symbol(eta),
    )


#: Why ``efficiency_from_<port>`` has no efficiency, as ``reason_from_<port>`` numbers it:
#: the reasons of the Python module (`davies_sym.emit.formula_runtime`) and the API.
REASONS = (
    (0, "an efficiency (the train runs)"),
    (1, "outside the admissible parameters (PARAMETERS, RELATIONS)"),
    (2, "no variant's power flow agrees with its own forces (the losses reverse forces as no variant covers)"),
    (3, "the train self-locks (efficiency outside (0, 1])"),
    (4, "a port does not turn (speed ratio 0 or infinite, or the train locks: a denominator of the motions vanishes)"),
)

#: Beyond this a speed ratio counts as infinite (a division by zero in floating point; a
#: bound every language prints as a finite double).
LARGEST = sympy.Float(1e300)


def port_reason(variants: VariantSet, port: str, names: tuple[str, ...], choice: Choice) -> Routine:
    """``reason_from_<port>(...)``: why the choice of ``port`` has an efficiency or not
    (`REASONS`), decided as the Python module decides: where no variant agrees with its
    loaded forces, the train self-locks if its region's own variant is not positive."""
    # Piecewise steps, which every language prints as statements: a disjunction of
    # conjunctions would need parentheses that C compilers ask for.  ``held`` numbers the
    # branch that held (distinct values: sympy would merge equal ones into one condition).
    held, own, code = choice.local("held"), choice.local("own"), choice.local("code")
    found = sympy.Piecewise(
        *((sympy.Integer(k), condition) for k, condition in enumerate(choice.held, 1)),
        (sympy.Integer(0), True),
        evaluate=False,
    )
    region = sympy.Piecewise(*choice.regions, (NOT_COVERED, True), evaluate=False)
    number = sympy.Piecewise(
        (sympy.Integer(1), sympy.Not(choice.ok)),
        (sympy.Integer(4), sympy.Not(choice.turns)),
        (sympy.Integer(0), working(choice.chosen)),
        (sympy.Integer(3), relation(sympy.Symbol(held), ">", sympy.Integer(0))),
        (sympy.Integer(3), relation(sympy.Symbol(own), "<=", sympy.Integer(0))),
        (sympy.Integer(2), True),
        evaluate=False,
    )
    codes = "; ".join(f"{k}: {text}" for k, text in REASONS)
    return Routine(
        f"reason_from_{identifier_part(port)}",
        f"why efficiency_from_{identifier_part(port)} has an efficiency or not: {codes}",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(held, Kind.REAL, found), Step(own, Kind.REAL, region), Step(code, Kind.REAL, number)),
        sympy.Symbol(code),
    )


def port_variant(variants: VariantSet, port: str, names: tuple[str, ...], choice: Choice) -> Routine:
    """``variant_from_<port>(...)``: the number of the variant the choice of ``port``
    picks (its turning conditions hold and its loaded forces agree), self-locking or
    not; 0 outside the admissible parameters, where a port does not turn or no
    variant holds (``reason_from_<port>`` says which)."""
    number = {v.name: v.number for v in variants.variants}
    code = choice.local("number")
    picked = sympy.Piecewise(
        (sympy.Integer(0), sympy.Not(sympy.And(choice.ok, choice.turns))),
        *((sympy.Integer(number[name]), held) for name, held in zip(choice.order, choice.held, strict=True)),
        (sympy.Integer(0), True),
        evaluate=False,
    )
    return Routine(
        f"variant_from_{identifier_part(port)}",
        f"the number of the variant efficiency_from_{identifier_part(port)} takes (self-locking or not); 0 "
        "where none holds",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*(s for s in choice.steps if s.target != str(choice.chosen)), Step(code, Kind.REAL, picked)),
        sympy.Symbol(code),
    )


def by_port(name: str, what: str, choices: list[Routine], signature: PortSignature) -> Routine:
    """``name(..., input_port)``: ``choices[input_port]`` (the routine of that input port)."""
    names, port_argument, ports = signature.names, signature.port_argument, signature.ports
    port = sympy.Symbol(port_argument, integer=True)
    picked = sympy.Piecewise(
        *((call(choice), sympy.Eq(port, k)) for k, choice in enumerate(choices)), (NOT_COVERED, True), evaluate=False
    )
    result = fresh("value", names)
    return Routine(
        name,
        f"{what} with {port_argument} = 0: {ports[0]} the input, {ports[1]} the "
        f"output, = 1: {ports[1]} the input, {ports[0]} the output; "
        f"{signature.not_covered} for any other value",
        (*(Argument(n, Kind.REAL) for n in names), Argument(port_argument, Kind.PORT)),
        Kind.REAL,
        (Step(result, Kind.REAL, picked),),
        sympy.Symbol(result),
    )
