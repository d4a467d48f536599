"""The options that choose what ``derive`` computes, checked against the train: the sweep
of ``--plot``, ``--vs`` and ``--at`` (bounds that are not finite, one parameter swept
twice or swept and held, nothing admissible, a train that self-locks throughout), the
ports of ``--input`` and ``--output`` (with ``--eval`` or without, of a state, of a
machine, of a train driven at several ports), and what ``derive calibrate`` reads besides
the train (its ``--at`` values, the measured rows).  A bad option is refused with exit
status 2 naming it (``FILE: OPTION: ...``, docs/errors.md); a design the formulas do not
cover gets exit status 3 and its reason.
"""

from __future__ import annotations

import pytest
from harness.helpers import (
    CATALOG,
    DATA,
    assert_refused,
    problem_lines,
    replaced,
    run_main,
    write,
)

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
PAIR_VALUES = ["r2=50", "eta_C=0.98"]
#: A planetary set in two operating states (fast to derive).
STATES = (DATA / "two_states.yaml").read_text(encoding="utf-8")
SR20 = (CATALOG / "sr20_differential.yaml").read_text(encoding="utf-8")
SR20_DATA = CATALOG / "data" / "sr20_table1.csv"


# --- --plot, --vs and --at --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("bounds", ["10:1e400", "10:inf", "nan:30", "-1e400:30", "10:1e13", "10:10.0000000000001"])
def test_absurd_sweep_bounds_are_refused_naming_plot(tmp_path, bounds):
    path = write(tmp_path, PAIR, "pair.yaml")
    figure = tmp_path / "fig.png"
    result = run_main([path, "--quiet", "--plot", f"r1={bounds}", "--at", *PAIR_VALUES, "-o", figure])
    assert_refused(result, path, ("--plot",), line=False)
    assert "Warning" not in result.stderr, result.describe()
    assert not figure.exists()


def test_the_same_parameter_on_both_axes_is_refused(tmp_path):
    path = write(tmp_path, PAIR, "pair.yaml")
    figure = tmp_path / "fig.png"
    result = run_main([path, "--quiet", "--plot", "r1=10:30", "--vs", "r1=5:40", "--at", *PAIR_VALUES, "-o", figure])
    assert_refused(result, path, ("--vs",), line=False)
    assert "r1 is swept by --plot already" in result.stderr, result.describe()
    assert not figure.exists()


@pytest.mark.parametrize(
    ("plot", "at", "option", "words"),
    [
        ("r1=-30:-10", ["r2=50", "eta_C=0.98"], "--plot", "r1 lies in (0, inf)"),
        ("eta_C=1.5:2.5", ["r1=20", "r2=50"], "--plot", "eta_C lies in (0, 1]"),
        ("r1=10:30", ["r1=5", "r2=50", "eta_C=0.98"], "--at", "r1 is swept by --plot"),
    ],
    ids=["radius-all-negative", "efficiency-all-above-one", "swept-and-held"],
)
def test_a_sweep_with_nothing_admissible_or_held_twice_is_refused(tmp_path, plot, at, option, words):
    """These drew an empty figure (or ignored --at) with exit status 0."""
    figure = tmp_path / "p.png"
    result = run_main([CATALOG / "simple_pair.yaml", "--quiet", "--plot", plot, "--at", *at, "-o", figure])
    assert_refused(result, CATALOG / "simple_pair.yaml", (option,), line=False)
    assert words in result.stderr and not figure.exists(), result.describe()


def test_a_sweep_of_a_mesh_friction_coefficient_is_refused_as_its_value_is(tmp_path):
    """--plot zeta_C drew a flat line (the formulas are in eta_C), exit 0."""
    result = run_main(
        [
            CATALOG / "simple_pair.yaml",
            "--quiet",
            "--plot",
            "zeta_C=0:1",
            "--at",
            "r1=20",
            "r2=50",
            "-o",
            tmp_path / "p.png",
        ]
    )
    assert_refused(result, CATALOG / "simple_pair.yaml", ("--plot",), line=False)
    assert "zeta_C is the friction coefficient of mesh C" in result.stderr, result.describe()


def test_a_sweep_where_the_train_self_locks_throughout_gets_the_reason_and_exit_3(tmp_path):
    """Tuplin driven at B with mesh efficiencies 0.7 self-locks for r1 in [40, 41] (the
    design of the issue, r2 = 60, r3 = 15): no efficiency to draw, said with the module's
    reason at the first point instead of an empty figure."""
    figure = tmp_path / "p.png"
    at = ["r2=60", "r3=15", "eta_C=0.7", "eta_D=0.7"]
    result = run_main(
        [CATALOG / "tuplin.yaml", "--quiet", "--plot", "r1=40:41", "--at", *at, "--input", "B", "-o", figure]
    )
    # As for --eval, the answer (why there is no number) is the last line of the output.
    assert result.returncode == 3, result.describe()
    last = result.stdout.splitlines()[-1]
    assert "--plot" in last and "self-locks" in last and "r1=40" in last and not figure.exists(), result.describe()
    assert not problem_lines(result), result.describe()


