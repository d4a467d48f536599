"""``derive FILES... --out DIR``: the LaTeX document and the formula module of every
train (or only the document asked for: ``--json`` the JSON document, ``--latex`` the
LaTeX one, what ``derive FILE`` prints with that option), each file one task.
The tasks run in this process, on N local processes (``--jobs N``, the standard
library's process pool) or on a Dask cluster (``--scheduler ADDRESS``); the results come
back as text and are written here, atomically, as each task finishes.  A file that
fails is reported and the others are still derived."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from davies_sym.cli.file_outputs import file_outputs
from davies_sym.cli.machine_input import machine_derivations
from davies_sym.cli.messages import INTERNAL_ERROR, internal_error, message
from davies_sym.cli.one_input import write_derivations
from davies_sym.cli.parser import parser
from davies_sym.cli.several_inputs import several_degrees_of_freedom, several_derivations
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.errors import DaviesError, InputError, MissingDependencyError, Problem, TopologyError
from davies_sym.machines.loader import build_machine, is_machine
from davies_sym.topology.documents import document_from_bytes, read_train_file
from davies_sym.topology.loader import build_train
from davies_sym.topology.yaml_source import SourceDocument

Progress = Callable[[str], None]


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
    """What one task gives back: its exit status (0, or 2 for a file or state refused),
    the lines for standard error, and the files to write as (name in DIR, content)."""

    path: str
    status: int
    messages: tuple[str, ...]
    written: tuple[tuple[str, str], ...]


def _silent(text: str) -> None:
    """No step-by-step progress from a worker: the finished files are the progress."""


def derive_task(task: Task, progress: Progress = _silent) -> Derived:
    """Derive one train file (run by a worker process or in this one); a refusal is a
    message in the result, never an exception, so one bad file stops nothing else."""
    try:
        document = document_from_bytes(task.data, task.path)
        if task.document is not None:
            return _document_alone(document, task, task.document, progress)
        if is_machine(document.data):
            return Derived(task.path, 0, (), tuple(machine_derivations(build_machine(document), task.stem, progress)))
        train = build_train(document)
        failures: list[str] = []
        written = (
            several_derivations(train, task.stem, progress)
            if several_degrees_of_freedom(train)
            else write_derivations(train, task.stem, progress, failures)
        )
    except DaviesError as exc:
        return Derived(task.path, 2, (message(exc, task.path),), ())
    notes = tuple(failures)
    if not written:
        notes += (
            f"derive: {task.path}: {train.degrees_of_freedom} degrees of freedom and one input port: only its "
            "kinematics is derived (list one input port per degree of freedom for formulas)",
        )
    return Derived(task.path, 2 if failures else 0, notes, tuple(written))


#: The single-file option of each document, and the suffix of its file.
DOCUMENTS = {"json": "--json", "tex": "--latex"}


def _document_alone(document: SourceDocument, task: Task, kind: str, progress: Progress) -> Derived:
    """The one document of ``kind`` (a key of `DOCUMENTS`) that ``task`` asks for: what
    ``derive FILE`` with its option prints (`file_outputs`, given the arguments that command
    line parses to)."""
    failures: list[str] = []
    args = parser().parse_args([task.path, DOCUMENTS[kind]])
    ((_, text),) = file_outputs(document, args, progress, failures)
    content = text if isinstance(text, str) else text.decode()
    return Derived(task.path, 2 if failures else 0, tuple(failures), ((f"{task.stem}.{kind}", content),))


def _crashed(path: str, exc: BaseException) -> Derived:
    """A task that raised past the refusals (a worker that died, an engine error): reported
    as an internal error with its cause, and the other files go on."""
    return Derived(path, INTERNAL_ERROR, (internal_error(exc, path, "deriving it"),), ())


def _in_this_process(tasks: Sequence[Task], progress: Progress) -> Iterator[Derived]:
    for task in tasks:
        try:
            yield derive_task(task, progress)
        except Exception as exc:  # reported per file, as on the pool
            yield _crashed(task.path, exc)


def _on_processes(tasks: Sequence[Task], jobs: int) -> Iterator[Derived]:
    with ProcessPoolExecutor(max_workers=min(jobs, len(tasks))) as pool:
        futures: dict[Future[Derived], str] = {pool.submit(derive_task, t): t.path for t in tasks}
        for future in as_completed(futures):
            try:
                yield future.result()
            except Exception as exc:  # reported per file; the pool goes on
                yield _crashed(futures[future], exc)


def _on_cluster(tasks: Sequence[Task], address: str) -> Iterator[Derived]:
    """The tasks on the Dask cluster whose scheduler listens at ``address``."""
    try:
        from dask.distributed import Client
        from dask.distributed import as_completed as finished
    except ImportError:
        raise MissingDependencyError("--scheduler needs dask.distributed (pip install 'davies_sym[dask]')") from None
    try:
        client = Client(address, timeout="10s")  # type: ignore[no-untyped-call]
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError(
            [Problem("--scheduler", f"cannot reach a Dask scheduler at {address!r}: {exc}")], "derive"
        ) from None
    with client:
        futures = {client.submit(derive_task, t, pure=False): t.path for t in tasks}
        for future in finished(futures):  # type: ignore[no-untyped-call]
            try:
                yield future.result()
            except Exception as exc:  # reported per file; the cluster goes on
                yield _crashed(futures[future], exc)


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


class _Counter:
    """Progress over finished files: a bar on a terminal (tqdm), a line per file otherwise."""

    def __init__(self, total: int, progress: Progress, quiet: bool):
        self.total, self.done, self.progress = total, 0, progress
        self.bar = None
        if not quiet and total > 1 and sys.stderr.isatty():
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit="file", file=sys.stderr)

    def report(self, lines: Sequence[str]) -> None:
        for line in lines:
            if self.bar is not None:
                self.bar.write(line, file=sys.stderr)
            else:
                print(line, file=sys.stderr)

    def finished(self, derived: Derived) -> None:
        self.done += 1
        if self.bar is not None:
            self.bar.update(1)
        elif derived.written:
            stem = os.path.splitext(os.path.basename(derived.path))[0]
            self.progress(f"[{self.done}/{self.total}] wrote the derivations of {stem}")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def derive_into(
    directory: str,
    files: Sequence[str],
    progress: Progress,
    quiet: bool = False,
    jobs: int = 1,
    scheduler: str | None = None,
    document: str | None = None,
) -> int:
    """LaTeX document and formula module of every train file into ``directory`` (a train
    with states gets one document and a module per state), or only the ``document``
    named (a key of `DOCUMENTS`); the exit status is the worst of the files' (0 all derived, 2 a
    file or state refused, 4 a task that failed: an internal error)."""
    os.makedirs(directory, exist_ok=True)
    tasks, refused = _tasks(directory, files, document)
    counter = _Counter(len(tasks), progress, quiet)
    counter.report(refused)
    statuses = {2} if refused else set()
    if scheduler is not None:
        results = _on_cluster(tasks, scheduler)
    elif jobs > 1 and len(tasks) > 1:
        results = _on_processes(tasks, jobs)
    else:
        results = _in_this_process(tasks, progress)
    try:
        for derived in results:
            counter.report(derived.messages)
            for name, content in derived.written:
                target = os.path.join(directory, name)
                try:
                    write_atomic(target, content)
                except OSError as exc:  # reported per file, like a refusal: the others are still written
                    counter.report(
                        [f"input error: {derived.path}: --out: cannot write {target}: {exc.strerror or exc}"]
                    )
                    statuses.add(2)
            statuses.add(derived.status)
            counter.finished(derived)
    finally:
        counter.close()
    # A task that failed (an internal error) outranks a refused input (2): it needs a look at the engine.
    return next((s for s in (INTERNAL_ERROR, 2) if s in statuses), 0)
