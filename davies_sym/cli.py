"""Command line: ``derive FILE [--json | --latex] [--python OUT.py] [--eval NAME=VALUE ...]``."""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Callable, Sequence

import sympy

from davies_sym.calibration.command import run as calibration_command
from davies_sym.efficiency.parameters import file_parameters, formula_symbols
from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.atomic import write_atomic
from davies_sym.emit.evaluation import evaluate
from davies_sym.emit.latex import latex_document, latex_states_document
from davies_sym.emit.plots import Sweep, efficiency_figure, png_bytes, region_figure
from davies_sym.emit.python_module import python_module
from davies_sym.emit.report import kinematics_document, kinematics_text, text_summary, train_document
from davies_sym.emit.several_inputs_report import evaluate_several, several_inputs_document, several_inputs_text
from davies_sym.emit.variant_report import variants_document, variants_text
from davies_sym.errors import DaviesError, InputError, NotCoveredError, Problem
from davies_sym.network.analysis import Analysis
from davies_sym.topology.checks import mesh_efficiency_symbols, role_problem
from davies_sym.topology.expressions import ExpressionError, assignments, parse_expression, shortened
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state
from davies_sym.topology.symbols import exact_number

Progress = Callable[[str], None]


def parser() -> argparse.ArgumentParser:
    """The argument parser of ``derive`` (also read by the documentation's command-line page)."""
    p = argparse.ArgumentParser(
        prog="derive", description="Derive the efficiency of a gear train (or machine) described in a YAML "
        "topology file, by Davies' method: every turning-condition variant in ordinary mesh efficiencies.")
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="topology file (YAML); several files need --out DIR")
    form = p.add_mutually_exclusive_group()
    form.add_argument("--json", action="store_true", help="print the JSON document")
    form.add_argument("--latex", action="store_true", help="print a standalone LaTeX document of the variants")
    p.add_argument("-o", "--out", metavar="FILE|DIR",
                   help="write the document to FILE (atomically) instead of stdout; with a directory, write "
                   "<name>.tex and <name>.py of every train there (e.g. derive catalog/*.yaml --out derivations/)")
    p.add_argument("--python", metavar="OUT.py", help="write a Python module with one function per variant")
    p.add_argument("--eval", nargs="*", metavar="NAME=VALUE",
                   help="print the variant, the speed ratio and, as the last line, the efficiency at these values "
                   "(exact where possible; no values when every quantity of the train is a number); with --json "
                   "one JSON object")
    p.add_argument("--input", metavar="PORT", help="input port for --eval (default: the declared input)")
    p.add_argument("--output", metavar="PORT", help="output port for --eval (the other port)")
    p.add_argument("--state", metavar="NAME", help="operating state of a multi-speed set (default: every state; "
                   "--eval, --python and --plot need one)")
    p.add_argument("--plot", metavar="NAME=START:STOP",
                   help="figure of the efficiency and the losses against one parameter (PNG, -o FILE)")
    p.add_argument("--vs", metavar="NAME=START:STOP",
                   help="with --plot: a second parameter; the figure shows the variant regions, the turning-condition "
                   "curves and efficiency contours over both")
    p.add_argument("--at", nargs="+", metavar="NAME=VALUE", default=[],
                   help="with --plot: values of the other parameters (default: the first published check of the file)")
    p.add_argument("--quiet", action="store_true", help="no progress messages on standard error")
    return p


