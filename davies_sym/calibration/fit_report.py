"""What a fit says, as text and as a residual plot.

The text gives each parameter as ``name = value ± standard error``, the number of rows,
the rms of the residuals and the largest residuals with their row numbers (from 1, as in
the fit's messages).  The figure is built on ``matplotlib.figure.Figure`` with the Agg
canvas (no pyplot state) and written by the project's PNG helper, so its bytes are the
same on every run.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from davies_sym.calibration.least_squares import Fit

#: The text lists this many of the largest residuals.
LARGEST = 5


def _number(value: float, digits: int) -> str:
    return f"{value:.{digits}g}" if math.isfinite(value) else str(value)


def fit_text(fit: Fit, measured_label: str = "eta") -> str:
    """The fit as lines of text: parameters, rows, rms and the largest residuals."""
    width = max(len(name) for name in fit.names)
    lines = [
        f"{name:<{width}} = {_number(value, 6)} ± {_number(error, 3)}"
        for name, value, error in zip(fit.names, fit.values, fit.standard_errors, strict=True)
    ]
    if fit.note:
        lines.append(f"note: {fit.note}")
    lines.append(f"rows: {fit.rows} ({fit.degrees_of_freedom} degrees of freedom)")
    lines.append(f"rms of the {measured_label} residuals: {_number(fit.rms, 3)}")
    order = np.argsort(-np.abs(fit.residuals), kind="stable")[:LARGEST]
    lines.append(f"largest residuals (model - measured {measured_label}):")
    lines += [f"  row {int(i) + 1}: {fit.residuals[i]:+.3g}" for i in order]
    return "\n".join(lines) + "\n"


def residual_figure(
    fit: Fit,
    x: npt.NDArray[np.float64] | None = None,
    x_label: str = "row",
    *,
    measured_label: str = "eta",
    suffix: str = ".png",
) -> bytes:
    """The residuals (model - measured) against ``x`` (default: the row number), as the
    bytes of a figure in the format of ``suffix`` (``.png``, ``.svg``, ``.pdf``)."""
    from davies_sym.emit.plots import figure_bytes, new_figure

    xs = np.arange(1, fit.rows + 1, dtype=np.float64) if x is None else np.asarray(x, dtype=np.float64)
    if xs.shape != fit.residuals.shape:
        raise ValueError(f"x has {xs.size} values for {fit.rows} residuals")
    figure = new_figure(7.0, 4.0)
    axes = figure.add_subplot()
    axes.axhline(0.0, color="black", linewidth=0.8)
    # The band of one rms either side shows which rows stand out.
    for level in (fit.rms, -fit.rms):
        axes.axhline(level, color="tab:gray", linestyle="--", linewidth=0.8)
    axes.plot(xs, fit.residuals, "o", color="tab:blue", markersize=4)
    axes.set_xlabel(x_label)
    axes.set_ylabel(f"model - measured {measured_label}")
    fitted = ", ".join(f"{n} = {_number(v, 4)}" for n, v in zip(fit.names, fit.values, strict=True))
    axes.set_title(f"residuals of {fit.rows} rows (rms {_number(fit.rms, 3)}; dashed: ± rms)\n{fitted}", fontsize=9)
    axes.grid(True, alpha=0.3)
    return figure_bytes(figure, suffix)
