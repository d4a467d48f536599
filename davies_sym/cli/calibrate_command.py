"""``derive calibrate TRAIN.yaml DATA.csv [--fit NAME ...] [--predict OTHER.csv] [--json]
[-o FIG.png] [--at NAME=VALUE ...]``: fit loss parameters of a train to test-rig data.

The parameters named by ``--fit`` (default: the train's ``calibrate: {fit: [...]}``) are
fitted by least squares to the measured efficiencies (column ``eta``) of DATA; the others
take the values of ``--at``.  The answer holds each fitted value with its standard
error, the residuals and, with ``--predict``, the efficiency predicted at every row of
the other file and, where it has ``eta``, the mean absolute error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence

import numpy as np

from davies_sym.calibration.fit_report import fit_text, residual_figure
from davies_sym.calibration.fit_starts import MultiStart, best_of, start_groups, start_points
from davies_sym.calibration.least_squares import Fit
from davies_sym.calibration.measurements import Measurements, read_measurements
from davies_sym.calibration.train_fit import (
    StartGroup,
    calibrate,
    derived_model,
    fit_bounds,
    fit_start_group,
    fits_from,
)
from davies_sym.calibration.train_model import TrainModel, check_loaded, columns_of
from davies_sym.efficiency.design_values import design_values
from davies_sym.efficiency.several_inputs import SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.atomic import same_file, write_atomic
from davies_sym.emit.plots import figure_format
from davies_sym.errors import CalibrationError, DaviesError, InputError, Problem
from davies_sym.fan_out import Counted, Workers, fan_out
from davies_sym.progress import Display
from davies_sym.topology.catalog_files import catalog_file
from davies_sym.topology.expressions import assignments
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train


def _refused_options(args: argparse.Namespace) -> str | None:
    """Why the options cannot be taken as written (``OPTION: what is wrong``), or None:
    an empty or unsuitable figure name, a figure over an input, a parameter both fitted
    and held."""
    if args.out is not None:
        if not args.out.strip():
            return "-o: the file name is empty; give the figure's file (.png, .svg or .pdf)"
        if figure_format(args.out) is None:
            return f"-o: {args.out}: name the figure's file .png, .svg or .pdf (the suffix says the format)"
        for given in (args.train, args.data, *(args.predict or ())):
            if given and os.path.exists(given) and same_file(args.out, given):
                return f"-o: refusing to overwrite the input file {given}"
    fitted = set(args.fit or ())
    held = [pair.partition("=")[0].strip() for pair in args.at]
    both = [name for name in held if name in fitted]
    if both:
        return f"--at: {both[0]} is fitted (--fit {both[0]}): give it to one of --fit and --at"
    return None


def _fixed(train: Train, pairs: Sequence[str]) -> dict[str, float]:
    """The values of ``--at`` by name, each checked against its symbol's role as every
    entry point checks a design (`design_values`)."""
    given = assignments(pairs, "--at", train.path)
    return {str(symbol): float(value) for symbol, value in design_values(train, given, "--at", ()).items()}


def _train_file(args: argparse.Namespace) -> str:
    """TRAIN.yaml, or the catalog's file of ``--catalog NAME`` (one of the two)."""
    if args.catalog is not None and args.train is not None:
        if args.data is None:  # `--catalog NAME DATA.csv`: the one positional is the data
            args.train, args.data = None, args.train
        else:
            raise InputError(
                [Problem("--catalog", "give the train as TRAIN.yaml or as --catalog NAME, not both")],
                "derive calibrate",
            )
    if args.catalog is not None:
        return catalog_file(args.catalog)
    if args.train is None:
        raise InputError(
            [Problem("TRAIN.yaml", "give the train's file (or --catalog NAME) and its DATA.csv")], "derive calibrate"
        )
    return str(args.train)


def _data_files(args: argparse.Namespace, train: Train) -> tuple[str, list[str]]:
    """DATA.csv and the --predict files: as given, else those the train file names
    (``calibrate: {data: ..., predict: [...]}``, relative to the file) when DATA.csv is
    not given."""
    if args.data is not None:
        return str(args.data), list(args.predict or ())
    defaults = train.calibrate
    if defaults is None or defaults.data is None:
        raise InputError(
            [Problem("DATA.csv", "give the measurements' file (the train file names no calibrate: data)")],
            train.path,
        )
    folder = os.path.dirname(train.path or "")
    located = [defaults.data, *defaults.predict]
    for name, entry in located:
        if not os.path.isfile(os.path.join(folder, name)):
            raise InputError([train.problem(entry, f"no file {name!r} beside the train file")], train.path)
    files = [os.path.join(folder, name) for name, _ in located]
    return files[0], list(args.predict) if args.predict is not None else files[1:]


