"""How ``derive`` routes its other commands: by the first word only, through the table
of `davies_sym.cli.subcommand_parsers`; ``derive search`` is one parser for a train file
or ``--atlas N``, and mixing the two is refused with the option named (exit status 2)."""

from __future__ import annotations

from pathlib import Path

import pytest

from davies_sym.cli import main
from davies_sym.cli.subcommand_parsers import SUBCOMMANDS

CATALOG = Path(__file__).resolve().parent.parent / "davies_sym" / "catalog"


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Exit status, standard output and standard error of ``derive ARGV`` here."""
    try:
        status = main(argv)
    except SystemExit as exc:  # argparse's own refusals and --help
        status = int(exc.code or 0)
    out, err = capsys.readouterr()
    return status, out, err


def test_every_command_is_in_the_table_and_in_the_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert [c.name for c in SUBCOMMANDS] == ["atlas", "calibrate", "shifts", "search"]
    status, out, _ = _run(["--help"], capsys)
    assert status == 0
    for command in SUBCOMMANDS:
        assert f"derive {command.name}" in out and command.line in out


def test_atlas_written_after_a_file_is_no_longer_a_command(capsys: pytest.CaptureFixture[str]) -> None:
    """``--atlas`` among a train's arguments is an option of `derive search` (refused with
    a train file), not a switch found by scanning the whole command line."""
    train = str(CATALOG / "planetary_simple.yaml")
    status, _, err = _run(["search", train, "--atlas", "5", "--target", "4"], capsys)
    assert status == 2
    assert "--atlas searches the atlas, not a file" in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (["--weights", "a=1"], "--weights is for a search over one train file"),
        (["--write-best", "best.yaml"], "--write-best is for a search over one train file"),
        (["--target", "4", "5"], "--target: with --atlas, one speed ratio"),
        (["--teeth", "17:30", "20:40"], "--teeth: with --atlas, one LO:HI"),
        (["--tolerance", "tight"], "--tolerance: expected a number such as 12.5 or 25/2, got 'tight'"),
        (["--budget", "0"], "--budget: expected a whole number of designs, at least 1, got '0'"),
    ],
)
def test_options_of_a_file_search_are_refused_with_atlas(
    extra: list[str], says: str, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["search", "--atlas", "5", "--target", "4", *extra]
    if extra[0] == "--target":
        argv = ["search", "--atlas", "5", *extra]
    status, _, err = _run(argv, capsys)
    assert status == 2
    assert says in err, err


def test_a_search_needs_a_file_or_the_atlas(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = _run(["search", "--target", "4", "--teeth", "z=17:20"], capsys)
    assert status == 2
    assert "give the train file TRAIN.yaml, or --atlas N" in err


def test_a_budget_is_refused_for_a_file_search(capsys: pytest.CaptureFixture[str]) -> None:
    """A train file's search scores every design: a budget would stop it unannounced."""
    train = str(CATALOG / "planetary_simple.yaml")
    status, _, err = _run(["search", train, "--target", "4", "--teeth", "z=17:20", "--budget", "10"], capsys)
    assert status == 2
    assert "--budget is for a search over the atlas (--atlas N)" in err and "Traceback" not in err


def test_the_budgets_default_is_the_searchs(capsys: pytest.CaptureFixture[str]) -> None:
    from davies_sym.synthesis.best_first import BUDGET

    status, out, _ = _run(["search", "--help"], capsys)
    assert status == 0
    assert f"(default {BUDGET})" in " ".join(out.split())


def test_a_file_search_needs_its_tooth_bounds(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = _run(["search", str(CATALOG / "planetary_simple.yaml"), "--target", "4"], capsys)
    assert status == 2
    assert "the following arguments are required: --teeth" in err


def test_atlas_given_with_an_equals_sign_routes_alike(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = _run(["search", "--atlas=3", "--target", "4"], capsys)
    assert status == 2
    assert "--atlas: expected the most links, from 4 to 8" in err
