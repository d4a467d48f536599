"""Geometry from the topology: the same train whatever the order of its entries, states
that need no hints, and geometric constraints applied to every output.

Expected numbers here come from hand derivations written in the docstrings (Willis in
the carrier frame), from the textbook ratios, or from the same train written another
way; none is a value the engine produced and the test pinned.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
import sympy
import yaml

import davies_sym
from davies_sym.cli import main
from davies_sym.efficiency.parameter_domain import ParameterDomain

from conftest import catalog_path, efficiency_or_refusal

R = sympy.Rational


def _permuted(text: str, seed: int) -> str:
    """The file with every mesh's gears reversed and the links, gears and couplings
    mappings (and lists) shuffled."""
    data = yaml.safe_load(text)
    rng = random.Random(seed)
    for key in ("links", "gears", "couplings"):
        entries = data.get(key)
        if isinstance(entries, dict):
            items = list(entries.items())
            rng.shuffle(items)
            data[key] = dict(items)
        elif isinstance(entries, list):
            rng.shuffle(entries)
    for entry in data["couplings"].values():
        if entry.get("type") == "mesh":
            entry["gears"] = entry["gears"][::-1]
            if isinstance(entry.get("efficiency"), list):
                entry["efficiency"] = entry["efficiency"][::-1]
        elif entry.get("type") == "revolute":
            entry["links"] = entry["links"][::-1]
    return yaml.safe_dump(data, sort_keys=False)


def _sets(train: davies_sym.Train) -> dict[str, davies_sym.VariantSet]:
    if not train.states:
        return {"": davies_sym.derive(train)}
    return {st.name: davies_sym.derive(davies_sym.train_in_state(train, st)) for st in train.states}


def _points(vs: davies_sym.VariantSet, count: int) -> list[dict[sympy.Symbol, sympy.Expr]]:
    domain = ParameterDomain.of(vs.train, vs.analysis.network.layout)
    etas = [s for s in vs.symbols if str(s).startswith("eta")]
    return [{**p, **{e: R(90 + k, 100) for k, e in enumerate(etas)}} for p in domain.samples(count, seed=3, extra=etas)]


CATALOG_ONE_DOF = [
    "simple_pair",
    "tuplin",
    "planetary_simple",
    "wolfrom",
    "simpson",
    "ravigneaux",
    "litvin_face_drive",
    "humpage",
]


@pytest.mark.slow
@pytest.mark.parametrize("name", CATALOG_ONE_DOF)
def test_every_catalog_train_is_the_same_in_any_order(name: str) -> None:
    """Reversing every mesh's gears and every bearing's links and shuffling the entries
    changes neither the speed ratio nor the efficiency, in any state or input direction."""
    text = Path(catalog_path(name)).read_text()
    original = _sets(davies_sym.loads(text, f"{name}.yaml"))
    for seed in (1,):
        permuted = _sets(davies_sym.loads(_permuted(text, seed), f"{name}-permuted.yaml"))
        assert permuted.keys() == original.keys()
        for state, vs in original.items():
            other = permuted[state]
            ratio, other_ratio = vs.analysis.speed_ratio().to_expr(), other.analysis.speed_ratio().to_expr()
            assert sympy.simplify(ratio - other_ratio) == 0, (state, ratio, other_ratio)
            for point in _points(vs, 4):
                for port in (vs.train.ports.input, vs.train.ports.output):
                    assert efficiency_or_refusal(other, point, port) == efficiency_or_refusal(vs, point, port), (
                        state,
                        port,
                        point,
                    )


def test_tuplin_reversed_meshes_give_laus_eq_76() -> None:
    """Laus 2011 eq. (76), z = 80, 60, 30, 35 with modules 1 and 2 mm: 0.9462 with A as input,
    written with every mesh's gears and every bearing's links in the other order."""
    text = _permuted(Path(catalog_path("tuplin")).read_text(), 7)
    vs = davies_sym.derive(davies_sym.loads(text, "tuplin.yaml"))
    values = {
        vs.train.symbols[k]: R(v)
        for k, v in {"r1": 40, "r2": 60, "r3": 15, "r4": 35, "eta_C": "99/100", "eta_D": "99/100"}.items()
    }
    assert abs(float(vs.evaluate(values, "A")) - 0.9462) < 5e-5
    assert abs(float(vs.evaluate(values, "B")) - 0.9443) < 5e-5


STEPPED = """
name: stepped planet, sun fixed, carrier in, ring out
links: [h, c, p, r]
reference: h
gears:
  S: {link: h, radius: 20}
  P1: {link: p, radius: 30}
  P2: {link: p, radius: 15}
  R: {link: r, radius: 65, internal: true}
