"""Calibration stage: named loss parameters of a model fitted to measured operating points.

It owns reading the measurements (`.measurements`: a CSV file of finite numbers, every
problem with its line and column), the least-squares fit with standard errors and the
refusals of a fit the data cannot support (`.least_squares`, scipy), and the text and
residual figure of a fit (`.fit_report`).  The fit itself knows nothing about gear trains:
the model is any function of the parameter values giving one residual per measured row;
`.train_model` and `.train_fit` make that model of a derived train.
"""

from davies_sym.calibration.fit_report import fit_text, residual_figure
from davies_sym.calibration.least_squares import Fit, fit
from davies_sym.calibration.measurements import Measurements, read_measurements

__all__ = ["Fit", "Measurements", "fit", "fit_text", "read_measurements", "residual_figure"]
