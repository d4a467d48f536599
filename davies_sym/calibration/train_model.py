"""A derived train as the model of measured operating points: the efficiency its closed
forms predict at each row of a test-rig file.

Columns (one row per operating point): ``w_<PORT>`` the speed in rpm and ``T_<PORT>``
the torque in N m of the port couplings, optional ``eta`` the measured efficiency.  A
train with one input reads the input's speed and torque (its formulas take them as
magnitudes); a train driven on several shafts reads every input's speed and the output's
torque, the load.  In each row the variant or power-flow region is the one the generated
formula module picks: its turning or speed conditions hold there, and its loaded forces
have the signs it assumes (the losses reverse some at light load).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import ModuleType

import numpy as np
import numpy.typing as npt
import sympy

from davies_sym.calibration.measurements import Measurements
from davies_sym.efficiency.operating_point import INPUT_SPEED, INPUT_TORQUE
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.emit.several_inputs_module import several_inputs_formulas
from davies_sym.errors import InputError, MeasurementError, Problem
from davies_sym.losses.definitions import substituted

FloatArray = npt.NDArray[np.float64]
RPM = 2 * math.pi / 60  # rad/s per rpm: viscous coefficients are per rad/s


@dataclass(frozen=True, eq=False)
class TrainModel:
    """Predicted efficiency per row; ``fixed`` holds the values of the parameters not fitted."""

    derived: VariantSet | SeveralInputs
    fitted: tuple[str, ...]
    fixed: Mapping[str, float]
    required: tuple[str, ...] = field(init=False)
    #: Per formula: the function, its argument names and the number of its variant or region.
    _pieces: tuple[tuple[Callable[..., FloatArray], tuple[str, ...], int], ...] = field(init=False)
    _regions: ModuleType = field(init=False)

    def __post_init__(self) -> None:
        train = self.derived.train
        required = columns_of(self.derived)
        if isinstance(self.derived, SeveralInputs):
            pieces = [self._piece(r.efficiency, r.number) for r in self.derived.regions]
            regions = several_inputs_formulas(self.derived)
        else:
            port = train.ports.input
            pieces = [self._piece(v.efficiency, v.number) for v in self.derived.variants if v.input == port]
            regions = compiled_module(python_module(self.derived), train.name)
        object.__setattr__(self, "required", required)
        object.__setattr__(self, "_pieces", tuple(pieces))
        object.__setattr__(self, "_regions", regions)

    def _piece(self, formula: sympy.Expr, number: int) -> tuple[Callable[..., FloatArray], tuple[str, ...], int]:
        train = self.derived.train
        expr = substituted(formula, train.definitions)
        names = tuple(sorted(str(s) for s in expr.free_symbols))
        operating = {str(s) for s in (INPUT_SPEED, INPUT_TORQUE, LOAD_TORQUE)}
        if isinstance(self.derived, SeveralInputs):
            operating |= {str(s) for s in self.derived.speeds}
        missing = [n for n in names if n not in operating and n not in self.fitted and n not in self.fixed]
        if missing:
            raise InputError(
                [Problem("--at", f"give values for {', '.join(missing)} (or fit them with --fit)")], train.path
            )
        symbols = {str(s): s for s in expr.free_symbols}
        function = sympy.lambdify([symbols[n] for n in names], expr, "numpy")
        return function, names, number

    def predict(self, data: Measurements, values: Mapping[str, float]) -> FloatArray:
        """The efficiency the formulas give at every row, NaN where no formula applies."""
        known = {**self.fixed, **values}
        if isinstance(self.derived, SeveralInputs):
            ports = self.derived.train.ports.inputs
            speeds = {str(s): data.column(f"w_{p}") * RPM for p, s in zip(ports, self.derived.speeds, strict=True)}
            operating = {**speeds, str(LOAD_TORQUE): np.abs(data.column(self.required[-1]))}
        else:
            operating = {
                str(INPUT_SPEED): np.abs(data.column(self.required[0])) * RPM,
                str(INPUT_TORQUE): np.abs(data.column(self.required[1])),
            }
        # The variant or region of each row: the one the generated formula module picks.
        parameters = {p["name"]: operating.get(p["name"], known.get(p["name"])) for p in self._regions.PARAMETERS}
        if isinstance(self.derived, SeveralInputs):
            chosen = self._regions.region(**parameters)
        else:
            chosen = self._regions.variant(input=self.derived.train.ports.input, errors="ignore", **parameters)
        numbers = np.broadcast_to(chosen, (len(data),))
        out = np.full(len(data), np.nan)
        for function, names, number in self._pieces:
            mask = numbers == number
            if mask.any():
                args = [operating[n][mask] if n in operating else known[n] for n in names]
                out[mask] = np.broadcast_to(function(*args), (int(mask.sum()),))
        return out


def columns_of(derived: VariantSet | SeveralInputs) -> tuple[str, ...]:
    """The columns a data file needs for ``derived``."""
    train = derived.train
    if isinstance(derived, SeveralInputs):
        return (*(f"w_{p}" for p in train.ports.inputs), f"T_{train.ports.output}")
    return (f"w_{train.ports.input}", f"T_{train.ports.input}")


def check_loaded(derived: VariantSet | SeveralInputs, data: Measurements) -> None:
    """Refuse (`MeasurementError`, at each row's line) rows of ``data`` whose torque the
    formulas take (the input's, or the load of a train driven on several shafts) is zero:
    no power crosses the train there, so it has no efficiency to fit."""
    column = columns_of(derived)[-1]
    rows = np.flatnonzero(data.column(column) == 0)
    if rows.size:
        raise MeasurementError(
            [
                Problem(
                    f"column {column!r}",
                    "0: no power crosses the train, so it has no efficiency; remove the row",
                    data.lines[k],
                )
                for k in rows[:5].tolist()
            ],
            data.path,
        )


def fittable_parameters(derived: VariantSet | SeveralInputs) -> Sequence[str]:
    """The parameters the formulas take besides the operating point."""
    if isinstance(derived, SeveralInputs):
        train = derived.train
        symbols: set[sympy.Basic] = set()
        for r in derived.regions:
            symbols |= substituted(r.efficiency, train.definitions).free_symbols
        symbols -= {*derived.speeds, LOAD_TORQUE}
        return sorted(str(s) for s in symbols)
    return [str(s) for s in formula_symbols(derived) if s not in (INPUT_SPEED, INPUT_TORQUE)]