couplings:
  A: {type: revolute, links: [h, c]}
  B: {type: revolute, links: [h, r]}
  E: {type: revolute, links: [c, p]}
  M1: {type: mesh, gears: [S, P1], efficiency: 0.98}
  M2: {type: mesh, gears: [R, P2], efficiency: 0.99}
ports: {input: A, output: B}
"""


@pytest.mark.parametrize("spelling", ["as written", "gears reversed", "bearings reversed"])
def test_stepped_planet_by_hand(spelling: str) -> None:
    """Carrier frame: i0 = w_R'/w_S' = -(rS rP2)/(rP1 rR) = -2/13, so w_R = (1 - i0) w_C = 15/13 w_C
    (sun fixed).  The sun delivers power in the carrier frame (T_S = 2/13 T_R lossless, w_S' = -w_C),
    so T_R w_R' = -eta0 T_S w_S' with eta0 = 0.98 * 0.99, and eta = 15 eta0 / (13 eta0 + 2)."""
    text = STEPPED
    if spelling == "gears reversed":
        text = text.replace("[S, P1]", "[P1, S]").replace("[R, P2]", "[P2, R]")
    elif spelling == "bearings reversed":
        text = text.replace("[h, c]", "[c, h]").replace("[c, p]", "[p, c]").replace("[h, r]", "[r, h]")
    vs = davies_sym.derive(davies_sym.loads(text, "stepped.yaml"))
    eta0 = R(98, 100) * R(99, 100)
    assert vs.evaluate({}, "A") == 15 * eta0 / (13 * eta0 + 2)
    assert vs.analysis.speed_ratio().to_expr() == R(13, 15)


SIMPSON_WITHOUT_HINTS = Path(catalog_path("simpson")).read_text().replace(", at: 0}", "}").replace(", axis: p1}", "}")


def test_simpson_needs_neither_at_nor_axis() -> None:
    """The Simpson set with a gearless housing and no `at:` or `axis:` hints: every state
    gives the textbook ratio, 1st (R1 + R2 + S)/R1, 2nd 1 + S/R1, 3rd 1, reverse -R2/S."""
    assert " at: " not in SIMPSON_WITHOUT_HINTS and " axis: " not in SIMPSON_WITHOUT_HINTS
    train = davies_sym.loads(SIMPSON_WITHOUT_HINTS, "simpson.yaml")
    rs, rr1, rr2 = (train.symbols[n] for n in ("rs", "rr1", "rr2"))
    expected = {
        "first": (rr1 + rr2 + rs) / rr1,
        "second": 1 + rs / rr1,
        "third": sympy.Integer(1),
        "reverse": -rr2 / rs,
    }
    for st in train.states:
        ratio = davies_sym.analyse(davies_sym.train_in_state(train, st)).speed_ratio().to_expr()
        assert sympy.simplify(ratio - expected[st.name]) == 0, st.name


CLUTCHED_CARRIER = """
name: simple planetary set with a clutch from the gearless carrier to the sun
links: [0, s, c, p, r]
reference: 0
gears:
  S: {link: s, radius: 20}
  P: {link: p, radius: 10}
  R: {link: r, radius: 40, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, r]}
  K: {type: revolute, links: [0, c]}
  J: {type: revolute, links: [c, p]}
  M1: {type: mesh, gears: [P, S]}
  M2: {type: mesh, gears: [P, R]}
