"""Files are written quietly: with ``--python``, ``--emit ... -o`` or ``-o`` the standard
output carries only the document asked for (nothing when every output went to a file)."""

from __future__ import annotations

import json
from pathlib import Path

from harness.helpers import run_main

from conftest import catalog_path


def test_python_module_alone_prints_nothing(tmp_path: Path) -> None:
    module = tmp_path / "pair.py"
    result = run_main([catalog_path("simple_pair"), "--python", str(module), "--quiet"])
    assert result.returncode == 0, result.describe()
    assert result.stdout == ""
    assert "def efficiency(" in module.read_text(encoding="utf-8")


def test_python_module_with_json_prints_the_json_only(tmp_path: Path) -> None:
    result = run_main([catalog_path("simple_pair"), "--python", str(tmp_path / "m.py"), "--json", "--quiet"])
    assert result.returncode == 0, result.describe()
    assert json.loads(result.stdout)["name"] == "Simple gear pair"


def test_emit_to_a_file_and_document_to_a_file_print_nothing(tmp_path: Path) -> None:
    for args in (["--emit", "c", "-o", str(tmp_path / "pair.c")], ["-o", str(tmp_path / "pair.txt")]):
        result = run_main([catalog_path("simple_pair"), *args, "--quiet"])
        assert result.returncode == 0, result.describe()
        assert result.stdout == "", args
    assert (tmp_path / "pair.c").read_text(encoding="utf-8").startswith("/*")
    assert "Simple gear pair" in (tmp_path / "pair.txt").read_text(encoding="utf-8")


def test_python_module_and_eval_print_the_value_last(tmp_path: Path) -> None:
    """An evaluation beside a module prints the evaluation, not the derivation (Laus eq.
    (36): the simple pair's efficiency is its mesh's, 0.98)."""
    result = run_main(
        [catalog_path("simple_pair"), "--python", str(tmp_path / "m.py"), "--eval", "r1=20", "r2=50", "eta_C=0.98"]
    )
    assert result.returncode == 0, result.describe()
    assert "speed ratio (A over B speed)" not in result.stdout
    assert float(result.stdout.split()[-1]) == 0.98


def test_several_inputs_module_alone_prints_nothing(tmp_path: Path) -> None:
    module = tmp_path / "sr20.py"
    result = run_main([catalog_path("sr20_differential"), "--python", str(module), "--quiet"])
    assert result.returncode == 0, result.describe()
    assert result.stdout == ""
    assert module.exists()
