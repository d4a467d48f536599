"""A standard output that cannot take the text (closed before the run, full, or closed by
a reader that stopped early, as ``derive ... | head -1``) is said in one line or ends the
run quietly, never with a traceback.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from harness.helpers import (
    CATALOG,
)


@pytest.mark.parametrize("args", [["--completion", "bash"], [str(CATALOG / "tuplin.yaml"), "--latex", "--quiet"]])
def test_a_reader_that_stops_early_gets_no_traceback(args):
    """``derive ... | head -1``: the pipe is closed before the command writes (here before it
    has even started: the reader is gone); it stops quietly instead of a BrokenPipeError."""
    import subprocess
    import sys

    process = subprocess.Popen(
        [sys.executable, "-m", "davies_sym.cli", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    assert process.stdout is not None and process.stderr is not None
    process.stdout.close()
    stderr = process.stderr.read().decode()
    assert process.wait() == 0, stderr
    assert "Traceback" not in stderr and "BrokenPipe" not in stderr, stderr


def test_a_closed_standard_output_is_said_instead_of_a_traceback():
    """``derive FILE >&-``: Python leaves sys.stdout None; the text had nowhere to go."""
    process = subprocess.run(
        ["sh", "-c", '"$0" -m davies_sym.cli "$1" --quiet >&-', sys.executable, str(CATALOG / "simple_pair.yaml")],
        capture_output=True,
        text=True,
        check=False,
    )
    assert process.returncode == 2, process.stderr
    assert "cannot write to standard output (it is closed)" in process.stderr, process.stderr
    assert "Traceback" not in process.stderr


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs Linux /dev/full")
@pytest.mark.parametrize(
    "args",
    [
        ["simple_pair.yaml", "--eval", "r1=20", "r2=50", "eta_C=0.9"],
        ["--completion", "zsh"],
        ["calibrate", "sr20_differential.yaml", "data/sr20_table1.csv"],
        ["worm_drive.yaml", "--eval", "gamma=0.1", "alpha_n=0.3", "mu=1e6"],  # exit 3's answer
    ],
    ids=["eval", "completion", "calibrate", "not-covered"],
)
def test_a_full_standard_output_is_said_instead_of_a_traceback(args):
    """``derive ... > /dev/full``: the text fails at its write or at the final flush."""
    named = [str(CATALOG / a) if a.endswith((".yaml", ".csv")) else a for a in args]
    with open("/dev/full", "w") as full:
        process = subprocess.run(
            [sys.executable, "-m", "davies_sym.cli", *named, "--quiet"],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            check=False,
        )
    assert process.returncode == 2, process.stderr
    assert process.stderr.strip() == (
        "derive: cannot write to standard output (No space left on device): write to a file with -o FILE"
    ), process.stderr
