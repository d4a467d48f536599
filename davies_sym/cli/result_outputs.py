"""The outputs every derived train shares, asked of its `DerivedResult`: the code in
another language (``--emit``), the formula module (``--python``), the document (text,
JSON or LaTeX) and the answer of ``--eval``, all computed before anything is written.
A train driven at one port and one driven at several give them the same way; what is
theirs alone (the figures, the operating states, how ``--eval`` reads its values) stays
in `davies_sym.cli.one_input_outputs` and `davies_sym.cli.several_input_outputs`."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from typing import Protocol

from davies_sym.cli.arguments import document_asked
from davies_sym.emit.derived_result import DerivedResult
from davies_sym.emit.languages import emit_code

Outputs = list[tuple[str | None, str | bytes]]


class Answer(Protocol):
    """The answer of ``--eval``: a variant's or a region's (`davies_sym.emit.evaluation`)."""

    def document(self) -> dict[str, object]: ...

    def text(self) -> str: ...


def result_outputs(result: DerivedResult, args: argparse.Namespace, answer: Callable[[], Answer]) -> Outputs:
    """The outputs ``args`` ask of ``result`` (target and content; None: the standard
    output); ``answer`` evaluates ``--eval`` when it is given."""
    if args.emit:
        code = emit_code(result, args.emit)
        return [*([(args.python, result.module())] if args.python else []), (args.out, code)]
    evaluation = answer() if args.eval is not None else None
    outputs: Outputs = []
    if args.python:
        outputs.append((args.python, result.module()))
    # The document only where it is asked for: a module or an evaluation alone is written quietly.
    if document_asked(args, evaluation is not None):
        outputs.append((args.out, result.latex() if args.latex else result.report(args.json)))
    if evaluation is not None:
        state = {"state": args.state} if args.state else {}
        document = {"file": result.train.path, **state, **evaluation.document()}
        outputs.append((None, json.dumps(document, indent=2) + "\n" if args.json else evaluation.text()))
    return outputs
