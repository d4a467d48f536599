"""``derive FILES... --out DIR`` on several processes (``--jobs N``) and on a Dask cluster
(``--scheduler ADDRESS``): the files written are byte for byte those of the serial run
(the committed ``derivations/``), with ``--json`` or ``--latex`` byte for byte what
``derive FILE`` prints with that option, a file that fails is reported while the others
are still written, and the options refuse what they cannot do with exit status 2."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from harness.helpers import run_cli, run_main

from conftest import ROOT

CATALOG = Path(ROOT) / "catalog"
DERIVATIONS = Path(ROOT) / "derivations"
TRAINS = ["simple_pair", "tuplin", "wolfrom", "worm_drive"]


def _same_as_committed(folder: Path, stems: list[str]) -> None:
    written = sorted(p.name for p in folder.iterdir())
    assert written == sorted(f"{s}{x}" for s in stems for x in (".py", ".tex")), written
    for name in written:
        assert (folder / name).read_bytes() == (DERIVATIONS / name).read_bytes(), name


def test_jobs_write_what_the_serial_run_writes(tmp_path: Path) -> None:
    result = run_cli([*(CATALOG / f"{t}.yaml" for t in TRAINS), "--out", tmp_path, "--jobs", "2"], timeout=300)
    assert result.returncode == 0, result.describe()
    _same_as_committed(tmp_path, TRAINS)
    # Without a terminal, one progress line per finished file, counted.
    assert sorted(line.split("] ")[-1] for line in result.stderr.splitlines() if "wrote" in line) == sorted(
        f"wrote the derivations of {t}" for t in TRAINS
    ), result.describe()
    assert f"[{len(TRAINS)}/{len(TRAINS)}]" in result.stderr


def test_json_documents_are_what_derive_file_json_prints(tmp_path: Path) -> None:
    """A train with operating states, one driven at two ports, a machine and a plain
    train: each ``.json`` is the document ``derive FILE --json`` prints, and nothing else
    is written."""
    names = ["simpson", "sr20_differential", "four_bar", "tuplin"]
    files = [CATALOG / f"{n}.yaml" for n in names]
    result = run_main([*files, "--out", tmp_path, "--json", "--jobs", "2", "--quiet"], timeout=600)
    assert result.returncode == 0, result.describe()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(f"{n}.json" for n in names)
    for name, path in zip(names, files, strict=True):
        alone = run_main([path, "--json", "--quiet"], timeout=600)
        assert alone.returncode == 0, alone.describe()
        assert (tmp_path / f"{name}.json").read_text(encoding="utf-8") == alone.stdout, name


def test_latex_writes_the_documents_alone(tmp_path: Path) -> None:
    result = run_main([*(CATALOG / f"{t}.yaml" for t in TRAINS[:2]), "--out", tmp_path, "--latex", "--quiet"])
    assert result.returncode == 0, result.describe()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(f"{t}.tex" for t in TRAINS[:2])
    for t in TRAINS[:2]:
        assert (tmp_path / f"{t}.tex").read_bytes() == (DERIVATIONS / f"{t}.tex").read_bytes(), t


@pytest.mark.parametrize("option", [["--python", "x.py"], ["--emit", "c"], ["--eval"], ["--plot"]])
def test_one_file_options_are_refused_with_several(tmp_path: Path, option: list[str]) -> None:
    files = [CATALOG / "simple_pair.yaml", CATALOG / "tuplin.yaml"]
    result = run_main([*files, "--out", tmp_path, *option])
    assert result.returncode == 2, result.describe()
    assert "--python, --emit, --eval and --plot take one file" in result.stderr, result.describe()
    assert list(tmp_path.iterdir()) == []


def test_a_bad_file_is_reported_and_the_others_are_written(tmp_path: Path) -> None:
    bad = tmp_path / "in" / "broken.yaml"
    bad.parent.mkdir()
    bad.write_text("links: [0, 1]\ncouplings:\n  A: {type: revolute, links: [0, 9]}\n")
    out = tmp_path / "out"
    out.mkdir()
    files = [CATALOG / "simple_pair.yaml", bad, CATALOG / "tuplin.yaml"]
    result = run_cli([*files, "--out", out, "--jobs", "2", "--quiet"], timeout=300)
    assert result.returncode == 2, result.describe()
    assert str(bad) in result.stderr and "error" in result.stderr, result.describe()
    _same_as_committed(out, ["simple_pair", "tuplin"])


def test_a_task_that_raises_is_an_internal_error_with_status_4(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An error past the refusals (here planted in the module writer for one train) does
    not stop the run: the other files are written, the failed one is reported as an internal
    error naming the file and the place in the package, and the status is 4 (docs/errors.md)."""
    from davies_sym.cli import many_files

    real = many_files.write_derivations

    def planted(train, stem, progress, failures):  # type: ignore[no-untyped-def]
        if stem == "tuplin":
            raise RuntimeError("planted failure")
        return real(train, stem, progress, failures)

    monkeypatch.setattr(many_files, "write_derivations", planted)
    files = [CATALOG / "simple_pair.yaml", CATALOG / "tuplin.yaml", CATALOG / "wolfrom.yaml"]
    result = run_main([*files, "--out", tmp_path, "--quiet"], timeout=300)
    assert result.returncode == 4, result.describe()
    assert "internal error: " in result.stderr and "tuplin.yaml: deriving it: RuntimeError: planted failure" in (
        result.stderr
    ), result.describe()
    assert "Traceback" not in result.stderr
    _same_as_committed(tmp_path, ["simple_pair", "wolfrom"])