def _values(train: Train, pairs: Sequence[str], option: str = "--eval") -> dict[sympy.Symbol, sympy.Expr]:
    """``NAME=VALUE`` pairs as exact values of the train's symbols (sizes positive, mesh
    efficiencies in (0, 1])."""
    problems, out = [], {}
    efficiencies = mesh_efficiency_symbols(train.couplings)
    defined = {str(d.symbol): d for d in train.definitions}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        name = name.strip()
        if not sep or not name:
            problems.append(Problem(option, f"expected NAME=VALUE, got {shortened(pair)}"))
            continue
        if name not in train.symbols:
            problems.append(Problem(option, f"unknown symbol {shortened(name)} (the train has: "
                                    f"{', '.join(sorted(train.symbols))})"))
            continue
        if name in defined:
            d = defined[name]
            problems.append(Problem(option, f"{name} is the {d.meaning} ({d.source}); give "
                                    f"{', '.join(sorted(map(str, d.expression.free_symbols)))} instead"))
            continue
        try:
            value = parse_expression(text)
        except ExpressionError as exc:
            problems.append(Problem(option, f"{name}: {exc}"))
            continue
        why = role_problem(name, train.symbols[name], value, text, efficiencies)
        if why is not None:
            problems.append(Problem(option, why))
            continue
        out[train.symbols[name]] = value
    if problems:
        raise InputError(problems, train.path)
    return out


def _sweep(train: Train, option: str, text: str) -> Sweep:
    """``NAME=START:STOP`` as a sweep of a symbol of the train."""
    name, sep, interval = text.partition("=")
    start, colon, stop = interval.partition(":")
    values = (exact_number(start.strip()), exact_number(stop.strip()))
    if not sep or not colon or None in values:
        raise InputError([Problem(option, f"expected NAME=START:STOP, got {text!r}")], train.path)
    if name.strip() not in train.symbols:
        raise InputError([Problem(option, f"unknown symbol {name.strip()!r} (the train has: "
                                  f"{', '.join(sorted(train.symbols))})")], train.path)
    low, high = (float(v) for v in values)  # type: ignore[arg-type]
    if not low < high:
        raise InputError([Problem(option, f"the interval {text!r} is empty (START < STOP)")], train.path)
    return Sweep(name.strip(), low, high)


def _plot(variants: VariantSet, args: argparse.Namespace) -> bytes:
    """The PNG of ``--plot`` (and ``--vs``): values from ``--at``, else the file's first check."""
    train = variants.train
    if not args.out:
        raise InputError([Problem("--plot", "give the figure's file with -o FILE.png")], train.path)
    port = _eval_port(train, args)
    x = _sweep(train, "--plot", args.plot)
    y = _sweep(train, "--vs", args.vs) if args.vs else None
    # A published value for a name the file no longer has (written as a number) is not a default.
    published = [f"{k}={v}" for k, v in train.published_design(args.state).items() if k in train.symbols]
    values = {str(k): float(v) for k, v in _values(train, [*published, *args.at], "--at").items()}
    swept = {x.name} | ({y.name} if y else set())
    needed = [str(s) for s in formula_symbols(variants) if str(s) not in swept]
    missing = [n for n in needed if n not in values]
    if missing:
        raise InputError([Problem("--at", f"missing values for {', '.join(missing)}")], train.path)
    fixed = {n: values[n] for n in needed}
    if y is None:
        return png_bytes(efficiency_figure(variants, x, fixed, port))
    return png_bytes(region_figure(variants, x, y, fixed, port))


def _eval_port(train: Train, args: argparse.Namespace) -> str:
    ports = (train.ports.input, train.ports.output)
    chosen = args.input
    if args.output is not None:
        if args.output not in ports:
            raise InputError([Problem("--output", f"{args.output!r} is not a port (ports: {', '.join(ports)})")],
                             train.path)
        other = ports[1] if args.output == ports[0] else ports[0]
        if chosen is not None and chosen != other:
            raise InputError([Problem("--input", f"input {chosen!r} and output {args.output!r} are not the two "
                                      f"ports of the train ({', '.join(ports)})")], train.path)
        chosen = other
    if chosen is not None and chosen not in ports:
        raise InputError([Problem("--input", f"{chosen!r} is not a port (ports: {', '.join(ports)})")], train.path)
    return chosen or train.ports.input


