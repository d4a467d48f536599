"""What a generated code file holds, said once for every target language.

A `Program` is a list of `Routine` s, each a function of named arguments
that computes a few `Step` s (local values) and returns one expression.  The
values are sympy expressions in plain symbols (no assumptions, so that a range check
such as ``r1 > 0`` stays a check instead of becoming ``True``): arithmetic, relations and
their conjunctions, calls of other routines of the program (undefined sympy functions)
and, in steps only, ``Piecewise`` choices, whose branches are tried in order and whose
``nan`` means "no efficiency here".  A language module prints each expression with sympy's
code printer for that language and writes only the frame around it (function head,
declarations, comments).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import sympy


class Kind(Enum):
    """The type of an argument, a step or a result."""

    REAL = "real"  # a double
    BOOL = "bool"  # a truth value
    PORT = "port"  # an integer: which port is the input (0: the declared input port, 1: the other)


@dataclass(frozen=True)
class Argument:
    name: str
    kind: Kind


@dataclass(frozen=True)
class Step:
    """``target = value``: a local value of a routine."""

    target: str
    kind: Kind
    value: sympy.Basic

    @property
    def is_choice(self) -> bool:
        """A ``Piecewise``: printed as a statement (if .. else if ..) where the language has one."""
        return isinstance(self.value, sympy.Piecewise)


@dataclass(frozen=True)
class Routine:
    """A function: its name, a one-line summary (what it is, for the comments), its
    arguments, its local steps and the expression it returns (never a ``Piecewise``:
    choices are steps).  ``exported``: part of the interface (the variants, the turning
    conditions, the choice), not a helper the choice uses."""

    name: str
    summary: str
    arguments: tuple[Argument, ...]
    returns: Kind
    steps: tuple[Step, ...]
    result: sympy.Basic
    exported: bool = True

    @property
    def argument_names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.arguments)


@dataclass(frozen=True)
class Program:
    """Everything a generated file holds.

    ``module``: an identifier for the file's namespace (Julia module, Modelica package),
    made from the topology file's name; ``header``: the lines of the opening comment
    (train, source, the functions, the variants and their conditions), plain text;
    ``routines``: in definition order, every routine after those it calls; ``entry``: the
    name of the choice function; ``parameters``: the arguments of the choice without the
    port; ``ports``: the port names in the order of the port argument's values (empty
    for a train driven at several ports, whose choice has no port argument)."""

    module: str
    header: tuple[str, ...]
    routines: tuple[Routine, ...]
    entry: str
    parameters: tuple[str, ...]
    ports: tuple[str, ...]


#: The value of a choice where no formula holds (outside every variant or region,
#: self-locking, outside the admissible parameters).
NOT_COVERED = sympy.nan

#: An efficiency above 1 by less than this is rounding, as in the Python module.
UPPER = sympy.Float(1 + 1e-12)
