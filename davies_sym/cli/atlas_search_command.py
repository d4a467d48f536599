"""``derive search --atlas N --target RATIO --teeth LO:HI ...``: the tooth-number search
over every planetary train of the atlas up to N links, every held member and both
directions, ranked by the closed-form efficiency; ``--out DIR`` writes the best designs
as train files with numbers, which ``derive --eval`` evaluates to the same efficiency.

Bad input exits with status 2 and one message naming the option.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeVar

from davies_sym.cli.atlas_command import folder_refused
from davies_sym.cli.messages import INTERNAL_ERROR, internal_error
from davies_sym.cli.subcommand_parsers import ATLAS_TOP, fraction, tooth_range
from davies_sym.emit.atomic import write_atomic
from davies_sym.fan_out import Workers
from davies_sym.progress import Display, note

if TYPE_CHECKING:
    from davies_sym.atlas.search import AtlasQuestion

Value = TypeVar("Value")


def _line(rank: int, design: Any) -> str:
    c, choice = design.candidate, design.choice
    teeth = " ".join(f"{n}={v}" for n, v in c.teeth.items())
    ratio = float(c.ratios[choice.name])
    line = (
        f"{rank:4d}. {design.train} l{choice.held} held, l{choice.input} in, l{choice.output} out: "
        f"{teeth}  ratio {ratio:.4f}  efficiency {c.score:.5f}"
    )
    # A search stopped at its budget gives the best it scored, not a proven best.
    return line if design.proven else f"{line}  (best scored; others may reach {design.unexplored:.5f})"


def _read(parser: argparse.ArgumentParser, option: str, reader: Callable[[str], Value], text: str) -> Value:
    """``text`` read as ``option``'s value; refused as argparse refuses a bad value."""
    try:
        return reader(text)
    except argparse.ArgumentTypeError as exc:
        parser.error(f"argument {option}: {exc}")  # exits with status 2


def _question(args: argparse.Namespace, parser: argparse.ArgumentParser) -> AtlasQuestion | None:
    """What ``derive search --atlas`` asks, read from the options (None, said why, when
    it cannot be asked)."""
    if args.train is not None:
        parser.error(f"--atlas searches the atlas, not a file: drop {args.train} or --atlas")
    for option, given in (
        ("--weights", args.weights),
        ("--plot", args.plot),
        ("--write-best", args.write_best),
    ):
        if given:
            parser.error(f"{option} is for a search over one train file, not with --atlas")
    if len(args.target) != 1:
        parser.error("argument --target: with --atlas, one speed ratio (the atlas trains have no states)")
    if args.teeth is not None and len(args.teeth) != 1:
        parser.error("argument --teeth: with --atlas, one LO:HI for every gear")
    target = _read(parser, "--target", fraction, args.target[0])
    tolerance = _read(parser, "--tolerance", fraction, args.tolerance)
    teeth = _read(parser, "--teeth", tooth_range, args.teeth[0]) if args.teeth else (17, 100)
    if target == 0:
        print("derive search: --target: a speed ratio is not zero", file=sys.stderr)
        return None
    if tolerance < 0:
        print("derive search: --tolerance: a relative deviation is >= 0", file=sys.stderr)
        return None
    from davies_sym.atlas.search import AtlasQuestion

    question = AtlasQuestion(target, tolerance, teeth, args.planets, args.min_teeth)
    return question if args.budget is None else replace(question, budget=args.budget)


def atlas_search(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """``derive search --atlas N``; returns the exit status (0, 2 for bad input, 4 where
    the search of a train failed: the others are ranked)."""
    question = _question(args, parser)
    if question is None:
        return 2
    top = ATLAS_TOP if args.top is None else args.top
    if folder_refused("derive search", args.out):
        return 2
    from davies_sym.atlas.search import atlas_search as search_atlas
    from davies_sym.atlas.search import design_file

    say = Display("derive search", args.quiet)
    found = search_atlas(args.atlas, question, Workers(args.jobs, args.scheduler), say)
    designs, trains = found.designs, found.trains
    for failure in found.failures:
        note(say, internal_error(failure.error, f"derive search: {failure.train}", "searching it"))
    # A train whose search failed needs a look at the engine: the ranking lacks it.
    status = INTERNAL_ERROR if found.failures else 0
    shown = designs[:top]
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        for rank, design in enumerate(shown, 1):
            path = os.path.join(args.out, f"design{rank:02d}_{design.train}_{design.choice.name}.yaml")
            write_atomic(path, design_file(design, rank))
    if args.json:
        document = {
            "atlas": args.atlas,
            "target": float(question.target),
            "trains": trains,
            "kept_per_direction": question.per_state,
            "kept": len(designs),
            "failed": [failure.train for failure in found.failures],
            "undecided": list(found.undecided),
            "refused": list(found.refused),
            "designs": [d.document() for d in shown],
        }
        sys.stdout.write(json.dumps(document, indent=2) + "\n")
        return status
    lines = [
        f"atlas up to {args.atlas} links: {trains} trains searched for ratio {float(question.target):g} "
        f"within {float(question.tolerance):g}; {len(designs)} design(s) kept, "
        "the best of each train and direction"
    ]
    lines += [_line(rank, d) for rank, d in enumerate(shown, 1)]
    if len(designs) > len(shown):
        lines.append(f"      ... {len(designs) - len(shown)} more (--top)")
    if found.refused:
        lines.append(f"{len(found.refused)} direction(s) not derived (--json gives each reason): {found.refused[0]}")
    if found.undecided:
        lines.append(
            f"{len(found.undecided)} direction(s) stopped at the work budget before a design reaching the ratio "
            f"was found (--json lists them): {', '.join(found.undecided[:3])}"
            + (", ..." if len(found.undecided) > 3 else "")
        )
    sys.stdout.write("\n".join(lines) + "\n")
    return status
