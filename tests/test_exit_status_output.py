"""What ``derive`` prints with each exit status (docs/errors.md): 0 a result, the
efficiency alone on the last line; 2 bad input, nothing on standard output and one line
per problem on standard error, in this process and in a fresh one; 3 a valid design the
formulas do not cover (a self-locking train), the last line a one-line reason, never a
number and never an efficiency outside (0, 1].
"""

from __future__ import annotations

import re
from functools import partial

import pytest
from harness.helpers import (
    CATALOG,
    HANG_GUARD,
    assert_refused,
    replaced,
    run_cli,
    run_main,
)
from harness.helpers import write_file as write

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
TUPLIN = (CATALOG / "tuplin.yaml").read_text(encoding="utf-8")
RADIUS_LINE = "  1: {link: 1, radius: r1}"  # line 11 of simple_pair.yaml
#: The simple pair with its first ``old`` (which must be there) replaced by ``new``.
simple_pair_with = partial(replaced, SIMPLE_PAIR)
#: A hang guard only, never a claim about speed: a run still going after this long is killed (and fails).
KILL_AFTER = HANG_GUARD


SELF_LOCKING = ["--eval", "r1=40", "r2=60", "r3=15", "r4=35", "eta_C=0.7", "eta_D=0.7"]
FLOAT = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?(nan|inf|oo|zoo)$", re.IGNORECASE)


def _numbers(text: str) -> list[float]:
    """Every stdout line that is a bare number."""
    return [
        float(line.strip().replace("zoo", "nan").replace("oo", "inf"))
        for line in text.splitlines()
        if FLOAT.match(line.strip())
    ]


@pytest.mark.parametrize("ports", [["--input", "B"], ["--output", "A"]], ids=["input_B", "output_A"])
def test_self_locking_design_exits_3_with_a_reason(tmp_path, ports):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", *ports, *SELF_LOCKING])
    assert "Traceback" not in result.stderr, result.describe()
    assert result.returncode == 3, f"a self-locking design must exit 3:\n{result.describe()}"
    lines = [line for line in result.stdout.splitlines() if line.strip()]
    assert lines, result.describe()
    last = lines[-1].strip()
    assert not FLOAT.match(last), f"the last line is a number, not a reason: {last!r}"
    assert re.search(r"self-lock", last, re.IGNORECASE), f"the last line does not say why: {last!r}"
    outside = [v for v in _numbers(result.stdout) if not 0 < v <= 1]
    assert not outside, f"an efficiency outside (0, 1] was printed: {outside}"


def test_admissible_design_exits_0_with_the_efficiency_last(tmp_path):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", "--eval", "r1=40", "r2=60", "r3=15", "r4=35", "eta_C=0.99", "eta_D=0.99"])
    assert result.returncode == 0, result.describe()
    value = float(result.stdout.splitlines()[-1])
    assert value == pytest.approx(0.9462, abs=5e-5)


def test_bad_input_exits_2_and_prints_nothing_on_stdout(tmp_path):
    path = write(tmp_path, "tuplin.yaml", TUPLIN)
    result = run_main([str(path), "--quiet", "--eval", "r9=40"])
    assert_refused(result, path, ("--eval",), line=False)
    assert result.stdout == ""


def test_several_problems_give_one_line_each(tmp_path):
    text = simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: -40}")
    text = text.replace("  2: {link: 2, radius: r2}", "  2: {link: 2, radius: 0}")
    path = write(tmp_path, "pair.yaml", text)
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1.radius",), max_lines=2)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 2, result.describe()
    assert re.search(re.escape(str(path)) + r":11: gears\.1\.radius: ", lines[0]), result.describe()
    assert re.search(re.escape(str(path)) + r":12: gears\.2\.radius: ", lines[1]), result.describe()


def test_fresh_process_refusal_has_the_same_shape(tmp_path):
    """The contract holds for the real command (exit status of the process, not of ``main``)."""
    path = write(tmp_path, "pair.yaml", simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: -40}"))
    result = run_cli([str(path), "--quiet"], timeout=KILL_AFTER)
    assert_refused(result, path, ("gears.1.radius",))
