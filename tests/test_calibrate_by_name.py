"""`derive calibrate --catalog NAME` runs from any folder: the train file names its own
measurements (``calibrate: {data, predict}``, relative to the file), so the SR20 study of
docs/calibration.md needs no path (Mantriota and Pennestri 2003, Tables I-V: fitted on
Table I, the predictions of Tables II-V differ from the measured efficiency by 0.0102 on
average, against 0.0244 for the paper's own model).  Every way to leave something out
is refused with what to write."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from harness.helpers import assert_refused, run_main

from conftest import CATALOG, catalog_path


@pytest.fixture
def empty(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_catalog_train_with_its_own_data_from_an_empty_folder(empty: Path) -> None:
    result = run_main(["calibrate", "--catalog", "sr20_differential", "--json", "--quiet"])
    assert result.returncode == 0, result.describe()
    answer = json.loads(result.stdout)
    assert Path(answer["data"]).name == "sr20_table1.csv"
    assert len(answer["predicted_efficiency"]) == 23
    assert round(answer["mean_absolute_error"], 4) == 0.0102


def test_given_data_replaces_the_files_and_drops_their_predictions(empty: Path) -> None:
    """With DATA.csv on the command line only that file is fitted (no --predict: none)."""
    table = str(Path(CATALOG, "data", "sr20_table2.csv"))
    result = run_main(["calibrate", "--catalog", "sr20_differential", table, "--json", "--quiet"])
    assert result.returncode == 0, result.describe()
    answer = json.loads(result.stdout)
    assert answer["data"] == table and "predicted_efficiency" not in answer


def test_nothing_to_calibrate_is_refused(empty: Path) -> None:
    result = run_main(["calibrate"])
    assert_refused(result, None, ("TRAIN.yaml",))
    result = run_main(["calibrate", catalog_path("simple_pair")])
    assert_refused(result, catalog_path("simple_pair"), ("DATA.csv",), line=False)
    result = run_main(["calibrate", catalog_path("simple_pair"), "a.csv", "--catalog", "tuplin"])
    assert_refused(result, None, ("--catalog",))


def test_data_the_file_names_must_be_there(empty: Path) -> None:
    text = Path(catalog_path("sr20_differential")).read_text(encoding="utf-8")
    train = empty / "sr20.yaml"
    train.write_text(text, encoding="utf-8")  # the data folder is not beside this copy
    result = run_main(["calibrate", str(train)])
    assert_refused(result, train, ("calibrate.data",))
    line = text.splitlines().index("  data: data/sr20_table1.csv") + 1
    assert f"{train}:{line}:" in result.stderr
    train.write_text(text.replace("data: data/sr20_table1.csv", "data: [1, 2]"), encoding="utf-8")
    assert_refused(run_main(["calibrate", str(train)]), train, ("calibrate.data",))
