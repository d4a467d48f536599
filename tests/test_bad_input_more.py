"""Bad input found by a second generated sweep of 953 cases, one regression test per class:
each is refused by the contract of docs/errors.md (exit status 2 with one line
``FILE[:LINE]: ENTRY: what is wrong and what to write instead``; exit status 3 with the
reason for a design the formulas do not cover; no traceback), and the Python API refuses
the same design with the same reason.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from harness.helpers import (
    CATALOG,
    DATA,
    assert_edit_refused,
    assert_refused,
    line_of,
    problem_lines,
    replaced,
    run_main,
    write,
)

import davies_sym

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
PAIR_DESIGN = ["r1=20", "r2=50", "eta_C=0.98"]
SR20 = (CATALOG / "sr20_differential.yaml").read_text(encoding="utf-8")
SR20_DATA = CATALOG / "data" / "sr20_table1.csv"


# --- a symbol named like a quantity of the formulas -----------------------------------------------------------


def test_a_radius_named_like_the_sign_of_a_friction_force_is_refused_at_its_line(tmp_path):
    """sigma_C is the sign of mesh C's Coulomb force (Laus eq. (37)); a radius of that name
    failed deep in the algebra ('two sets of assumptions') without a line."""
    old, new = "  1: {link: 1, radius: r1}", "  1: {link: 1, radius: sigma_C}"
    assert_edit_refused(tmp_path, PAIR, old, new, "sigma_C", "gears.1.radius", "sign of a friction force of coupling C")


def test_a_mesh_friction_coefficient_given_a_value_is_refused_by_every_entry_point(tmp_path):
    """zeta_C is solved from the ordinary efficiency eta_C: given besides it, its value was
    silently ignored (the result was eta_C's whatever zeta_C said)."""
    result = run_main([CATALOG / "simple_pair.yaml", "--quiet", "--eval", *PAIR_DESIGN, "zeta_C=300"])
    assert_refused(result, CATALOG / "simple_pair.yaml", ("--eval",), line=False)
    assert "zeta_C is the friction coefficient of mesh C" in result.stderr and "give eta_C" in result.stderr
    variants = davies_sym.derive(davies_sym.load(CATALOG / "simple_pair.yaml"))
    with pytest.raises(davies_sym.InputError, match="zeta_C is the friction coefficient of mesh C"):
        variants.evaluate({"r1": 20, "r2": 50, "eta_C": 0.98, "zeta_C": 300})


# --- published checks -------------------------------------------------------------------------------------------


def test_a_check_that_leaves_a_parameter_out_is_said_at_its_line(tmp_path):
    """A published check without r2 can never be evaluated: said on standard error with
    its line (it was accepted silently); the derivation itself stands."""
    text = replaced(PAIR, "values: {r1: 20, r2: 50, eta_C: 0.98}", "values: {r1: 20, eta_C: 0.98}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert result.returncode == 0 and "eta = eta_C" in result.stdout, result.describe()
    said = f"derive: warning: {path}:{line_of(text, 'values:')}: expected[0].values: the check gives no value for r2"
    assert said in result.stderr, result.describe()


def test_a_check_whose_input_is_a_mesh_is_refused_at_its_line(tmp_path):
    old, new = "    value: 0.98\n", "    value: 0.98\n    input: C\n"
    assert_edit_refused(tmp_path, PAIR, old, new, "input: C", "expected[0].input", "is a gear mesh")


def test_a_calibration_start_above_one_for_an_efficiency_is_refused_at_its_line(tmp_path):
    old, new = "start: {eta_M: 0.95", "start: {eta_M: 1.95"
    assert_edit_refused(tmp_path, SR20, old, new, "start:", "calibrate.start.eta_M", "eta_M is an efficiency")


# --- command-line values ------------------------------------------------------------------------------------------


def test_a_dependent_radius_that_breaks_its_relation_is_refused_under_eval():
    """Tuplin's r4 follows from r1 - r3 = r2 - r4 (35 for 40, 60, 15): 30 is refused under
    --eval with the relation and both numbers, as every other bad value is."""
    design = ["r1=40", "r2=60", "r3=15", "r4=30", "eta_C=0.99", "eta_D=0.99"]
    result = run_main([CATALOG / "tuplin.yaml", "--quiet", "--eval", *design])
    assert_refused(result, CATALOG / "tuplin.yaml", ("--eval",), line=False)
    assert "r4 = 30 breaks the relation" in result.stderr and "which gives 35" in result.stderr, result.describe()


def test_an_empty_output_name_is_refused_before_the_derivation(tmp_path):
    for option in ("--python", "-o"):
        result = run_main([CATALOG / "simple_pair.yaml", "--quiet", option, ""])
        assert_refused(result, CATALOG / "simple_pair.yaml", (option,), line=False)
        assert "the file name is empty" in result.stderr, result.describe()


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


# --- figures ------------------------------------------------------------------------------------------------------


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


# --- calibration ----------------------------------------------------------------------------------------------------


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


# --- a train of two degrees of freedom with one input -----------------------------------------------------------


def test_two_degrees_of_freedom_with_one_input_print_the_motions_and_say_what_is_missing(tmp_path):
    """The SR20 differential with one input port: its motions (w_O = (w_A + w_K)/2 in the
    primary speeds, Mantriota and Pennestri eq. (1)) and why no efficiency follows."""
    path = write(tmp_path, replaced(SR20, "input: [A, K]", "input: A"))
    result = run_main([path, "--quiet"])
    assert result.returncode == 0, result.describe()
    assert "t_A = -t_K + 2*t_O" in result.stdout, result.describe()
    assert "2 degrees of freedom needs as many input ports" in result.stdout, result.describe()


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


def test_naming_the_output_of_a_train_driven_at_several_ports_changes_nothing():
    """SR20 (Mantriota and Pennestri 2003, Table I row 1): --output O is its output already."""
    design = ["omega_A=309", "omega_K=51", "tau_out=5.08", "eta_M=0.957", "D_P=0.639"]
    plain = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design])
    named = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design, "--output", "O"])
    assert plain.returncode == named.returncode == 0, named.describe()
    assert plain.stdout == named.stdout and 0 < float(named.stdout.splitlines()[-1]) < 1
    other = run_main([CATALOG / "sr20_differential.yaml", "--quiet", "--eval", *design, "--output", "A"])
    assert_refused(other, CATALOG / "sr20_differential.yaml", ("--output",), line=False)


