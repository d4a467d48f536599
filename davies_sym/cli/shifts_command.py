"""``derive shifts GEARSETS.yaml --target GEAR=RATIO ... --tolerance REL``: the shift
elements and schedules that give a ratio table with the file's gearsets and permanent
connections, ranked by the exact efficiency of every gear
(`davies_sym.synthesis.shift_search`).

Bad input exits with status 2 and one message naming the file or the option; a ratio
table no scheme reaches exits with status 3 and names the closest ratios there are.
"""

from __future__ import annotations

import argparse
import json
import sys

from davies_sym.cli.subcommand_parsers import fraction, tooth_bounds
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.errors import DaviesError, InputError, Problem
from davies_sym.fan_out import Workers
from davies_sym.progress import Display
from davies_sym.synthesis.best_design import best_design_text
from davies_sym.synthesis.shift_connections import ConnectedScheme
from davies_sym.synthesis.shift_kinematics import member_forms, member_speeds
from davies_sym.synthesis.shift_schedules import GearTarget, ShiftQuestion, element_letter, gear_order
from davies_sym.synthesis.shift_search import (
    Ranking,
    ShiftResult,
    gear_state,
    port_member,
    ports_joined,
    shift_search,
    unreached,
)
from davies_sym.synthesis.shift_teeth import ToothRanges, shift_teeth_search
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train

COMMAND = "derive shifts"


def _targets(pairs: list[str]) -> tuple[GearTarget, ...]:
    """``GEAR=RATIO`` pairs: named once each, ratios non-zero numbers."""
    out: dict[str, GearTarget] = {}
    for pair in pairs:
        gear, sep, ratio = pair.partition("=")
        gear = gear.strip()
        if not sep or not gear:
            raise InputError([Problem("--target", f"expected GEAR=RATIO (e.g. 1=4.6957, R=-3.2968), got {pair!r}")])
        try:
            value = fraction(ratio.strip())
        except argparse.ArgumentTypeError as exc:
            raise InputError([Problem("--target", f"{gear}: {exc}")]) from None
        if value == 0:
            raise InputError([Problem("--target", f"{gear}: a speed ratio is not zero")])
        if gear in out:
            raise InputError([Problem("--target", f"gear {gear} is named twice; name each gear once")])
        out[gear] = GearTarget(gear, value)
    return tuple(out.values())


def _weights(pairs: list[str], targets: tuple[GearTarget, ...]) -> dict[str, float]:
    names = {t.name for t in targets}
    out = {}
    for pair in pairs:
        gear, sep, weight = pair.partition("=")
        try:
            value = float(fraction(weight.strip())) if sep else -1.0
        except argparse.ArgumentTypeError:
            value = -1.0
        if value < 0:
            raise InputError([Problem("--weights", f"expected GEAR=W with W a number >= 0, got {pair!r}")])
        if gear.strip() not in names:
            raise InputError([Problem("--weights", f"{gear.strip()!r} is not a gear of --target")])
        out[gear.strip()] = value
    return out


def _question(args: argparse.Namespace, train: Train, freedom: int) -> ShiftQuestion:
    """The question the options ask of ``train`` (of ``freedom`` degrees of freedom)."""
    if not 0 <= args.connections <= freedom - 2:
        why = f"from 0 to {freedom - 2}: each join takes one of the {freedom} degrees of freedom, and a gear needs two"
        raise InputError([Problem("--connections", why)])
    left = freedom - args.connections
    engaged = args.engaged if args.engaged is not None else left - 1
    if engaged != left - 1:
        joined = f" with {args.connections} connection(s)" if args.connections else ""
        why = f"the train has {left} degrees of freedom{joined}: a gear engages {left - 1} elements to leave one"
        raise InputError([Problem("--engaged", why)])
    if args.elements is not None and args.elements < engaged:
        raise InputError([Problem("--elements", f"at least {engaged}, the elements one gear engages")])
    if args.tolerance < 0:
        raise InputError([Problem("--tolerance", "a relative deviation is >= 0")])
    return ShiftQuestion(
        _targets(args.target), args.tolerance, args.elements, engaged, not args.any_shifts, args.connections
    )


