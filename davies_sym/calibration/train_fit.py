"""The fit of a derived train's loss parameters to measured efficiencies: the parameters
named (or the file's ``calibrate: fit``), checked against the formulas' own, fitted by
least squares (`davies_sym.calibration.least_squares.fit`) within their ranges (an
ordinary efficiency in (0, 1], a coefficient >= 0)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from davies_sym.calibration.least_squares import Fit, fit
from davies_sym.calibration.measurements import Measurements
from davies_sym.calibration.train_model import TrainModel, fittable_parameters
from davies_sym.efficiency.parameter_domain import efficiency_symbols
from davies_sym.efficiency.several_inputs import SeveralInputs, derive_several_inputs
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.errors import InputError, Problem
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


def calibrate(
    derived: VariantSet | SeveralInputs,
    data: Measurements,
    names: Sequence[str] | None = None,
    fixed: dict[str, float] | None = None,
) -> tuple[TrainModel, Fit]:
    """The fitted model of a derived train on ``data`` (the rows' ``eta``)."""
    train = derived.train
    fitted = _fitted(train, derived, names)
    model = TrainModel(derived, fitted, fixed or {})
    efficiencies = {str(s) for s in efficiency_symbols(train)}
    given = train.calibrate.start if train.calibrate else {}
    start = {n: given.get(n, START_EFFICIENCY if n in efficiencies else START_COEFFICIENT) for n in fitted}
    upper = {n: 1.0 if n in efficiencies else np.inf for n in fitted}
    lower = {n: 1e-9 if n in efficiencies else 0.0 for n in fitted}
    measured = data.column("eta")
    return model, fit(
        lambda values: model.predict(data, values) - measured, fitted, start, lower, upper, source=data.path
    )
