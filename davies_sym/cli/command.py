"""The ``derive`` command: one file to standard output or to files, many files into a
directory, and ``derive calibrate``; every refusal is a located message and an exit
status (2 bad input, 3 a design the formulas do not cover), never a traceback."""

from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import os
import sys
import tempfile
from collections.abc import Callable, Sequence
from typing import Any

from davies_sym.cli.completion import completion_script
from davies_sym.cli.messages import INTERNAL_ERROR, internal_error, message, named_by_option, status_json
from davies_sym.cli.parser import parser
from davies_sym.cli.state_failures import StateFailures
from davies_sym.cli.subcommand_parsers import SUBCOMMANDS
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.errors import DaviesError, InputError, NotCoveredError, Problem, shortened
from davies_sym.fan_out import Workers
from davies_sym.progress import Display, Progress


def _check_target(target: str, option: str, inputs: Sequence[str]) -> None:
    """Before anything is derived: an output goes into an existing folder and never
    replaces an input file."""
    if not target.strip():
        raise InputError([Problem(option, "the file name is empty; give a file name")], inputs[0])
    folder = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(folder):
        # The nearest ancestor that exists says why: a missing folder or a file in the way.
        above = folder
        while not os.path.exists(above):
            above = os.path.dirname(above)
        why = (
            f"{_path_text(above)} is a file, not a folder"
            if not os.path.isdir(above)
            else f"the folder {_path_text(folder)} does not exist (create it first)"
        )
        raise InputError([Problem(option, why)], inputs[0])
    if os.path.isdir(target):
        raise InputError([Problem(option, f"{_path_text(target)} is a folder; give a file name")], inputs[0])
    for path in inputs:
        if os.path.exists(path) and same_file(target, path):
            named = "" if target == path else f" ({_path_text(target)} names it)"
            raise InputError([Problem(option, f"refusing to overwrite the input file {_path_text(path)}{named}")], path)


def _check_distinct(targets: Sequence[tuple[str, str]], source: str) -> None:
    """Before anything is derived: no two outputs ((file, option) pairs) name the same
    file, however the paths are written (relative, ``..``, a symbolic or hard link)."""
    for k, (target, option) in enumerate(targets):
        for other, first in targets[:k]:
            if same_file(target, other):
                raise InputError(
                    [
                        Problem(
                            option,
                            f"{first} and {option} both name the file {_path_text(target)}: one would "
                            "overwrite the other; give two files",
                        )
                    ],
                    source,
                )


def _folder_for_outputs(folder: str, source: str) -> None:
    """``--out DIR``: the folder exists (made if missing) and takes files, checked before
    anything is derived."""
    existed = os.path.isdir(folder)
    try:
        os.makedirs(folder, exist_ok=True)
        handle, probe = tempfile.mkstemp(prefix=".", suffix=".tmp", dir=folder)
        os.close(handle)
        os.unlink(probe)
    except OSError as exc:
        what = "write into" if existed else "create"
        why = f"cannot {what} the folder {_path_text(folder)}: {exc.strerror or exc}; give a folder you can write"
        raise InputError([Problem("--out", why)], source) from None


def _write(outputs: Sequence[tuple[str | None, str | bytes]], options: dict[str, str], source: str) -> None:
    """Each output to its file (atomically) or to standard output; a file the system will
    not let us write is reported at its option (``-o``, ``--python``) by the name given."""
    for target, content in outputs:
        if target is None:
            sys.stdout.write(content if isinstance(content, str) else content.decode())
            continue
        try:
            write_atomic(target, content)
        except OSError as exc:
            raise InputError(
                [Problem(options.get(target, "-o"), f"cannot write {_path_text(target)}: {exc.strerror or exc}")],
                source,
            ) from None


def _path_text(path: str) -> str:
    """A path as the user can find it: whole unless absurdly long."""
    return path if len(path) <= 300 else shortened(path)


def _one_file(args: argparse.Namespace, progress: Progress) -> int:
    from davies_sym.cli.file_outputs import file_outputs
    from davies_sym.topology.documents import read_document

    path = args.files[0]
    targets = [(t, option) for t, option in ((args.python, "--python"), (args.out, "-o")) if t is not None]
    for target, option in targets:
        _check_target(target, option, [path])
    _check_distinct(targets, path)
    failures = StateFailures()
    outputs = file_outputs(read_document(path), args, progress, failures)
    _write(outputs, {target: option for target, option in targets}, path)
    for line in failures:
        print(line, file=sys.stderr)
    return failures.status


def _many_files(args: argparse.Namespace, progress: Progress) -> int:
    if not args.out or (os.path.exists(args.out) and not os.path.isdir(args.out)):
        print("derive: several files need --out DIR (a directory)", file=sys.stderr)
        return 2
    if args.python or args.emit or args.eval is not None or args.plot is not None:
        print(
            "derive: with --out DIR each train gets its .tex and .py (with --json its .json, with --latex its "
            ".tex alone); --python, --emit, --eval and --plot take one file",
            file=sys.stderr,
        )
        return 2
    from davies_sym.cli.many_files import derive_into

    _folder_for_outputs(args.out, args.files[0])
    document = "json" if args.json else "tex" if args.latex else None
    return derive_into(args.out, args.files, progress, Workers(args.jobs, args.scheduler), document)


class _StdoutFailed(Exception):
    """Standard output took no text: closed by the shell (``derive ... >&-``), or the
    system refused the write (``> /dev/full``)."""


