"""The parser of ``derive``: every option with its help.  It imports nothing heavy (no
sympy, no matplotlib), so ``derive --help`` and ``derive --version`` answer at once;
what the options mean is read afterwards by `.arguments`."""

from __future__ import annotations

import argparse
from importlib import metadata

from davies_sym.cli.completion import ANY_FILE, SHELLS, YAML_FILES, catalog_completion
from davies_sym.cli.subcommand_parsers import SUBCOMMANDS
from davies_sym.emit.language_names import EMIT_TARGETS, LANGUAGES
from davies_sym.option_types import Parser, jobs


def _version() -> str:
    """The installed package's version."""
    try:
        return metadata.version("davies_sym")
    except metadata.PackageNotFoundError:  # pragma: no cover - run from a checkout never installed
        return "(not installed)"


def parser() -> argparse.ArgumentParser:
    """The argument parser of ``derive`` (also read by the documentation's command-line page)."""
    p = Parser(
        prog="derive",
        description="Derive the efficiency of a gear train (or machine) described in a YAML topology file,\n"
        "by Davies' method: every turning-condition variant in ordinary mesh efficiencies.",
        epilog="\n".join(
            [
                "other commands (each has its own --help):",
                *(f"  derive {c.name:<10} {c.line}" for c in SUBCOMMANDS),
            ]
        ),
        # The epilog's lines stay as written (one command a line).
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    _input_options(p)
    _document_options(p)
    _evaluation_options(p)
    _figure_options(p)
    _worker_options(p)
    p.add_argument("--quiet", action="store_true", help="no progress messages on standard error")
    return p


def _input_options(p: argparse.ArgumentParser) -> None:
    """What to derive: files, a catalog train, a state; the version."""
    # ``.complete``: what shtab offers for the argument in a completion script (--completion).
    files = p.add_argument(
        "files", nargs="*", metavar="FILE", help="topology file (YAML); several files need --out DIR"
    )
    files.complete = YAML_FILES  # type: ignore[attr-defined]
    catalog = p.add_argument(
        "--catalog",
        nargs="?",
        const="",
        metavar="NAME",
        help="alone: list the catalog of literature trains that comes with the package; with a "
        "NAME: derive that train in place of FILE (e.g. derive --catalog tuplin --latex)",
    )
    catalog.complete = catalog_completion()  # type: ignore[attr-defined]
    p.add_argument("--version", action="version", version=f"%(prog)s (davies_sym) {_version()}")
    p.add_argument(
        "--state",
        metavar="NAME",
        help="operating state of a multi-speed set (default: every state; "
        "--eval, --python, --emit and --plot need one)",
    )


def _document_options(p: argparse.ArgumentParser) -> None:
    """What is written: the documents, the formula module, code in other languages."""
    form = p.add_mutually_exclusive_group()
    form.add_argument("--json", action="store_true", help="print the JSON document")
    form.add_argument(
        "--latex",
        action="store_true",
        help="print a standalone LaTeX document of the variants (of "
        "the power-flow regions for a train with several inputs)",
    )
    out = p.add_argument(
        "-o",
        "--out",
        metavar="FILE|DIR",
        help="write the document to FILE (atomically) instead of stdout; with a directory, write "
        "<name>.tex and <name>.py of every train there (e.g. derive catalog/*.yaml --out "
        "derivations/), with --json <name>.json alone, with --latex <name>.tex alone",
    )
    out.complete = ANY_FILE  # type: ignore[attr-defined]
    python = p.add_argument(
        "--python",
        metavar="OUT.py",
        help="write a Python module with one function per variant "
        "(per power-flow region for a train with several inputs)",
    )
    python.complete = ANY_FILE  # type: ignore[attr-defined]
    p.add_argument(
        "--emit",
        choices=EMIT_TARGETS,
        metavar="LANG",
        help=f"print (or with -o FILE write) the formulas as code in LANG ({', '.join(LANGUAGES)}): one "
        "function per variant (per power-flow region for a train with several inputs) and per turning "
        "condition, and the choice efficiency(...) that picks the one that holds; in place of the document; "
        "fmu: write a Functional Mock-up Unit (FMI 2.0 co-simulation) to -o TRAIN.fmu, its parameters "
        "starting at --at NAME=VALUE (default: the file's first published check)",
    )
    p.add_argument(
        "--completion",
        choices=SHELLS,
        metavar="SHELL",
        help=f"print a completion script for SHELL ({', '.join(SHELLS)}), e.g. "
        "derive --completion bash > ~/.local/share/bash-completion/completions/derive",
    )


def _evaluation_options(p: argparse.ArgumentParser) -> None:
    """Numbers from the formulas: values, sensitivities, the ports they are taken at."""
    p.add_argument(
        "--eval",
        nargs="*",
        metavar="NAME=VALUE",
        help="print the variant, the speed ratio and, as the last line, the efficiency at these values "
        "(exact where possible; no values when every quantity of the train is a number); 'published' "
        "takes the values of the file's first check (expected:), NAME=VALUE after it changes one; "
        "with --json one JSON object",
    )
    p.add_argument(
        "--sensitivity",
        metavar="NAME",
        help="print (with --latex: a LaTeX document of) the partial derivative of every variant's efficiency "
        "in the parameter NAME, from the exact closed form",
    )
    p.add_argument("--input", metavar="PORT", help="input port for --eval (default: the declared input)")
    p.add_argument("--output", metavar="PORT", help="output port for --eval (the other port)")


def _figure_options(p: argparse.ArgumentParser) -> None:
    """Figures over one or two parameters, and a machine's task."""
    p.add_argument(
        "--plot",
        nargs="?",
        const="",
        metavar="NAME=START:STOP",
        help="figure of the efficiency and the losses (the port torques for a train with several "
        "inputs) against one parameter (PNG, -o FILE); with --task (no value): the power curves of the task",
    )
    p.add_argument(
        "--task",
        metavar="NAME",
        help="a machine's task defined in its file (e.g. lift): the powers at every time step, the energy "
        "lost in every coupling and, as the last line, the task efficiency",
    )
    p.add_argument(
        "--vs",
        metavar="NAME=START:STOP",
        help="with --plot: a second parameter; the figure shows the variant regions, the turning-condition "
        "curves and efficiency contours over both (e.g. the two input speeds of a differential: its "
        "power-flow regions)",
    )
    p.add_argument(
        "--at",
        nargs="+",
        metavar="NAME=VALUE",
        default=[],
        help="with --plot: values of the other parameters; with --emit fmu: the parameters' start values "
        "(default: the first published check of the file)",
    )


def _worker_options(p: argparse.ArgumentParser) -> None:
    """Where many files are derived (`davies_sym.fan_out`)."""
    p.add_argument(
        "--jobs",
        type=jobs,
        default=1,
        metavar="N",
        help="with --out DIR: derive the files on N processes at once (auto: one per core); a file that "
        "fails is reported and the others go on",
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="with --out DIR: derive the files on the Dask cluster whose scheduler listens at ADDRESS "
        "(e.g. tcp://10.0.0.5:8786; needs pip install 'davies_sym[dask]')",
    )
