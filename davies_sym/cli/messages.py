"""How ``derive`` reports a refusal: one located message per problem on standard error,
and with ``--json`` a JSON answer carrying the status and the reason."""

from __future__ import annotations

import json
import traceback
from dataclasses import replace

from davies_sym.errors import VALUES, DaviesError, InputError

#: The exit status of a fault of davies_sym itself: an exception that no stage turned into
#: a refusal (docs/errors.md).  Never a verdict on the file: the same file may derive once fixed.
INTERNAL_ERROR = 4


def named_by_option(exc: DaviesError, option: str | None) -> DaviesError:
    """``exc`` with the problems the engine files under ``values`` (the API's argument)
    filed under the command-line ``option`` that gave the values (``--eval``, ``--at``)."""
    if option is None or not isinstance(exc, InputError) or all(p.entry != VALUES for p in exc.problems):
        return exc
    problems = [replace(p, entry=option) if p.entry == VALUES else p for p in exc.problems]
    return type(exc)(problems, exc.source)


def message(exc: DaviesError, path: str) -> str:
    """One message per problem: the located report of an input error, else the file and the reason."""
    return exc.report() if isinstance(exc, InputError) else f"derive: {path}: {exc}"


def internal_error(exc: BaseException, where: str, doing: str) -> str:
    """The report of an exception that escaped every stage (exit status `INTERNAL_ERROR`):
    ``where`` (the file, or the subcommand), what was being done, the exception and the
    place in davies_sym it came from, and a request to report it."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if "davies_sym" in f.filename.replace("\\", "/")]
    origin = ""
    if frames:
        last = frames[-1]
        module = last.filename.replace("\\", "/").rpartition("davies_sym/")[2]
        origin = f" (in davies_sym/{module}:{last.lineno}, {last.name})"
    cause = f"{type(exc).__name__}: {exc}".strip().splitlines()[0][:300]
    return (
        f"internal error: {where}: {doing}: {cause}{origin}. This is a fault of davies_sym, not of your input: "
        "please report it with the file and this message"
    )


_EXIT_STATUS = {"bad input": 2, "not covered": 3, "internal error": INTERNAL_ERROR}


def status_json(status: str, reason: str) -> str:
    """The JSON answer of a refusal: ``status`` ("bad input", exit 2; "not covered", exit 3;
    "internal error", exit 4) and the ``reason`` that standard error or the last line gives."""
    return json.dumps({"status": status, "exit_status": _EXIT_STATUS[status], "reason": reason}, indent=2)
