"""The target languages by their command-line names, and the one call the command line
makes: the code of a derived train in a language."""

from __future__ import annotations

from davies_sym.efficiency.several_inputs import SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.formula_code import refused_name
from davies_sym.emit.language_names import LANGUAGES
from davies_sym.emit.languages.c import C
from davies_sym.emit.languages.julia import JULIA
from davies_sym.emit.languages.modelica import MODELICA
from davies_sym.emit.languages.names import RefusedName
from davies_sym.emit.languages.octave import OCTAVE
from davies_sym.emit.languages.one_input import one_input_program
from davies_sym.emit.languages.program import Program
from davies_sym.emit.languages.rust import RUST
from davies_sym.emit.languages.several_inputs import several_inputs_program
from davies_sym.emit.languages.target import Target
from davies_sym.emit.languages.text import module_name

_BY_NAME = {t.name: t for t in (C, JULIA, OCTAVE, RUST, MODELICA)}
if set(_BY_NAME) != set(LANGUAGES):  # the parser lists the names without importing the printers
    raise ImportError(f"the --emit names {LANGUAGES} and the printers {tuple(_BY_NAME)} differ")
#: Every target by its command-line name, in the order of the help.
TARGETS: dict[str, Target] = {name: _BY_NAME[name] for name in LANGUAGES}


def program_of(derived: VariantSet | SeveralInputs, language: str, state: str | None = None) -> Program:
    """The language-neutral program of a derived train (the variants of a train driven at
    one port, or the regions of one driven at several), with what ``language`` returns
    where there is no efficiency."""
    target = TARGETS[language]
    train = derived.train
    module = module_name(train.path, state, train.name)
    if isinstance(derived, SeveralInputs):
        return several_inputs_program(derived, module, target.not_covered)
    return one_input_program(derived, module, target.not_covered, state)


def emit_code(derived: VariantSet | SeveralInputs, language: str, state: str | None = None) -> str:
    """The source text of ``derived`` in ``language`` (one of `LANGUAGES`); the same
    train gives the same bytes."""
    try:
        return TARGETS[language].write(program_of(derived, language, state))
    except RefusedName as exc:
        raise refused_name(derived.train, exc.kind, exc.name, exc.why, exc.code) from None
