"""The ``derive`` command: JSON output, atomic writes and one clear message per bad input."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import pytest
import sympy

from conftest import MALFORMED, catalog_path, equal

# file -> (entry named in the message, words the message must contain, line or None)
MALFORMED_CASES = {
    "syntax_error.yaml": ("", "expected ',' or ']'", 3),
    "unknown_link.yaml": ("couplings.B.links[1]", "unknown link '7'", 8),
    "unknown_gear.yaml": ("couplings.C.gears", "unknown gear '3'", 9),
    "mesh_same_link.yaml": ("couplings.C.gears", "both on link '1'", 9),
    "duplicate_link.yaml": ("links[3]", "duplicate link '1'", 2),
    "duplicate_coupling.yaml": ("couplings.A", "duplicate key 'A'", 9),
    "not_connected.yaml": ("couplings", "not connected", 6),
    "port_missing_coupling.yaml": ("ports.output", "port on a missing coupling 'Z'", 10),
    "missing_port.yaml": ("ports", "missing required key 'output'", 10),
    "wrong_mobility.yaml": ("degrees_of_freedom", "1 degree(s) of freedom, the file says 2", 11),
    "two_dof_one_input.yaml": ("ports", "2 degrees of freedom but one input port", 15),
    "inconsistent_geometry.yaml": ("couplings.D", "inconsistent geometry", 13),
    "unknown_key.yaml": ("gears.2.radus", "unknown key 'radus'", 5),
    "gear_pair_without_position.yaml": ("gears.3", "no mesh connects it to the main axis", 6),
    "bad_efficiency.yaml": ("couplings.C.efficiency", "an ordinary efficiency must lie in (0, 1], got 1.5", 9),
    "tilted_one_mesh.yaml": ("gears.2.axis", "a tilted axis needs two meshes with gears of known axes, found 1", 6),
    "bad_placement.yaml": ("placement", "expected [x, y] or an angle in degrees, got 'sideways'", 3),
    "two_pitch_circles.yaml": ("couplings.D", "one gear has one pitch circle", 21),
}


def run(*args: str, cwd: str | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", *args], capture_output=True, text=True, cwd=cwd, check=False
    )


def test_every_malformed_file_has_a_case():
    assert sorted(os.listdir(MALFORMED)) == sorted(MALFORMED_CASES)


@pytest.mark.parametrize("name", sorted(MALFORMED_CASES))
def test_malformed_input_gives_one_clear_error(name):
    entry, words, line = MALFORMED_CASES[name]
    path = os.path.join(MALFORMED, name)
    result = run(path, "--json", "--quiet")
    assert result.returncode == 2
    # With --json, standard output carries the status and the same reason as standard error.
    answer = json.loads(result.stdout)
    assert answer["status"] == "bad input" and answer["exit_status"] == 2
    assert answer["reason"] == result.stderr.strip()
    assert "Traceback" not in result.stderr
    first = result.stderr.splitlines()[0]
    assert f"{path}:{line}:" in first
    assert words in result.stderr
    if entry:
        assert f" {entry}:" in result.stderr


def test_json_document_of_tuplin():
    """``derive catalog/tuplin.yaml --json``: links, couplings, mobility, screw system,
    geometric constraint r1 - r3 = r2 - r4 and the efficiency in friction coefficients."""
    result = run(catalog_path("tuplin"), "--json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["links"] == ["1", "2", "3/4", "5"]
    assert [c["name"] for c in doc["couplings"]] == list("ABCDE")
    assert doc["degrees_of_freedom"] == 1
    assert doc["screw_system_order"] == 2
    assert doc["geometric_constraints"] == ["r1 - r3 = r2 - r4"]
    eff = doc["efficiency_friction_form"]
    assert (eff["input"], eff["output"]) == ("A", "B")
    names = {n: sympy.Symbol(n, positive=True) for n in ("r1", "r2", "r3", "zeta_C", "zeta_D")}
    names.update({n: sympy.Symbol(n, integer=True, nonzero=True) for n in ("sigma_C", "sigma_D")})
    expr = sympy.sympify(eff["expression"], locals=names)
    r1, r2, r3, zC, zD = (names[n] for n in ("r1", "r2", "r3", "zeta_C", "zeta_D"))
    eta71 = (r2 - r1) * (zD - r2) * (zC - r3) / (r2 * r3 * (zC - zD - r1 + r2))
    assert equal(expr.subs({names["sigma_C"]: -1, names["sigma_D"]: -1}), eta71)
    assert {s["symbol"] for s in eff["sign_conditions"]} == {"sigma_C", "sigma_D"}


def test_output_file_is_written_and_input_never_overwritten(tmp_path):
    src = tmp_path / "pair.yaml"
    shutil.copy(catalog_path("simple_pair"), src)
    before = src.read_text()
    out = tmp_path / "pair.json"
    assert run(str(src), "--json", "-o", str(out)).returncode == 0
    assert json.loads(out.read_text())["degrees_of_freedom"] == 1
    refused = run(str(src), "--json", "-o", str(src))
    assert refused.returncode == 2 and "refusing to overwrite" in refused.stderr
    assert src.read_text() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.json", "pair.yaml"]


def test_missing_file_is_a_clear_error(tmp_path):
    result = run(str(tmp_path / "nope.yaml"))
    assert result.returncode == 2 and "cannot read the file" in result.stderr
    assert "Traceback" not in result.stderr


def test_console_script_installed():
    exe = shutil.which("derive")
    assert exe is not None, "pip install -e . must install the derive command"
    result = subprocess.run([exe, catalog_path("simple_pair")], capture_output=True, text=True, check=False)
    assert result.returncode == 0
    assert "r1*(r2 - zeta_C)/(r2*(r1 + zeta_C))" in result.stdout
