"""The target languages by their command-line names, and the one call the command line
makes: the code of a derived train in a language."""

from __future__ import annotations

from typing import Protocol

from davies_sym.emit.formula_code import refused_name
from davies_sym.emit.language_names import LANGUAGES
from davies_sym.emit.languages.c import C
from davies_sym.emit.languages.julia import JULIA
from davies_sym.emit.languages.modelica import MODELICA
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.octave import OCTAVE
from davies_sym.emit.languages.program import Program
from davies_sym.emit.languages.rust import RUST
from davies_sym.emit.languages.target import Target
from davies_sym.emit.languages.text import module_name
from davies_sym.topology.model import Train

_BY_NAME = {t.name: t for t in (C, JULIA, OCTAVE, RUST, MODELICA)}
if set(_BY_NAME) != set(LANGUAGES):  # the parser lists the names without importing the printers
    raise ImportError(f"the --emit names {LANGUAGES} and the printers {tuple(_BY_NAME)} differ")
#: Every target by its command-line name, in the order of the help.
TARGETS: dict[str, Target] = {name: _BY_NAME[name] for name in LANGUAGES}


class Programmed(Protocol):
    """A derived train as the other languages see it: the variants of a train driven at
    one port or the regions of one driven at several
    (`davies_sym.emit.derived_result`)."""

    @property
    def train(self) -> Train:
        """The train the formulas are of (of the chosen state, if the file has states)."""
        ...

    @property
    def state(self) -> str | None:
        """The operating state chosen, if the file has states."""
        ...

    def program(self, module: str, not_covered: str) -> Program:
        """The language-neutral program (``module``: its namespace; ``not_covered``:
        what the language returns where no formula holds)."""
        ...


def program_of(derived: Programmed, language: str) -> Program:
    """The language-neutral program of a derived train, with what ``language`` returns
    where there is no efficiency."""
    train = derived.train
    return derived.program(module_name(train.path, derived.state, train.name), TARGETS[language].not_covered)


def emit_code(derived: Programmed, language: str, program: Program | None = None) -> str:
    """The source text of ``derived`` in ``language`` (one of `LANGUAGES`); the same
    train gives the same bytes.  ``program``: its `program_of` where the caller built it."""
    try:
        return TARGETS[language].write(program or program_of(derived, language))
    except RefusedName as exc:
        raise refused_name(derived.train, exc.kind, exc.name, exc.why, exc.code) from None