def test_two_files_of_one_name_are_not_written_over_each_other(tmp_path: Path) -> None:
    other = tmp_path / "copy" / "simple_pair.yaml"
    other.parent.mkdir()
    other.write_bytes((CATALOG / "simple_pair.yaml").read_bytes())
    out = tmp_path / "out"
    result = run_main([CATALOG / "simple_pair.yaml", other, "--out", out, "--jobs", "2", "--quiet"], timeout=300)
    assert result.returncode == 2, result.describe()
    assert f"{other}: --out:" in result.stderr and "rename one of the two files" in result.stderr
    _same_as_committed(out, ["simple_pair"])


@pytest.mark.parametrize("value", ["0", "-1", "two", "1.5"])
def test_jobs_must_be_a_count(value: str) -> None:
    result = run_main([CATALOG / "simple_pair.yaml", "--jobs", value])
    assert result.returncode == 2
    assert "--jobs" in result.stderr and "number of processes" in result.stderr, result.describe()


@pytest.mark.parametrize("option", [["--jobs", "2"], ["--scheduler", "tcp://127.0.0.1:9"]])
def test_jobs_and_scheduler_need_a_directory(option: list[str]) -> None:
    result = run_main([CATALOG / "simple_pair.yaml", *option])
    assert result.returncode == 2, result.describe()
    assert f"{option[0]} derives several files into a directory: add --out DIR" in result.stderr


def test_jobs_auto_is_one_process_per_core(tmp_path: Path) -> None:
    from davies_sym.cli import parser

    assert parser().parse_args(["--jobs", "auto"]).jobs == (os.cpu_count() or 1)


@pytest.mark.slow
def test_dask_cluster_writes_what_the_serial_run_writes(tmp_path: Path) -> None:
    """A local Dask cluster of two worker processes, as a user's cluster would be."""
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        files = [CATALOG / f"{t}.yaml" for t in TRAINS[:3]]
        result = run_main([*files, "--out", tmp_path, "--scheduler", cluster.scheduler_address], timeout=300)
    assert result.returncode == 0, result.describe()
    _same_as_committed(tmp_path, TRAINS[:3])


@pytest.mark.slow
def test_an_unreachable_scheduler_is_named(tmp_path: Path) -> None:
    pytest.importorskip("dask.distributed")
    files = [CATALOG / "simple_pair.yaml", CATALOG / "tuplin.yaml"]
    result = run_main([*files, "--out", tmp_path, "--scheduler", "tcp://127.0.0.1:9"], timeout=120)
    assert result.returncode == 2, result.describe()
    assert "--scheduler" in result.stderr and "cannot reach a Dask scheduler at 'tcp://127.0.0.1:9'" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_terminal_gets_a_progress_bar(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """On a terminal the finished files show as a bar (tqdm) instead of one line each."""
    import io
    import sys

    from davies_sym.cli.many_files import derive_into
    from davies_sym.fan_out import Workers
    from davies_sym.progress import Display

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    files = [str(CATALOG / "simple_pair.yaml"), str(CATALOG / "wolfrom.yaml")]
    assert derive_into(str(tmp_path), files, Display("derive"), Workers(jobs=2)) == 0
    assert "2/2" in screen.getvalue() and "file" in screen.getvalue(), screen.getvalue()
    assert "wrote the derivations" not in screen.getvalue()
    _same_as_committed(tmp_path, ["simple_pair", "wolfrom"])
