"""What the user writes on the command line, read once the parser (`.parser`) has
accepted it: the readers of ``NAME=VALUE`` values, ``NAME=START:STOP`` sweeps and the ``--input``/``--output``
choice, each refusing bad input with a message naming the option."""

from __future__ import annotations

import argparse
from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import replace

import sympy

from davies_sym.efficiency.design_values import design_values
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.emit.plots import Sweep, figure_format
from davies_sym.errors import InputError, MissingValuesError, Problem, shortened
from davies_sym.topology.model import Train
from davies_sym.topology.symbols import exact_number


def values(
    train: Train,
    pairs: Sequence[str],
    option: str = "--eval",
    operating: Collection[sympy.Symbol] = (),
    defaults: Mapping[str, str] | None = None,
) -> dict[sympy.Symbol, sympy.Expr]:
    """``NAME=VALUE`` pairs as exact values of the train's symbols and of the ``operating``
    symbols the formulas take besides (input torque and speed), read and checked as the
    Python API reads them (`design_values`); a name given twice is refused, a name of
    ``defaults`` (the published design a figure starts from) is overridden."""
    problems: list[Problem] = []
    given: dict[str, str] = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        name = name.strip()
        if not sep or not name:
            problems.append(Problem(option, f"expected NAME=VALUE, got {shortened(pair)}"))
        elif name in given:
            problems.append(
                Problem(option, f"{shortened(name)} is given twice ({name}={given[name]}, {name}={text}): give it once")
            )
        else:
            given[name] = text
    if problems:
        raise InputError(problems, train.path)
    return design_values(train, {**(defaults or {}), **given}, option, operating)


#: Largest magnitude of a sweep's bound: far beyond any size or coefficient of a train, and
#: small enough that the formulas' powers of it stay finite in floating point.
LARGEST_BOUND = 1e12


def sweep(train: Train, option: str, text: str, names: Collection[str] | None = None) -> Sweep:
    """``NAME=START:STOP`` as a sweep of one of ``names`` (default: the train's symbols),
    its bounds finite, at most `LARGEST_BOUND` in magnitude and far enough apart to draw."""
    known = sorted(train.symbols if names is None else names)
    name, sep, interval = text.partition("=")
    start, colon, stop = interval.partition(":")
    bounds = (exact_number(start.strip()), exact_number(stop.strip()))
    if not sep or not colon:
        raise InputError([Problem(option, f"expected NAME=START:STOP, got {shortened(text)}")], train.path)
    if name.strip() not in known:
        raise InputError(
            [Problem(option, f"unknown symbol {shortened(name.strip())} (the train has: {', '.join(known)})")],
            train.path,
        )
    for written, bound in zip((start, stop), bounds, strict=True):
        if bound is None or abs(bound) > LARGEST_BOUND:
            what = "not a finite number" if bound is None else "too large to draw"
            raise InputError(
                [
                    Problem(
                        option,
                        f"the bound {shortened(written.strip())} of {shortened(text)} is {what}: give numbers "
                        f"between {-LARGEST_BOUND:g} and {LARGEST_BOUND:g}",
                    )
                ],
                train.path,
            )
    low, high = (float(v) for v in bounds)  # type: ignore[arg-type]
    if not low < high:
        raise InputError([Problem(option, f"the interval {shortened(text)} is empty (START < STOP)")], train.path)
    if high - low <= 1e-9 * max(abs(low), abs(high)):
        raise InputError(
            [Problem(option, f"the interval {shortened(text)} is too narrow to draw; widen it")], train.path
        )
    return Sweep(name.strip(), low, high)


def plot_sweeps(
    train: Train, args: argparse.Namespace, names: Collection[str] | None = None
) -> tuple[Sweep, Sweep | None]:
    """``--plot`` and ``--vs`` as sweeps of ``names`` (default: the train's symbols); a
    figure needs its file (``-o FILE.png``)."""
    if not args.out:
        raise InputError([Problem("--plot", "give the figure's file with -o FILE.png")], train.path)
    figure_suffix(args.out, train.path)
    x = sweep(train, "--plot", args.plot, names)
    y = sweep(train, "--vs", args.vs, names) if args.vs else None
    if y is not None and y.name == x.name:
        raise InputError(
            [Problem("--vs", f"{x.name} is swept by --plot already: give --vs another parameter")], train.path
        )
    swept = {s.name: option for s, option in ((x, "--plot"), (y, "--vs")) if s is not None}
    for pair in args.at or ():
        name = pair.partition("=")[0].strip()
        if name in swept:
            raise InputError([Problem("--at", f"{name} is swept by {swept[name]}: leave it out of --at")], train.path)
    return x, y


