"""Symbol names a train file cannot use, refused at the line and entry that write them: a
name the generated code cannot hold (a keyword, a name the module binds), a name the
formulas already give a meaning (a mesh efficiency, the input torque, the sign of a
friction force), one symbol in two roles.
"""

from __future__ import annotations

import pytest
from harness.helpers import (
    CATALOG,
    assert_at,
    assert_edit_refused,
    line_of,
    replaced,
    run_main,
    write,
)

PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("name", "output"),
    [
        *((name, option) for name in ("PORTS", "values", "float") for option in ("--python", "")),
        ("fn", "--emit rust"),  # a keyword of the language
        ("efficiency", "--emit c"),  # the name of a generated function
    ],
)
def test_a_reserved_symbol_is_refused_at_its_line_and_entry(tmp_path, name, output):
    """A symbol the generated code cannot take is refused where the file writes it, as
    ``float`` (refused on load) is."""
    old = "C: {type: mesh, gears: [1, 2], friction: {coulomb: zeta_C}}"
    # Without the published check, whose eta_C the renamed efficiency no longer is.
    unchecked = PAIR.partition("expected:")[0]
    text = replaced(unchecked, old, f"C: {{type: mesh, gears: [1, 2], efficiency: {name}}}")
    path = write(tmp_path, text)
    option, _, language = output.partition(" ")
    asked = [option, language or tmp_path / "m.py"] if option else []  # a name the module binds is refused on load
    result = run_main([path, "--quiet", *asked])
    assert_at(result, path, line_of(text, f"efficiency: {name}"), "couplings.C.efficiency")
    assert repr(name) in result.stderr, result.describe()
    assert not (tmp_path / "m.py").exists()


@pytest.mark.parametrize(
    ("old", "new", "entry", "words"),
    [
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: eta_C}", "gears.1.radius", "eta_C is the name of"),
        ("  1: {link: 1, radius: r1}", "  1: {link: 1, radius: tau_in}", "gears.1.radius", "input torque"),
        ("friction: {coulomb: zeta_C}}", "efficiency: r1}", "couplings.C.efficiency", "one symbol has one meaning"),
    ],
    ids=["radius-is-the-mesh-efficiency", "radius-is-the-input-torque", "efficiency-is-a-radius"],
)
def test_one_symbol_in_two_roles_is_refused_where_the_second_is_written(tmp_path, old, new, entry, words):
    """A radius called eta_C (the name of mesh C's ordinary efficiency), a radius called
    tau_in (the formulas' input torque), a mesh efficiency written as the radius r1: each
    was derived as if the two meanings were one."""
    text = replaced(PAIR, old, new)
    path = write(tmp_path, text)
    result = run_main([path, "--quiet"])
    assert_at(result, path, line_of(text, new.strip()[:20]), entry)
    assert words in result.stderr, result.describe()


def test_a_radius_named_like_the_sign_of_a_friction_force_is_refused_at_its_line(tmp_path):
    """sigma_C is the sign of mesh C's Coulomb force (Laus eq. (37)); a radius of that name
    failed deep in the algebra ('two sets of assumptions') without a line."""
    old, new = "  1: {link: 1, radius: r1}", "  1: {link: 1, radius: sigma_C}"
    assert_edit_refused(tmp_path, PAIR, old, new, "sigma_C", "gears.1.radius", "sign of a friction force of coupling C")


@pytest.mark.parametrize(("name", "language"), [("M_PI", "c"), ("fn", "rust")])
def test_a_symbol_only_the_speed_ratio_takes_is_refused_too(tmp_path, name, language):
    """A radius that enters the speed ratio and no efficiency (the mesh's efficiency is a
    constant) is an argument of ``speed_ratio`` alone; named ``M_PI`` it collided with the
    constant the C file defines, and the file did not compile."""
    unchecked = PAIR.partition("expected:")[0]
    text = replaced(unchecked, "friction: {coulomb: zeta_C}", "efficiency: eta_C")
    text = replaced(text, "  1: {link: 1, radius: r1}", f"  1: {{link: 1, radius: {name}}}")
    path = write(tmp_path, text)
    result = run_main([path, "--quiet", "--emit", language, "-o", tmp_path / "m.out"])
    assert_at(result, path, line_of(text, f"radius: {name}"), "gears.1.radius")
    assert repr(name) in result.stderr, result.describe()
    assert not (tmp_path / "m.out").exists()