def _derive_sets(train: Train, state: str | None, progress: Progress,
                 failures: list[str]) -> list[tuple[str, VariantSet]]:
    """The variants of the train, or of each of its states (only ``state`` if given).  A
    state that cannot be derived is reported in ``failures`` (its message names the state)
    and the others are still derived; when none can be, the first error is raised."""
    if not train.states:
        if state is not None:
            raise InputError([Problem("--state", "the train has no states")], train.path)
        return [("", derive_variants(train, progress=progress))]
    names = [st.name for st in train.states]
    if state is not None and state not in names:
        raise InputError([Problem("--state", f"unknown state {state!r} (states: {', '.join(names)})")], train.path)
    chosen = [st for st in train.states if state is None or st.name == state]
    out, first = [], None
    for st in chosen:
        progress(f"state {st.name}")
        try:
            out.append((st.name, derive_variants(train_in_state(train, st), progress=progress)))
        except DaviesError as exc:
            first = first or exc
            failures += [f"{line} (state {st.name})" for line in _message(exc, train.path or "").splitlines()]
    if not out and first is not None:
        failures.clear()
        raise first
    return out


def _state_entry(vs: VariantSet) -> dict[str, object]:
    ratio = vs.analysis.speed_ratio().to_expr()
    return {"name": vs.train.name, "input": vs.train.ports.input, "output": vs.train.ports.output,
            "speed_ratio": sympy.sstr(ratio), **variants_document(vs)}


def _document(train: Train, sets: list[tuple[str, VariantSet]], as_json: bool, progress: Progress) -> str:
    if not train.states:
        ((_, vs),) = sets
        document = {"status": "ok", **train_document(Analysis(train, progress=progress))}
        if as_json:
            document.update(variants_document(vs))
            return json.dumps(document, indent=2) + "\n"
        return text_summary(document) + "\n" + variants_text(vs) + "\n"
    if as_json:
        return json.dumps({"status": "ok", "name": train.name, "source": train.source, "file": train.path,
                           "states": {name: _state_entry(vs) for name, vs in sets}}, indent=2) + "\n"
    parts = [train.name]
    for name, vs in sets:
        parts.append(f"state {name}: {vs.train.name}; input {vs.train.ports.input}, output "
                     f"{vs.train.ports.output}; speed ratio {sympy.sstr(vs.analysis.speed_ratio().to_expr())}")
        parts.append(variants_text(vs))
    return "\n".join(parts) + "\n"


def _derive_into(directory: str, files: Sequence[str], progress: Progress) -> int:
    """LaTeX and Python module of every train, named after its file (``derivations/``);
    a train with states gets one LaTeX file and a module per state.  A file that fails
    is reported and the others are still written."""
    os.makedirs(directory, exist_ok=True)
    status = 0
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0]
        outputs = [os.path.join(directory, f"{stem}{suffix}") for suffix in (".tex", ".py")]
        clash = [o for o in outputs if any(os.path.exists(o) and os.path.samefile(o, f) for f in files
                                           if os.path.exists(f))]
        clash += [o for o in os.listdir(directory) if o.startswith(f"{stem}_") and
                  any(os.path.samefile(os.path.join(directory, o), f) for f in files if os.path.exists(f))]
        if clash:
            print(f"input error: {path}: --out: refusing to overwrite the input file {clash[0]}", file=sys.stderr)
            status = 2
            continue
        try:
            train = load(path)
            if _kinematics_only(train):
                print(f"derive: {path}: {train.degrees_of_freedom} degrees of freedom: no LaTeX or module is "
                      "written for it yet (derive it alone for its regions)", file=sys.stderr)
                continue
            failures: list[str] = []
            sets = _derive_sets(train, None, progress, failures)
        except DaviesError as exc:
            print(_message(exc, path), file=sys.stderr)
            status = 2
            continue
        for line in failures:
            print(line, file=sys.stderr)
            status = 2
        if train.states:
            write_atomic(os.path.join(directory, f"{stem}.tex"), latex_states_document([vs for _, vs in sets]))
            for name, vs in sets:
                write_atomic(os.path.join(directory, f"{stem}_{name}.py"), python_module(vs, file_parameters(train)))
        else:
            write_atomic(os.path.join(directory, f"{stem}.tex"), latex_document(sets[0][1]))
            write_atomic(os.path.join(directory, f"{stem}.py"), python_module(sets[0][1], file_parameters(train)))
        progress(f"wrote the derivations of {stem}")
    return status


