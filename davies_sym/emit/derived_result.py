"""One protocol for what a derivation gives its outputs, whichever train it is.

A train driven at one port has variants (Laus Tables 5 and 6), one set per operating
state; a train driven at several ports has power-flow regions (Mantriota and Pennestri
2003).  Both are handed to the outputs as a `DerivedResult`: the command line (``derive
FILE``, ``derive FILES --out DIR``), the other languages (`davies_sym.emit.languages`)
and the catalog check ask it for each output by the same name, so each output is asked
for once and written by the module of its kind."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Protocol

import sympy

from davies_sym.efficiency.parameters import file_parameters
from davies_sym.efficiency.several_inputs import SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.json_document import summary_document, text_summary, train_document
from davies_sym.emit.languages.one_input_program import one_input_program
from davies_sym.emit.languages.program import Program
from davies_sym.emit.languages.registry import Programmed
from davies_sym.emit.languages.several_input_program import several_inputs_program
from davies_sym.emit.latex import latex_document, latex_states_document
from davies_sym.emit.python_module import python_module
from davies_sym.emit.several_inputs_latex import several_inputs_latex
from davies_sym.emit.several_inputs_module import several_inputs_module
from davies_sym.emit.several_inputs_report import several_inputs_document, several_inputs_text
from davies_sym.emit.variant_report import variants_document, variants_text
from davies_sym.network.analysis import Analysis
from davies_sym.progress import Progress
from davies_sym.topology.model import Train


def _quiet(message: str) -> None:
    """No progress to report."""


class DerivedResult(Programmed, Protocol):
    """What every derived train gives its outputs: besides its program for the other
    languages (`Programmed`: the train its formulas are of, the chosen state), its
    report, LaTeX document, formula module and the files ``derive FILES --out DIR``
    writes."""

    def report(self, as_json: bool) -> str:
        """The text report, or with ``as_json`` the JSON document."""
        ...

    def latex(self) -> str:
        """The LaTeX document."""
        ...

    def module(self) -> str:
        """The Python formula module."""
        ...

    def derivations(self, stem: str) -> list[tuple[str, str]]:
        """(file name, content) of the LaTeX document and the formula modules."""
        ...


@dataclass(frozen=True)
class OneInputResult:
    """The variants of a train driven at one port (Laus Tables 5 and 6): of the train as
    the file writes it, or of each of its operating states that derives; ``state`` names
    the one chosen (its formulas are the module's and the other languages')."""

    file_train: Train
    sets: tuple[tuple[str, VariantSet], ...]
    state: str | None = None
    progress: Progress = field(default=_quiet, compare=False)

    @property
    def chosen(self) -> VariantSet:
        """The variants of the train, or of its first (or chosen) state."""
        return self.sets[0][1]

    @property
    def train(self) -> Train:
        """The train the chosen formulas are of: a state's train has the state's ports."""
        return self.chosen.train

    def report(self, as_json: bool) -> str:
        """The text report (or the JSON document) of the variants, or of each state's."""
        self.progress("writing the report")
        train = self.file_train
        if not train.states:
            analysis = Analysis(train, progress=self.progress)
            if as_json:
                document = {"status": "ok", **train_document(analysis), **variants_document(self.chosen)}
                return json.dumps(document, indent=2) + "\n"
            # The text prints a summary: the screws, magnitudes and LaTeX are not formed.
            return text_summary(summary_document(analysis)) + "\n" + variants_text(self.chosen) + "\n"
        # The states share the file's geometry: its constraints hold in each.
        relations = list(dict.fromkeys(r for _, vs in self.sets for r in vs.train.dependent or ()))
        if as_json:
            states = {name: _state_entry(vs) for name, vs in self.sets}
            document = {
                "status": "ok",
                "name": train.name,
                "source": train.source,
                "file": train.path,
                "geometric_constraints": [r.constraint for r in relations],
                "dependent_parameters": {str(r.symbol): sympy.sstr(r.expression) for r in relations},
                "states": states,
            }
            return json.dumps(document, indent=2) + "\n"
        parts = [train.name, *(f"  geometric constraint: {r.constraint}, so {r}" for r in relations)]
        for name, vs in self.sets:
            parts.append(
                f"state {name}: {vs.train.name}; input {vs.train.ports.input}, output "
                f"{vs.train.ports.output}; speed ratio {_speed_ratio(vs)}"
            )
            parts.append(variants_text(vs))
        return "\n".join(parts) + "\n"

    def latex(self) -> str:
        """One document: of the variants, or with a section per state."""
        if len(self.sets) == 1:
            return latex_document(self.chosen)
        return latex_states_document([vs for _, vs in self.sets])

    def module(self) -> str:
        return python_module(self.chosen, file_parameters(self.file_train))

    def program(self, module: str, not_covered: str) -> Program:
        return one_input_program(self.chosen, module, not_covered, self.state)

    def derivations(self, stem: str) -> list[tuple[str, str]]:
        """The LaTeX document of every state that derives and a module per state, or
        the train's document and module."""
        if not self.file_train.states:
            return [(f"{stem}.tex", self.latex()), (f"{stem}.py", self.module())]
        accepted = file_parameters(self.file_train)
        return [(f"{stem}.tex", latex_states_document([vs for _, vs in self.sets]))] + [
            (f"{stem}_{name}.py", python_module(vs, accepted)) for name, vs in self.sets
        ]


def _speed_ratio(variants: VariantSet) -> str:
    return str(sympy.sstr(variants.analysis.speed_ratio().to_expr()))


def _state_entry(variants: VariantSet) -> dict[str, object]:
    return {
        "name": variants.train.name,
        "input": variants.train.ports.input,
        "output": variants.train.ports.output,
        "speed_ratio": _speed_ratio(variants),
        **variants_document(variants),
    }


@dataclass(frozen=True)
class SeveralInputResult:
    """The power-flow regions of a train driven at several ports (Mantriota and
    Pennestri 2003, eq. (6))."""

    regions: SeveralInputs

    @property
    def train(self) -> Train:
        return self.regions.train

    @property
    def state(self) -> str | None:
        return None  # the states of a file are trains of one degree of freedom

    def report(self, as_json: bool) -> str:
        document = several_inputs_document(self.regions)
        return json.dumps(document, indent=2) + "\n" if as_json else several_inputs_text(document) + "\n"

    def latex(self) -> str:
        return several_inputs_latex(self.regions)

    def module(self) -> str:
        return several_inputs_module(self.regions)

    def program(self, module: str, not_covered: str) -> Program:
        return several_inputs_program(self.regions, module, not_covered)

    def derivations(self, stem: str) -> list[tuple[str, str]]:
        return [(f"{stem}.tex", self.latex()), (f"{stem}.py", self.module())]
