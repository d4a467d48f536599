"""`derive calibrate --starts N`: the fit repeated from N start points (the file's, then a
seeded Sobol sequence over the parameters' ranges), the least sum of squares kept, and
the count of starts that reached it reported; the starts fitted in groups through the
fan-out (`--jobs`, `--scheduler`) give the same answer as in this process."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from harness.helpers import run_main

from davies_sym.calibration.fit_starts import (
    FitBounds,
    StartFailure,
    best_of,
    start_groups,
    start_points,
)
from davies_sym.calibration.least_squares import fit
from davies_sym.errors import CalibrationError, FitFailure

BOUNDS = FitBounds(
    fitted=("eta_M", "D_P"),
    start={"eta_M": 0.95, "D_P": 0.1},
    lower={"eta_M": 1e-9, "D_P": 0.0},
    upper={"eta_M": 1.0, "D_P": math.inf},
    efficiencies=frozenset({"eta_M"}),
)


def test_start_points_begin_at_the_files_start_and_stay_in_their_ranges() -> None:
    points = start_points(BOUNDS, 9)
    assert len(points) == 9 and points[0] == {"eta_M": 0.95, "D_P": 0.1}
    assert all(0.5 <= p["eta_M"] < 1.0 and 0.0 <= p["D_P"] <= 1.0 for p in points[1:])
    assert len({(p["eta_M"], p["D_P"]) for p in points}) == 9  # no start twice
    assert start_points(BOUNDS, 9) == points  # seeded: the same on every run
    assert start_points(BOUNDS, 1) == (points[0],)


def test_groups_keep_every_point_in_order() -> None:
    points = start_points(BOUNDS, 7)
    groups = start_groups(points, 3)
    assert len(groups) == 3 and [p for g in groups for p in g] == list(points)
    assert start_groups(points, 20) == tuple((p,) for p in points)


def test_the_least_squares_among_local_minima_is_kept() -> None:
    """y = sin(a x) sampled at a = 3 has local minima of the squares in a; a start at
    0.5 stops in one of them, a start near 3 finds the data's own a = 3 (rms 0)."""
    x = np.linspace(0.0, 4.0, 41)
    measured = np.sin(3.0 * x)

    def residuals(values: dict[str, float]) -> np.ndarray:
        return np.sin(values["a"] * x) - measured

    fits = [fit(residuals, ["a"], {"a": a}) for a in (0.5, 2.8, 3.1)]
    assert abs(fits[0].values[0] - 3.0) > 0.5  # the first start's own minimum is not the data's
    best = best_of(fits)
    assert best.best.values[0] == pytest.approx(3.0, abs=1e-9)
    assert (best.tried, best.converged, best.at_best) == (3, 3, 2)
    assert best.other_rms == pytest.approx((fits[0].rms,))


def test_no_start_converging_is_refused_with_the_first_reason() -> None:
    failures = [StartFailure("data.csv: the fit did not converge", FitFailure.CONVERGENCE)] * 2
    with pytest.raises(CalibrationError, match="did not converge") as caught:
        best_of(failures)
    assert caught.value.cause is FitFailure.CONVERGENCE


def test_sr20_from_eight_starts_on_two_processes_agrees_with_one_start() -> None:
    """The SR20 fit of Mantriota and Pennestri 2003, Table I (docs/calibration.md): every
    start reaches the same least squares, so the answer is the single start's."""
    one = run_main(["calibrate", "--catalog", "sr20_differential", "--json", "--quiet"])
    many = run_main(
        ["calibrate", "--catalog", "sr20_differential", "--json", "--quiet", "--starts", "8", "--jobs", "2"]
    )
    assert one.returncode == 0 and many.returncode == 0, many.describe()
    single, multi = json.loads(one.stdout), json.loads(many.stdout)
    assert "starts" not in single
    assert multi["starts"] == {"tried": 8, "converged": 8, "at_best": 8, "other_minima_rms": []}
    for name, entry in single["parameters"].items():
        assert multi["parameters"][name]["value"] == pytest.approx(entry["value"], rel=1e-6)


@pytest.mark.parametrize("given", ["0", "1025", "two"])
def test_a_number_of_starts_out_of_range_is_refused(given: str) -> None:
    result = run_main(["calibrate", "--catalog", "sr20_differential", "--starts", given])
    assert result.returncode == 2 and "--starts" in result.stderr and "Traceback" not in result.stderr
