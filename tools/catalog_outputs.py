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
import sys
from pathlib import Path

from davies_sym.cli import main
from davies_sym.cli.one_input_outputs import derive_sets
from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.emit.derived_result import DerivedResult, OneInputResult, SeveralInputResult
from davies_sym.emit.languages import LANGUAGES, emit_code
from davies_sym.emit.latex import latex_states_document
from davies_sym.errors import DaviesError
from davies_sym.machines.machine_loader import is_machine
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


def _code(result: DerivedResult, language: str) -> str:
    """The ``--emit`` code, or the refusal (a symbol the language cannot hold) as the output."""
    try:
        return emit_code(result, language)
    except DaviesError as exc:
        return f"refused: {exc}\n"


def _documents(result: DerivedResult) -> dict[str, str]:
    return {".txt": result.report(False), ".json": result.report(True), ".tex": result.latex()}


def outputs(path: Path) -> dict[str, str]:
    """File suffix (after the train's name) -> content."""
    document = read_document(str(path))
    if is_machine(document.data):
        return _machine_outputs(path)
    train = build_train(document)
    if len(train.ports.inputs) > 1:
        regions = SeveralInputResult(derive_several_inputs(train))
        return {
            **_documents(regions),
            ".py": regions.module(),
            **{f".{language}": _code(regions, language) for language in LANGUAGES},
        }
    failures: list[str] = []
    sets = tuple(derive_sets(train, None, _quiet, failures))
    # Every state's own document would be one state's: the file's documents have them all.
    out = {**_documents(OneInputResult(train, sets, None, _quiet)), ".failures": "\n".join(failures)}
    if train.states and len(sets) == 1:  # `latex` writes a lone state's section alone
        out[".tex"] = latex_states_document([sets[0][1]])
    for name, vs in sets:
        stem = f"_{name}" if name else ""
        state = OneInputResult(train, ((name, vs),), name or None, _quiet)
        out[f"{stem}.py"] = state.module()
        out.update({f"{stem}.{language}": _code(state, language) for language in LANGUAGES})
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
