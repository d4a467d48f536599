"""A rack and its pinion (``type: rack``), checked against hand derivations.

The expected values are force balances of the rack written in the docstrings: the mesh
passes its ordinary efficiency of the power (eta_P pinion driving, eta_R rack driving),
and a guide pressed by the mesh (``pressed_by``) takes the tooth force's separating
component tan(alpha) U, whose Coulomb friction mu tan(alpha) |U| the rack pays.  They are
evaluated exactly at rational points (cos and sin of the pressure angle on the unit
circle), in several spellings of one train, and the file's refusals are checked entry by
entry.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
import sympy
from harness.helpers import assert_edit_refused, run_main

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.network.analysis import Analysis

ROOT = Path(__file__).resolve().parents[1]

RACK = """
name: rack
links: [0, {p}, {k}]
reference: 0
gears:
  {P}: {{link: {p}, radius: r}}
couplings:
  A: {{type: revolute, links: [0, {p}]}}
  G: {{type: prismatic, links: [0, {k}], direction: {d}{guide}}}
  C: {{type: rack, pinion: {P}, rack: {k}, direction: {d}{mesh}}}
ports: {{input: A, output: G}}
"""

#: A spur pair whose second shaft carries the pinion: the rack is the second stage.
COMPOUND = """
name: pair then rack
links: [0, 1, 2, k]
reference: 0
gears:
  "1": {link: 1, radius: r1}
  "2": {link: 2, radius: r2}
  P: {link: 2, radius: rp}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 2]}
  M: {type: mesh, gears: ["1", "2"], efficiency: eta_M}
  C: {type: rack, pinion: P, rack: k, direction: -y, pressure_angle: alpha, efficiency: eta_C}
  G: {type: prismatic, links: [0, k], direction: -y, friction: {coulomb: mu, pressed_by: C}}
