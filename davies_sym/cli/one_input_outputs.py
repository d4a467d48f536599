"""The outputs of a train driven at one port: the document of every variant (text, JSON,
LaTeX, of every operating state), the formula module, the figures and ``--eval``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from dataclasses import replace

import sympy

from davies_sym.cli.arguments import (
    check_emit,
    check_sweep_ranges,
    eval_port,
    figure_suffix,
    held_values,
    not_a_port,
    plot_sweeps,
    published_hint,
    published_start,
    values,
)
from davies_sym.cli.messages import message
from davies_sym.cli.result_outputs import result_outputs
from davies_sym.cli.state_failures import StateFailures
from davies_sym.efficiency.design_values import solved_coefficients
from davies_sym.efficiency.operating_point import OPERATING_SYMBOLS
from davies_sym.efficiency.parameters import formula_symbols, given_parameters
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.derived_result import OneInputResult
from davies_sym.emit.evaluation import Evaluation, evaluate
from davies_sym.emit.plots import efficiency_figure, figure_bytes, region_figure
from davies_sym.emit.sensitivity import sensitivity_latex, sensitivity_text
from davies_sym.errors import DaviesError, InputError, MissingValuesError, NotCoveredError, Problem
from davies_sym.progress import Progress
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state


def operating_symbols(variants: VariantSet) -> list[sympy.Symbol]:
    """The input torque and speed where the formulas take them (drag, viscous friction)."""
    used = set(formula_symbols(variants))
    return [s for s in OPERATING_SYMBOLS if s in used]


def _published(file_train: Train, train: Train, state: str | None) -> dict[str, str]:
    """The values of the file's first check (of ``state``) that ``train`` takes: the
    defaults of ``--at``; a published value for a name written as a number is none."""
    return {k: v for k, v in file_train.published_design(state).items() if k in train.symbols}


def _plot(variants: VariantSet, args: argparse.Namespace) -> bytes:
    """The PNG of ``--plot`` (and ``--vs``): values from ``--at``, else the file's first check."""
    train = variants.train
    operating = operating_symbols(variants)
    solved = {str(k): why for k, why in solved_coefficients(train).items()}
    for option, text in (("--plot", args.plot), ("--vs", args.vs)):
        name = (text or "").partition("=")[0].strip()
        if name in solved:  # a mesh's friction coefficient: the formulas are in its efficiency
            raise InputError([Problem(option, solved[name])], train.path)
    x, y = plot_sweeps(train, args, [*train.symbols, *map(str, operating)])
    check_sweep_ranges((x, y), variants.parameter_table, train.path)
    port = eval_port(train, args)
    # A published value for a name the file no longer has (written as a number) is not a default.
    published = _published(train, train, args.state)
    given = {str(k): float(v) for k, v in values(train, args.at, "--at", operating, published).items()}
    fixed = held_values(train, given, [str(s) for s in formula_symbols(variants)], (x, y))
    if y is None:
        return figure_bytes(efficiency_figure(variants, x, fixed, port), figure_suffix(args.out, train.path))
    return figure_bytes(region_figure(variants, x, y, fixed, port), figure_suffix(args.out, train.path))


def _fmu(result: OneInputResult, args: argparse.Namespace) -> bytes:
    """The ``.fmu`` of ``--emit fmu -o TRAIN.fmu``: the parameters start at ``--at``'s
    values, else the file's first check's, each checked as ``--eval`` checks it."""
    from davies_sym.emit.fmu_archive import fmu_archive
    from davies_sym.emit.fmu_one_input import one_input_fmu_model

    train = result.train
    if not args.out:
        raise InputError([Problem("--emit", "fmu writes an archive: give its file with -o TRAIN.fmu")], train.path)
    given = values(train, args.at, "--at", (), _published(result.file_train, train, args.state))
    return fmu_archive(*one_input_fmu_model(result, {str(k): float(v) for k, v in given.items()}))


def derive_sets(
    train: Train, state: str | None, progress: Progress, failures: StateFailures, inputs: Sequence[str] | None = None
) -> list[tuple[str, VariantSet]]:
    """The variants of the train, or of each of its states (only ``state`` if given;
    only those with the ``inputs`` ports if given).  A state that cannot be derived is
    reported in ``failures`` (its message names the state) and the others are still
    derived; when none can be, the first error is raised."""
    if not train.states:
        if state is not None:
            raise InputError([Problem("--state", "the train has no states")], train.path)
        return _published_complete(train, [("", derive_variants(train, progress=progress, inputs=inputs))])
    names = [st.name for st in train.states]
    if state is not None and state not in names:
        raise InputError([Problem("--state", f"unknown state {state!r} (states: {', '.join(names)})")], train.path)
    chosen = [st for st in train.states if state is None or st.name == state]
    out, first = [], None
    for st in chosen:
        progress(f"state {st.name}")
        try:
            out.append((st.name, derive_variants(train_in_state(train, st), progress=progress, inputs=inputs)))
        except DaviesError as exc:
            first = first or _in_state(exc, st.name)
            lines = [f"{line} (state {st.name})" for line in message(exc, train.path or "").splitlines()]
            failures.add(lines, isinstance(exc, NotCoveredError))
    if not out and first is not None:
        failures.clear()
        raise first
    return _published_complete(train, out)


def _taking(sets: list[tuple[str, VariantSet]], name: str, train: Train) -> list[tuple[str, VariantSet]]:
    """The states whose formulas take the parameter ``name`` (a mesh that carries no power
    in a state has no efficiency there); none: refused, naming what each state takes."""
    if len(sets) == 1:
        return sets  # refused, if at all, with the parameters the one derivation takes
    taking = [(state, vs) for state, vs in sets if name in given_parameters(vs)]
    if not taking:
        takes = "; ".join(f"state {state}: {', '.join(sorted(given_parameters(vs)))}" for state, vs in sets)
        why = f"{name!r} is not a parameter of the formulas in any state ({takes})"
        raise InputError([Problem("--sensitivity", why)], train.path)
    return taking


