"""Least-squares fit of named parameters to measured rows (``scipy.optimize.least_squares``).

The model is a function of the parameter values giving one residual per measured row
(model minus measured); nothing here knows what the parameters mean.  A fit the data
cannot support is refused with a `CalibrationError` naming the
cause, never returned as numbers: fewer rows than parameters, a residual that is not
finite, no convergence, or a parameter the data do not determine.

The standard errors come from the covariance s^2 (J^T J)^-1 at the solution, with
s^2 = SSR / (n - p) and J the Jacobian of the residuals in the parameters.  Rows are
numbered from 1 in messages (row 1 is ``residuals[0]``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.optimize import least_squares

from davies_sym.errors import CalibrationError, FitFailure

FloatArray = npt.NDArray[np.float64]
Residuals = Callable[[Mapping[str, float]], FloatArray]

#: J^T J (columns scaled to unit length) with a larger condition number is singular.
MAX_CONDITION = 1e12
#: Stopping tolerances of scipy (relative change of cost, of the parameters; gradient).
TOLERANCE = 1e-12


@dataclass(frozen=True, eq=False)
class Fit:
    """The fitted parameters, their standard errors and the residuals at the solution.

    ``residuals`` is model minus measured per row; ``iterations`` counts scipy's function
    evaluations (``nfev``, those for the finite-difference Jacobian excluded) and
    ``evaluations`` every call of the model.  ``note`` says when the standard errors are
    not meaningful (no degrees of freedom left, a parameter at its bound), else "".
    """

    names: tuple[str, ...]
    values: tuple[float, ...]
    standard_errors: tuple[float, ...]
    residuals: FloatArray
    rms: float
    rows: int
    iterations: int
    converged: bool
    message: str
    covariance: FloatArray
    evaluations: int = 0
    note: str = ""

    @property
    def parameters(self) -> dict[str, float]:
        """name -> fitted value."""
        return dict(zip(self.names, self.values, strict=True))

    @property
    def degrees_of_freedom(self) -> int:
        """Rows minus parameters."""
        return self.rows - len(self.names)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready data (a standard error that is not finite becomes null; ``note`` says why)."""
        return {
            "parameters": {
                name: {"value": value, "standard_error": error if math.isfinite(error) else None}
                for name, value, error in zip(self.names, self.values, self.standard_errors, strict=True)
            },
            "residuals": [float(r) for r in self.residuals],
            "rms": self.rms,
            "rows": self.rows,
            "iterations": self.iterations,
            "note": self.note,
        }


class _NotFinite(Exception):
    """A residual that is NaN or infinite, with the parameter values it came from."""

    def __init__(self, point: Mapping[str, float], row: int, value: float) -> None:
        super().__init__()
        self.point, self.row, self.value = dict(point), row, value


def fit(
    residuals: Residuals,
    names: Sequence[str],
    start: Mapping[str, float],
    lower: Mapping[str, float] | None = None,
    upper: Mapping[str, float] | None = None,
    *,
    source: str | None = None,
    max_evaluations: int | None = None,
) -> Fit:
    """Fit ``names`` so that ``residuals(values)`` (model minus measured per row) is least in squares.

    ``start`` gives every parameter's start value; ``lower`` and ``upper`` bound any of
    them (then the method is "trf" with bounds).  ``source`` (e.g. the measurements file)
    begins every refusal message.  ``max_evaluations`` caps scipy's function evaluations.
    (Seven parameters, as scipy's own ``least_squares`` takes them: the bounds and the
    cap are separate choices of the caller.)
    """
    prefix = f"{source}: " if source else ""
    names = tuple(names)
    x0, low, high = _arguments(names, start, lower or {}, upper or {}, max_evaluations, prefix)
    model = _FiniteModel(residuals, names, prefix)
    rows = _rows(model, x0, names, prefix)
    bounded = bool(np.isfinite(low).any() or np.isfinite(high).any())
    try:
        result = least_squares(
            model,
            x0,
            jac="3-point",
            bounds=(low, high),
            method="trf",
            x_scale="jac",
            ftol=TOLERANCE,
            xtol=TOLERANCE,
            gtol=TOLERANCE,
            max_nfev=max_evaluations,
        )
    except _NotFinite as exc:
        hint = "; bound the parameters (lower, upper) to where the model is defined" if not bounded else ""
        raise CalibrationError(
            f"{prefix}the residual of row {exc.row + 1} became {exc.value} during the fit, "
            f"at {_values(exc.point)}{hint}",
            FitFailure.NON_FINITE,
        ) from None
    return _fitted(result, names, rows, model.count, prefix)


