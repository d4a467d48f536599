"""How ``derive`` reports a refusal: one located message per problem on standard error,
and with ``--json`` a JSON answer carrying the status and the reason."""

from __future__ import annotations

import json

from davies_sym.errors import DaviesError, InputError


def message(exc: DaviesError, path: str) -> str:
    """One message per problem: the located report of an input error, else the file and the reason."""
    return exc.report() if isinstance(exc, InputError) else f"derive: {path}: {exc}"


def status_json(status: str, reason: str) -> str:
    """The JSON answer of a refusal: ``status`` ("bad input", exit 2; "not covered", exit 3)
    and the ``reason`` that standard error or the last line gives."""
    return json.dumps({"status": status, "exit_status": 2 if status == "bad input" else 3, "reason": reason}, indent=2)
