"""The fit of a derived train's loss parameters to measured efficiencies: the parameters
named (or the file's ``calibrate: fit``), checked against the formulas' own, fitted by
least squares (`davies_sym.calibration.least_squares.fit`) within their ranges (an
ordinary efficiency in (0, 1], a coefficient >= 0)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from davies_sym.calibration.fit_starts import FitBounds, StartFailure, best_of, start_points
from davies_sym.calibration.least_squares import Fit, fit
from davies_sym.calibration.measurements import Measurements, read_measurements
from davies_sym.calibration.train_model import TrainModel, columns_of, fittable_parameters
from davies_sym.efficiency.parameter_domain import efficiency_symbols
from davies_sym.efficiency.several_inputs import SeveralInputs, derive_several_inputs
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.errors import CalibrationError, InputError, Problem
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train

#: Start values where the file gives none: an ordinary efficiency, any other coefficient.
START_EFFICIENCY, START_COEFFICIENT = 0.95, 0.1


def _fitted(train: Train, derived: VariantSet | SeveralInputs, names: Sequence[str] | None) -> tuple[str, ...]:
    if names is None:
        if train.calibrate is None:
            raise InputError(
                [Problem("--fit", "name the parameters to fit (the file has no calibrate: fit)")], train.path
            )
        names = train.calibrate.fit
    known = fittable_parameters(derived)
    unknown = [n for n in names if n not in known]
    if unknown:
        raise InputError(
            [
                Problem(
                    "--fit", f"{', '.join(unknown)} is not a parameter of the formulas (they take: {', '.join(known)})"
                )
            ],
            train.path,
        )
    return tuple(names)


def derived_model(train: Train) -> VariantSet | SeveralInputs:
    """What the formulas of ``train`` are: its variants, or the regions of a train driven
    on several shafts."""
    return derive_several_inputs(train) if len(train.ports.inputs) > 1 else derive_variants(train)


def fit_bounds(derived: VariantSet | SeveralInputs, names: Sequence[str] | None = None) -> FitBounds:
    """The parameters to fit (``names``, else the file's ``calibrate: fit``), their start
    values (the file's ``calibrate: start``, else the defaults) and their ranges."""
    train = derived.train
    fitted = _fitted(train, derived, names)
    efficiencies = frozenset(str(s) for s in efficiency_symbols(train)) & frozenset(fitted)
    given = train.calibrate.start if train.calibrate else {}
    start = {n: given.get(n, START_EFFICIENCY if n in efficiencies else START_COEFFICIENT) for n in fitted}
    upper = {n: 1.0 if n in efficiencies else np.inf for n in fitted}
    lower = {n: 1e-9 if n in efficiencies else 0.0 for n in fitted}
    return FitBounds(fitted, start, lower, upper, efficiencies)


def fits_from(
    model: TrainModel, data: Measurements, bounds: FitBounds, starts: Sequence[Mapping[str, float]]
) -> tuple[Fit | StartFailure, ...]:
    """The fit of ``model`` to the rows' ``eta`` from each start point (or why it failed)."""
    measured = data.column("eta")
    results: list[Fit | StartFailure] = []
    for start in starts:
        try:
            results.append(
                fit(
                    lambda values: model.predict(data, values) - measured,
                    bounds.fitted,
                    start,
                    bounds.lower,
                    bounds.upper,
                    source=data.path,
                )
            )
        except CalibrationError as exc:
            results.append(StartFailure(str(exc), exc.cause))
    return tuple(results)


def calibrate(
    derived: VariantSet | SeveralInputs,
    data: Measurements,
    names: Sequence[str] | None = None,
    fixed: dict[str, float] | None = None,
) -> tuple[TrainModel, Fit]:
    """The fitted model of a derived train on ``data`` (the rows' ``eta``), from the start values."""
    bounds = fit_bounds(derived, names)
    model = TrainModel(derived, bounds.fitted, fixed or {})
    return model, best_of(fits_from(model, data, bounds, start_points(bounds, 1))).best


@dataclass(frozen=True)
class StartGroup:
    """A group of start points fitted by one worker: the files it reads (the train, the
    measurements), the parameters fitted, those held and the starts."""

    train_file: str
    data_file: str
    fitted: tuple[str, ...]
    fixed: tuple[tuple[str, float], ...]
    starts: tuple[tuple[tuple[str, float], ...], ...]


def fit_start_group(group: StartGroup) -> tuple[Fit | StartFailure, ...]:
    """The fits of one `StartGroup`, the train derived once in this worker."""
    derived = derived_model(load(group.train_file))
    model = TrainModel(derived, group.fitted, dict(group.fixed))
    data = read_measurements(group.data_file, [*columns_of(derived), "eta"])
    return fits_from(model, data, fit_bounds(derived, group.fitted), [dict(s) for s in group.starts])