class _FiniteModel:
    """The residuals as scipy calls them (an array of values in the order of ``names``),
    counted, each checked to be one finite number per row."""

    def __init__(self, residuals: Residuals, names: tuple[str, ...], prefix: str) -> None:
        self.residuals, self.names, self.prefix, self.count = residuals, names, prefix, 0

    def __call__(self, x: FloatArray) -> FloatArray:
        point = dict(zip(self.names, (float(v) for v in x), strict=True))
        self.count += 1
        r = np.asarray(self.residuals(point), dtype=np.float64)
        if r.ndim != 1:
            raise CalibrationError(
                f"{self.prefix}the residuals must be one number per row, got shape {r.shape}", FitFailure.ARGUMENTS
            )
        bad = np.flatnonzero(~np.isfinite(r))
        if bad.size:
            raise _NotFinite(point, int(bad[0]), float(r[bad[0]]))
        return r


def _rows(model: _FiniteModel, x0: FloatArray, names: tuple[str, ...], prefix: str) -> int:
    """The number of rows, from the residuals at the start values, refused where they
    are not finite or fewer than the parameters."""
    try:
        rows = int(model(x0).size)
    except _NotFinite as exc:
        raise CalibrationError(
            f"{prefix}the residual of row {exc.row + 1} is {exc.value} at the start values "
            f"({_values(exc.point)}): the model is not defined there",
            FitFailure.NON_FINITE,
        ) from None
    if rows < len(names):
        raise CalibrationError(
            f"{prefix}{rows} row{'s' if rows != 1 else ''} cannot determine {len(names)} "
            f"parameters ({', '.join(names)}): give at least {len(names)} rows",
            FitFailure.ROWS,
        )
    return rows


def _fitted(result: Any, names: tuple[str, ...], rows: int, count: int, prefix: str) -> Fit:
    """The `Fit` of scipy's ``result``, refused where the parameters are not determined
    or the fit did not converge; standard errors from the covariance."""
    values = tuple(float(v) for v in result.x)
    reached = dict(zip(names, values, strict=True))
    jacobian = np.asarray(result.jac, dtype=np.float64)
    _check_determined(jacobian, names, prefix)
    if result.status <= 0:
        raise CalibrationError(
            f"{prefix}the fit did not converge ({result.message.rstrip('.')}) after "
            f"{result.nfev} evaluations; it reached {_values(reached)}",
            FitFailure.CONVERGENCE,
        )
    r = np.asarray(result.fun, dtype=np.float64)
    r.setflags(write=False)
    covariance, note = _covariance(jacobian, r, len(names))
    at_bound = [n for n, active in zip(names, result.active_mask, strict=True) if active]
    if at_bound:
        bound = (
            f"{', '.join(at_bound)} at {'its' if len(at_bound) == 1 else 'their'} "
            "bound: the standard errors assume an interior solution."
        )
        note = " ".join(filter(None, [note, bound]))
    errors = tuple(float(math.sqrt(v)) if v >= 0 else math.nan for v in np.diag(covariance))
    rms = float(np.sqrt(np.mean(r * r)))
    message = str(result.message)
    return Fit(
        names, values, errors, r, rms, rows, int(result.nfev), bool(result.success), message, covariance, count, note
    )