class _GuardedOutput(io.TextIOBase):
    """Standard output for the command: a failed write or flush raises `_StdoutFailed`
    (a reader that went away still raises BrokenPipeError); ``None`` when the shell
    closed it, where Python leaves ``sys.stdout`` None."""

    def __init__(self, stream: Any) -> None:
        self.stream = stream

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        return int(self._guarded(lambda: self.stream.write(text)))

    def flush(self) -> None:
        if self.stream is not None:
            self._guarded(self.stream.flush)

    def _guarded(self, action: Callable[[], Any]) -> Any:
        if self.stream is None:
            raise _StdoutFailed("it is closed")
        try:
            return action()
        except BrokenPipeError:
            raise
        except (OSError, ValueError) as exc:  # ValueError: a closed file object
            raise _StdoutFailed(getattr(exc, "strerror", None) or str(exc)) from None


def main(argv: Sequence[str] | None = None) -> int:
    """The ``derive`` command; returns the exit status (0 a result, 2 bad input, 3 not
    covered, 4 an internal error: an exception no stage turned into a refusal)."""
    real = sys.stdout
    sys.stdout = _GuardedOutput(real)
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        status = _main(argv)
        sys.stdout.flush()  # buffered text meets a full device only here
        return status
    except _StdoutFailed as exc:
        if sys.stderr is not None:
            print(
                f"derive: cannot write to standard output ({exc}): write to a file with -o FILE",
                file=sys.stderr,
            )
        if real is not None:  # what is still buffered would fail again at exit
            with contextlib.suppress(OSError, ValueError, io.UnsupportedOperation):
                os.dup2(os.open(os.devnull, os.O_WRONLY), real.fileno())
        return 2
    except BrokenPipeError:
        # The reader of the output went away (derive ... | head): it has what it wanted.
        # Python would report the pipe again when it flushes stdout at exit: point it nowhere.
        if real is not None:
            with contextlib.suppress(OSError, ValueError, io.UnsupportedOperation):
                os.dup2(os.open(os.devnull, os.O_WRONLY), real.fileno())
        return 0
    except KeyboardInterrupt:
        print("derive: interrupted; nothing was written", file=sys.stderr)
        return 130
    except Exception as exc:  # a fault of davies_sym: reported, never a traceback
        command = f"derive {argv[0]}" if argv and argv[0] in {c.name for c in SUBCOMMANDS} else "derive"
        print(internal_error(exc, command, f"running {' '.join(argv)[:200]}"), file=sys.stderr)
        return INTERNAL_ERROR
    finally:
        sys.stdout = real


def _subcommand(name: str, argv: list[str]) -> int:
    """``derive NAME ARGS``: parsed by the command's parser, carried out by its module."""
    command = next(c for c in SUBCOMMANDS if c.name == name)
    own = command.parser()
    args = own.parse_args(argv)
    status: int = importlib.import_module(command.module).run(args, own)
    return status


def _main(argv: list[str]) -> int:
    if argv and argv[0] in {c.name for c in SUBCOMMANDS}:
        return _subcommand(argv[0], argv[1:])
    args = parser().parse_args(argv)
    # The derivation's modules (sympy, flint, matplotlib) load only now: --help and
    # --version answer without them.
    from davies_sym.cli.catalog import catalog_listing, chosen_files

    if args.completion:
        return _completion(args.completion)
    try:
        files = chosen_files(args)
    except InputError as exc:
        print(exc.report(), file=sys.stderr)
        return 2
    if files is None:
        sys.stdout.write(catalog_listing())
        return 0
    args.files = files

    progress = Display("derive", args.quiet)  # its last step: where an internal error happened

    if len(args.files) > 1 or (args.out and os.path.isdir(args.out)):
        try:
            return _many_files(args, progress)
        except DaviesError as exc:  # the cluster cannot be reached, dask is missing
            print(exc.report() if isinstance(exc, InputError) else f"derive: {exc}", file=sys.stderr)
            return 2
    if args.jobs != 1 or args.scheduler:
        option = "--scheduler" if args.scheduler else "--jobs"
        print(f"derive: {option} derives several files into a directory: add --out DIR", file=sys.stderr)
        return 2
    return _one_file_refused_or_done(args, progress)


def _completion(shell: str) -> int:
    """``derive --completion SHELL``: the script completing every command's options."""
    try:
        commands = {c.name: c.parser() for c in SUBCOMMANDS}
        sys.stdout.write(completion_script(parser(), shell, commands))
    except DaviesError as exc:
        print(f"derive: --completion: {exc}", file=sys.stderr)
        return 2
    return 0


def _one_file_refused_or_done(args: argparse.Namespace, progress: Display) -> int:
    """``derive FILE ...``: its outputs, or the one line that says why not with its exit
    status (2 bad input, 3 not covered, 4 an internal error)."""
    try:
        return _one_file(args, progress)
    except NotCoveredError as exc:
        # A design outside the formulas: the last line says why, never a number.
        reason = f"derive: {args.files[0]}: {exc}"
        print(status_json("not covered", reason) if args.json else reason)
        return 3
    except DaviesError as exc:
        given_by = "--eval" if args.eval is not None else "--at" if args.at else None
        reason = message(named_by_option(exc, given_by), args.files[0])
        print(reason, file=sys.stderr)
        if args.json:
            print(status_json("bad input", reason))
        return 2
    except BrokenPipeError:
        raise  # the reader of the output went away: `main` stops quietly
    except OSError as exc:  # the system refused something the checks above did not foresee
        print(f"derive: {args.files[0]}: {exc.strerror or exc} ({shortened(str(exc.filename))})", file=sys.stderr)
        return 2
    except _StdoutFailed:
        raise
    except Exception as exc:  # a fault of davies_sym: the file and what was being derived
        state = f"state {args.state}, " if args.state else ""
        reason = internal_error(exc, args.files[0], f"{state}{progress.last or 'reading the file'}")
        print(reason, file=sys.stderr)
        if args.json:
            print(status_json("internal error", reason))
        return INTERNAL_ERROR
