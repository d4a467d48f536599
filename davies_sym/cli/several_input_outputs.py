"""The outputs of a train of several degrees of freedom: with one input port per degree
of freedom its power-flow regions (text, JSON, LaTeX, formula module, figures,
``--eval``), else its motions in the primary speeds."""

from __future__ import annotations

import argparse
import json

from davies_sym.cli.arguments import (
    check_emit,
    check_sweep_ranges,
    figure_suffix,
    held_values,
    plot_sweeps,
    published_hint,
    published_start,
)
from davies_sym.cli.result_outputs import result_outputs
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.several_inputs import SeveralInputs, derive_several_inputs
from davies_sym.emit.derived_result import SeveralInputResult
from davies_sym.emit.json_document import kinematics_document, kinematics_text
from davies_sym.emit.plots import figure_bytes
from davies_sym.emit.several_inputs_module import several_inputs_formulas
from davies_sym.emit.several_inputs_plots import (
    several_efficiency_figure,
    several_region_figure,
)
from davies_sym.emit.several_inputs_report import SeveralEvaluation, evaluate_several
from davies_sym.errors import InputError, MissingValuesError, Problem
from davies_sym.network.analysis import Analysis
from davies_sym.progress import Progress
from davies_sym.topology.expressions import assignments
from davies_sym.topology.model import Train


def several_degrees_of_freedom(train: Train) -> bool:
    """A train of several degrees of freedom, or one driven at several ports."""
    return (train.degrees_of_freedom is not None and train.degrees_of_freedom > 1) or len(train.ports.inputs) > 1


def _refuse(train: Train, args: argparse.Namespace) -> None:
    """Options that do not apply: a state, a chosen input or output (the regions say where
    power goes in); and for a train with fewer input ports than freedoms, everything but
    its kinematics."""
    several = len(train.ports.inputs) > 1
    if not several and (args.latex or args.python or args.emit or args.plot or args.eval is not None):
        raise InputError(
            [
                Problem(
                    "ports.input",
                    f"the train has {train.degrees_of_freedom or 'several'} degrees "
                    "of freedom: list one input port per degree of freedom (ports: {input: [A, B], "
                    "...}) to derive the efficiency",
                )
            ],
            train.path,
        )
    if args.state:
        raise InputError(
            [Problem("--state", "operating states are derived for trains of one degree of freedom only")], train.path
        )
    for option, given in (("--input", args.input), ("--output", args.output)):
        # Naming the train's own output says nothing new: it is the output already.
        if given is not None and not (option == "--output" and given == train.ports.output):
            raise InputError(
                [
                    Problem(
                        option,
                        "a train driven at several ports has no single input: its "
                        "power-flow regions say which ports put power in (give the input speeds "
                        "to --eval instead)",
                    )
                ],
                train.path,
            )
    if args.vs and not args.plot:
        raise InputError([Problem("--vs", "only with --plot")], train.path)
    if args.at and not (args.plot or args.emit == "fmu"):
        raise InputError([Problem("--at", "only with --plot or --emit fmu")], train.path)
    check_emit(args, train.path)
    if args.emit == "fmu" and not args.out:
        raise InputError([Problem("--emit", "fmu writes an archive: give its file with -o TRAIN.fmu")], train.path)


def _plot(si: SeveralInputs, args: argparse.Namespace) -> bytes:
    """The PNG of ``--plot`` (and ``--vs``) with the other parameters from ``--at``."""
    train = si.train
    module = several_inputs_formulas(si)
    names = [p["name"] for p in module.PARAMETERS]
    x, y = plot_sweeps(train, args, names)
    check_sweep_ranges((x, y), [Parameter(**p) for p in module.PARAMETERS], train.path)
    given = assignments(args.at, "--at", train.path)
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise InputError(
            [Problem("--at", f"unknown symbol {unknown[0]} (the formulas take: {', '.join(names)})")], train.path
        )
    fixed = held_values(train, {n: float(v) for n, v in given.items()}, names, (x, y))
    if y is None:
        return figure_bytes(several_efficiency_figure(si, x, fixed, module), figure_suffix(args.out, train.path))
    return figure_bytes(several_region_figure(si, x, y, fixed, module), figure_suffix(args.out, train.path))


def _fmu(result: SeveralInputResult, args: argparse.Namespace) -> bytes:
    """The ``.fmu`` of ``--emit fmu -o TRAIN.fmu``: the parameters start at ``--at``'s values."""
    from davies_sym.emit.fmu_archive import fmu_archive
    from davies_sym.emit.fmu_several_inputs import several_inputs_fmu_model

    given = assignments(args.at, "--at", result.train.path)
    return fmu_archive(*several_inputs_fmu_model(result, {n: float(v) for n, v in given.items()}))


def several_outputs(train: Train, args: argparse.Namespace, progress: Progress) -> list[tuple[str | None, str | bytes]]:
    """The outputs asked for, all computed before anything is written."""
    _refuse(train, args)
    if len(train.ports.inputs) == 1:
        document = kinematics_document(Analysis(train, progress=progress))
        return [(args.out, json.dumps(document, indent=2) + "\n" if args.json else kinematics_text(document) + "\n")]
    si = derive_several_inputs(train, progress=progress)
    if args.plot:
        return [(args.out, _plot(si, args))]
    result = SeveralInputResult(si)
    if args.emit == "fmu":
        return [(args.out, _fmu(result, args))]

    def answer() -> SeveralEvaluation:
        pairs, published = published_start(train, args.eval, None)
        try:
            return evaluate_several(si, {**published, **assignments(pairs, "--eval", train.path)})
        except MissingValuesError as exc:
            raise published_hint(exc, train, None, args.eval) from None

    return result_outputs(result, args, answer)


def several_derivations(train: Train, stem: str, progress: Progress) -> list[tuple[str, str]]:
    """(file name, content) of the LaTeX document and formula module of a train driven
    at several ports; none for one with fewer input ports than freedoms (its kinematics
    has no formulas to write)."""
    if len(train.ports.inputs) == 1:
        return []
    return SeveralInputResult(derive_several_inputs(train, progress=progress)).derivations(stem)
