"""The code is kept in ruff's format (configuration in pyproject.toml): the package, the
tests, the tools and the benchmarks; generated formula modules are laid out by the
generator and checked by the linter (tests/test_outputs.py)."""

from __future__ import annotations

import subprocess
import sys

from conftest import ROOT


def test_code_is_in_ruff_format():
    result = subprocess.run(
        [sys.executable, "-m", "ruff", "format", "--check", "."], cwd=ROOT, capture_output=True, text=True, check=False
    )
    assert result.returncode == 0, result.stdout + result.stderr