def _search(
    args: argparse.Namespace, parser: argparse.ArgumentParser, train: Train, question: ShiftQuestion, say: Display
) -> ShiftResult:
    """The schemes the options ask for: of the file's teeth, or with ``--teeth`` of every
    tooth design within the ranges."""
    if args.drag < 0:
        raise InputError([Problem("--drag", f"a drag coefficient is >= 0, got {args.drag}")])
    ranking = Ranking(_weights(args.weights, question.targets), float(args.drag))
    workers = Workers(args.jobs, args.scheduler)
    if args.teeth is not None:
        if question.connections:
            why = "searches the tooth numbers of the connections as written: give --connections 0 with --teeth"
            raise InputError([Problem("--teeth", why)])
        ranges = ToothRanges(tooth_bounds(args.teeth), args.planets, args.min_teeth)
        return shift_teeth_search(train, question, ranges, ranking, workers, say)
    for option in ("--planets", "--min-teeth"):
        if getattr(args, option[2:].replace("-", "_")) != parser.get_default(option[2:].replace("-", "_")):
            raise InputError([Problem(option, "applies to a tooth search: give --teeth NAME=LO:HI too")])
    return shift_search(train, question, ranking, workers, say)


def _not_found(
    args: argparse.Namespace, train: Train, question: ShiftQuestion, result: ShiftResult, ports: tuple[str, str]
) -> list[str]:
    """Why no scheme gives the table: the closest ratios of each gear no combination
    reaches, or the rule that leaves none."""
    if result.tooth_designs is not None:
        return [
            f"none of the {result.tooth_designs} admissible tooth designs within the --teeth ranges gives every "
            "gear under the rules: widen the ranges or the --tolerance"
        ]
    return unreached(member_speeds(train), ports, question) or [
        f"every gear is reached, but no scheme of {args.elements or 'any number of'} elements meets the rules"
        + ("" if args.any_shifts else " (single transitions: --any-shifts lifts that one)")
    ]


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """The ``derive shifts`` command; returns the exit status (0, 2 bad input, 3 no
    scheme gives the table)."""
    say = Display(COMMAND, args.quiet)
    try:
        for option, path in (("-o", args.out), ("--write-best", args.write_best)):
            if path is not None and (not path.strip() or same_file(path, args.train)):
                raise InputError([Problem(option, f"{path!r}: name another file than the train's")])
        train = load(args.train)
        if train.states:
            why = "the file has states: derive shifts finds the gears itself; take the states: entry out"
            raise InputError([train.problem("states", why)], train.path)
        forms = member_forms(train)
        ports = (port_member(train, train.ports.input), port_member(train, train.ports.output))
        if set(forms.forms) <= set(ports):
            why = (
                "no member can be braked: only the input and output shafts run in bearings of the reference; "
                "give every main-axis member of the sets a bearing of the reference"
            )
            raise InputError([train.problem("couplings", why)], train.path)
        question = _question(args, train, len(forms.free))
        result = _search(args, parser, train, question, say)
    except DaviesError as exc:
        text = exc.report() if isinstance(exc, InputError) else f"{COMMAND}: {args.train}: {exc}"
        print(text.replace("<input>", args.train), file=sys.stderr)
        return 2
    if not result.candidates:
        lines = _not_found(args, train, question, result, ports)
        print("\n".join(f"{COMMAND}: {args.train}: {line}" for line in lines), file=sys.stderr)
        return 3
    answer = (
        json.dumps({"status": "ok", "train": args.train, **result.document(args.top)}, indent=2) + "\n"
        if args.json
        else shifts_text(result, question, args.top)
    )
    try:
        if args.write_best:
            write_atomic(args.write_best, best_scheme_text(args.train, train, result))
        if args.out:
            write_atomic(args.out, answer)
        else:
            sys.stdout.write(answer)
    except OSError as exc:
        print(f"{COMMAND}: cannot write {exc.filename}: {exc.strerror}", file=sys.stderr)
        return 2
    return 0


