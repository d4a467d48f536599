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
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

from davies_sym.arguments import Parser, jobs
from davies_sym.atlas.command import MOST_LINKS, folder_refused
from davies_sym.emit.atomic import write_atomic
from davies_sym.fan_out import Workers
from davies_sym.progress import Display

#: Designs listed unless ``--top`` says otherwise.
TOP = 10


def _links(text: str) -> int:
    if not text.isdigit() or not 4 <= int(text) <= MOST_LINKS:
        raise argparse.ArgumentTypeError(f"expected the most links, from 4 to {MOST_LINKS}, got {text!r}")
    return int(text)


def _fraction(text: str) -> Fraction:
    try:
        return Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"expected a number such as 12.5 or 25/2, got {text!r}") from None


def _range(text: str) -> tuple[int, int]:
    low, _, high = text.partition(":")
    if not (low.isdigit() and high.isdigit()) or not 1 <= int(low) <= int(high):
        raise argparse.ArgumentTypeError(f"expected LO:HI, whole numbers with 1 <= LO <= HI, got {text!r}")
    return int(low), int(high)


def parser() -> argparse.ArgumentParser:
    p = Parser(
        prog="derive search --atlas",
        description="Search every planetary train of the atlas up to N links, every held member and both "
        "directions, for tooth numbers that give the target speed ratio; rank by exact efficiency.",
    )
    p.add_argument("--atlas", type=_links, required=True, metavar="N", help="the most links of a train (4 to 8)")
    p.add_argument("--target", type=_fraction, required=True, metavar="RATIO", help="input speed over output speed")
    p.add_argument("--tolerance", type=_fraction, default=Fraction(1, 100), metavar="REL", help="relative (0.01)")
    p.add_argument("--teeth", type=_range, default=(17, 100), metavar="LO:HI", help="every gear's teeth (17:100)")
    p.add_argument("--planets", type=int, metavar="N", help="planets per set, equally spaced")
    p.add_argument("--min-teeth", type=int, default=17, metavar="Z", help="fewest teeth on any gear (17)")
    p.add_argument("--top", type=int, default=TOP, metavar="K", help=f"designs listed ({TOP})")
    p.add_argument("--json", action="store_true", help="one JSON document")
    p.add_argument("--out", metavar="DIR", help="write the listed designs as train files with numbers into DIR")
    p.add_argument("--jobs", type=jobs, default=1, metavar="N", help="worker processes (or auto)")
    p.add_argument("--quiet", action="store_true", help="no progress on standard error")
    return p


def _line(rank: int, design: Any) -> str:
    c, choice = design.candidate, design.choice
    teeth = " ".join(f"{n}={v}" for n, v in c.teeth.items())
    ratio = float(c.ratios[choice.name])
    return (
        f"{rank:4d}. {design.train} l{choice.held} held, l{choice.input} in, l{choice.output} out: "
        f"{teeth}  ratio {ratio:.4f}  efficiency {c.score:.5f}"
    )


def run(argv: Sequence[str]) -> int:
    """The command; returns the exit status (0, or 2 for bad input)."""
    args = parser().parse_args(argv)
    if args.target <= 0 and args.target >= 0:
        print("derive search: --target: a speed ratio is not zero", file=sys.stderr)
        return 2
    if args.tolerance < 0:
        print("derive search: --tolerance: a relative deviation is >= 0", file=sys.stderr)
        return 2
    if folder_refused("derive search", args.out):
        return 2
    from davies_sym.atlas.search import AtlasQuestion, atlas_search, design_file

    say = Display("derive search", args.quiet)
    question = AtlasQuestion(args.target, args.tolerance, args.teeth, args.planets, args.min_teeth)
    designs, trains = atlas_search(args.atlas, question, Workers(args.jobs), say)
    shown = designs[: args.top]
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        for rank, design in enumerate(shown, 1):
            path = os.path.join(args.out, f"design{rank:02d}_{design.train}_{design.choice.name}.yaml")
            write_atomic(path, design_file(design, rank))
    if args.json:
        document = {
            "atlas": args.atlas,
            "target": float(args.target),
            "trains": trains,
            "kept_per_direction": question.per_state,
            "kept": len(designs),
            "designs": [d.document() for d in shown],
        }
        sys.stdout.write(json.dumps(document, indent=2) + "\n")
        return 0
    lines = [
        f"atlas up to {args.atlas} links: {trains} trains searched for ratio {float(args.target):g} "
        f"within {float(args.tolerance):g}; {len(designs)} design(s) kept, "
        "the best of each train and direction"
    ]
    lines += [_line(rank, d) for rank, d in enumerate(shown, 1)]
    if len(designs) > len(shown):
        lines.append(f"      ... {len(designs) - len(shown)} more (--top)")
    sys.stdout.write("\n".join(lines) + "\n")
    return 0
