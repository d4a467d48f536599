"""Least-squares fit of named parameters (davies_sym.calibration.least_squares): recovery of
known parameters, standard errors against the textbook formulas computed here with
numpy.linalg, every refusal with its message, and the text and figure of a fit."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from davies_sym.calibration import Fit, fit, fit_text, residual_figure
from davies_sym.calibration.least_squares import FloatArray
from davies_sym.errors import CalibrationError, DaviesError, FitFailure

SIGMA = 0.002
ROWS = 40


def _linear_data(seed: int = 7, sigma: float = SIGMA) -> tuple[FloatArray, FloatArray]:
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 2.0, ROWS)
    return x, 0.3 + 0.8 * x + rng.normal(0.0, sigma, ROWS)


def _linear_fit(x: FloatArray, y: FloatArray) -> Fit:
    return fit(lambda p: p["a"] + p["b"] * x - y, ["a", "b"], {"a": 0.0, "b": 0.0})


def _saturating(torque: FloatArray, e: float, drag: float) -> FloatArray:
    """A mesh efficiency that falls at low load: a drag torque against the transmitted one."""
    return e * torque / (torque + drag)


def _saturating_fit(torque: FloatArray, eta: FloatArray) -> Fit:
    return fit(
        lambda p: _saturating(torque, p["e"], p["D"]) - eta,
        ["e", "D"],
        {"e": 0.9, "D": 1.0},
        lower={"e": 0.0, "D": 0.0},
        upper={"e": 1.0},
    )


def test_linear_model_recovered_with_the_textbook_standard_errors() -> None:
    x, y = _linear_data()
    result = _linear_fit(x, y)
    design = np.column_stack([np.ones(ROWS), x])
    coefficients, ssr, _, _ = np.linalg.lstsq(design, y, rcond=None)
    s2 = float(ssr[0]) / (ROWS - 2)
    textbook = np.sqrt(np.diag(s2 * np.linalg.inv(design.T @ design)))
    np.testing.assert_allclose(result.values, coefficients, rtol=0, atol=1e-10)
    np.testing.assert_allclose(result.standard_errors, textbook, rtol=1e-6)
    for value, error, truth in zip(result.values, result.standard_errors, (0.3, 0.8), strict=True):
        assert abs(value - truth) < 3 * error
    np.testing.assert_allclose(result.residuals, design @ coefficients - y, atol=1e-10)  # model minus measured
    assert result.rms == pytest.approx(math.sqrt(float(ssr[0]) / ROWS), rel=1e-9)
    assert result.rows == ROWS and result.degrees_of_freedom == ROWS - 2 and result.converged
    assert result.parameters == {"a": result.values[0], "b": result.values[1]} and result.note == ""


def test_nonlinear_model_recovered_within_three_standard_errors() -> None:
    rng = np.random.default_rng(11)
    torque = np.linspace(2.0, 60.0, ROWS)
    eta = _saturating(torque, 0.97, 2.5) + rng.normal(0.0, SIGMA, ROWS)
    result = _saturating_fit(torque, eta)
    for value, error, truth in zip(result.values, result.standard_errors, (0.97, 2.5), strict=True):
        assert abs(value - truth) < 3 * error
    # The linearised covariance with the analytic Jacobian at the solution.
    e, drag = result.values
    jacobian = np.column_stack([torque / (torque + drag), -e * torque / (torque + drag) ** 2])
    s2 = float(result.residuals @ result.residuals) / (ROWS - 2)
    expected = np.sqrt(np.diag(s2 * np.linalg.inv(jacobian.T @ jacobian)))
    np.testing.assert_allclose(result.standard_errors, expected, rtol=1e-5)


def test_exact_data_recovered_exactly() -> None:
    x = np.linspace(0.0, 2.0, 12)
    assert _linear_fit(x, 0.3 + 0.8 * x).values == pytest.approx((0.3, 0.8), abs=1e-9)
    torque = np.linspace(2.0, 60.0, 12)
    result = _saturating_fit(torque, _saturating(torque, 0.97, 2.5))
    assert result.values == pytest.approx((0.97, 2.5), abs=1e-9)
    assert max(result.standard_errors) < 1e-9 and result.rms < 1e-12


@given(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0))
def test_any_line_recovered_exactly(a: float, b: float) -> None:
    x = np.linspace(-1.0, 3.0, 8)
    assert _linear_fit(x, a + b * x).values == pytest.approx((a, b), abs=1e-9)


def test_the_fit_is_deterministic() -> None:
    x, y = _linear_data()
    first, second = _linear_fit(x, y), _linear_fit(x, y)
    assert first.values == second.values and first.standard_errors == second.standard_errors
    assert first.residuals.tobytes() == second.residuals.tobytes()


def test_as_many_rows_as_parameters_gives_infinite_errors_and_says_so() -> None:
    x, y = np.array([0.0, 1.0]), np.array([0.3, 1.1])
    result = _linear_fit(x, y)
    assert result.values == pytest.approx((0.3, 0.8), abs=1e-9)
    assert result.standard_errors == (math.inf, math.inf)
    assert result.note.startswith("as many rows as parameters (2): no degrees of freedom")
    data = result.as_dict()
    assert data["parameters"]["a"] == {"value": result.values[0], "standard_error": None}
    json.dumps(data, allow_nan=False)  # JSON-ready: no Infinity


def test_as_dict_is_json_ready() -> None:
    x, y = _linear_data()
    result = _linear_fit(x, y)
    data = json.loads(json.dumps(result.as_dict(), allow_nan=False))
    assert data["parameters"]["b"] == {"value": result.values[1], "standard_error": result.standard_errors[1]}
    assert data["residuals"] == result.residuals.tolist() and data["rows"] == ROWS and data["rms"] == result.rms


def test_a_parameter_at_its_bound_is_noted() -> None:
    x, y = _linear_data()
    result = fit(lambda p: p["a"] + p["b"] * x - y, ["a", "b"], {"a": 0.0, "b": 0.5}, upper={"b": 0.7})
    assert result.values[1] == pytest.approx(0.7)
    assert result.note == "b at its bound: the standard errors assume an interior solution."


def _refusal(*args: object, **kwargs: object) -> CalibrationError:
    with pytest.raises(CalibrationError) as caught:
        fit(*args, **kwargs)  # type: ignore[arg-type]
    assert isinstance(caught.value, DaviesError)
    return caught.value


def test_refuses_a_parameter_the_residuals_do_not_change_with() -> None:
    x, y = _linear_data()
    error = _refusal(
        lambda p: p["a"] + p["b"] * x + 0.0 * p["D_K"] - y,
        ["a", "b", "D_K"],
        {"a": 0.0, "b": 0.0, "D_K": 1.0},
        source="rig.csv",
    )
    assert str(error) == "rig.csv: the data do not determine D_K: the residuals do not change with it"
    assert error.cause is FitFailure.UNDETERMINED


def test_refuses_parameters_determined_only_in_combination() -> None:
    x, y = _linear_data()
    error = _refusal(lambda p: p["a"] + p["k"] * p["m"] * x - y, ["a", "k", "m"], {"a": 0.0, "k": 1.0, "m": 1.0})
    assert str(error).startswith(
        "the data do not determine k and m separately: the residuals change only with a "
        "combination of them (condition number of J^T J "
    )
    # Two columns that are the same at every row (the operating points never vary x).
    error = _refusal(lambda p: p["a"] + p["b"] * np.ones(ROWS) - y, ["a", "b"], {"a": 0.0, "b": 0.0})
    assert "do not determine a and b separately" in str(error) and error.cause is FitFailure.UNDETERMINED


def test_refuses_fewer_rows_than_parameters() -> None:
    error = _refusal(
        lambda p: np.array([p["a"] + p["b"] + p["c"] - 1.0, p["a"] - 2.0]),
        ["a", "b", "c"],
        {"a": 0.0, "b": 0.0, "c": 0.0},
        source="rig.csv",
    )
    assert str(error) == "rig.csv: 2 rows cannot determine 3 parameters (a, b, c): give at least 3 rows"
    assert error.cause is FitFailure.ROWS


def test_refuses_a_residual_that_is_not_finite_at_the_start() -> None:
    torque, eta = np.array([2.0, 1.0, 4.0]), np.array([0.5, 0.5, 0.5])
    with np.errstate(divide="ignore", invalid="ignore"):
        error = _refusal(lambda p: _saturating(torque, p["e"], p["D"]) - eta, ["e", "D"], {"e": 0.9, "D": -1.0})
    assert str(error) == (
        "the residual of row 2 is inf at the start values (e = 0.9, D = -1): the model is not defined there"
    )
    assert error.cause is FitFailure.NON_FINITE


def test_refuses_a_residual_that_becomes_nan_during_the_fit() -> None:
    x = np.linspace(1.0, 2.0, 10)
    with np.errstate(invalid="ignore"):
        error = _refusal(lambda p: np.sqrt(p["c"]) * x - 0.1 * x - 0.5, ["c"], {"c": 4.0})
    message = str(error)
    assert message.startswith("the residual of row 1 became nan during the fit, at c = -")
    assert message.endswith("; bound the parameters (lower, upper) to where the model is defined")


def test_refuses_a_fit_that_does_not_converge() -> None:
    torque = np.linspace(2.0, 60.0, ROWS)
    eta = _saturating(torque, 0.97, 2.5)
    error = _refusal(
        lambda p: _saturating(torque, p["e"], p["D"]) - eta,
        ["e", "D"],
        {"e": 0.5, "D": 20.0},
        source="rig.csv",
        max_evaluations=2,
    )
    message = str(error)
    assert message.startswith(
        "rig.csv: the fit did not converge (The maximum number of function evaluations is exceeded) after "
    )
    assert "evaluations; it reached e = " in message and error.cause is FitFailure.CONVERGENCE


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"start": {"a": 1.0}}, "no start value for b"),
        ({"start": {"a": 1.0, "b": 1.0, "q": 2.0}}, "start names q, not among the parameters (a, b)"),
        ({"lower": {"a": 2.0}}, "the start value a = 1 is outside its bounds (2 to inf)"),
        (
            {"lower": {"b": 1.0}, "upper": {"b": 1.0}},
            "the bounds of b leave no interval (1 to 1); to hold a parameter fixed, leave it out of the fit",
        ),
        ({"start": {"a": math.nan, "b": 1.0}}, "the start value of a is nan"),
        ({"max_evaluations": 0}, "max_evaluations must be at least 1, got 0"),
    ],
)
def test_refuses_bad_arguments(kwargs: dict[str, object], message: str) -> None:
    x, y = _linear_data()
    arguments: dict[str, object] = {"start": {"a": 1.0, "b": 1.0}, **kwargs}
    error = _refusal(lambda p: p["a"] + p["b"] * x - y, ["a", "b"], **arguments)
    assert str(error) == message and error.cause is FitFailure.ARGUMENTS


def test_text_report_holds_each_value_error_and_the_largest_residuals() -> None:
    x, y = _linear_data()
    result = _linear_fit(x, y)
    text = fit_text(result, "eta")
    for name, value, error in zip(result.names, result.values, result.standard_errors, strict=True):
        assert f"{name} = {value:.6g} ± {error:.3g}" in text
    assert f"rows: {ROWS} ({ROWS - 2} degrees of freedom)" in text
    assert f"rms of the eta residuals: {result.rms:.3g}" in text
    worst = int(np.argmax(np.abs(result.residuals)))
    assert f"  row {worst + 1}: {result.residuals[worst]:+.3g}" in text.splitlines()[5]


def test_residual_figure_is_a_reproducible_png() -> None:
    x, y = _linear_data()
    result = _linear_fit(x, y)
    png = residual_figure(result)
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    assert residual_figure(result, x, "x") == residual_figure(result, x, "x")
    with pytest.raises(ValueError, match="x has 3 values for 40 residuals"):
        residual_figure(result, np.arange(3.0))