def test_an_output_named_by_a_link_to_the_input_is_refused_by_both_names(tmp_path):
    source = write(tmp_path, PAIR, "pair.yaml")
    link = tmp_path / "link.tex"
    link.symlink_to(source)
    result = run_main([source, "--quiet", "--latex", "-o", link])
    assert_refused(result, source, ("-o",), line=False)
    assert f"refusing to overwrite the input file {source} ({link} names it)" in result.stderr, result.describe()
    assert source.read_text(encoding="utf-8") == PAIR


WORM = (CATALOG / "worm_drive.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("source", "old", "new", "at", "entry", "words"),
    [
        (PAIR, "radius: r2}", "radius: r2#big}", "r2#big", "gears.2.radius", "'#' is not part"),
        (
            PAIR,
            "  2: {description: gear 2}\n",
            "  2: {description: gear 2}\n  3: {description: spare}\n",
            "spare",
            "links.3",
            "no coupling joins link '3'",
        ),
        (
            PAIR,
            "  C: {type: mesh",
            "  D: {type: revolute, links: [0, 1]}\n  C: {type: mesh",
            "D: {type",
            "couplings.D",
            "U_D stay free",
        ),
        (WORM, "lead_angle: gamma", "lead_angle: -gamma", "-gamma", "couplings.W.lead_angle", "is negative"),
        (
            WORM,
            "{link: 1, radius: 1}",
            "{link: 1, radius: 1, internal: true}",
            "internal: true",
            "gears.worm.internal",
            "skew axes",
        ),
    ],
    ids=[
        "hash-in-a-radius",
        "lone-link",
        "twin-bearing",
        "negative-lead-angle",
        "internal-worm",
    ],
)
def test_a_second_sweep_of_file_mistakes_is_refused_at_the_entry_written(tmp_path, source, old, new, at, entry, words):
    """`r2#big` read as r2 (Python's parser dropped a comment) and a negative symbolic lead
    angle were accepted; a lone link, a second bearing and an
    internal worm were refused at the wrong entry."""
    assert_edit_refused(tmp_path, source, old, new, at, entry, words)


