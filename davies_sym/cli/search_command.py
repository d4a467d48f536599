"""``derive search TRAIN.yaml --target [STATE=]RATIO ... --tolerance REL --teeth NAME=LO:HI
...``: the tooth numbers that give the target speed ratios, feasible by every rule of
`davies_sym.synthesis.rules`, ranked by the closed-form efficiency; with ``--atlas N``
over every train of the atlas (`davies_sym.cli.atlas_search_command`).

Bad input exits with status 2 and one message naming the option; a search that finds no
feasible design answers so (status 0, ``feasible: 0``).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from fractions import Fraction

from davies_sym.cli.atlas_search_command import atlas_search
from davies_sym.cli.subcommand_parsers import TOP, tooth_bounds
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.errors import DaviesError, InputError, Problem
from davies_sym.fan_out import Workers
from davies_sym.progress import Display
from davies_sym.topology.expressions import ExpressionError, parse_expression


def _number(text: str, option: str) -> Fraction:
    try:
        value = parse_expression(text)
    except ExpressionError as exc:
        raise InputError([Problem(option, str(exc))]) from None
    if not value.is_Rational:
        raise InputError([Problem(option, f"{text} is not a rational number")])
    return Fraction(int(value.p), int(value.q))


def _targets(pairs: Sequence[str]) -> list[tuple[str | None, Fraction]]:
    out = []
    for pair in pairs:
        state, sep, ratio = pair.rpartition("=")
        out.append((state.strip() if sep else None, _number(ratio, "--target")))
    return out


def _weights(pairs: Sequence[str]) -> dict[str, float]:
    out = {}
    for pair in pairs:
        state, sep, weight = pair.partition("=")
        if not sep:
            raise InputError([Problem("--weights", f"expected STATE=W, got {pair!r}")])
        out[state.strip()] = float(_number(weight, "--weights"))
    return out


def _check_outputs(args: argparse.Namespace) -> None:
    problems = []
    if args.top < 1:
        problems.append(Problem("--top", f"list at least one design, got {args.top}"))
    if args.plot and not args.out:
        problems.append(Problem("--plot", "name the figure's file with -o FRONT.png"))
    for option, path in (("-o", args.out), ("--write-best", args.write_best)):
        if path is not None and not path.strip():
            problems.append(Problem(option, "the file name is empty; give a file name"))
        elif path and same_file(path, args.train):
            problems.append(Problem(option, f"{path} is the train file itself: name another file"))
    if args.out and args.write_best and same_file(args.out, args.write_best):
        problems.append(Problem("--write-best", "-o and --write-best name the same file"))
    if problems:
        raise InputError(problems)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """The ``derive search`` command, its arguments parsed by ``parser``: over the atlas
    with ``--atlas``, else over the train file; returns the exit status (0, or 2 for
    bad input)."""
    if args.atlas is not None:
        return atlas_search(args, parser)
    if args.train is None:
        parser.error("give the train file TRAIN.yaml, or --atlas N to search the atlas")
    if args.budget is not None:
        parser.error("--budget is for a search over the atlas (--atlas N): a train file's search scores every design")
    if args.teeth is None:
        parser.error("the following arguments are required: --teeth")
    args.top = TOP if args.top is None else args.top
    from davies_sym.emit.plots import figure_bytes, figure_format
    from davies_sym.synthesis.best_design import best_design_text
    from davies_sym.synthesis.problem import search_problem
    from davies_sym.synthesis.search_report import pareto_figure, search_text
    from davies_sym.synthesis.tooth_search import run_search
    from davies_sym.topology.loader import load

    say = Display("derive search", args.quiet)
    try:
        _check_outputs(args)
        if args.plot and figure_format(args.out) is None:
            raise InputError([Problem("-o", f"{args.out}: name the figure's file .png, .svg or .pdf")])
        train = load(args.train)
        problem = search_problem(
            train,
            _targets(args.target),
            _number(args.tolerance, "--tolerance"),
            tooth_bounds(args.teeth),
            args.planets,
            args.min_teeth,
            _weights(args.weights),
        )
        result = run_search(problem, say, Workers(args.jobs, args.scheduler))
    except DaviesError as exc:
        text = exc.report() if isinstance(exc, InputError) else f"derive search: {args.train}: {exc}"
        print(text.replace("<input>", args.train), file=sys.stderr)
        return 2
    document = {"status": "ok", "train": args.train, **result.document(args.top)}
    answer = json.dumps(document, indent=2) + "\n" if args.json else search_text(result, args.top)
    try:
        if args.write_best and result.candidates:
            best = result.candidates[0]
            with open(args.train, encoding="utf-8") as handle:
                source = handle.read()
            note = f"The best design of derive search {args.train}: efficiency {best.score:.6f}"
            write_atomic(args.write_best, best_design_text(source, best.teeth, note))
        if args.plot:
            write_atomic(args.out, figure_bytes(pareto_figure(result), figure_format(args.out) or ".png"))
            sys.stdout.write(answer)
        elif args.out:
            write_atomic(args.out, answer)
        else:
            sys.stdout.write(answer)
    except OSError as exc:
        print(f"derive search: cannot write {exc.filename}: {exc.strerror}", file=sys.stderr)
        return 2
    if args.write_best and not result.candidates:
        print("derive search: --write-best: no feasible design to write", file=sys.stderr)
    return 0