def _kinematics_only(train: Train) -> bool:
    """A train of several degrees of freedom: its kinematics, and with one input port per
    degree of freedom its power-flow regions and efficiency."""
    return (train.degrees_of_freedom is not None and train.degrees_of_freedom > 1) or len(train.ports.inputs) > 1


def _kinematics(train: Train, args: argparse.Namespace, progress: Progress) -> list[tuple[str | None, str]]:
    """The outputs of a train with several degrees of freedom: with several input ports the
    regions and efficiency (text, JSON, --eval), else the motions in the primary speeds."""
    several = len(train.ports.inputs) > 1
    if args.latex or args.python or args.state or args.plot or (args.eval is not None and not several):
        why = ("--latex, --python and --plot are not written for trains with several inputs yet" if several else
               "list one input port per degree of freedom (ports: {input: [A, B], ...}) to derive the efficiency")
        raise InputError([Problem("ports.input", f"the train has {train.degrees_of_freedom or 'several'} degrees "
                                  f"of freedom: {why}")], train.path)
    if not several:
        document = kinematics_document(Analysis(train, progress=progress))
        return [(args.out, json.dumps(document, indent=2) + "\n" if args.json else kinematics_text(document) + "\n")]
    regions = derive_several_inputs(train, progress=progress)
    if args.eval is not None:
        answer = evaluate_several(regions, assignments(args.eval, "--eval", train.path))
        return [(None, json.dumps(answer.document(), indent=2) + "\n" if args.json else answer.text())]
    document = several_inputs_document(regions)
    return [(args.out, json.dumps(document, indent=2) + "\n" if args.json else several_inputs_text(document) + "\n")]


def _efficiency(train: Train, args: argparse.Namespace, progress: Progress,
                failures: list[str]) -> list[tuple[str | None, str | bytes]]:
    """The outputs of a one-degree-of-freedom train: document, module, figure, evaluation
    (of the states that derive; the others are reported in ``failures``)."""
    if (args.vs or args.at) and not args.plot:
        raise InputError([Problem("--vs" if args.vs else "--at", "only with --plot")], train.path)
    sets = _derive_sets(train, args.state, progress, failures)
    if (args.python or args.eval is not None or args.plot) and len(sets) > 1:
        raise InputError([Problem("--state", "the train has states: choose one with --state (states: "
                                  f"{', '.join(st.name for st in train.states)})")], train.path)
    if args.plot:
        return [(args.out, _plot(sets[0][1], args))]
    if args.latex:
        text = latex_document(sets[0][1]) if len(sets) == 1 else latex_states_document([vs for _, vs in sets])
    else:
        text = _document(train, sets, args.json, progress)
    # Everything is computed (and every value checked) before anything is written.
    chosen = sets[0][1].train  # the state's train: its own ports and symbols
    evaluation = (evaluate(sets[0][1], _values(chosen, args.eval), _eval_port(chosen, args))
                  if args.eval is not None else None)
    outputs: list[tuple[str | None, str | bytes]] = []
    if args.python:
        outputs.append((args.python, python_module(sets[0][1], file_parameters(train))))
    if args.out:
        outputs.append((args.out, text))
    elif evaluation is None or args.latex:
        outputs.append((None, text))
    if evaluation is not None:
        state = {"state": args.state} if args.state else {}
        outputs.append((None, json.dumps({"file": train.path, **state, **evaluation.document()}, indent=2) + "\n"
                        if args.json else evaluation.text()))
    return outputs