def test_a_bearing_coefficient_beyond_a_double_still_gives_a_module(tmp_path):
    """coulomb: 1e-300 made the module writer recurse without end on a 301-digit number;
    the module now gives the efficiency, which tends to eta_C as the loss vanishes."""
    text = replaced(
        PAIR,
        "  A: {type: revolute, links: [0, 1]}",
        "  A: {type: revolute, links: [0, 1], friction: {coulomb: 1e-300}}",
    )
    path = write(tmp_path, text)
    module = tmp_path / "m.py"
    result = run_main([path, "--quiet", "--python", module])
    assert result.returncode == 0, result.describe()
    namespace: dict[str, object] = {}
    exec(compile(module.read_text(encoding="utf-8"), str(module), "exec"), namespace)
    value = namespace["efficiency"](r1=20.0, r2=50.0, eta_C=0.98)  # type: ignore[operator]
    assert abs(float(value) - 0.98) < 1e-12


# --- the Python API refuses what the command line refuses, with the same reason ---------------------------------

TUPLIN_DESIGN = {"r1": 40, "r2": 60, "r3": 15, "eta_C": 0.99, "eta_D": 0.99}


def _refusal(call):  # type: ignore[no-untyped-def]
    with pytest.raises(davies_sym.DaviesError) as caught:
        call()
    return caught.value


