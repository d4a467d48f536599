"""What each size parameter of a gear is, in every output that describes it: a tooth
number is a number of teeth of its gear, a module a length of the gears it sizes, a
pitch radius a length of its gear, each naming the gear as the file writes it (not the
gear a geometric constraint moved the symbol into).

The trains are written here: a simple planetary by teeth with a numeric module, a
stepped planetary with two symbolic modules, and a Simpson-like pair of planetary sets
by teeth with operating states.  Each label is read from the ``PARAMETERS`` of the
module ``derive FILE --python OUT.py`` writes, the opening comment of ``--emit c``, the
JSON refusal of a ``--plot`` range outside the parameter's, and the plot's axis label.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path
from types import ModuleType

import pytest
from harness.helpers import run_main

from davies_sym import Train, derive_variants, loads, train_in_state
from davies_sym.efficiency.parameters import parameter_table
from davies_sym.emit.plots import label

LENGTH = "length (one unit for all)"

PLANETARY = """
name: Planetary reduction
links:
  0: {description: housing and annulus}
  s: {description: sun shaft (input)}
  p: {description: planet}
  c: {description: carrier (output)}
reference: 0
gears:
  S: {link: s, teeth: zs, module: 2}
  P: {link: p, teeth: zp, module: 2}
  R: {link: 0, teeth: zr, module: 2, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  D: {type: revolute, links: [c, p]}
  SP: {type: mesh, gears: [S, P], efficiency: eta_SP}
  PR: {type: mesh, gears: [P, R], efficiency: eta_PR}
ports: {input: A, output: B}
"""

STEPPED = """
name: Stepped planetary, two modules
links:
  0: {description: housing and annulus}
  s: {description: sun shaft (input)}
  p: {description: stepped planet}
  c: {description: carrier (output)}
reference: 0
independent: [m1, m2, zs, zp1, zp2]
gears:
  S: {link: s, teeth: zs, module: m1}
  P1: {link: p, teeth: zp1, module: m1}
  P2: {link: p, teeth: zp2, module: m2}
  R: {link: 0, teeth: zr, module: m2, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  D: {type: revolute, links: [c, p]}
  SP: {type: mesh, gears: [S, P1], efficiency: eta_SP}
  PR: {type: mesh, gears: [P2, R], efficiency: eta_PR}
ports: {input: A, output: B}
"""

# The rings come first: the constraints put zs and zpf into ring Rf's radius.
SIMPSON = """
name: Simpson-like set by teeth
links:
  0: {description: housing}
  s: {description: common sun shaft}
  rf: {description: front ring}
  pf: {description: front planet}
  o: {description: "front carrier and rear ring, output"}
  pr: {description: rear planet}
  cr: {description: rear carrier}
reference: 0
gears:
  Rf: {link: rf, teeth: zrf, module: 3, internal: true}
  Pf: {link: pf, teeth: zpf, module: 3}
  S: {link: s, teeth: zs, module: 3}
  Pr: {link: pr, teeth: zpr, module: 3}
  Rr: {link: o, teeth: zrr, module: 3, internal: true}
couplings:
  A: {type: revolute, links: [0, rf], at: 0}
  B: {type: revolute, links: [0, o], at: 0}
  G: {type: revolute, links: [0, s]}
  K: {type: revolute, links: [0, cr], at: 0}
  C: {type: mesh, gears: [S, Pf]}
  D: {type: mesh, gears: [Rf, Pf]}
  E: {type: mesh, gears: [S, Pr]}
  F: {type: mesh, gears: [Rr, Pr]}
  H: {type: revolute, links: [pf, o], axis: pf}
  J: {type: revolute, links: [pr, cr]}
ports: {input: A, output: B}
states:
  first: {description: first gear, input: A, output: B, brake: [cr]}
  second: {description: second gear, input: A, output: B, brake: [s]}
"""

TEETH = "teeth"

#: (train, state) -> name -> (meaning, unit) of every size parameter of the formulas.
EXPECTED: dict[tuple[str, str | None], dict[str, tuple[str, str]]] = {
    ("planetary", None): {
        "zp": ("number of teeth of gear P (link p)", TEETH),
        "zs": ("number of teeth of gear S (link s)", TEETH),
    },
    ("stepped", None): {
        "m1": ("module of gears S, P1", LENGTH),
        "m2": ("module of gears P2, R", LENGTH),
        "zp1": ("number of teeth of gear P1 (link p)", TEETH),
        "zp2": ("number of teeth of gear P2 (link p)", TEETH),
        "zs": ("number of teeth of gear S (link s)", TEETH),
    },
    ("simpson", "first"): {
        "zpf": ("number of teeth of gear Pf (link pf)", TEETH),
        "zpr": ("number of teeth of gear Pr (link pr)", TEETH),
        "zs": ("number of teeth of gear S (link s)", TEETH),
    },
    # The braked sun turns with the housing: its link is 0 in this state.
    ("simpson", "second"): {
        "zpf": ("number of teeth of gear Pf (link pf)", TEETH),
        "zs": ("number of teeth of gear S (link 0)", TEETH),
    },
}
TEXTS = {"planetary": PLANETARY, "stepped": STEPPED, "simpson": SIMPSON}
CASES = list(EXPECTED)


def _ids(case: tuple[str, str | None]) -> str:
    return "-".join(filter(None, case))


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("trains")
    for name, text in TEXTS.items():
        (folder / f"{name}.yaml").write_text(text)
    return folder


def _state(state: str | None) -> list[str]:
    return ["--state", state] if state else []


def _module(path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"labels_{path.stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("case", CASES, ids=_ids)
def test_module_parameters_and_plot_axes_name_each_gear_size(files: Path, case: tuple[str, str | None]) -> None:
    train, state = case
    out = files / f"{_ids(case).replace('-', '_')}.py"
    result = run_main([str(files / f"{train}.yaml"), *_state(state), "--python", str(out), "--quiet"])
    assert result.returncode == 0, result.describe()
    module = _module(out)
    sizes = {p["name"]: (p["meaning"], p["unit"]) for p in module.PARAMETERS if not p["name"].startswith("eta_")}
    assert sizes == EXPECTED[case]
    for name, (meaning, unit) in EXPECTED[case].items():
        assert label(module, name) == f"{name}: {meaning} [{unit}]"


@pytest.mark.parametrize("case", CASES, ids=_ids)
def test_c_header_names_each_gear_size(files: Path, case: tuple[str, str | None]) -> None:
    train, state = case
    result = run_main([str(files / f"{train}.yaml"), *_state(state), "--emit", "c", "--quiet"])
    assert result.returncode == 0, result.describe()
    # The opening comment, its wrapped lines joined: one entry per parameter.
    header = " ".join(line.lstrip(" /*") for line in result.stdout.split("*/")[0].splitlines())
    for name, (meaning, unit) in EXPECTED[case].items():
        assert f" {name} in (0, inf): {meaning} [{unit}] " in " ".join(header.split()) + " ", name


@pytest.mark.parametrize("case", CASES, ids=_ids)
def test_json_refusal_of_a_plot_range_names_each_gear_size(files: Path, case: tuple[str, str | None]) -> None:
    train, state = case
    name, (meaning, _) = next(iter(EXPECTED[case].items()))
    result = run_main(
        [str(files / f"{train}.yaml"), *_state(state), "--plot", f"{name}=-3:-1", "-o", str(files / "x.png"), "--json"]
    )
    assert result.returncode == 2, result.describe()
    reason = json.loads(result.stdout)["reason"]
    assert f"{name} lies in (0, inf) ({meaning}): the interval -3:-1 has no admissible value" in reason


def _first(text: str) -> Train:
    """The train of ``text`` in its state ``first``."""
    train = loads(text)
    return train_in_state(train, train.state("first"))


def test_a_tooth_symbol_on_two_gears_names_both() -> None:
    """Both planets of the Simpson-like set written with one tooth number."""
    table = {
        p.name: (p.meaning, p.unit) for p in parameter_table(derive_variants(_first(SIMPSON.replace("zpr", "zpf"))))
    }
    assert table["zpf"] == ("number of teeth of gears Pf, Pr", TEETH)
    assert table["zs"] == ("number of teeth of gear S (link s)", TEETH)


def test_a_dependent_tooth_number_says_it_is_given_by_the_geometry() -> None:
    """The planet's teeth, solved from the constraint, are a parameter of the tooth-contact
    efficiency of the sun-planet mesh."""
    text = PLANETARY.replace("efficiency: eta_SP", "efficiency: {mu: mu, pressure_angle: 20}").replace(
        "reference: 0", "reference: 0\nindependent: [zs, zr]"
    )
    table = {p.name: (p.meaning, p.unit) for p in parameter_table(derive_variants(loads(text)))}
    assert table["zp"] == (
        "number of teeth of gear P (link p), given by the geometric constraint as zp = zr/2 - zs/2",
        TEETH,
    )
    assert table["zr"] == ("number of teeth of internal gear R (link 0)", TEETH)


def test_a_radius_solved_from_the_geometry_leaves_the_others_their_own_gear() -> None:
    """The same set by radii: the ring radii are the dependent ones, and the sun's and the
    planets' radii stay their own gears', not lengths in ring Rf's radius."""
    text = SIMPSON.replace("teeth: z", "radius: r").replace(", module: 3", "")
    table = {p.name: (p.meaning, p.unit) for p in parameter_table(derive_variants(_first(text)))}
    assert table == {
        **{n: table[n] for n in table if n.startswith("eta_")},
        "rpf": ("pitch radius of gear Pf (link pf)", LENGTH),
        "rpr": ("pitch radius of gear Pr (link pr)", LENGTH),
        "rs": ("pitch radius of gear S (link s)", LENGTH),
    }
