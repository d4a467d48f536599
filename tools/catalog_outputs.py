"""Every output of every catalog train, written to one folder, so that a change meant to
keep them (a refactoring) can be checked byte for byte: ``diff -r BEFORE AFTER``.

    python3 tools/catalog_outputs.py OUT_DIR [NAME ...]

For each train (each state of a multi-state one): the text report, the JSON document,
the LaTeX document, the formula module and the code of every ``--emit`` language; for a
train driven at several ports the same outputs of its power-flow regions; for a machine
its text and JSON.  The derivation runs once per train (and state); the outputs are the
functions the ``derive`` command calls.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
from pathlib import Path

from davies_sym.cli import main
from davies_sym.cli.one_input import derive_sets, one_input_document
from davies_sym.efficiency.parameters import file_parameters
from davies_sym.efficiency.several_inputs import SeveralInputs, derive_several_inputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.languages import LANGUAGES, emit_code
from davies_sym.emit.latex import latex_document, latex_states_document
from davies_sym.emit.python_module import python_module
from davies_sym.emit.several_inputs_latex import several_inputs_latex
from davies_sym.emit.several_inputs_module import several_inputs_module
from davies_sym.emit.several_inputs_report import several_inputs_document, several_inputs_text
from davies_sym.errors import DaviesError
from davies_sym.machines.loader import is_machine
from davies_sym.topology.catalog_files import catalog_folder
from davies_sym.topology.documents import read_document
from davies_sym.topology.loader import build_train


def _quiet(text: str) -> None:
    """Progress messages are not outputs."""


def _machine_outputs(path: Path) -> dict[str, str]:
    out = {}
    for suffix, options in ((".txt", []), (".json", ["--json"])):
        text = io.StringIO()
        with contextlib.redirect_stdout(text):
            main([str(path), "--quiet", *options])
        out[suffix] = text.getvalue()
    return out


def _code(derived: VariantSet | SeveralInputs, language: str, state: str | None = None) -> str:
    """The ``--emit`` code, or the refusal (a symbol the language cannot hold) as the output."""
    try:
        return emit_code(derived, language, state)
    except DaviesError as exc:
        return f"refused: {exc}\n"


def outputs(path: Path) -> dict[str, str]:
    """File suffix (after the train's name) -> content."""
    document = read_document(str(path))
    if is_machine(document.data):
        return _machine_outputs(path)
    train = build_train(document)
    if len(train.ports.inputs) > 1:
        si = derive_several_inputs(train)
        return {
            ".txt": several_inputs_text(several_inputs_document(si)) + "\n",
            ".json": json.dumps(several_inputs_document(si), indent=2) + "\n",
            ".tex": several_inputs_latex(si),
            ".py": several_inputs_module(si),
            **{f".{language}": _code(si, language) for language in LANGUAGES},
        }
    failures: list[str] = []
    sets = derive_sets(train, None, _quiet, failures)
    out = {
        ".txt": one_input_document(train, sets, False, _quiet),
        ".json": one_input_document(train, sets, True, _quiet),
        ".tex": latex_states_document([vs for _, vs in sets]) if train.states else latex_document(sets[0][1]),
        ".failures": "\n".join(failures),
    }
    for name, vs in sets:
        stem = f"_{name}" if name else ""
        out[f"{stem}.py"] = python_module(vs, file_parameters(train))
        out.update({f"{stem}.{language}": _code(vs, language, name or None) for language in LANGUAGES})
    return out


def run(folder: Path, names: list[str]) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for path in sorted(catalog_folder().glob("*.yaml")):
        if names and path.stem not in names:
            continue
        print(path.stem, file=sys.stderr, flush=True)
        for suffix, content in outputs(path).items():
            (folder / f"{path.stem}{suffix}").write_text(content, encoding="utf-8")


if __name__ == "__main__":
    run(Path(sys.argv[1]), sys.argv[2:])