ports: {input: A, output: B}
states:
  reduction: {input: A, output: K, brake: [r]}
  locked: {input: A, output: B, clutch: [[c, s]]}
  fixed_carrier: {input: A, output: B, brake: [c]}
"""


def test_braking_or_clutching_a_gearless_carrier() -> None:
    """Ring braked: sun in, carrier out, 1 + R/S = 3; carrier clutched to the sun: the set
    turns as a block, ratio 1, no loss; carrier braked: -R/S = -2 with eta = eta_M1 eta_M2."""
    train = davies_sym.loads(CLUTCHED_CARRIER, "clutched.yaml")
    sets = {st.name: davies_sym.derive(davies_sym.train_in_state(train, st)) for st in train.states}
    assert sets["reduction"].analysis.speed_ratio().to_expr() == 3
    assert sets["locked"].analysis.speed_ratio().to_expr() == 1
    assert sets["fixed_carrier"].analysis.speed_ratio().to_expr() == -2
    eta = {
        sets["fixed_carrier"].train.symbols["eta_M1"]: R(97, 100),
        sets["fixed_carrier"].train.symbols["eta_M2"]: R(99, 100),
    }
    assert sets["fixed_carrier"].evaluate(eta, "A") == R(97, 100) * R(99, 100)
    locked = sets["locked"]
    assert locked.evaluate({s: R(9, 10) for s in locked.symbols}, "A") == 1


def test_dependent_radius_is_checked_not_used(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Tuplin: r4 = r2 + r3 - r1 (Laus section 3.4.1.6).  A consistent r4 is accepted; r4 = 36
    with r1, r2, r3 = 40, 60, 15 is refused with the relation, both values and the difference,
    by the command line (exit 2), the API and the generated module."""
    tuplin = catalog_path("tuplin")
    base = ["r1=40", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99"]
    assert main([tuplin, "--quiet", "--eval", *base, "r4=35"]) == 0
    consistent = capsys.readouterr().out.splitlines()[-1]
    assert main([tuplin, "--quiet", "--eval", *base]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == consistent
    assert main([tuplin, "--quiet", "--eval", *base, "r4=36"]) == 2
    err = capsys.readouterr().err
    assert "r4 = -r1 + r2 + r3" in err and "gives 35" in err and "difference is 1" in err
    vs = davies_sym.derive(davies_sym.load(tuplin))
    values = {
        vs.train.symbols[k]: R(v)
        for k, v in {"r1": 40, "r2": 60, "r3": 15, "r4": 36, "eta_C": "99/100", "eta_D": "99/100"}.items()
    }
    with pytest.raises(davies_sym.DesignError, match="breaks the relation"):
        vs.evaluate(values, "A")
    module = tmp_path / "tuplin_module.py"
    assert main([tuplin, "--quiet", "--python", str(module)]) == 0
    namespace: dict[str, object] = {}
    exec(compile(module.read_text(), str(module), "exec"), namespace)  # the module this test generated
    efficiency = namespace["efficiency"]
    assert efficiency(r1=40, r2=60, r3=15, r4=35, eta_C=0.99, eta_D=0.99) == efficiency(  # type: ignore[operator]
        r1=40, r2=60, r3=15, eta_C=0.99, eta_D=0.99
    )
    with pytest.raises(Exception, match=r"r4 = 36.0 breaks the relation r4 = -r1 \+ r2 \+ r3"):
        efficiency(r1=40, r2=60, r3=15, r4=36, eta_C=0.99, eta_D=0.99)  # type: ignore[operator]


def test_independent_parameters_and_tooth_numbers() -> None:
    """Tuplin in symbolic tooth numbers with one module: the constraint z1 - z3 = z2 - z4
    (the module divides out) is solved for the parameter `independent:` leaves free, and the
    efficiency is the same whichever it is (z = 80, 60, 30, 10)."""
    text = """
name: Tuplin in tooth numbers
links: [1, 2, 3/4, 5]
reference: 1
gears:
  1: {link: 1, teeth: z1, module: m, internal: true}
  2: {link: 2, teeth: z2, module: m, internal: true}
  3: {link: 3/4, teeth: z3, module: m}
  4: {link: 3/4, teeth: z4, module: m}
couplings:
  A: {type: revolute, links: [1, 5]}
  B: {type: revolute, links: [1, 2]}
  C: {type: mesh, gears: [3, 1]}
  D: {type: mesh, gears: [4, 2]}
  E: {type: revolute, links: [5, 3/4]}
ports: {input: A, output: B}
"""
    numbers = {"z1": 80, "z2": 60, "z3": 30, "z4": 10, "m": 2, "eta_C": R(99, 100), "eta_D": R(98, 100)}
    results = []
    for independent in (None, "[z2, z3, z4]", "[z1, z2, z4]"):
        source = text if independent is None else text + f"independent: {independent}\n"
        vs = davies_sym.derive(davies_sym.loads(source, "z.yaml"))
        (relation,) = vs.train.dependent or ()
        assert str(relation.symbol) == {None: "z4", "[z2, z3, z4]": "z1", "[z1, z2, z4]": "z3"}[independent]
        results.append(vs.evaluate({vs.train.symbols[k]: R(v) for k, v in numbers.items()}, "A"))
    assert results[0] == results[1] == results[2]


def test_independent_must_leave_something_to_solve() -> None:
    text = Path(catalog_path("tuplin")).read_text() + "independent: [r1, r2, r3, r4]\n"
    with pytest.raises(davies_sym.GeometryError, match="leaves no parameter to solve for"):
        davies_sym.derive(davies_sym.loads(text, "tuplin.yaml"))


STEPPED_TWO_MODULES = """\
name: stepped planetary, two modules
{independent}
links:
  0: {{description: housing and ring}}
  s: {{description: sun}}
  p: {{description: stepped planet}}
  c: {{description: carrier}}
reference: 0
gears:
  S: {{link: s, teeth: z1, module: m1}}
  P1: {{link: p, teeth: z2, module: m1}}
  P2: {{link: p, teeth: z3, module: m2}}
  R: {{link: 0, teeth: z4, module: m2, internal: true}}
couplings:
  A: {{type: revolute, links: [0, s]}}
  B: {{type: revolute, links: [0, c]}}
  D: {{type: revolute, links: [c, p]}}
  C: {{type: mesh, gears: [S, P1], efficiency: eta_1}}
  E: {{type: mesh, gears: [P2, R], efficiency: eta_2}}
ports: {{input: A, output: B}}
"""


@pytest.mark.parametrize(
    "independent",
    ["", "independent: [z1, z2, z3, z4, m1]", "independent: [z1, z2, z3, z4, m2]", "independent: [z1, z2, z3, m1, m2]"],
    ids=["default", "m2-dependent", "m1-dependent", "z4-dependent"],
)
def test_a_stepped_planetary_with_two_symbolic_modules(tmp_path: Path, independent: str) -> None:
    """Sun z1 and planet z2 in module m1, the planet's second gear z3 and the ring z4 in
    module m2, the ring held: whichever symbol the coaxial condition m1 (z1 + z2) = m2 (z4 - z3)
    gives (a module made the dependent one used to end in a sympy PolynomialError), the
    train derives.  By hand (Willis, carrier frame): k = z2 z4 / (z1 z3), speed ratio 1 + k,
    efficiency sun -> carrier (1 + eta_1 eta_2 k) / (1 + k); at m1 = 2, z1 = 20, z2 = 30,
    m2 = 5/2, z3 = 16, z4 = 56 (50 = 50 on both sides) with eta = 0.98, 0.97."""
    path = tmp_path / "stepped.yaml"
    path.write_text(STEPPED_TWO_MODULES.format(independent=independent))
    variants = davies_sym.derive(davies_sym.load(str(path)))
    design = {"m1": 2, "z1": 20, "z2": 30, "m2": R(5, 2), "z3": 16, "z4": 56, "eta_1": R(98, 100), "eta_2": R(97, 100)}
    given = {k: v for k, v in design.items() if k not in {str(r.symbol) for r in variants.train.dependent or ()}}
    k = R(30 * 56, 20 * 16)
    assert variants.evaluate(given, "A") == (1 + R(98 * 97, 10000) * k) / (1 + k)
    point = variants.design_point(given, "A")
    assert point.speed_ratio == 1 + k
    # No identity is printed as a constraint: the text names the one coaxial condition.
    out = tmp_path / "out.txt"
    assert main([str(path), "--quiet", "-o", str(out)]) == 0
    assert out.read_text().count("geometric constraint:") == 1


def test_a_file_with_states_prints_its_geometric_constraints(tmp_path: Path) -> None:
    """The states share the file's geometry, so its text and JSON give the constraints once,
    for all: in the Simpson set each planet spans sun to ring, r_p = (r_ring - r_sun) / 2."""
    text = tmp_path / "simpson.txt"
    assert main([catalog_path("simpson"), "--quiet", "-o", str(text)]) == 0
    lines = text.read_text().splitlines()
    assert "  geometric constraint: rp1 + rs = -rp1 + rr1, so rp1 = rr1/2 - rs/2" in lines[1:3]
    assert "  geometric constraint: rp2 + rs = -rp2 + rr2, so rp2 = rr2/2 - rs/2" in lines[1:3]
    document = tmp_path / "simpson.json"
    assert main([catalog_path("simpson"), "--quiet", "--json", "-o", str(document)]) == 0
    data = yaml.safe_load(document.read_text())
    assert data["dependent_parameters"] == {"rp1": "rr1/2 - rs/2", "rp2": "rr2/2 - rs/2"}
    assert len(data["geometric_constraints"]) == 2


def test_a_module_solved_from_the_constraint_leaves_its_tooth_number_free(tmp_path: Path) -> None:
    """Tuplin's second annulus in teeth and a module, the module the dependent symbol:
    m2 = 2 (r1 - r3 + 40) / z2 leaves z2 in no radius, only in the fact m2 > 0 (the sampled
    regions once missed it: KeyError z2).  By hand (Willis, carrier frame, annulus 1 held):
    w2 / wc = 1 - 40 r1 / (r2 r3) with r2 = r1 - r3 + 40; at r1 = 55, r3 = 35 (r2 = 60,
    z2 = 30, m2 = 4) the speed ratio carrier over annulus 2 is -21."""
    path = tmp_path / "tuplin.yaml"
    path.write_text(
        "name: Tuplin with a module\nlinks: [1, 2, 3/4, 5]\nreference: 1\ngears:\n"
        "  1: {link: 1, radius: r1, internal: true}\n  2: {link: 2, teeth: z2, module: m2, internal: true}\n"
        "  3: {link: 3/4, radius: r3}\n  4: {link: 3/4, radius: 40}\ncouplings:\n"
        "  A: {type: revolute, links: [1, 5]}\n  B: {type: revolute, links: [1, 2]}\n"
        "  C: {type: mesh, gears: [1, 3]}\n  D: {type: mesh, gears: [2, 4]}\n"
        "  E: {type: revolute, links: [3/4, 5]}\nports: {input: A, output: B}\n"
    )
    variants = davies_sym.derive(davies_sym.load(str(path)))
    point = variants.design_point({"r1": 55, "r3": 35, "z2": 30, "eta_C": 1, "eta_D": 1}, "A")
    assert point.speed_ratio == -21 and point.efficiency == 1


def test_modules_solved_from_the_constraints_in_any_symbol_names(tmp_path: Path) -> None:
    """Two more trains whose dependent symbol is a module.  A stepped planet, sun (z1,
    module 1) held, ring 80 teeth of module m2 = (z1 + a) / (80 - b) the output, carrier
    the input: drawing designs once divided by zero on the pole b = 80.  By hand,
    w_ring / w_carrier = 1 + b z1 / (80 a).  A Wolfrom set with the sun held, module L of sun,
    planet and first ring solved from the second ring's loop (a relation over a quotient
    once failed in sympy's degree): r1 = z1 + 2 z2 whatever L, and by hand
    |w_r1 / w_r2| = 2 (z1 + z2) z2 jnp / ((z1 + 2 z2) (jnp z2 + i32 z1))."""
    stepped = tmp_path / "stepped.yaml"
    stepped.write_text(
        "name: stepped\nlinks: [0, r, p, c]\nreference: 0\ngears:\n"
        "  S: {link: 0, teeth: z1, module: 1}\n  P1: {link: p, teeth: a, module: 1}\n"
        "  P2: {link: p, teeth: b, module: m2}\n  R: {link: r, teeth: 80, module: m2, internal: true}\n"
        "couplings:\n  A: {type: revolute, links: [0, c]}\n  B: {type: revolute, links: [0, r]}\n"
        "  D: {type: revolute, links: [c, p]}\n  SP: {type: mesh, gears: [S, P1]}\n  PR: {type: mesh, gears: [P2, R]}\n"
        "ports: {input: A, output: B}\n"
    )
    variants = davies_sym.derive(davies_sym.load(str(stepped)))
    point = variants.design_point({"z1": 30, "a": 20, "b": 30, "eta_SP": 1, "eta_PR": 1}, "A")
    assert point.speed_ratio == 1 / (1 + R(30 * 30, 80 * 20)) and point.efficiency == 1
    wolfrom = tmp_path / "wolfrom.yaml"
    wolfrom.write_text(
        "name: wolfrom\nlinks: [0, r1, r2, p, c]\nreference: 0\nindependent: [i32, z2, jnp, z1]\ngears:\n"
        "  S: {link: 0, teeth: z1, module: L}\n  P1: {link: p, teeth: z2, module: L}\n"
        "  R1: {link: r1, teeth: r1, module: L, internal: true}\n  P2: {link: p, teeth: i32, module: 1}\n"
        "  R2: {link: r2, teeth: jnp, module: 1, internal: true}\ncouplings:\n"
        "  H: {type: revolute, links: [c, p]}\n  K: {type: revolute, links: [c, 0]}\n"
        "  SP: {type: mesh, gears: [S, P1]}\n  D: {type: mesh, gears: [R1, P1]}\n"
        "  In: {type: revolute, links: [0, r1]}\n  E: {type: mesh, gears: [R2, P2]}\n"
        "  Out: {type: revolute, links: [0, r2]}\nports: {input: In, output: Out}\n"
    )
    variants = davies_sym.derive(davies_sym.load(str(wolfrom)))
    relations = {str(r.symbol): r.expression for r in variants.train.dependent or ()}
    assert (
        sympy.expand(relations["r1"] - sympy.Symbol("z1", positive=True) - 2 * sympy.Symbol("z2", positive=True)) == 0
    )
    z1, z2, i32, jnp = 18, 20, 22, 64
    point = variants.design_point(
        {"z1": z1, "z2": z2, "i32": i32, "jnp": jnp, **dict.fromkeys(("eta_SP", "eta_D", "eta_E"), 1)}
    )
    assert abs(point.speed_ratio) == R(2 * (z1 + z2) * z2 * jnp, (z1 + 2 * z2) * (jnp * z2 + i32 * z1))
