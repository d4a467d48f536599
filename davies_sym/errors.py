"""Typed errors of davies_sym.

Every problem found in a topology file is collected with its location (file, line,
entry path) and raised once, so the user sees all of them together.  The command-line
interface turns these errors into one-line messages and exit status 2.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import Enum

#: The entry of a problem with the values an evaluation is given (the API's ``values``
#: argument; the command line files it under the option that gave them, ``--eval``): not
#: an entry of the file, so it has no line.
VALUES = "values"


@dataclass(frozen=True)
class Problem:
    """One problem in an input file: where it is and what is wrong."""

    entry: str
    message: str
    line: int | None = None

    def format(self, source: str | None) -> str:
        where = source or "<input>"
        if self.line is not None:
            where = f"{where}:{self.line}"
        # An entry path holds the user's keys: a huge key is shown by its ends.
        shown = self.entry if len(self.entry) <= 80 else f"{self.entry[:50]} ... {self.entry[-25:]}"
        entry = f" {_one_line(shown)}:" if self.entry else ""
        return f"{where}:{entry} {_one_line(self.message)}"


@dataclass(frozen=True)
class FileLines:
    """Where a file writes its entries: the file's path, the line of each entry path
    (``couplings.C.gears`` -> 12) and the entries the later stages name that the file
    writes elsewhere (a state's ports: ``ports.input`` -> ``states.NAME.input``).

    The stages after loading name the entry a problem is about; the error they raise,
    given these lines, puts each problem where the file writes it."""

    path: str | None
    lines: Mapping[str, int]
    renamed: Mapping[str, str]

    def locate(self, problem: Problem) -> Problem:
        """``problem`` at the entry the file writes, with that entry's line (the nearest
        enclosing entry that has one); a problem already given a line, or with an option
        of the command (``--eval``) or with the given values (`VALUES`), is kept."""
        if problem.line is not None or problem.entry.startswith("--") or problem.entry == VALUES:
            return problem
        entry = problem.entry
        for name in sorted(self.renamed, key=len, reverse=True):
            if entry == name or entry.startswith((f"{name}.", f"{name}[")):
                entry = self.renamed[name] + entry[len(name) :]
                break
        path = entry
        while path and path not in self.lines:
            path = path.rpartition(".")[0]
        return Problem(entry, problem.message, self.lines.get(path))


def _one_line(text: str) -> str:
    """``text`` with control characters escaped, so a problem stays on one line whatever
    the user's keys and values hold."""
    return "".join(ch if ch.isprintable() else ch.encode("unicode_escape").decode("ascii") for ch in text)


class DaviesError(Exception):
    """Base class of every error raised by davies_sym."""


class InputError(DaviesError):
    """A problem with what the user wrote; carries every problem found."""

    kind = "input error"

    def __init__(self, problems: list[Problem], source: str | FileLines | None = None):
        if isinstance(source, FileLines):
            problems = [source.locate(p) for p in problems]
            source = source.path
        self.problems = list(problems)
        self.source = source
        super().__init__(self.report())

    def report(self) -> str:
        lines = [p.format(self.source) for p in self.problems]
        return "\n".join(f"{self.kind}: {line}" for line in lines)


class TopologySyntaxError(InputError):
    """The file is not valid YAML."""

    kind = "YAML syntax error"


class TopologyError(InputError):
    """The YAML is well formed but does not describe a valid train."""

    kind = "topology error"


class GeometryError(InputError):
    """The gear geometry is inconsistent (e.g. a mesh loop that cannot close)."""

    kind = "geometry error"


class MobilityError(InputError):
    """The degree of freedom does not match the declared one or the ports."""

    kind = "mobility error"


class MissingValuesError(InputError):
    """Values that leave the efficiency or a turning condition undetermined; the problem
    names the symbols still needed."""


class DesignError(InputError):
    """Values that contradict the train's own relations (a dependent radius that breaks
    its geometric constraint): refused, never evaluated as another train."""

    kind = "design error"


class MeasurementError(InputError):
    """A file of measured operating points (CSV) that cannot be read as a table of
    finite numbers: every problem with its line and column."""

    kind = "data error"


class NotCoveredError(DaviesError):
    """A valid design the formulas do not cover (it self-locks, or lies outside every
    variant's region): the command line gives the reason and exit status 3."""


class BeyondWorkBound(NotCoveredError):
    """A closed form whose derivation swells past the work bound (a bound by size, the
    same on every machine): the reason instead of minutes and gigabytes."""


class DerivationError(DaviesError):
    """The symbolic derivation cannot proceed (e.g. an unsupported friction case)."""


class FitFailure(Enum):
    """Why measurements cannot support a fit (`CalibrationError.cause`)."""

    ROWS = "rows"  # fewer rows than parameters
    NON_FINITE = "non-finite"  # the model is undefined at the data
    CONVERGENCE = "convergence"  # the least-squares solver does not converge
    UNDETERMINED = "undetermined"  # the data do not determine a parameter
    ARGUMENTS = "arguments"  # the parameters or start values asked for cannot be fitted


class CalibrationError(DaviesError):
    """Measurements that cannot support a fit of the loss parameters: too few rows, a
    model undefined at the data, no convergence, or a parameter the data do not determine;
    ``cause`` says which (for a caller that maps causes to exit statuses)."""

    def __init__(self, message: str, cause: FitFailure | None = None):
        self.cause = cause
        super().__init__(message)


class MissingDependencyError(DaviesError):
    """An optional dependency a requested output needs is not installed (exit status 2)."""


def shortened(text: str, limit: int = 60) -> str:
    """``text`` for a message: its repr, cut in the middle when long."""
    shown = repr(text)
    if len(shown) <= limit:
        return shown
    half = (limit - 5) // 2
    return f"{shown[:half]} ... {shown[-half:]} ({len(text)} characters)"