ports: {input: A, output: G}
"""


def _rack(
    p: str = "p", k: str = "k", pinion: str = "P", d: str = "x", guide: str = "", mesh: str = ""
) -> davies_sym.Train:
    return davies_sym.loads(RACK.format(p=p, k=k, P=pinion, d=d, guide=guide, mesh=mesh), "rack.yaml")


def _unit_circle(rng: random.Random) -> tuple[sympy.Rational, sympy.Rational]:
    """cos and sin of an angle in (0, 90 deg) at a rational point of the unit circle."""
    t = sympy.Rational(rng.randint(1, 99), 100)
    return (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)


def _values(train: davies_sym.Train, **numbers: sympy.Expr) -> dict[sympy.Symbol, sympy.Expr]:
    return {train.symbols[k]: v for k, v in numbers.items()}


@pytest.mark.parametrize(
    ("p", "k", "pinion", "d"),
    [("p", "k", "P", "x"), ("shaft", "bar", "pinion", "-x"), ("a", "b", "z1", "y"), ("p", "k", "P", "-y")],
)
def test_mesh_efficiency_alone_either_side_driving(p: str, k: str, pinion: str, d: str) -> None:
    """No other loss: the pinion's power T w reaches the rack as eta_P T w, and the rack's
    F v reaches the pinion as eta_R F v, in every spelling (link and gear names, the
    rack's direction).  The speed ratio is the pitch radius: v = r w."""
    train = _rack(p, k, pinion, d, mesh=", efficiency: [eta_P, eta_R]")
    variants = derive_variants(train)
    eta_p, eta_r = train.symbols["eta_P"], train.symbols["eta_R"]
    assert {(v.input, v.output): v.efficiency for v in variants.variants} == {("A", "G"): eta_p, ("G", "A"): eta_r}
    ratio = Analysis(train).speed_ratio().to_expr()
    assert sympy.cancel(ratio**2 - 1 / train.symbols["r"] ** 2) == 0


@pytest.mark.parametrize("d", ["x", "-y"])
def test_guide_pressed_by_the_separating_force_by_hand(d: str) -> None:
    """Pinion driving: the rack takes the tooth force U with U v = eta_P T w, the separating
    force tan(alpha) U presses the guide, and mu tan(alpha) U v is lost there: eta =
    eta_P (1 - mu tan(alpha)).  Rack driving: the force F on the rack pushes U through the
    guide, F = U (1 + mu tan(alpha)), and eta_R U v reaches the pinion: eta = eta_R / (1 +
    mu tan(alpha))."""
    train = _rack(
        d=d,
        guide=", friction: {coulomb: mu, pressed_by: C}",
        mesh=", pressure_angle: alpha, efficiency: [eta_P, eta_R]",
    )
    variants = derive_variants(train)
    rng = random.Random(11)
    for _ in range(5):
        cos, sin = _unit_circle(rng)
        eta_p, eta_r = (sympy.Rational(rng.randint(85, 99), 100) for _ in range(2))
        mu, r = sympy.Rational(rng.randint(1, 30), 100), sympy.Rational(rng.randint(5, 80))
        values = _values(train, r=r, eta_P=eta_p, eta_R=eta_r, mu=mu, cos_alpha=cos, sin_alpha=sin)
        assert variants.evaluate(values, "A") == eta_p * (1 - mu * sin / cos)
        assert variants.evaluate(values, "G") == eta_r / (1 + mu * sin / cos)


def test_second_stage_rack_multiplies_the_efficiencies_and_self_locks_at_mu_tan_alpha_one() -> None:
    """A spur pair (eta_M) then the rack (eta_C) and its pressed guide: the power the pair
    delivers is the rack stage's input, so eta = eta_M eta_C (1 - mu tan(alpha)); the
    efficiency is zero where mu tan(alpha) = 1 and the drive locks beyond."""
    train = davies_sym.loads(COMPOUND, "compound.yaml")
    variants = derive_variants(train)
    rng = random.Random(3)
    for _ in range(4):
        cos, sin = _unit_circle(rng)
        eta_m, eta_c = sympy.Rational(rng.randint(90, 99), 100), sympy.Rational(rng.randint(90, 99), 100)
        mu = sympy.Rational(rng.randint(1, 20), 100)
        numbers = dict(r1=20, r2=50, rp=15, eta_M=eta_m, eta_C=eta_c, mu=mu, cos_alpha=cos, sin_alpha=sin)
        values = _values(train, **{k: sympy.Integer(v) if isinstance(v, int) else v for k, v in numbers.items()})
        assert variants.evaluate(values, "A") == eta_m * eta_c * (1 - mu * sin / cos)
    forward = next(v for v in variants.variants if (v.input, v.output) == ("A", "G"))
    s = train.symbols
    at_lock = forward.efficiency.subs({s["mu"]: s["cos_alpha"] / s["sin_alpha"]})
    assert sympy.cancel(at_lock) == 0


def test_lossless_limit_is_one() -> None:
    """eta_P = eta_R = 1 and mu = 0: no loss anywhere, efficiency 1 both ways."""
    train = _rack(
        guide=", friction: {coulomb: mu, pressed_by: C}",
        mesh=", pressure_angle: 20, efficiency: [eta_P, eta_R]",
    )
    variants = derive_variants(train)
    values = _values(train, r=sympy.Integer(12), eta_P=sympy.Integer(1), eta_R=sympy.Integer(1), mu=sympy.Integer(0))
    assert variants.evaluate(values, "A") == 1
    assert variants.evaluate(values, "G") == 1


def test_catalog_rack_pinion_through_the_command_line() -> None:
    """`derive catalog/rack_pinion.yaml --eval` gives the hand-derived numbers the file's
    checks state (0.98 (1 - 0.1 tan 20 deg) and 0.97 / (1 + 0.1 tan 20 deg))."""
    import math

    path = str(ROOT / "catalog" / "rack_pinion.yaml")
    tan = math.tan(math.radians(20))
    for port, expected in (("A", 0.98 * (1 - 0.1 * tan)), ("G", 0.97 / (1 + 0.1 * tan))):
        result = run_main([path, "--eval", "r=20", "eta_P=0.98", "eta_R=0.97", "mu=0.1", "--input", port])
        assert result.returncode == 0, result.describe()
        assert float(result.stdout.split()[-1]) == pytest.approx(expected, rel=1e-12)


CATALOG_TEXT = (ROOT / "catalog" / "rack_pinion.yaml").read_text(encoding="utf-8")
MESH_LINE = "C: {type: rack, pinion: P, rack: k, direction: x, pressure_angle: 20, efficiency: [eta_P, eta_R]}"
GUIDE_LINE = "G: {type: prismatic, links: [0, k], direction: x, friction: {coulomb: mu, pressed_by: C}}"


@pytest.mark.parametrize(
    ("old", "new", "at", "entry", "words"),
    [
        ("pinion: P,", "pinion: Q,", "C: {type: rack", "couplings.C.pinion", "Q"),
        ("pinion: P, ", "", "C: {type: rack", "couplings.C", "pinion"),
        ("rack: k,", "rack: p,", "C: {type: rack", "couplings.C.rack", "another link"),
        ("rack: k, direction: x,", "rack: k, direction: z,", "C: {type: rack", "couplings.C.direction", "across"),
        ("rack: k, direction: x,", "rack: k, direction: [1, 0, 0],", "C: {type: rack", "couplings.C.direction", "axis"),
        ("pressure_angle: 20", "pressure_angle: 95", "C: {type: rack", "couplings.C.pressure_angle", "degrees"),
        ("pressed_by: C", "pressed_by: A", "G: {type: prismatic", "couplings.G.friction.pressed_by", "no mesh"),
        ("pressed_by: C", "pressed_by: X", "G: {type: prismatic", "couplings.G.friction.pressed_by", "no coupling"),
        (
            "{coulomb: mu, pressed_by: C}",
            "{pressed_by: C}",
            "G: {type: prismatic",
            "couplings.G.friction.pressed_by",
            "coulomb",
        ),
        (", pressure_angle: 20", "", "G: {type: prismatic", "couplings.G.friction.pressed_by", "pressure_angle"),
        ("output: G", "output: C", "output: C", "ports.output", "gear mesh"),
    ],
)
def test_rack_entries_refused_where_written(
    tmp_path: Path, old: str, new: str, at: str, entry: str, words: str
) -> None:
    """Each field of the rack and of a pressed guide refused at its line, exit status 2."""
    assert MESH_LINE in CATALOG_TEXT and GUIDE_LINE in CATALOG_TEXT
    result = assert_edit_refused(tmp_path, CATALOG_TEXT, old, new, at, entry, words)
    assert result.returncode == 2


def test_pressed_by_on_a_bearing_is_refused(tmp_path: Path) -> None:
    """`pressed_by` loads a guide; a revolute's friction refuses it where written."""
    text = CATALOG_TEXT.replace(
        "A: {type: revolute, links: [0, p]}",
        "A: {type: revolute, links: [0, p], friction: {coulomb: z, pressed_by: C}}",
    )
    assert_edit_refused(tmp_path, text, "z", "z", "A: {type: revolute", "couplings.A.friction.pressed_by", "prismatic")


def test_chen_balance_says_the_rack_is_outside_its_scope() -> None:
    """Chen's virtual-power balance covers gear pairs, bearings and lossless sliders: on the
    rack it refuses, naming the couplings, instead of leaving them out of the balance."""
    from davies_sym.efficiency.virtual_power_balance import virtual_power_balance
    from davies_sym.errors import DerivationError

    train = _rack(mesh=", efficiency: [eta_P, eta_R]")
    values = {"r": 20, "eta_P": 0.98, "eta_R": 0.97}
    with pytest.raises(DerivationError, match=r"couplings \['C'\] are outside its scope"):
        virtual_power_balance(train, values)
    # The catalog file's pressure angle is no algebraic number: the scope is still the reason given.
    catalog = davies_sym.load(str(ROOT / "catalog" / "rack_pinion.yaml"))
    with pytest.raises(DerivationError, match=r"couplings \['G', 'C'\] are outside its scope"):
        virtual_power_balance(catalog, {**values, "mu": 0.1})