def _in_state(error: DaviesError, state: str) -> DaviesError:
    """``error`` of the train in operating state ``state``, its problems saying so where
    they do not point at the state's own entry (a geometry the state's brakes leave)."""
    if not isinstance(error, InputError):
        return error
    problems = [
        p if p.entry.startswith(f"states.{state}") else replace(p, message=f"{p.message} (state {state})")
        for p in error.problems
    ]
    return type(error)(problems, error.source)


def _published_complete(train: Train, sets: list[tuple[str, VariantSet]]) -> list[tuple[str, VariantSet]]:
    """``sets``; a published check (``expected:``) of their states that leaves out a
    parameter of the formulas can never be evaluated: said on standard error (the
    derivation stands; a figure's defaults then lack that value)."""
    for i, check in enumerate(train.expected):
        for name, vs in sets:
            missing = vs.missing(check.values) if check.state in (None, name or None) else []
            if missing:
                taken = ", ".join(map(str, vs.parameters))
                problem = train.problem(
                    f"expected[{i}].values",
                    f"the check gives no value for {', '.join(missing)} and cannot be evaluated: add "
                    f"{missing[0]}: NUMBER (the formulas take {taken})",
                )
                print(f"derive: warning: {problem.format(train.path)}", file=sys.stderr)
                break
    return sets


def _chosen(train: Train, state: str | None) -> Train:
    """The train of the chosen state (the train itself without one, or for an unknown one,
    which `derive_sets` refuses)."""
    if train.states and state is not None:
        return next((train_in_state(train, st) for st in train.states if st.name == state), train)
    return train


def _check_ports(train: Train, args: argparse.Namespace) -> None:
    """``--input`` and ``--output`` name ports, with ``--eval`` or without (refused as
    ``--eval`` refuses them): of the chosen state, or without one of the file or any state."""
    if args.input is None and args.output is None:
        return
    if not (train.states and args.state is None):
        eval_port(_chosen(train, args.state), args)
        return
    every = [(train.ports.input, train.ports.output), *((st.input, st.output) for st in train.states)]
    ports = tuple(dict.fromkeys(p for pair in every for p in pair))
    for option, given in (("--input", args.input), ("--output", args.output)):
        if given is not None and given not in ports:
            raise not_a_port(option, given, ports, train.path)


def _eval_inputs(train: Train, args: argparse.Namespace) -> list[str] | None:
    """The input port an evaluation asks for (of the chosen state), or None when it is
    not a port (the full derivation then refuses it as usual)."""
    try:
        return [eval_port(_chosen(train, args.state), args)]
    except DaviesError:
        return None


def one_input_outputs(
    train: Train, args: argparse.Namespace, progress: Progress, failures: StateFailures
) -> list[tuple[str | None, str | bytes]]:
    """The outputs of a one-degree-of-freedom train: document, module, figure, evaluation
    (of the states that derive; the others are reported in ``failures``)."""
    if args.vs and not args.plot:
        raise InputError([Problem("--vs", "only with --plot")], train.path)
    if args.at and not (args.plot or args.emit == "fmu"):
        raise InputError([Problem("--at", "only with --plot or --emit fmu")], train.path)
    check_emit(args, train.path)
    _check_ports(train, args)
    # An evaluation alone needs only the variants of its input port.
    alone = args.eval is not None and not (args.python or args.emit or args.plot or args.out or args.latex)
    sets = derive_sets(train, args.state, progress, failures, _eval_inputs(train, args) if alone else None)
    if (args.python or args.emit or args.eval is not None or args.plot) and len(sets) > 1:
        raise InputError(
            [
                Problem(
                    "--state",
                    "the train has states: choose one with --state (states: "
                    f"{', '.join(st.name for st in train.states)})",
                )
            ],
            train.path,
        )
    if args.plot:
        return [(args.out, _plot(sets[0][1], args))]
    if args.sensitivity is not None:
        if args.eval is not None or args.python or args.emit or args.json:
            raise InputError([Problem("--sensitivity", "alone, or with --latex and -o FILE")], train.path)
        writer = sensitivity_latex if args.latex else sensitivity_text
        return [(args.out, "".join(writer(vs, args.sensitivity) for _, vs in _taking(sets, args.sensitivity, train)))]
    result = OneInputResult(train, tuple(sets), args.state, progress)
    if args.emit == "fmu":
        return [(args.out, _fmu(result, args))]

    def answer() -> Evaluation:
        chosen = result.train  # the state's train: its own ports and symbols
        pairs, published = published_start(train, args.eval, args.state)
        # A published value for a name the state's formulas do not take is no value to refuse.
        published = {k: v for k, v in published.items() if k in chosen.symbols}
        try:
            given = values(chosen, pairs, "--eval", operating_symbols(result.chosen), published)
            return evaluate(result.chosen, given, eval_port(chosen, args))
        except MissingValuesError as exc:
            raise published_hint(exc, train, args.state, args.eval) from None

    return result_outputs(result, args, answer)


def write_derivations(train: Train, stem: str, progress: Progress, failures: StateFailures) -> list[tuple[str, str]]:
    """(file name, content) of the LaTeX document and formula module of every state that
    derives (a state that does not is reported in ``failures``)."""
    return OneInputResult(train, tuple(derive_sets(train, None, progress, failures))).derivations(stem)
