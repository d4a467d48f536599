"""Output never destroys a file: ``-o``, ``--python`` or ``--out`` into a missing, blocked
or read-only folder is refused and creates nothing; ``-o``/``--python`` onto the input
file (by any path) is refused and the input keeps its bytes; ``--out DIR`` never
overwrites an input that lives in DIR; a refused ``--eval`` or ``--plot`` leaves an
existing module or figure untouched (refusals come before any write); a refusal leaves
no temporary file; a device named by ``-o`` stays a device; the catalog is never
written.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from harness.helpers import (
    CATALOG,
    HANG_GUARD,
    Result,
    assert_refused,
    run_cli,
    run_main,
)
from harness.helpers import write_file as write

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
#: A hang guard only, never a claim about speed: a run still going after this long is killed (and fails).
KILL_AFTER = HANG_GUARD


def _input(tmp_path: Path, name: str = "pair.yaml") -> tuple[Path, bytes]:
    path = write(tmp_path, name, SIMPLE_PAIR)
    return path, path.read_bytes()


def _assert_clean_refusal(result: Result, *words: str) -> None:
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode == 2, result.describe()
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected one line:\n{result.describe()}"
    if words:
        assert any(w in result.stderr for w in words), f"the message names none of {words}:\n{result.describe()}"


# --- folders that cannot take the output ------------------------------------------------------------------------------


@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_into_a_missing_folder_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    target = tmp_path / "missing" / "deeper" / "out.py"
    result = run_main([str(path), "--quiet", option, str(target)])
    _assert_clean_refusal(result, str(target.parent), str(target))
    assert not target.parent.exists()


@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_below_a_regular_file_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    blocker = write(tmp_path, "blocker", "not a folder\n")
    result = run_main([str(path), "--quiet", option, str(blocker / "out.py")])
    _assert_clean_refusal(result, str(blocker))
    assert blocker.read_text() == "not a folder\n"


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root ignores folder permissions")
@pytest.mark.parametrize("option", ["-o", "--python", "--out"])
def test_output_into_a_read_only_folder_is_a_clear_refusal(tmp_path, option):
    path, _ = _input(tmp_path)
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        target = folder if option == "--out" else folder / "out.py"
        result = run_main([str(path), "--quiet", option, str(target)])
        _assert_clean_refusal(result, str(folder))
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(0o755)


# --- the input keeps its bytes ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("how", ["same_path", "relative", "dot_segments", "symlink", "hard_link"])
@pytest.mark.parametrize("option", ["-o", "--python"])
def test_output_onto_the_input_is_refused_and_the_input_keeps_its_bytes(tmp_path, monkeypatch, option, how):
    path, before = _input(tmp_path)
    monkeypatch.chdir(tmp_path)
    target = {
        "same_path": str(path),
        "relative": "pair.yaml",
        "dot_segments": str(tmp_path / "." / "x" / ".." / "pair.yaml"),
        "symlink": str(tmp_path / "link.yaml"),
        "hard_link": str(tmp_path / "hard.yaml"),
    }[how]
    (tmp_path / "x").mkdir()
    if how == "symlink":
        os.symlink(path, target)
    if how == "hard_link":
        os.link(path, target)
    result = run_main([str(path), "--quiet", "--json", option, target])
    assert path.read_bytes() == before, "the input file was overwritten"
    _assert_clean_refusal(result, str(path), target)


@pytest.mark.parametrize("name", ["pair.py", "pair.tex"])
def test_out_dir_never_overwrites_an_input_in_that_folder(tmp_path, name):
    """``derive d/pair.py --out d`` would write d/pair.tex and d/pair.py: the input must survive."""
    folder = tmp_path / "d"
    folder.mkdir()
    path, before = _input(folder, name)
    result = run_cli([str(path), "--quiet", "--out", str(folder)], timeout=KILL_AFTER)
    assert path.read_bytes() == before, f"--out overwrote its own input {path}:\n{result.describe()}"
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode in (0, 2), result.describe()


def test_out_dir_with_two_inputs_of_one_name_does_not_overwrite_an_input(tmp_path):
    """Two inputs ``a/pair.py`` and ``b/pair.yaml`` with ``--out a``: the module of b must not replace a's input."""
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first, before = _input(tmp_path / "a", "pair.py")
    second, _ = _input(tmp_path / "b", "pair.yaml")
    result = run_cli([str(first), str(second), "--quiet", "--out", str(tmp_path / "a")], timeout=KILL_AFTER)
    assert first.read_bytes() == before, f"an input was overwritten:\n{result.describe()}"
    assert "Traceback" not in result.stderr, result.describe()


def test_catalog_copy_is_untouched_by_every_run(tmp_path):
    """Sanity for the tests above: the catalog itself is never written by them."""
    before = {p.name: p.read_bytes() for p in CATALOG.glob("*.yaml")}
    path = tmp_path / "copy.yaml"
    shutil.copy(CATALOG / "simple_pair.yaml", path)
    run_main([str(path), "--quiet", "--json", "-o", str(path)])
    assert {p.name: p.read_bytes() for p in CATALOG.glob("*.yaml")} == before


# --- a refusal writes nothing -----------------------------------------------------------------------------------------


KNOWN_MODULE = "# written by the user before the run\nKNOWN = 1\n"


@pytest.mark.parametrize(
    "bad",
    [
        ["--eval", "nosuch=3", "r1=20", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=abc", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=-3", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=20", "r2=50"],
        ["--eval", "r1", "r2=50", "eta_C=0.98"],
        ["--eval", "r1=20", "r2=50", "eta_C=0.98", "--input", "Z"],
    ],
    ids=["unknown_name", "not_a_number", "negative_radius", "missing_value", "no_equals", "bad_port"],
)
def test_refused_eval_leaves_an_existing_module_untouched(tmp_path, bad):
    path, _ = _input(tmp_path)
    module = write(tmp_path, "m.py", KNOWN_MODULE)
    result = run_main([str(path), "--quiet", "--python", str(module), *bad])
    assert module.read_text(encoding="utf-8") == KNOWN_MODULE, f"m.py was rewritten:\n{result.describe()}"
    assert_refused(result, path, ("--eval", "--input"), line=False)


def test_refused_plot_writes_no_figure_and_keeps_an_existing_one(tmp_path):
    path, _ = _input(tmp_path)
    figure = write(tmp_path, "fig.png", b"not really a png")
    result = run_main([str(path), "--quiet", "--plot", "r1=10:30", "--at", "r2=-50", "eta_C=0.98", "-o", str(figure)])
    assert figure.read_bytes() == b"not really a png"
    assert_refused(result, path, ("--at",), line=False)


def test_no_temporary_files_are_left_behind_by_a_refusal(tmp_path):
    path, _ = _input(tmp_path)
    run_main([str(path), "--quiet", "--json", "-o", str(tmp_path / "missing" / "out.json")])
    run_main([str(path), "--quiet", "--python", str(tmp_path / "m.py"), "--eval", "r1=oops()"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.yaml"]


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="making a device node needs root")
def test_output_to_a_device_writes_to_it_and_keeps_it(tmp_path):
    """``-o /dev/null`` as root: renaming a file over the device would have replaced it."""
    import stat

    device = tmp_path / "nulldev"
    os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    result = run_main([CATALOG / "simple_pair.yaml", "--quiet", "-o", device])
    assert result.returncode == 0, result.describe()
    assert stat.S_ISCHR(os.stat(device).st_mode)
