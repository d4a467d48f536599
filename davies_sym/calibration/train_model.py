"""A derived train as the model of measured operating points: the efficiency its closed
forms predict at each row of a test-rig file.

Columns (one row per operating point): ``w_<PORT>`` the speed in rpm and ``T_<PORT>``
the torque in N m of the port couplings, optional ``eta`` the measured efficiency.  A
train with one input reads the input's speed and torque (its formulas take them as
magnitudes); a train driven on several shafts reads every input's speed and the output's
torque, the load.  In each row the variant or power-flow region is the one whose
conditions hold there.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
import sympy

from davies_sym.calibration.measurements import Measurements
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, SeveralInputs
from davies_sym.efficiency.variants import INPUT_SPEED, INPUT_TORQUE, VariantSet
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
    _pieces: tuple[tuple[Callable[..., FloatArray], tuple[str, ...], dict[str, int]], ...] = field(init=False)

    def __post_init__(self) -> None:
        train = self.derived.train
        if isinstance(self.derived, SeveralInputs):
            required = columns_of(self.derived)
            pieces = [self._piece(r.efficiency, dict(r.signs)) for r in self.derived.regions]
        else:
            required = columns_of(self.derived)
            values = {s: sympy.Float(v) for s in train.symbols.values() if str(s) in self.fixed
                      for v in [self.fixed[str(s)]]}
            variant = self.derived.variant_for(values)
            pieces = [self._piece(variant.efficiency, {})]
        object.__setattr__(self, "required", required)
        object.__setattr__(self, "_pieces", tuple(pieces))

    def _piece(self, formula: sympy.Expr, signs: dict[str, int]
               ) -> tuple[Callable[..., FloatArray], tuple[str, ...], dict[str, int]]:
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
        return function, names, signs

    def predict(self, data: Measurements, values: Mapping[str, float]) -> FloatArray:
        """The efficiency the formulas give at every row, NaN where no formula applies."""
        known = {**self.fixed, **values}
        condition_signs: dict[str, FloatArray] = {}
        if isinstance(self.derived, SeveralInputs):
            ports = self.derived.train.ports.inputs
            speeds = {str(s): data.column(f"w_{p}") * RPM for p, s in zip(ports, self.derived.speeds, strict=True)}
            operating = {**speeds, str(LOAD_TORQUE): np.abs(data.column(self.required[-1]))}
            for c in self.derived.conditions:
                form = sympy.lambdify(list(self.derived.speeds), c.form, "numpy")
                value = form(*(speeds[str(s)] for s in self.derived.speeds))
                condition_signs[c.name] = np.sign(np.broadcast_to(value, (len(data),)))
        else:
            operating = {str(INPUT_SPEED): np.abs(data.column(self.required[0])) * RPM,
                         str(INPUT_TORQUE): np.abs(data.column(self.required[1]))}
        out = np.full(len(data), np.nan)
        for function, names, signs in self._pieces:
            mask = np.ones(len(data), dtype=bool)
            for name, sign in signs.items():
                mask &= condition_signs[name] == sign
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