def check_sweep_ranges(sweeps: Iterable[Sweep | None], parameters: Iterable[Parameter], source: str | None) -> None:
    """Refuse a sweep that lies wholly outside its parameter's admissible range (the
    formula module's ``PARAMETERS``): the figure would have no admissible point."""
    ranges = {p.name: p for p in parameters}
    for sweep, option in zip(sweeps, ("--plot", "--vs"), strict=False):
        p = ranges.get(sweep.name) if sweep is not None else None
        if sweep is None or p is None:
            continue
        below = sweep.stop < p.low or (sweep.stop == p.low and not p.closed_low)
        if below or sweep.start > p.high:
            raise InputError(
                [
                    Problem(
                        option,
                        f"{sweep.name} lies in {p.range_text} ({p.meaning}): the interval "
                        f"{sweep.start:g}:{sweep.stop:g} has no admissible value",
                    )
                ],
                source,
            )


def figure_suffix(path: str, source: str | None) -> str:
    """The figure format ``-o`` names by its suffix (``.png``, ``.svg`` or ``.pdf``)."""
    suffix = figure_format(path)
    if suffix is None:
        raise InputError(
            [
                Problem(
                    "-o", f"{shortened(path)}: name the figure's file .png, .svg or .pdf (the suffix says the format)"
                )
            ],
            source,
        )
    return suffix


def held_values(
    train: Train, given: Mapping[str, float], needed: Iterable[str], sweeps: tuple[Sweep, Sweep | None]
) -> dict[str, float]:
    """The values a figure holds fixed: every ``needed`` name but the swept ones, each
    from ``given`` (``--at``); the missing ones are named."""
    swept = {s.name for s in sweeps if s is not None}
    held = [n for n in needed if n not in swept]
    missing = [n for n in held if n not in given]
    if missing:
        raise InputError([Problem("--at", f"missing values for {', '.join(missing)}")], train.path)
    return {n: float(given[n]) for n in held}


def not_a_port(option: str, given: str, ports: Sequence[str], source: str | None) -> InputError:
    """The refusal of ``--input`` or ``--output`` naming no port."""
    return InputError([Problem(option, f"{shortened(given)} is not a port (ports: {', '.join(ports)})")], source)


def eval_port(train: Train, args: argparse.Namespace) -> str:
    """The input port ``--input`` or ``--output`` choose (default: the declared input),
    each checked to name a port of ``train``."""
    ports = (train.ports.input, train.ports.output)
    chosen = args.input
    if args.output is not None:
        if args.output not in ports:
            raise not_a_port("--output", args.output, ports, train.path)
        other = ports[1] if args.output == ports[0] else ports[0]
        if chosen is not None and chosen != other:
            raise InputError(
                [
                    Problem(
                        "--input",
                        f"input {chosen!r} and output {args.output!r} are not the two "
                        f"ports of the train ({', '.join(ports)})",
                    )
                ],
                train.path,
            )
        chosen = other
    if chosen is not None and chosen not in ports:
        raise not_a_port("--input", chosen, ports, train.path)
    return chosen or train.ports.input


def check_emit(args: argparse.Namespace, source: str | None) -> None:
    """``--emit`` writes code in place of the document: refuse what would need both."""
    if not args.emit:
        return
    for option, given in (
        ("--json", args.json),
        ("--latex", args.latex),
        ("--plot", args.plot),
        ("--eval", args.eval is not None),
    ):
        if given:
            raise InputError(
                [Problem("--emit", f"writes code in place of the document: not with {option} (run derive twice)")],
                source,
            )


def document_asked(args: argparse.Namespace, evaluating: bool) -> bool:
    """Whether the derivation's document is an output of this call: written with ``-o``,
    asked for as ``--latex`` (or ``--json`` without ``--eval``), or the call's only output.
    A module written with ``--python`` or an evaluation alone leaves stdout to the value."""
    if args.out or args.latex or (args.json and not evaluating):
        return True
    return not (evaluating or args.python)


#: The word of ``--eval`` that takes the file's published design (its first check).
PUBLISHED = "published"


def published_start(train: Train, pairs: Sequence[str], state: str | None) -> tuple[list[str], dict[str, str]]:
    """``--eval``'s NAME=VALUE pairs, and the published design they override where the word
    ``published`` is among them (the values of the first check, ``expected:``, of ``state``)."""
    if PUBLISHED not in pairs:
        return list(pairs), {}
    design = train.published_design(state)
    if not design:
        where = f" for state {state}" if state else ""
        raise InputError(
            [
                Problem(
                    "--eval",
                    f"`published` takes the values of the file's first check (expected:), but it has none{where}",
                )
            ],
            train.path,
        )
    return [p for p in pairs if p != PUBLISHED], dict(design)


def published_hint(
    error: MissingValuesError, train: Train, state: str | None, pairs: Sequence[str]
) -> MissingValuesError:
    """``error`` saying how to evaluate the published design where the file holds one."""
    if PUBLISHED in pairs or not train.published_design(state):
        return error
    hint = "; the file holds a published design: --eval published takes its values (NAME=VALUE after it changes one)"
    return MissingValuesError([replace(p, message=p.message + hint) for p in error.problems], error.source)
