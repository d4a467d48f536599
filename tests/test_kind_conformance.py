"""Every coupling kind of the registry passes one contract (as every estimator passes
scikit-learn's ``check_estimator``): a kind added to `KINDS` fails here until it has an
example train below, on which

- both power directions derive, and at a lossy design both efficiencies lie in (0, 1);
- as every loss vanishes (ordinary efficiencies 1, friction coefficients to 0) the
  efficiency tends to 1 both ways;
- renaming every link and coupling changes no efficiency;
- the powers of all couplings sum to zero (Tellegen's theorem on the coupling network:
  the ports' powers and the losses balance, P_in + P_out + losses = 0), identically in
  the parameters;
- each of its fields, removed where required or written as a mapping where a value
  belongs, is refused at its entry with exit status 2.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy
import yaml
from harness.helpers import assert_refused, run_main
from test_chain_drive import CHAIN

import davies_sym
from davies_sym.network.analysis import Analysis
from davies_sym.topology.coupling_kinds import KINDS
from davies_sym.topology.couplings import coupling_fields

ROOT = Path(__file__).resolve().parents[1]

#: One example train per kind: its file text, the coupling of that kind, and a lossy
#: design (values of every parameter); the lossless design sets efficiencies to 1 and
#: every other loss coefficient named in ``losses`` to 0.
EXAMPLES: dict[str, tuple[str, str, dict[str, object], tuple[str, ...]]] = {
    "revolute": (
        """
name: journal on the input shaft
links: [0, 1, 2]
reference: 0
gears:
  a: {link: 1, radius: r1}
  b: {link: 2, radius: r2}
couplings:
  A: {type: revolute, links: [0, 1], friction: {bearing: {mu: mu_A, radius: s}}}
  B: {type: revolute, links: [0, 2]}
  C: {type: mesh, gears: [a, b], efficiency: eta_C}
ports: {input: A, output: B}
""",
        "A",
        {"r1": 20, "r2": 45, "eta_C": sympy.Rational(97, 100), "mu_A": sympy.Rational(1, 20), "s": 3},
        ("mu_A",),
    ),
    "mesh": (
        """
name: internal pair
links: [0, 1, 2]
reference: 0
gears:
  p: {link: 1, radius: r1}
  R: {link: 2, radius: r2, internal: true}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  C: {type: mesh, gears: [p, R], efficiency: [eta_1, eta_2]}
ports: {input: A, output: B}
""",
        "C",
        {"r1": 15, "r2": 60, "eta_1": sympy.Rational(98, 100), "eta_2": sympy.Rational(96, 100)},
        (),
    ),
    "worm": (
        (ROOT / "catalog" / "worm_drive.yaml").read_text(encoding="utf-8"),
        "W",
        {"gamma": sympy.pi / 5, "alpha_n": sympy.pi / 9, "mu": sympy.Rational(3, 100)},
        ("mu",),
    ),
    "crossed_helical": (
        (ROOT / "catalog" / "crossed_helical.yaml").read_text(encoding="utf-8"),
        "X",
        {},
        ("mu",),
    ),
    "prismatic": (
        """
name: rack in a guide
links: [0, p, k]
reference: 0
gears:
  P: {link: p, radius: r}
couplings:
  A: {type: revolute, links: [0, p]}
  G: {type: prismatic, links: [0, k], direction: y, friction: {coulomb: mu, pressed_by: C}}
  C: {type: rack, pinion: P, rack: k, direction: y, pressure_angle: 25, efficiency: eta_C}
ports: {input: A, output: G}
""",
        "G",
        {"r": 30, "eta_C": sympy.Rational(97, 100), "mu": sympy.Rational(1, 10)},
        ("mu",),
    ),
    "rack": (
        (ROOT / "catalog" / "rack_pinion.yaml").read_text(encoding="utf-8"),
        "C",
        {"r": 20, "eta_P": sympy.Rational(98, 100), "eta_R": sympy.Rational(97, 100), "mu": sympy.Rational(1, 10)},
        ("mu",),
    ),
    "chain": (
        CHAIN,
        "K",
        {
            "z1": 46,
            "z2": 17,
            "r3": 20,
            "r4": 50,
            "eta_1": sympy.Rational(98, 100),
            "eta_2": sympy.Rational(97, 100),
            "eta_C": sympy.Rational(99, 100),
        },
        (),
    ),
    "belt": (
        """
name: belt to an internal gear pair
links: [0, 1, 2, 3]
reference: 0
gears:
  a: {link: 1, radius: r1}
  b: {link: 2, radius: r2}
  c: {link: 2, radius: r3}
  d: {link: 3, radius: r4, internal: true}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  D: {type: revolute, links: [0, 3]}
  V: {type: belt, gears: [a, b], efficiency: eta_V}
  C: {type: mesh, gears: [c, d], efficiency: eta_C}
ports: {input: A, output: D}
""",
        "V",
        {"r1": 40, "r2": 90, "r3": 15, "r4": 60, "eta_V": sympy.Rational(95, 100), "eta_C": sympy.Rational(98, 100)},
        (),
    ),
    "screws": (
        """
name: simple pair, explicit screws (Laus Tables 3 and 4)
links: [0, 1, 2]
reference: 0
couplings:
  A: {type: screws, links: [0, 1], motions: {t_A: {t: 1}}, actions: {U_A: {U: 1}}}
  B: {type: screws, links: [0, 2], motions: {t_B: {t: 1, u: r1 + r2}}, actions: {U_B: {T: -r1 - r2, U: 1}}}
  C:
    type: screws
    links: [1, 2]
    motions: {t_C: {t: 1, u: r1}}
    actions: {U_C: {T: -r1, U: 1}}
    friction: {coulomb: zeta_C}
