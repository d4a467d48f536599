"""The parsers of ``derive``'s other commands (``derive atlas``, ``derive calibrate``,
``derive search``) and the table that routes the first word of the command line to them.
Like `.parser`, it imports nothing heavy: ``derive search --help`` answers at once; the
command's module (`Subcommand.module`, whose ``run`` takes the parsed arguments) loads
only when the command runs."""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction

from davies_sym.errors import InputError, Problem
from davies_sym.option_types import Parser, jobs, starts

#: Link counts the atlas enumerates (9 links: 71,837 trains, beyond a command's minutes).
FEWEST_LINKS, MOST_LINKS = 3, 8
#: Designs listed unless ``--top`` says otherwise: of one train, of the atlas.
TOP, ATLAS_TOP = 20, 10


def _atlas_links(text: str) -> int:
    if not text.isdigit() or not FEWEST_LINKS <= int(text) <= MOST_LINKS:
        raise argparse.ArgumentTypeError(
            f"expected a number of links from {FEWEST_LINKS} to {MOST_LINKS} (the frame counted), got {text!r}"
        )
    return int(text)


def _most_links(text: str) -> int:
    if not text.isdigit() or not 4 <= int(text) <= MOST_LINKS:
        raise argparse.ArgumentTypeError(f"expected the most links, from 4 to {MOST_LINKS}, got {text!r}")
    return int(text)


def _work(text: str) -> int:
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number of designs, at least 1, got {text!r}")
    return int(text)


def fraction(text: str) -> Fraction:
    """A number as written (12.5, 25/2), exactly."""
    try:
        return Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"expected a number such as 12.5 or 25/2, got {text!r}") from None


def tooth_range(text: str) -> tuple[int, int]:
    """``LO:HI``, whole numbers with 1 <= LO <= HI."""
    low, _, high = text.partition(":")
    if not (low.isdigit() and high.isdigit()) or not 1 <= int(low) <= int(high):
        raise argparse.ArgumentTypeError(f"expected LO:HI, whole numbers with 1 <= LO <= HI, got {text!r}")
    return int(low), int(high)


def tooth_bounds(pairs: Sequence[str]) -> dict[str, tuple[int, int]]:
    """``--teeth NAME=LO:HI ...`` of `derive search` and `derive shifts`: the bounds by name, each once."""
    out: dict[str, tuple[int, int]] = {}
    for pair in pairs:
        name, sep, span = pair.partition("=")
        low, colon, high = span.partition(":")
        try:
            bounds = (int(low), int(high))
        except ValueError:
            bounds = None
        if not sep or not colon or bounds is None:
            raise InputError([Problem("--teeth", f"expected NAME=LO:HI with whole LO and HI, got {pair!r}")])
        if name.strip() in out:
            raise InputError([Problem("--teeth", f"{name.strip()} has bounds twice")])
        out[name.strip()] = bounds
    return out


def _tooth_options(p: argparse.ArgumentParser, teeth: str, condition: str = "with --teeth: ") -> None:
    """``--teeth``, ``--planets`` and ``--min-teeth``, as `derive search` and `derive shifts` take them."""
    p.add_argument("--teeth", nargs="+", metavar="NAME=LO:HI", help=teeth)
    planets = "planets per set, equally spaced (assembly and tip clearance)"
    p.add_argument("--planets", type=int, metavar="N", help=condition + planets)
    p.add_argument("--min-teeth", type=int, default=17, metavar="Z", help=f"{condition}fewest teeth on any gear (17)")


def atlas_parser() -> argparse.ArgumentParser:
    """``derive atlas``."""
    p = Parser(
        prog="derive atlas",
        description="Enumerate the one-degree-of-freedom planetary gear trains of N links (rotation and "
        "displacement graphs, up to isomorphism) and write a train file for each.",
    )
    p.add_argument("--links", type=_atlas_links, required=True, metavar="N", help="number of links, the frame counted")
    p.add_argument("--json", action="store_true", help="the atlas as JSON (counts, codes, levels, coaxial members)")
    p.add_argument("--out", metavar="DIR", help="write one train file per displacement graph into DIR")
    p.add_argument("--draw", action="store_true", help="with --out: an SVG of each graph and of its train's layout")
    p.add_argument("--count", action="store_true", help="only the counts, beside the published ones (no train is read)")
    p.add_argument("--jobs", type=jobs, default=1, metavar="N", help="worker processes (or auto)")
    p.add_argument("--quiet", action="store_true", help="no progress on standard error")
    return p


