"""``derive --help`` and ``derive --version`` answer without loading the derivation's
heavy dependencies (sympy, flint, matplotlib, scipy, numpy): the start-up a user waits for
on every call.  The time itself is measured by ``benchmarks/cli_startup.py``."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("sympy", "flint", "matplotlib", "scipy", "numpy")

# Runs ``derive ARGS`` in a fresh interpreter and prints which heavy modules got loaded.
PROBE = """
import json, sys
from davies_sym.cli import main
try:
    main(sys.argv[1:])
except SystemExit:
    pass
print(json.dumps(sorted(m for m in {heavy} if m in sys.modules)), file=sys.stderr)
"""


def _loaded(*args: str) -> list[str]:
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(heavy=HEAVY), *args], capture_output=True, text=True, check=True
    )
    return json.loads(done.stderr.strip().splitlines()[-1])


@pytest.mark.parametrize("option", ["--help", "--version"])
def test_help_and_version_load_no_heavy_module(option: str) -> None:
    assert _loaded(option) == []


def test_a_derivation_does_load_them() -> None:
    """The probe can fail: a real derivation loads sympy and flint."""
    assert {"sympy", "flint"} <= set(_loaded("--catalog", "simple_pair", "--eval", "r1=20", "r2=50", "eta_C=0.98"))


def test_import_of_the_package_is_lazy_but_complete() -> None:
    """``import davies_sym`` loads no sympy; each public name still resolves (and ``derive``
    is ``derive_variants``)."""
    code = (
        "import sys, davies_sym\n"
        "assert 'sympy' not in sys.modules\n"
        "names = [getattr(davies_sym, n) for n in davies_sym.__all__]\n"
        "assert davies_sym.derive is davies_sym.derive_variants\n"
        "assert set(davies_sym.__all__) <= set(dir(davies_sym))\n"
        "print(len(names))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert int(done.stdout) == len(__import__("davies_sym").__all__)


def test_unknown_attribute_is_an_attribute_error() -> None:
    import davies_sym

    with pytest.raises(AttributeError, match="no attribute 'derivee'"):
        _ = davies_sym.derivee  # type: ignore[attr-defined]


def test_help_lists_every_other_command_and_each_answers_its_own_help() -> None:
    """`derive --help` names calibrate and search with a line each; `derive NAME --help`
    answers for each, exit 0."""
    from harness.helpers import run_main

    from davies_sym.cli.subcommand_parsers import SUBCOMMANDS

    shown = run_main(["--help"])
    assert shown.returncode == 0
    for command in SUBCOMMANDS:
        assert f"derive {command.name}" in shown.stdout and command.line in shown.stdout
        own = run_main([command.name, "--help"])
        assert own.returncode == 0 and f"usage: derive {command.name}" in own.stdout