def _fit(
    args: argparse.Namespace,
    derived: VariantSet | SeveralInputs,
    data: Measurements,
    fixed: dict[str, float],
    say: Display,
) -> tuple[TrainModel, Fit, MultiStart | None]:
    """The fit from the file's start values, or with ``--starts N`` the best of N starts
    fitted in groups on the workers (each group derives the train once)."""
    if args.starts == 1:
        model, result = calibrate(derived, data, args.fit, fixed)
        return model, result, None
    bounds = fit_bounds(derived, args.fit)
    model = TrainModel(derived, bounds.fitted, fixed)
    workers = Workers(args.jobs, args.scheduler)
    points = start_points(bounds, args.starts)
    if workers.here(args.starts):
        results = fits_from(model, data, bounds, points)
    else:
        groups = [
            StartGroup(
                str(derived.train.path),
                data.path,
                bounds.fitted,
                tuple(sorted(fixed.items())),
                tuple(tuple(p.items()) for p in group),
            )
            for group in start_groups(points, args.starts if args.scheduler else args.jobs)
        ]
        say(f"fitting from {args.starts} starts {workers.describe(len(groups))}")
        counted = Counted(say, "start group")
        results = tuple(r for fits in fan_out(fit_start_group, groups, workers, counted) for r in fits)
    best = best_of(results)
    return model, best.best, best


def _predictions(
    model: TrainModel, result: Fit, others: list[Measurements], document: dict[str, object], lines: list[str]
) -> None:
    """The efficiency predicted at every row of the ``--predict`` files, added to the
    answer's ``document`` and text ``lines`` (with the mean absolute error where the
    files measure ``eta``)."""
    predicted = np.concatenate([model.predict(other, result.parameters) for other in others])
    document["predicted_efficiency"] = [None if np.isnan(v) else float(v) for v in predicted]
    rows = [(other.path, line) for other in others for line in other.lines]
    lines.append(f"predicted efficiency at the {len(rows)} rows of {', '.join(o.path for o in others)}:")
    lines += [f"  {path}:{line}: {v:.4f}" for (path, line), v in zip(rows, predicted, strict=True)]
    if all("eta" in other for other in others):
        measured = np.concatenate([other.column("eta") for other in others])
        error = float(np.nanmean(np.abs(predicted - measured)))
        document["mean_absolute_error"] = error
        lines.append(f"mean absolute error against the measured eta: {error:.4f}")


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """The ``derive calibrate`` command, its arguments parsed by ``parser``; returns the
    exit status (0, or 2 for bad input)."""
    try:
        train_file = _train_file(args)
    except InputError as exc:
        print(exc.report(), file=sys.stderr)
        return 2
    refusal = _refused_options(args)
    if refusal is not None:
        print(f"input error: {train_file}: {refusal}", file=sys.stderr)
        return 2
    suffix = (figure_format(args.out) if args.out else None) or ".png"
    say = Display("derive calibrate", args.quiet)
    try:
        train = load(train_file)
        args.data, args.predict = _data_files(args, train)
        refusal = _refused_options(args)  # the file's own data files too
        if refusal is not None:
            raise InputError([Problem(refusal.partition(":")[0], refusal.partition(": ")[2])], train_file)
        fixed = _fixed(train, args.at)  # checked before the derivation
        say(f"deriving the formulas of {train_file}")
        derived = derived_model(train)
        columns = columns_of(derived)
        data = read_measurements(args.data, [*columns, "eta"])
        check_loaded(derived, data)
        others = [read_measurements(path, columns, ["eta"]) for path in args.predict or ()]
        for other in others:
            check_loaded(derived, other)
        say(f"fitting to the {len(data.lines)} rows of {data.path}")
        model, result, starts = _fit(args, derived, data, fixed, say)
    except CalibrationError as exc:
        print(f"derive calibrate: {exc}", file=sys.stderr)
        return 2
    except DaviesError as exc:
        why = exc.report() if isinstance(exc, InputError) else f"derive calibrate: {train_file}: {exc}"
        print(why, file=sys.stderr)
        return 2
    document = {"status": "ok", "train": train.path, "data": data.path, **result.as_dict()}
    lines = [fit_text(result)]
    if starts is not None:
        document["starts"] = starts.as_dict()
        lines.append(starts.text())
    if others:
        _predictions(model, result, others, document, lines)
    if args.out:
        try:
            write_atomic(args.out, residual_figure(result, suffix=suffix))
        except OSError as exc:
            print(f"derive calibrate: -o: cannot write {exc.filename}: {exc.strerror or exc}", file=sys.stderr)
            return 2
    print(json.dumps(document, indent=2) if args.json else "\n".join(lines))
    return 0