def calibrate_parser() -> argparse.ArgumentParser:
    """``derive calibrate``."""
    p = Parser(
        prog="derive calibrate",
        description="Fit loss parameters of a train to "
        "measured operating points (columns w_<PORT> in rpm, T_<PORT> in N m, eta).",
    )
    p.add_argument("train", metavar="TRAIN.yaml", nargs="?", help="the train (or --catalog NAME)")
    p.add_argument("data", metavar="DATA.csv", nargs="?", help="the measurements (default: the file's calibrate: data)")
    p.add_argument(
        "--catalog",
        metavar="NAME",
        help="a catalog train in place of TRAIN.yaml, with its own data (derive calibrate --catalog sr20_differential)",
    )
    p.add_argument("--fit", nargs="+", metavar="NAME", help="parameters to fit (default: the file's calibrate: fit)")
    p.add_argument(
        "--predict",
        nargs="+",
        metavar="OTHER.csv",
        help="predict the efficiency at every row of other files (rows in the order of the files)",
    )
    p.add_argument("--at", nargs="+", metavar="NAME=VALUE", default=[], help="values of the parameters not fitted")
    p.add_argument("--json", action="store_true", help="one JSON object")
    p.add_argument("-o", "--out", metavar="FIG.png", help="write the residual plot (.png, .svg or .pdf)")
    p.add_argument(
        "--starts",
        type=starts,
        default=1,
        metavar="N",
        help="fit from N start points (the file's, then spread over the ranges) and keep the least squares",
    )
    where = p.add_mutually_exclusive_group()
    where.add_argument("--jobs", type=jobs, default=1, metavar="N", help="worker processes ('auto': one per core)")
    where.add_argument("--scheduler", metavar="ADDRESS", help="fit the starts on the Dask cluster at ADDRESS")
    p.add_argument("--quiet", action="store_true", help="no progress messages")
    return p


def search_parser() -> argparse.ArgumentParser:
    """``derive search``: over one train file, or with ``--atlas N`` over every
    planetary train of the atlas up to N links."""
    p = Parser(
        prog="derive search",
        description="Find the tooth numbers of a train (symbolic teeth, free ones listed in independent:) "
        "whose speed ratios hit the targets, and rank the feasible designs by their exact efficiency; "
        "with --atlas N, over every planetary train of the atlas up to N links, every held member and both "
        "directions.",
        epilog="Over the atlas: derive search --atlas 6 --target 12.5 --tolerance 0.2 --teeth 17:60 "
        "(one RATIO, one LO:HI for every gear, --out DIR for the listed designs as train files).",
    )
    p.add_argument("train", metavar="TRAIN.yaml", nargs="?", help="the train (not with --atlas)")
    p.add_argument("--atlas", type=_most_links, metavar="N", help="search the atlas up to N links (4 to 8) instead")
    p.add_argument(
        "--target",
        nargs="+",
        required=True,
        metavar="[STATE=]RATIO",
        help="speed ratio wanted (input over output speed), one per state (with --atlas: one)",
    )
    p.add_argument(
        "--tolerance", default="0.01", metavar="REL", help="relative deviation allowed from each target (default 0.01)"
    )
    _tooth_options(p, "bounds of every free tooth number (with --atlas: LO:HI for every gear, default 17:100)", "")
    p.add_argument(
        "--weights", nargs="+", default=[], metavar="STATE=W", help="weight of each state in the score (default equal)"
    )
    p.add_argument("--top", type=int, metavar="K", help=f"designs listed (default {TOP}; with --atlas {ATLAS_TOP})")
    p.add_argument(
        "--budget",
        type=_work,
        metavar="DESIGNS",
        help="with --atlas: designs scored per train and direction before its search stops and says its design "
        "is the best it scored, not a proven best (default 2000000)",
    )
    p.add_argument("--json", action="store_true", help="one JSON document")
    p.add_argument(
        "-o",
        "--out",
        metavar="FILE|DIR",
        help="write the answer (or, with --plot, the Pareto figure) to FILE; with --atlas, the listed designs "
        "as train files with numbers into DIR",
    )
    p.add_argument("--plot", action="store_true", help="the Pareto fronts as a figure (needs -o FRONT.png)")
    p.add_argument("--write-best", metavar="OUT.yaml", help="write the best design as a train file with numbers")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--jobs", type=jobs, default=1, metavar="N", help="worker processes ('auto': one per core)")
    where.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="derive the states (with --atlas: search the trains) on the Dask cluster at ADDRESS",
    )
    p.add_argument("--quiet", action="store_true", help="no progress messages")
    return p