def shifts_text(result: ShiftResult, question: ShiftQuestion, top: int) -> str:
    """The schemes as text: elements, the shift matrix (X: engaged), ratio, step to the
    next gear and efficiency per gear."""
    order = [t.name for t in gear_order(question.targets)]
    what = "scheme(s)" if result.tooth_designs is None else "design(s) (tooth numbers and scheme)"
    among = "" if result.tooth_designs is None else f" of {result.tooth_designs} admissible tooth designs"
    lines = [
        f"{result.feasible} {what} give the {len(order)} gears ({result.searched} combinations of engaged "
        f"elements evaluated{among}, {result.seconds:.1f} s); the best first, by mean efficiency over the gears",
    ]
    for rank, c in enumerate(result.candidates[:top], 1):
        s = c.scheme
        letters = [element_letter(k) for k in range(len(s.elements))]
        described = [
            f"{n} {e.text()}" + (f" (or {', '.join('-'.join(a) for a in e.alike)})" if e.alike else "")
            for n, e in zip(letters, s.elements, strict=True)
        ]
        lines += ["", f"{'scheme' if not c.teeth else 'design'} {rank}: score {c.score:.5f}"]
        if c.connections:
            joined = ", ".join("=".join(sorted(b)) for b in sorted(c.connections, key=sorted))
            lines.append(f"  connections: {joined}")
        if c.teeth:
            lines.append("  teeth: " + " ".join(f"{n}={v}" for n, v in c.teeth.items()))
        lines.append("  elements: " + "; ".join(described))
        lines.append(f"  {'gear':<6}{' '.join(letters)}   {'ratio':>9} {'step':>7} {'efficiency':>11}")
        for i, gear in enumerate(order):
            marks = " ".join("X" if k in s.schedule[gear] else "." for k in range(len(letters)))
            following = order[i + 1] if i + 1 < len(order) else None
            step = (
                f"{float(s.ratios[gear] / s.ratios[following]):7.3f}"
                if following is not None and s.ratios[gear] > 0 and s.ratios[following] > 0
                else " " * 7
            )
            eta = c.efficiency[gear]
            shown = "not covered" if eta is None else f"{float(eta):.5f}"
            lines.append(f"  {gear:<6}{marks}   {float(s.ratios[gear]):9.4f} {step} {shown:>11}")
    return "\n".join(lines) + "\n"


def best_scheme_text(path: str, train: Train, result: ShiftResult) -> str:
    """The train file as written with the best scheme appended as its states, one per
    gear (named as the targets), which ``derive --state GEAR`` derives to the same
    efficiency."""
    with open(path, encoding="utf-8") as handle:
        text = handle.read()
    best = result.candidates[0]
    s = best.scheme
    named = "; ".join(f"{element_letter(k)} {e.text()}" for k, e in enumerate(s.elements))
    joined = ", ".join("=".join(sorted(b)) for b in sorted(best.connections, key=sorted))
    if best.teeth:
        shown = " ".join(f"{n}={v}" for n, v in best.teeth.items())
        text = best_design_text(text, best.teeth, f"The tooth numbers of derive shifts' best design: {shown}.")
    lines = [f"# The best scheme of derive shifts (score {best.score:.5f}): {named}."]
    if joined:
        lines.append(f"# Permanent connections {joined}: clutches engaged in every gear.")
    lines.append("states:")
    for gear in s.schedule:
        state = gear_state(train, ConnectedScheme(best.connections, s), gear)
        if ports_joined(train, state):
            # One member carries both ports: no state of the file can name both (derive
            # refuses it), and the gear is a direct drive through no mesh.
            lines.append(
                f"  # gear {gear} ({state.description.partition('(')[2].rstrip(')')}) joins the input and output "
                "members: a direct drive (ratio 1) through no mesh, so no state is written for it"
            )
            continue
        fields = [f"description: {json.dumps(state.description)}", f"input: {state.input}", f"output: {state.output}"]
        if state.brake:
            fields.append(f"brake: [{', '.join(state.brake)}]")
        if state.clutch:
            fields.append(f"clutch: [{', '.join(f'[{a}, {b}]' for a, b in state.clutch)}]")
        lines.append(f"  {json.dumps(gear)}: {{{', '.join(fields)}}}")
    return text.rstrip("\n") + "\n" + "\n".join(lines) + "\n"
