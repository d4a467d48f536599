"""Output targets are refused by name before anything is written: a folder ``--out`` cannot
create, a file the system will not take (from ``-o``, ``--python`` or ``derive calibrate
-o``), an empty name, two outputs naming one file by any spelling, an output naming the
input through a link.  Each refusal has exit status 2 and names the option and the target
(``FILE: OPTION: ...``, docs/errors.md).
"""

from __future__ import annotations

import os

import pytest
from harness.helpers import (
    CATALOG,
    assert_refused,
    run_main,
    write,
)

from davies_sym.emit.atomic import write_atomic

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
#: /proc takes no new files, even from root (who passes every permission check).
NO_NEW_FILES = "/proc"
needs_proc = pytest.mark.skipif(not os.path.isdir(NO_NEW_FILES), reason="needs Linux /proc")


# --- targets that cannot be written -----------------------------------------------------------------------------------


@needs_proc
def test_out_folder_that_cannot_be_created_is_refused_by_name(tmp_path):
    first, second = write(tmp_path, PAIR, "a.yaml"), write(tmp_path, PAIR, "b.yaml")
    result = run_main([first, second, "--quiet", "--out", "/proc/some-dir"])
    assert_refused(result, first, ("--out",), line=False)
    assert "/proc/some-dir" in result.stderr and "cannot create the folder" in result.stderr, result.describe()


def test_out_folder_below_a_regular_file_is_refused_by_name(tmp_path):
    first, second = write(tmp_path, PAIR, "a.yaml"), write(tmp_path, PAIR, "b.yaml")
    blocker = write(tmp_path, "a file\n", "blocker")
    result = run_main([first, second, "--quiet", "--out", blocker / "derivations"])
    assert_refused(result, first, ("--out",), line=False)
    assert str(blocker / "derivations") in result.stderr, result.describe()
    assert blocker.read_text() == "a file\n"


@needs_proc
@pytest.mark.parametrize("option", ["-o", "--python"])
def test_a_refused_write_names_the_target(tmp_path, option):
    path = write(tmp_path, PAIR, "pair.yaml")
    target = f"{NO_NEW_FILES}/out.txt"
    result = run_main([path, "--quiet", option, target])
    assert_refused(result, path, (option,), line=False)
    assert f"cannot write {target}" in result.stderr and ".tmp" not in result.stderr, result.describe()


@needs_proc
def test_write_atomic_names_the_target_it_could_not_write():
    with pytest.raises(OSError) as raised:
        write_atomic(f"{NO_NEW_FILES}/out.txt", "text")
    assert raised.value.filename == f"{NO_NEW_FILES}/out.txt"


@needs_proc
def test_calibration_figure_that_cannot_be_written_is_refused_by_name(tmp_path):
    data = CATALOG / "data" / "sr20_table1.csv"
    result = run_main(["calibrate", CATALOG / "sr20_differential.yaml", data, "--quiet", "-o", "/proc/fit.png"])
    assert result.returncode == 2 and "Traceback" not in result.stderr, result.describe()
    assert "cannot write /proc/fit.png" in result.stderr, result.describe()


def test_an_empty_output_name_is_refused_before_the_derivation(tmp_path):
    for option in ("--python", "-o"):
        result = run_main([CATALOG / "simple_pair.yaml", "--quiet", option, ""])
        assert_refused(result, CATALOG / "simple_pair.yaml", (option,), line=False)
        assert "the file name is empty" in result.stderr, result.describe()


# --- one file named twice ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("spelling", ["same", "dotted", "absolute", "symlink"])
def test_two_outputs_naming_one_file_are_refused_before_anything_is_written(tmp_path, monkeypatch, spelling):
    monkeypatch.chdir(tmp_path)
    path = write(tmp_path, PAIR, "pair.yaml")
    (tmp_path / "x").mkdir()
    other = {
        "same": "same.py",
        "dotted": "x/../same.py",
        "absolute": str(tmp_path / "same.py"),
        "symlink": "link.py",
    }[spelling]
    if spelling == "symlink":
        os.symlink(tmp_path / "same.py", tmp_path / "link.py")
    result = run_main([path, "--quiet", "--python", "same.py", "-o", other])
    assert_refused(result, path, ("-o",), line=False)
    assert "both name the file" in result.stderr, result.describe()
    assert not (tmp_path / "same.py").exists(), "an output was written although the call was refused"


def test_emitted_code_and_module_on_one_file_are_refused(tmp_path):
    path = write(tmp_path, PAIR, "pair.yaml")
    target = tmp_path / "code.txt"
    result = run_main([path, "--quiet", "--emit", "c", "--python", target, "-o", target])
    assert_refused(result, path, ("-o",), line=False)
    assert not target.exists()


def test_an_output_named_by_a_link_to_the_input_is_refused_by_both_names(tmp_path):
    source = write(tmp_path, PAIR, "pair.yaml")
    link = tmp_path / "link.tex"
    link.symlink_to(source)
    result = run_main([source, "--quiet", "--latex", "-o", link])
    assert_refused(result, source, ("-o",), line=False)
    assert f"refusing to overwrite the input file {source} ({link} names it)" in result.stderr, result.describe()
    assert source.read_text(encoding="utf-8") == PAIR