def shifts_parser() -> argparse.ArgumentParser:
    """``derive shifts``."""
    p = Parser(
        prog="derive shifts",
        description="Find the shift elements (brakes and clutches among the main-axis members) and the "
        "schedule (which are engaged in each gear) that give a ratio table with the given gearsets and "
        "connections, and rank the schemes by the exact efficiency of every gear.",
        epilog="The file is a train of several degrees of freedom with its permanent connections, its input "
        "and output ports and no states:; every main-axis member runs in a bearing of the reference.",
    )
    p.add_argument("train", metavar="GEARSETS.yaml")
    p.add_argument(
        "--target",
        nargs="+",
        required=True,
        metavar="GEAR=RATIO",
        help="each gear's speed ratio (input over output speed; negative: a reverse gear)",
    )
    p.add_argument("--tolerance", type=fraction, default=Fraction(1, 200), metavar="REL", help="relative (0.005)")
    p.add_argument("--elements", type=int, metavar="N", help="shift elements in the scheme (default: the fewest)")
    p.add_argument(
        "--engaged", type=int, metavar="K", help="elements engaged per gear (default: degrees of freedom - 1)"
    )
    p.add_argument("--weights", nargs="+", default=[], metavar="GEAR=W", help="weight of each gear (default equal)")
    p.add_argument(
        "--connections",
        type=int,
        default=0,
        metavar="N",
        help="also search N permanent joins between members of different sets (or a shaft and a member)",
    )
    p.add_argument(
        "--drag",
        type=fraction,
        default=Fraction(0),
        metavar="COEFF",
        help="rank less the open elements' drag: torque COEFF v at relative speed v, in units of the input "
        "power at unit input speed (default 0)",
    )
    _tooth_options(p, "search the free tooth numbers within their bounds with the scheme (the teeth are symbols)")
    p.add_argument("--any-shifts", action="store_true", help="allow shifts that change more than one element")
    p.add_argument("--top", type=int, default=TOP, metavar="K", help=f"schemes listed (default {TOP})")
    p.add_argument("--json", action="store_true", help="one JSON document")
    p.add_argument("-o", "--out", metavar="FILE", help="write the answer to FILE")
    p.add_argument("--write-best", metavar="OUT.yaml", help="the best scheme as a train file, a state per gear")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--jobs", type=jobs, default=1, metavar="N", help="worker processes ('auto': one per core)")
    where.add_argument("--scheduler", metavar="ADDRESS", help="derive the gears on the Dask cluster at ADDRESS")
    p.add_argument("--quiet", action="store_true", help="no progress messages")
    return p


@dataclass(frozen=True)
class Subcommand:
    """One of ``derive``'s other commands: its name, its line in ``derive --help``, its
    parser and the module whose ``run(args, parser)`` carries it out."""

    name: str
    line: str
    parser: Callable[[], argparse.ArgumentParser]
    module: str


SUBCOMMANDS = (
    Subcommand(
        "atlas",
        "every 1-DOF planetary gear train of N links, with a train file for each",
        atlas_parser,
        "davies_sym.cli.atlas_command",
    ),
    Subcommand(
        "calibrate",
        "fit loss parameters to test-rig data (TRAIN.yaml DATA.csv, or --catalog NAME)",
        calibrate_parser,
        "davies_sym.cli.calibrate_command",
    ),
    Subcommand(
        "shifts",
        "brakes, clutches and schedule for a ratio table, ranked by exact efficiency",
        shifts_parser,
        "davies_sym.cli.shifts_command",
    ),
    Subcommand(
        "search",
        "tooth numbers for target speed ratios, ranked by exact efficiency",
        search_parser,
        "davies_sym.cli.search_command",
    ),
)