def _arguments(
    names: tuple[str, ...],
    start: Mapping[str, float],
    lower: Mapping[str, float],
    upper: Mapping[str, float],
    max_evaluations: int | None,
    prefix: str,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Start values and bounds as arrays in the order of ``names``, checked."""
    problems: list[str] = []
    if not names:
        problems.append("no parameters to fit")
    if len(set(names)) != len(names):
        problems.append(f"a parameter is named twice ({', '.join(names)})")
    for what, given in (("start", start), ("lower", lower), ("upper", upper)):
        unknown = [str(k) for k in given if k not in names]
        if unknown:
            problems.append(f"{what} names {', '.join(unknown)}, not among the parameters ({', '.join(names)})")
    missing = [n for n in names if n not in start]
    if missing:
        problems.append(f"no start value for {', '.join(missing)}")
    if max_evaluations is not None and max_evaluations < 1:
        problems.append(f"max_evaluations must be at least 1, got {max_evaluations}")
    if problems:
        raise CalibrationError(prefix + "; ".join(problems), FitFailure.ARGUMENTS)
    x0 = np.array([float(start[n]) for n in names])
    low = np.array([float(lower.get(n, -np.inf)) for n in names])
    high = np.array([float(upper.get(n, np.inf)) for n in names])
    for n, x, lo, hi in zip(names, x0, low, high, strict=True):
        if not math.isfinite(x):
            problems.append(f"the start value of {n} is {x}")
        elif not lo < hi:
            problems.append(
                f"the bounds of {n} leave no interval ({lo:g} to {hi:g}); to hold a parameter "
                "fixed, leave it out of the fit"
            )
        elif not lo <= x <= hi:
            problems.append(f"the start value {n} = {x:g} is outside its bounds ({lo:g} to {hi:g})")
    if problems:
        raise CalibrationError(prefix + "; ".join(problems), FitFailure.ARGUMENTS)
    return x0, low, high


def _check_determined(jacobian: FloatArray, names: tuple[str, ...], prefix: str) -> None:
    """Refuse when the residuals do not change with a parameter, or only with a combination of them."""
    norms = np.linalg.norm(jacobian, axis=0)
    flat = [n for n, norm in zip(names, norms, strict=True) if not norm > 0]
    if flat:
        them = "it" if len(flat) == 1 else "them"
        raise CalibrationError(
            f"{prefix}the data do not determine {', '.join(flat)}: the residuals do not change with {them}",
            FitFailure.UNDETERMINED,
        )
    # Columns scaled to unit length: the condition then says nothing about units.
    _, singular, right = np.linalg.svd(jacobian / norms, full_matrices=False)
    condition = math.inf if singular[-1] == 0 else float((singular[0] / singular[-1]) ** 2)
    if condition > MAX_CONDITION:
        direction = np.abs(right[-1])
        involved = [n for n, weight in zip(names, direction, strict=True) if weight > 0.1 * direction.max()]
        raise CalibrationError(
            f"{prefix}the data do not determine {' and '.join(involved)} separately: the "
            f"residuals change only with a combination of them (condition number of J^T J "
            f"{condition:.2g})",
            FitFailure.UNDETERMINED,
        )


def _covariance(jacobian: FloatArray, r: FloatArray, parameters: int) -> tuple[FloatArray, str]:
    """s^2 (J^T J)^-1, by the singular values of J; infinite when no degrees of freedom are left."""
    rows = r.size
    # With unit columns the inverse is well scaled whatever the parameters' units.
    norms = np.linalg.norm(jacobian, axis=0)
    _, singular, right = np.linalg.svd(jacobian / norms, full_matrices=False)
    inverse = (right.T / singular**2) @ right / np.outer(norms, norms)
    if rows == parameters:
        covariance = np.full_like(inverse, np.inf)
        note = (
            f"as many rows as parameters ({rows}): no degrees of freedom are left to estimate the "
            "scatter, so the standard errors are unknown (inf)."
        )
    else:
        covariance, note = float(r @ r) / (rows - parameters) * inverse, ""
    covariance.setflags(write=False)
    return covariance, note


def _values(point: Mapping[str, float]) -> str:
    return ", ".join(f"{name} = {value:.6g}" for name, value in point.items())
