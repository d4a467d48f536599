"""Command line: ``derive FILE [--json] [-o OUT] [--quiet]``."""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence

from .analysis import Analysis
from .atomic import write_atomic
from .errors import DaviesError, InputError
from .loader import load
from .report import text_summary, train_document


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="derive", description="Derive the efficiency of a gear train "
                                "(or machine) described in a YAML topology file, by Davies' method.")
    p.add_argument("file", help="topology file (YAML)")
    p.add_argument("--json", action="store_true", help="print the JSON document")
    p.add_argument("-o", "--output", help="write the output to this file (atomically) instead of stdout")
    p.add_argument("--quiet", action="store_true", help="no progress messages")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    show = not args.quiet and sys.stderr.isatty()

    def progress(message: str) -> None:
        if show:
            print(f"derive: {message}", file=sys.stderr, flush=True)

    try:
        if args.output and os.path.exists(args.output) and os.path.samefile(args.output, args.file):
            print(f"derive: refusing to overwrite the input file {args.file}", file=sys.stderr)
            return 2
        train = load(args.file)
        document = train_document(Analysis(train, progress=progress))
    except InputError as exc:
        print(exc.report(), file=sys.stderr)
        return 2
    except DaviesError as exc:
        print(f"derive: {args.file}: {exc}", file=sys.stderr)
        return 2
    text = json.dumps(document, indent=2) + "\n" if args.json else text_summary(document) + "\n"
    if args.output:
        write_atomic(args.output, text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
