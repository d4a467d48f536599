"""``derive FILES... --out DIR``: the LaTeX document and the formula module of every
train (or only the document asked for: ``--json`` the JSON document, ``--latex`` the
LaTeX one, what ``derive FILE`` prints with that option), each file one task.
The tasks run where `davies_sym.fan_out` puts them (``--jobs N``, ``--scheduler
ADDRESS``); the results come back as text and are written here, atomically, in the order
of the files.  A file that
fails is reported and the others are still derived."""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial

from davies_sym.cli.file_outputs import file_outputs
from davies_sym.cli.machine_input import machine_derivations
from davies_sym.cli.messages import INTERNAL_ERROR, internal_error, message
from davies_sym.cli.one_input_outputs import write_derivations
from davies_sym.cli.parser import parser
from davies_sym.cli.several_input_outputs import several_degrees_of_freedom, several_derivations
from davies_sym.cli.state_failures import StateFailures
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.errors import DaviesError, NotCoveredError, TopologyError
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.machines.machine_loader import build_machine, is_machine
from davies_sym.progress import Progress, note, silent
from davies_sym.topology.documents import document_from_bytes, read_train_file
from davies_sym.topology.loader import build_train
from davies_sym.topology.yaml_source import SourceDocument


@dataclass(frozen=True)
class Task:
    """One train file: its path (for messages), its bytes (read here, so a remote worker
    needs no access to the file) and the stem its outputs are named after."""

    path: str
    data: bytes
    stem: str
    #: The document asked for alone (``json``, ``tex``: the suffix of its file, a key of
    #: `DOCUMENTS`); None: the LaTeX document and the modules.
    document: str | None = None


@dataclass(frozen=True)
class Derived:
    """What one task gives back: its exit status (0; 2 for a file or state refused, 3
    where every one refused is a design the formulas do not cover),
    the lines for standard error, and the files to write as (name in DIR, content)."""

    path: str
    status: int
    messages: tuple[str, ...]
    written: tuple[tuple[str, str], ...]


def derive_task(task: Task, progress: Progress = silent) -> Derived:
    """Derive one train file (run by a worker process or in this one); a refusal is a
    message in the result, never an exception, so one bad file stops nothing else."""
    try:
        document = document_from_bytes(task.data, task.path)
        if task.document is not None:
            return _document_alone(document, task, task.document, progress)
        if is_machine(document.data):
            return Derived(task.path, 0, (), tuple(machine_derivations(build_machine(document), task.stem, progress)))
        train = build_train(document)
        failures = StateFailures()
        written = (
            several_derivations(train, task.stem, progress)
            if several_degrees_of_freedom(train)
            else write_derivations(train, task.stem, progress, failures)
        )
    except DaviesError as exc:
        return Derived(task.path, 3 if isinstance(exc, NotCoveredError) else 2, (message(exc, task.path),), ())
    notes = tuple(failures)
    if not written:
        notes += (
            f"derive: {task.path}: {train.degrees_of_freedom} degrees of freedom and one input port: only its "
            "kinematics is derived (list one input port per degree of freedom for formulas)",
        )
    return Derived(task.path, failures.status, notes, tuple(written))


#: The single-file option of each document, and the suffix of its file.
DOCUMENTS = {"json": "--json", "tex": "--latex"}


def _document_alone(document: SourceDocument, task: Task, kind: str, progress: Progress) -> Derived:
    """The one document of ``kind`` (a key of `DOCUMENTS`) that ``task`` asks for: what
    ``derive FILE`` with its option prints (`file_outputs`, given the arguments that command
    line parses to)."""
    failures = StateFailures()
    args = parser().parse_args([task.path, DOCUMENTS[kind]])
    ((_, text),) = file_outputs(document, args, progress, failures)
    content = text if isinstance(text, str) else text.decode()
    return Derived(task.path, failures.status, tuple(failures), ((f"{task.stem}.{kind}", content),))


def _crashed(path: str, exc: BaseException) -> Derived:
    """A task that raised past the refusals (a worker that died, an engine error): reported
    as an internal error with its cause, and the other files go on."""
    return Derived(path, INTERNAL_ERROR, (internal_error(exc, path, "deriving it"),), ())


def _clash(directory: str, stem: str, files: Sequence[str]) -> str | None:
    """An output of ``stem`` in ``directory`` that is one of the input files, if any."""
    inputs = [f for f in files if os.path.exists(f)]
    outputs = [os.path.join(directory, f"{stem}{suffix}") for suffix in (".tex", ".py", ".txt", ".json")]
    outputs += [os.path.join(directory, o) for o in os.listdir(directory) if o.startswith(f"{stem}_")]
    return next((o for o in outputs if os.path.exists(o) and any(same_file(o, f) for f in inputs)), None)


def _tasks(directory: str, files: Sequence[str], document: str | None) -> tuple[list[Task], list[str]]:
    """The tasks, and the refusals of files whose outputs would overwrite an input or the
    outputs of another file of the same name."""
    suffixes = (document,) if document is not None else ("tex", "py")
    tasks: list[Task] = []
    refused: list[str] = []
    stems: dict[str, str] = {}
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0]
        clash = _clash(directory, stem, files)
        if clash is not None:
            refused.append(f"input error: {path}: --out: refusing to overwrite the input file {clash}")
            continue
        if stem in stems:
            refused.append(
                f"input error: {path}: --out: {stems[stem]} writes "
                f"{' and '.join(f'{stem}.{x}' for x in suffixes)} into "
                f"{directory} already; rename one of the two files"
            )
            continue
        try:
            data = read_train_file(path)
        except TopologyError as exc:
            refused.append(exc.report())
            continue
        stems[stem] = path
        tasks.append(Task(path, data, stem, document))
    return tasks, refused


def derive_into(
    directory: str,
    files: Sequence[str],
    progress: Progress,
    workers: Workers = IN_THIS_PROCESS,
    document: str | None = None,
) -> int:
    """LaTeX document and formula module of every train file into ``directory`` (a train
    with states gets one document and a module per state), or only the ``document``
    named (a key of `DOCUMENTS`), the files derived by ``workers``; the exit status is the
    worst of the files' (0 all derived, 3 a design the formulas do not cover, 2 a file or
    state refused as bad input, 4 a task that failed: an internal error)."""
    os.makedirs(directory, exist_ok=True)
    tasks, refused = _tasks(directory, files, document)
    for line in refused:
        note(progress, line)
    statuses = {2} if refused else set()
    # In this process the steps of each file are shown; a worker's file is its progress.
    work = partial(derive_task, progress=progress) if workers.here(len(tasks)) else derive_task
    counted = Counted(progress, "file", _wrote)
    for derived in fan_out(work, tasks, workers, counted, lambda task, exc: _crashed(task.path, exc)):
        for line in derived.messages:
            note(progress, line)
        for name, content in derived.written:
            target = os.path.join(directory, name)
            try:
                write_atomic(target, content)
            except OSError as exc:  # reported per file, like a refusal: the others are still written
                note(progress, f"input error: {derived.path}: --out: cannot write {target}: {exc.strerror or exc}")
                statuses.add(2)
        statuses.add(derived.status)
    # A task that failed (an internal error) outranks a refused input (2): it needs a look at the engine.
    return next((s for s in (INTERNAL_ERROR, 2, 3) if s in statuses), 0)


def _wrote(derived: Derived) -> str | None:
    """The progress line of a finished file (none for a file refused)."""
    stem = os.path.splitext(os.path.basename(derived.path))[0]
    return f"wrote the derivations of {stem}" if derived.written else None