def _check_target(target: str, option: str, inputs: Sequence[str]) -> None:
    """Before anything is derived: an output goes into an existing folder and never
    replaces an input file."""
    folder = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(folder):
        # The nearest ancestor that exists says why: a missing folder or a file in the way.
        above = folder
        while not os.path.exists(above):
            above = os.path.dirname(above)
        why = (f"{_path_text(above)} is a file, not a folder" if not os.path.isdir(above)
               else f"the folder {_path_text(folder)} does not exist (create it first)")
        raise InputError([Problem(option, why)], inputs[0])
    if os.path.isdir(target):
        raise InputError([Problem(option, f"{_path_text(target)} is a folder; give a file name")], inputs[0])
    for path in inputs:
        if os.path.exists(target) and os.path.exists(path) and os.path.samefile(target, path):
            raise InputError([Problem(option, f"refusing to overwrite the input file {_path_text(path)}")], path)


def _path_text(path: str) -> str:
    """A path as the user can find it: whole unless absurdly long."""
    return path if len(path) <= 300 else shortened(path)


def _one_file(args: argparse.Namespace, progress: Progress) -> int:
    path = args.files[0]
    for target, option in ((args.out, "-o"), (args.python, "--python")):
        if target:
            _check_target(target, option, [path])
    train = load(path)
    failures: list[str] = []
    outputs = (_kinematics(train, args, progress) if _kinematics_only(train)
               else _efficiency(train, args, progress, failures))
    for target, content in outputs:
        if target is None:
            sys.stdout.write(content if isinstance(content, str) else content.decode())
        else:
            write_atomic(target, content)
    for line in failures:
        print(line, file=sys.stderr)
    return 2 if failures else 0


def _many_files(args: argparse.Namespace, progress: Progress) -> int:
    if not args.out or (os.path.exists(args.out) and not os.path.isdir(args.out)):
        print("derive: several files need --out DIR (a directory)", file=sys.stderr)
        return 2
    if args.json or args.latex or args.python or args.eval is not None or args.plot:
        print("derive: with --out DIR each train gets its .tex and .py; --json, --latex, --python, --eval and "
              "--plot take one file", file=sys.stderr)
        return 2
    return _derive_into(args.out, args.files, progress)


def _message(exc: DaviesError, path: str) -> str:
    """One message per problem: the located report of an input error, else the file and the reason."""
    return exc.report() if isinstance(exc, InputError) else f"derive: {path}: {exc}"


def _status_json(status: str, reason: str) -> str:
    """The JSON answer of a refusal: ``status`` ("bad input", exit 2; "not covered", exit 3)
    and the ``reason`` that standard error or the last line gives."""
    return json.dumps({"status": status, "exit_status": 2 if status == "bad input" else 3, "reason": reason},
                      indent=2)


def main(argv: Sequence[str] | None = None) -> int:
    """The ``derive`` command; returns the exit status (0 a result, 2 bad input)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["calibrate"]:
        return calibration_command(argv[1:])
    args = parser().parse_args(argv)

    def progress(message: str) -> None:
        if not args.quiet:
            print(f"derive: {message}", file=sys.stderr, flush=True)

    if len(args.files) > 1 or (args.out and os.path.isdir(args.out)):
        return _many_files(args, progress)
    try:
        return _one_file(args, progress)
    except NotCoveredError as exc:
        # A design outside the formulas: the last line says why, never a number.
        reason = f"derive: {args.files[0]}: {exc}"
        print(_status_json("not covered", reason) if args.json else reason)
        return 3
    except DaviesError as exc:
        message = _message(exc, args.files[0])
        print(message, file=sys.stderr)
        if args.json:
            print(_status_json("bad input", message))
        return 2
    except OSError as exc:
        print(f"derive: {args.files[0]}: cannot write the output: {exc.strerror} ({shortened(str(exc.filename))})",
              file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