# --- --input and --output ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("option", ["--input", "--output"])
def test_an_unknown_port_is_refused_with_or_without_eval(tmp_path, option):
    path = write(tmp_path, PAIR, "pair.yaml")
    alone = run_main([path, "--quiet", option, "Z"])
    evaluated = run_main([path, "--quiet", option, "Z", "--eval", "r1=20", *PAIR_VALUES])
    for result in (alone, evaluated):
        assert_refused(result, path, (option,), line=False)
        assert "'Z' is not a port (ports: A, B)" in result.stderr, result.describe()
    assert alone.stderr == evaluated.stderr


def test_a_port_of_any_state_is_a_port_without_state(tmp_path):
    path = write(tmp_path, STATES)
    result = run_main([path, "--quiet", "--input", "Z"])
    assert_refused(result, path, ("--input",), line=False)
    assert "(ports: A, B, K)" in result.stderr, result.describe()
    assert run_main([path, "--quiet", "--output", "K"]).returncode == 0


def test_an_unknown_port_of_a_machine_is_refused_without_eval():
    result = run_main([CATALOG / "three_upu.yaml", "--quiet", "--input", "Z"])
    assert_refused(result, CATALOG / "three_upu.yaml", ("--input",), line=False)


def test_naming_the_output_of_a_train_driven_at_several_ports_changes_nothing():
    """SR20 (Mantriota and Pennestri 2003, Table I row 1): --output O is its output already."""
    design = ["omega_A=309", "omega_K=51", "tau_out=5.08", "eta_M=0.957", "D_P=0.639"]
    plain = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design])
    named = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design, "--output", "O"])
    assert plain.returncode == named.returncode == 0, named.describe()
    assert plain.stdout == named.stdout and 0 < float(named.stdout.splitlines()[-1]) < 1
    other = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design, "--output", "A"])
    assert_refused(other, CATALOG / "sr20_differential.yaml", ("--output",), line=False)


def test_two_degrees_of_freedom_with_one_input_print_the_motions_and_say_what_is_missing(tmp_path):
    """The SR20 differential with one input port: its motions (w_O = (w_A + w_K)/2 in the
    primary speeds, Mantriota and Pennestri eq. (1)) and why no efficiency follows."""
    path = write(tmp_path, replaced(SR20, "input: [A, K]", "input: A"))
    result = run_main([path, "--quiet"])
    assert result.returncode == 0, result.describe()
    assert "t_A = -t_K + 2*t_O" in result.stdout, result.describe()
    assert "2 degrees of freedom needs as many input ports" in result.stdout, result.describe()


# --- derive calibrate: --at and the measured rows ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("fit", "at", "words"),
    [
        ("D_P", "eta_M=3", "eta_M = 3 is not an efficiency"),
        ("D_P", "eta_M=0", "eta_M = 0 is not an efficiency"),
        ("eta_M", "D_P=-1", "D_P = -1 is a friction coefficient"),
        ("eta_M", "zz=1", "unknown symbol 'zz'"),
    ],
    ids=["efficiency-above-one", "efficiency-zero", "negative-drag", "unknown-name"],
)
def test_calibration_values_are_checked_as_every_design_is(fit, at, words):
    """`derive calibrate --at` fitted with these (or failed on 'the data do not determine')."""
    result = run_main(["calibrate", CATALOG / "sr20_differential.yaml", SR20_DATA, "--quiet", "--fit", fit, "--at", at])
    assert_refused(result, CATALOG / "sr20_differential.yaml", ("--at",), line=False)
    assert words in result.stderr, result.describe()


@pytest.mark.parametrize("eta", ["1.7731", "-0.7731", "0"])
def test_a_measured_efficiency_outside_zero_one_is_refused_at_its_row(tmp_path, eta):
    lines = SR20_DATA.read_text(encoding="utf-8").splitlines()
    lines[1] = lines[1].replace(",0.7731,", f",{eta},", 1)
    data = write(tmp_path, "\n".join(lines) + "\n", "rig.csv")
    result = run_main(["calibrate", CATALOG / "sr20_differential.yaml", data, "--quiet"])
    assert_refused(result, data, ("column 'eta'",), line=False)
    assert f"{data}:2: column 'eta':" in result.stderr and "lies in (0, 1]" in result.stderr, result.describe()
