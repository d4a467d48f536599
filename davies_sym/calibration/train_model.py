"""A derived train as the model of measured operating points: the efficiency its closed
forms predict at each row of a test-rig file.

Columns (one row per operating point): ``w_<PORT>`` the speed in rpm and ``T_<PORT>``
the torque in N m of the port couplings, optional ``eta`` the measured efficiency.  A
train with one input reads the input's speed and torque (its formulas take them as
magnitudes); a train driven on several shafts reads every input's speed and the output's
torque, the load.  In each row the variant or power-flow region is the one whose
conditions hold there: for a train driven on several shafts the one the generated
formula module picks (speed conditions, then the signs of the loaded forces, which the
losses reverse at light load).
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
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, SeveralInputs
from davies_sym.efficiency.variants import INPUT_SPEED, INPUT_TORQUE, VariantSet
from davies_sym.emit.several_inputs_module import several_inputs_formulas
from davies_sym.errors import InputError, Problem
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
    #: Per formula: the function, its argument names and the region's number (0: the variant).
    _pieces: tuple[tuple[Callable[..., FloatArray], tuple[str, ...], int], ...] = field(init=False)
    _regions: ModuleType | None = field(init=False)

    def __post_init__(self) -> None:
        train = self.derived.train
        required = columns_of(self.derived)
        regions = None
        if isinstance(self.derived, SeveralInputs):
            pieces = [self._piece(r.efficiency, r.number) for r in self.derived.regions]
            regions = several_inputs_formulas(self.derived)
        else:
            values = {s: sympy.Float(v) for s in train.symbols.values() if str(s) in self.fixed
                      for v in [self.fixed[str(s)]]}
            variant = self.derived.variant_for(values)
            pieces = [self._piece(variant.efficiency, 0)]
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
            raise InputError([Problem("--at", f"give values for {', '.join(missing)} (or fit them with --fit)")],
                             train.path)
        symbols = {str(s): s for s in expr.free_symbols}
        function = sympy.lambdify([symbols[n] for n in names], expr, "numpy")
        return function, names, number

    def predict(self, data: Measurements, values: Mapping[str, float]) -> FloatArray:
        """The efficiency the formulas give at every row, NaN where no formula applies."""
        known = {**self.fixed, **values}
        numbers = np.zeros(len(data), dtype=np.int64)
        if isinstance(self.derived, SeveralInputs) and self._regions is not None:
            ports = self.derived.train.ports.inputs
            speeds = {str(s): data.column(f"w_{p}") * RPM for p, s in zip(ports, self.derived.speeds, strict=True)}
            operating = {**speeds, str(LOAD_TORQUE): np.abs(data.column(self.required[-1]))}
            parameters = [p["name"] for p in self._regions.PARAMETERS]
            numbers = np.broadcast_to(self._regions.region(**{n: operating.get(n, known.get(n)) for n in parameters}),
                                      (len(data),))
        else:
            operating = {str(INPUT_SPEED): np.abs(data.column(self.required[0])) * RPM,
                         str(INPUT_TORQUE): np.abs(data.column(self.required[1]))}
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
