"""Reading measured operating points from CSV: the numbers, and every problem with its file,
line and column (davies_sym.calibration.measurements)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from davies_sym.calibration.measurements import MAX_PROBLEMS, Measurements, read_measurements
from davies_sym.errors import InputError, MeasurementError


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Work in tmp_path, so messages name the file as given (``rig.csv``)."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _write(folder: Path, text: str | bytes, name: str = "rig.csv") -> str:
    data = text.encode("utf-8") if isinstance(text, str) else text
    (folder / name).write_bytes(data)
    return name


def _message(path: str, required: tuple[str, ...] = ("T", "eta"), optional: tuple[str, ...] = ()) -> str:
    with pytest.raises(MeasurementError) as caught:
        read_measurements(path, required, optional)
    return str(caught.value)


def test_reads_columns_lines_and_values(here: Path) -> None:
    path = _write(here, "T,w,eta\n10,100,0.95\n20,200,0.96\n")
    data = read_measurements(path, ["T", "eta"], ["w"])
    assert isinstance(data, Measurements)
    assert data.columns == ("T", "w", "eta") and data.lines == (2, 3)
    assert len(data) == data.rows == 2
    assert data.column("T").tolist() == [10.0, 20.0] and data.column("w").dtype == np.float64
    assert data.column("eta").tolist() == [0.95, 0.96]
    assert data.location(1) == "rig.csv:3"
    with pytest.raises(ValueError):
        data.column("T")[0] = 5.0  # the arrays are read-only: a frozen result stays frozen


def test_bom_comments_blank_lines_crlf_and_extra_columns(here: Path) -> None:
    text = (
        "\ufeff# rig 3, 2024-05-02\r\n\r\n  T , note, eta ,extra\r\n# warm-up done\r\n"
        '10, "cold, first" ,0.95,x\r\n\r\n,,,\r\n20,ok,0.96,\r\n'
    )
    data = read_measurements(_write(here, text), ["T", "eta"])
    assert data.columns == ("T", "note", "eta", "extra")
    assert data.lines == (5, 8)
    assert set(data.values) == {"T", "eta"}  # extra columns are kept in the header only, never read
    assert data.column("eta").tolist() == [0.95, 0.96]


def test_optional_columns_read_when_present(here: Path) -> None:
    path = _write(here, "T,eta\n1,0.9\n")
    data = read_measurements(path, ["T"], ["eta", "w"])
    assert "eta" in data and "w" not in data
    with pytest.raises(KeyError, match="no column 'w' was read"):
        data.column("w")


def test_subset_keeps_lines() -> None:
    data = Measurements("m.csv", ("x",), {"x": np.array([1.0, 2.0, 3.0])}, (4, 6, 9))
    part = data.subset([2, 0])
    assert part.column("x").tolist() == [3.0, 1.0] and part.lines == (9, 4)
    assert data.subset(np.array([True, False, True])).lines == (4, 9)


def test_file_missing_or_a_folder(here: Path) -> None:
    assert _message("nowhere.csv") == "data error: nowhere.csv: cannot read the file: No such file or directory"
    (here / "folder").mkdir()
    assert _message("folder") == "data error: folder: cannot read the file: Is a directory"


def test_not_utf8_names_the_line(here: Path) -> None:
    path = _write(here, b"T,eta\n1,0.9\n\xff,0.8\n")
    assert _message(path) == (
        "data error: rig.csv:3: not UTF-8 text (byte 0xff at offset 12); save the file as UTF-8 CSV"
    )


@pytest.mark.parametrize("text", ["", "  \n\n", "\ufeff"])
def test_empty_file(here: Path, text: str) -> None:
    assert _message(_write(here, text)) == (
        "data error: rig.csv: the file is empty (expected a header row naming the columns, then one row per point)"
    )


def test_no_header(here: Path) -> None:
    path = _write(here, "# T, eta\n\n# nothing measured yet\n")
    assert _message(path) == "data error: rig.csv: no header row: the file has only comments and blank lines"


def test_no_data_rows(here: Path) -> None:
    path = _write(here, "# rig\nT,eta\n\n# later\n")
    assert _message(path) == "data error: rig.csv: no data rows (only the header, on line 2)"


def test_missing_and_duplicated_columns_all_reported(here: Path) -> None:
    path = _write(here, "# rig\nT,w,T,eta\n1,2,3,0.9\n")
    assert _message(path, ("T", "T_O", "eta", "w_O")).splitlines() == [
        "data error: rig.csv:2: header: column 'T' appears 2 times (columns 1 and 3)",
        "data error: rig.csv:2: header: required column 'T_O' is missing (columns present: 'T', 'w', 'T', 'eta')",
        "data error: rig.csv:2: header: required column 'w_O' is missing (columns present: 'T', 'w', 'T', 'eta')",
    ]


def test_a_file_without_a_header_row(here: Path) -> None:
    path = _write(here, "# T, eta\n1,0.9\n2,0.8\n")
    assert _message(path) == (
        "data error: rig.csv:2: header: the first row holds numbers, not column names: begin "
        "the file with a header row naming the columns (T, eta)"
    )


def test_rows_with_too_few_or_too_many_fields(here: Path) -> None:
    path = _write(here, "T,eta\n1,0.9\n2\n3,0.9,7\n")
    assert _message(path).splitlines() == [
        "data error: rig.csv:3: the row has 1 fields but the header has 2",
        "data error: rig.csv:4: the row has 3 fields but the header has 2",
    ]


def test_empty_cells_in_required_and_optional_columns(here: Path) -> None:
    path = _write(here, "T,eta,w,note\n1, ,5,\n,0.9,,\n")
    assert _message(path, ("T", "eta"), ("w",)).splitlines() == [
        "data error: rig.csv:2: column 'eta': empty cell (every row needs a value here)",
        "data error: rig.csv:3: column 'T': empty cell (every row needs a value here)",
        "data error: rig.csv:3: column 'w': empty cell (every row needs a value here)",
    ]


def test_values_that_are_not_finite_numbers(here: Path) -> None:
    path = _write(
        here, f"T_O,eta\n1,0.9\n# a comment moves the lines on\n2,0.9\nabc,nan\ninf,-Infinity\n{'9' * 60}x,1e999\n"
    )
    assert _message(path, ("T_O", "eta")).splitlines() == [
        "data error: rig.csv:5: column 'T_O': 'abc' is not a number",
        "data error: rig.csv:5: column 'eta': 'nan' is not a finite number",
        "data error: rig.csv:6: column 'T_O': 'inf' is not a finite number",
        "data error: rig.csv:6: column 'eta': '-Infinity' is not a finite number",
        "data error: rig.csv:7: column 'T_O': '9999999999999999999999999...999999999x' is not a number",
        "data error: rig.csv:7: column 'eta': '1e999' is not a finite number",
    ]


def test_a_field_over_the_csv_limit(here: Path) -> None:
    path = _write(here, f"T,eta\n1,0.9\n2,{'1' * 200_000}\n")
    assert _message(path) == "data error: rig.csv:3: not readable as CSV: field larger than field limit (131072)"


def test_problems_are_capped(here: Path) -> None:
    path = _write(here, "T,eta\n" + "x,0.9\n" * (MAX_PROBLEMS + 5))
    lines = _message(path).splitlines()
    assert len(lines) == MAX_PROBLEMS + 1
    assert lines[0] == "data error: rig.csv:2: column 'T': 'x' is not a number"
    assert lines[-1] == "data error: rig.csv: ... and 5 more problems"


def test_the_error_is_an_input_error_with_every_problem(here: Path) -> None:
    path = _write(here, "T,eta\nx,y\n")
    with pytest.raises(InputError) as caught:
        read_measurements(path, ["T", "eta"])
    assert isinstance(caught.value, MeasurementError) and caught.value.kind == "data error"
    assert [(p.entry, p.line) for p in caught.value.problems] == [("column 'T'", 2), ("column 'eta'", 2)]
    assert caught.value.source == "rig.csv"


@given(
    st.lists(
        st.tuples(st.floats(allow_nan=False, allow_infinity=False), st.floats(allow_nan=False, allow_infinity=False)),
        min_size=1,
        max_size=20,
    )
)
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])  # one file, rewritten per example
def test_finite_numbers_come_back_exactly(tmp_path: Path, rows: list[tuple[float, float]]) -> None:
    path = tmp_path / "round_trip.csv"
    path.write_text("a,b\n" + "".join(f"{a!r},{b!r}\n" for a, b in rows), encoding="utf-8")
    data = read_measurements(str(path), ["a", "b"])
    assert data.column("a").tolist() == [a for a, _ in rows] and data.column("b").tolist() == [b for _, b in rows]
    assert data.lines == tuple(range(2, len(rows) + 2))
    assert all(math.isfinite(v) for v in data.column("a"))