@pytest.mark.parametrize(
    ("values", "port", "cli", "kind", "words"),
    [
        (
            {**TUPLIN_DESIGN, "r1": 60},
            None,
            ["r1=60", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"],
            davies_sym.NotCoveredError,
            "port B does not turn at these values",
        ),
        (
            TUPLIN_DESIGN,
            "C",
            [*(f"{k}={v}" for k, v in TUPLIN_DESIGN.items()), "--input", "C"],
            davies_sym.InputError,
            "'C' is not a port (ports: A, B)",
        ),
        (
            {k: v for k, v in TUPLIN_DESIGN.items() if k != "r3"},
            None,
            ["r1=40", "r2=60", "eta_C=0.99", "eta_D=0.99"],
            davies_sym.InputError,
            "missing values for r3",
        ),
    ],
    ids=["port-still", "mesh-as-input", "missing-value"],
)
def test_the_balance_refuses_a_design_as_the_command_line_does(values, port, cli, kind, words):
    """Chen's virtual-power balance (a route sharing no code with Davies') raised
    DerivationError, KeyError or a sympy TypeError where `derive --eval` gives a reason."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = davies_sym.load(CATALOG / "tuplin.yaml")
    error = _refusal(lambda: virtual_power_balance(train, values, port))
    assert isinstance(error, kind) and words in str(error), error
    result = run_main([CATALOG / "tuplin.yaml", "--quiet", "--eval", *cli])
    assert words in result.stdout + result.stderr, result.describe()


def test_the_balance_says_a_transcendental_efficiency_is_outside_its_scope():
    """Buckingham's mesh efficiency holds logarithms (Laus App. A): the exact balance cannot
    take it; it says so instead of a sympy TypeError."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance

    train = davies_sym.load(CATALOG / "buckingham_pair.yaml")
    error = _refusal(lambda: virtual_power_balance(train, {"mu": 0.0272}))
    assert isinstance(error, davies_sym.DerivationError) and "not an algebraic number" in str(error)


def test_design_values_of_numpy_decimal_and_foreign_symbols_are_read_exactly():
    """numpy scalars raised a sympy TypeError, a Decimal was 'not a number', True was 1 and
    sympy.Symbol("r1") (without the train's assumptions) was an unknown symbol r1."""
    from decimal import Decimal

    import numpy as np
    import sympy

    variants = davies_sym.derive(davies_sym.load(CATALOG / "simple_pair.yaml"))
    assert variants.evaluate({"r1": np.float64(20), "r2": np.int64(50), "eta_C": np.float32(0.5)}) == sympy.Rational(
        1, 2
    )
    assert variants.evaluate({"r1": Decimal("20"), "r2": 50, "eta_C": Decimal("0.98")}) == sympy.Rational(49, 50)
    assert variants.evaluate({sympy.Symbol("r1"): 20, "r2": 50, "eta_C": 0.9}) == sympy.Rational(9, 10)
    for bad, words in ((True, "a truth value is not a number"), (float("nan"), "not a finite number")):
        error = _refusal(lambda bad=bad: variants.evaluate({"r1": 20, "r2": 50, "eta_C": bad}))
        assert isinstance(error, davies_sym.InputError) and words in str(error)


def test_derive_and_a_state_lookup_refuse_unknown_names_as_the_options_do():
    train = davies_sym.load(CATALOG / "simple_pair.yaml")
    for port in ("Z", "C"):
        error = _refusal(lambda port=port: davies_sym.derive(train, inputs=[port]))
        assert isinstance(error, davies_sym.InputError) and f"'{port}' is not a port (ports: A, B)" in str(error)
    states = davies_sym.load(DATA / "two_states.yaml")
    error = _refusal(lambda: states.state("nope"))
    assert isinstance(error, davies_sym.InputError) and "unknown state 'nope'" in str(error)


TUPLIN = (CATALOG / "tuplin.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("source", "old", "new", "at", "entry", "words"),
    [
        (PAIR, "    value: 0.98\n", "    value: 1.5\n", "value: 1.5", "expected[0].value", "lies in (0, 1]"),
        (PAIR, "    value: 0.98\n", "    value: -0.2\n", "value: -0.2", "expected[0].value", "lies in (0, 1]"),
        (
            TUPLIN,
            "degrees_of_freedom: 1\n",
            "degrees_of_freedom: 1\nindependent: [r1, r1, r2]\n",
            "independent:",
            "independent[1]",
            "written twice",
        ),
        (
            TUPLIN,
            "degrees_of_freedom: 1\n",
            "degrees_of_freedom: 1\nindependent: [r1, r2, eta_C]\n",
            "independent:",
            "independent[2]",
            "no size of the geometry",
        ),
        (SR20, "D_P: 0.1}", "D_P: 1e400}", "start:", "calibrate.start.D_P", "expected a positive number"),
    ],
    ids=["check-above-one", "check-negative", "independent-twice", "independent-efficiency", "start-infinite"],
)
def test_a_train_file_value_out_of_its_role_is_refused_at_its_entry(tmp_path, source, old, new, at, entry, words):
    """Accepted before: a published efficiency of 1.5 or -0.2, a symbol listed twice or a
    mesh efficiency among the independent sizes, a calibration start of 1e400."""
    assert_edit_refused(tmp_path, source, old, new, at, entry, words)


def test_a_state_that_cannot_derive_names_itself(tmp_path):
    """The Wolfrom train with its carrier free has no geometry; the message said which
    mesh but not which state."""
    text = replaced(
        (CATALOG / "wolfrom.yaml").read_text(encoding="utf-8"),
        "degrees_of_freedom: 1\n",
        "degrees_of_freedom: 1\nstates:\n  nocar: {input: A, output: B, free: [c]}\n",
    )
    result = run_main([write(tmp_path, text), "--quiet", "--state", "nocar"])
    assert result.returncode == 2 and "(state nocar)" in result.stderr, result.describe()
