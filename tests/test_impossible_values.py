"""Numbers a train cannot have, in the file or on the command line: a radius of -40, 0,
oo, nan, inf, .nan, .inf or 1e400, a negative module or friction coefficient, an
efficiency outside (0, 1], an annulus smaller than its planet; ``--eval`` efficiencies
outside (0, 1], a negative or non-finite radius, a friction coefficient the formulas solve
from an efficiency, a dependent radius that breaks its relation.  Each gives exit status 2
with a message naming the entry or the option (docs/errors.md), and nothing on standard
output.
"""

from __future__ import annotations

from functools import partial

import pytest
from harness.helpers import (
    CATALOG,
    assert_refused,
    replaced,
    run_main,
)
from harness.helpers import write_file as write

import davies_sym

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
TUPLIN = (CATALOG / "tuplin.yaml").read_text(encoding="utf-8")
RADIUS_LINE = "  1: {link: 1, radius: r1}"  # line 11 of simple_pair.yaml
#: The simple pair with its first ``old`` (which must be there) replaced by ``new``.
simple_pair_with = partial(replaced, SIMPLE_PAIR)
PAIR_DESIGN = ["r1=20", "r2=50", "eta_C=0.98"]


# --- in the file ------------------------------------------------------------------------------------------------------


BAD_RADII = [
    "-40",
    "0",
    "oo",
    "-oo",
    "zoo",
    "nan",
    "inf",
    ".nan",
    ".inf",
    "-.inf",
    "1e400",
    "1.0e+400",
    "1/0",
    "-r1",
    "0*r1",
    "r1 - r1",
]


@pytest.mark.parametrize("radius", BAD_RADII)
def test_impossible_radius_is_refused_with_the_entry(tmp_path, radius):
    path = write(tmp_path, "pair.yaml", simple_pair_with(RADIUS_LINE, f"  1: {{link: 1, radius: {radius}}}"))
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1.radius",))
    assert ":11:" in result.stderr, result.describe()


@pytest.mark.parametrize(
    ("entry", "old", "new"),
    [
        ("gears.1.module", RADIUS_LINE, "  1: {link: 1, teeth: 20, module: -2}"),
        ("gears.1.module", RADIUS_LINE, "  1: {link: 1, teeth: 20, module: .nan}"),
        ("gears.1.teeth", RADIUS_LINE, "  1: {link: 1, teeth: 0, module: 2}"),
        ("couplings.C.friction.coulomb", "friction: {coulomb: zeta_C}", "friction: {coulomb: -1}"),
        ("couplings.C.friction.coulomb", "friction: {coulomb: zeta_C}", "friction: {coulomb: .inf}"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: 0"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: -0.5"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: .nan"),
        ("couplings.C.efficiency", "friction: {coulomb: zeta_C}", "efficiency: [0.98, 1.5]"),
    ],
    ids=[
        "module_negative",
        "module_nan",
        "teeth_zero",
        "coulomb_negative",
        "coulomb_inf",
        "efficiency_zero",
        "efficiency_negative",
        "efficiency_nan",
        "efficiency_pair_above_one",
    ],
)
def test_impossible_coefficient_is_refused_with_the_entry(tmp_path, entry, old, new):
    path = write(tmp_path, "pair.yaml", simple_pair_with(old, new))
    assert_refused(run_main([str(path), "--quiet"]), path, (entry,))


def test_annulus_smaller_than_its_planet_is_refused(tmp_path):
    text = TUPLIN.replace("1: {link: 1, radius: r1, internal: true}", "1: {link: 1, radius: 10, internal: true}")
    text = text.replace("3: {link: 3/4, radius: r3}", "3: {link: 3/4, radius: 15}")
    path = write(tmp_path, "tuplin.yaml", text)
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, ("gears.1", "gears.3", "couplings.C"), max_lines=None)


# --- on the command line ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "value",
    [
        "eta_C=1.5",
        "eta_C=0",
        "eta_C=-0.5",
        "eta_C=nan",
        "r1=-3",
        "r1=0",
        "r1=nan",
        "r1=oo",
        "r1=inf",
        "r1=zoo",
        "r1=1/0",
        "r1=-oo",
    ],
)
def test_impossible_eval_value_is_refused_with_the_name(tmp_path, value):
    path = write(tmp_path, "pair.yaml", SIMPLE_PAIR)
    name = value.partition("=")[0]
    others = [v for v in ("r1=20", "r2=50", "eta_C=0.98") if not v.startswith(name + "=")]
    result = run_main([str(path), "--quiet", "--eval", value, *others])
    assert_refused(result, path, ("--eval",), line=False)
    assert name in result.stderr, result.describe()
    assert result.stdout == "", "a number was printed although a value was refused"


def test_a_mesh_friction_coefficient_given_a_value_is_refused_by_every_entry_point(tmp_path):
    """zeta_C is solved from the ordinary efficiency eta_C: given besides it, its value was
    silently ignored (the result was eta_C's whatever zeta_C said)."""
    result = run_main([CATALOG / "simple_pair.yaml", "--quiet", "--eval", *PAIR_DESIGN, "zeta_C=300"])
    assert_refused(result, CATALOG / "simple_pair.yaml", ("--eval",), line=False)
    assert "zeta_C is the friction coefficient of mesh C" in result.stderr and "give eta_C" in result.stderr
    variants = davies_sym.derive(davies_sym.load(CATALOG / "simple_pair.yaml"))
    with pytest.raises(davies_sym.InputError, match="zeta_C is the friction coefficient of mesh C"):
        variants.evaluate({"r1": 20, "r2": 50, "eta_C": 0.98, "zeta_C": 300})


def test_a_dependent_radius_that_breaks_its_relation_is_refused_under_eval():
    """Tuplin's r4 follows from r1 - r3 = r2 - r4 (35 for 40, 60, 15): 30 is refused under
    --eval with the relation and both numbers, as every other bad value is."""
    design = ["r1=40", "r2=60", "r3=15", "r4=30", "eta_C=0.99", "eta_D=0.99"]
    result = run_main([CATALOG / "tuplin.yaml", "--quiet", "--eval", *design])
    assert_refused(result, CATALOG / "tuplin.yaml", ("--eval",), line=False)
    assert "r4 = 30 breaks the relation" in result.stderr and "which gives 35" in result.stderr, result.describe()