ports: {input: A, output: B}
""",
        "C",
        {"r1": 20, "r2": 50, "zeta_C": sympy.Rational(1, 2)},
        ("zeta_C",),
    ),
}


def test_every_kind_has_an_example() -> None:
    assert set(EXAMPLES) == set(KINDS)
    for kind, (text, name, _, _) in EXAMPLES.items():
        assert yaml.safe_load(text)["couplings"][name]["type"] == kind


def _design(train: davies_sym.Train, numbers: dict[str, object], parameters: list[sympy.Symbol]) -> dict:
    """The example's numbers, the parameters it leaves out at their catalog design point."""
    values = {s: sympy.sympify(numbers[str(s)]) for s in parameters if str(s) in numbers}
    missing = [s for s in parameters if s not in values]
    if missing:
        check = train.expected[0]
        values |= {s: sympy.nsimplify(check.values[str(s)]) for s in missing}
    return values


#: A loss coefficient near zero: some must be positive (a journal's mu), so the limit is
#: approached, exactly, rather than taken.
TINY = sympy.Rational(1, 10**30)


def _lossless(values: dict, losses: tuple[str, ...]) -> dict:
    return {s: (TINY if str(s) in losses else 1 if str(s).startswith("eta") else v) for s, v in values.items()}


def _renamed(text: str) -> str:
    """Every link and coupling renamed (``x_`` in front), the ports and the rack's link too."""
    data = yaml.safe_load(text)
    links = data["links"]
    names = {str(k): f"x_{k}" for k in links}
    couplings = {str(k): f"x_{k}" for k in data["couplings"]}

    def link(v: object) -> object:
        return names.get(str(v), v)

    data["links"] = [names[str(k)] for k in links]
    data["reference"] = names[str(data["reference"])]
    for gear in (data.get("gears") or {}).values():
        gear["link"] = link(gear["link"])
    renamed = {}
    for k, c in data["couplings"].items():
        if "links" in c:
            c["links"] = [link(v) for v in c["links"]]
        if c.get("type") == "rack":
            c["rack"] = link(c["rack"])
        friction = c.get("friction")
        if isinstance(friction, dict) and "pressed_by" in friction:
            friction["pressed_by"] = couplings[friction["pressed_by"]]
        renamed[couplings[str(k)]] = c
    data["couplings"] = renamed
    data["ports"] = {k: couplings[str(v)] for k, v in data["ports"].items()}
    data.pop("expected", None)
    data.pop("states", None)
    return yaml.safe_dump(data)


@pytest.mark.parametrize("kind", sorted(EXAMPLES))
def test_kind_contract(kind: str) -> None:
    text, _, numbers, losses = EXAMPLES[kind]
    train = davies_sym.loads(text, f"{kind}.yaml")
    variants = davies_sym.derive(train)
    values = _design(train, numbers, list(variants.parameters))
    ports = (train.ports.input, train.ports.output)
    other = davies_sym.derive(davies_sym.loads(_renamed(text), f"{kind}_renamed.yaml"))
    renamed = {p: values[next(s for s in values if str(s) == str(p))] for p in other.parameters}
    for port, twin in zip(ports, (f"x_{p}" for p in ports), strict=True):
        eta = variants.evaluate(values, port)
        assert 0 < float(eta) < 1, (kind, port, eta)
        gap = sympy.N(1 - variants.evaluate(_lossless(values, losses), port), 60)
        assert 0 <= gap < 10**-25, (kind, port, gap)
        assert float(other.evaluate(renamed, twin)) == pytest.approx(float(eta), rel=1e-12), (kind, port)


@pytest.mark.parametrize("kind", sorted(EXAMPLES))
def test_powers_of_all_couplings_balance(kind: str) -> None:
    """Tellegen's theorem: the twists lie in the circuit space and the wrenches in the cutset
    space of one graph, so the couplings' powers sum to zero for any parameters."""
    text = EXAMPLES[kind][0]
    train = davies_sym.loads(text, f"{kind}.yaml")
    analysis = Analysis(train)
    total = None
    for c in train.couplings:
        power = analysis.power_rf(c.name)
        total = power if total is None else total + power
    assert total is not None and total.is_zero(), kind


def _field_cases():
    for kind, (text, name, _, _) in sorted(EXAMPLES.items()):
        entry = yaml.safe_load(text)["couplings"][name]
        for field in coupling_fields(KINDS[kind]):
            if field.key == "type":
                continue
            if field.key in entry and field.required:
                yield pytest.param(kind, field.key, None, id=f"{kind}-{field.key}-removed")
            if field.key in entry:
                yield pytest.param(kind, field.key, {"bogus": [1]}, id=f"{kind}-{field.key}-mapping")


@pytest.mark.parametrize(("kind", "key", "value"), list(_field_cases()))
def test_each_field_refused_at_its_entry(tmp_path: Path, kind: str, key: str, value: object) -> None:
    """A required field removed, or any written field given a mapping of junk: exit 2, one
    message at the coupling's entry (its key where it was written)."""
    text, name, _, _ = EXAMPLES[kind]
    data = yaml.safe_load(text)
    if value is None:
        del data["couplings"][name][key]
    else:
        data["couplings"][name][key] = value
    path = tmp_path / "train.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    result = run_main([str(path), "--quiet"])
    assert_refused(result, path, (f"couplings.{name}",), max_lines=None)
