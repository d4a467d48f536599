"""Hypothesis strategies for valid planar parallel-axis gear trains, each drawn as the
canonical train the oracle solves (:class:`random_trains.RandomTrain`) together with one
spelling of its file (:class:`random_trains.Spelling`), so that :func:`compare.compare`
takes a drawn train as it takes a seeded one.  Every choice comes from Hypothesis: a
failing example shrinks, and a run is repeated or changed by its seed.

What `trains()` draws:

* the family: a fixed-axis pair (external, or pinion and annulus) or compound chain of
  3-4 shafts, or a coaxial set: simple, stepped and double-pinion planetary (the double
  pinion laid out in 2-D with ``placement``), Wolfrom (two rings, the carrier free),
  Tuplin's two annuli, the Simpson and Ravigneaux sets with their operating states;
* the sizes as tooth numbers with one module per group of meshing gears: the meshes of
  a chain each have their own, a stepped planet's second gear and its ring (and the
  second ring of a Wolfrom set, the second annulus of Tuplin's train) another than the
  sun and the first planet, so that one loop ties two modules (now and then each gear
  of a group with a module symbol of its own, of the same value);
* which central member is held and how: its gears written on the housing, braked in a
  state, or several operating states (brakes, and clutches that join two members);
* the spelling: names of links, gears, couplings, states and symbols in every form the
  language allows (ASCII only: digits, underscores, mixed case, spaces and ``/ . + -``
  in links and gears; plain, quoted and YAML-integer scalars; symbols that are words of
  C, Rust, Julia or <math.h>, or read like the engine's own names), free texts (the
  name, descriptions) of any characters, entries and keys in any order, flow or
  block mappings, links as a list or a mapping, sizes as radius symbols, numbers or
  scaled symbols, or as teeth and module (each a symbol or a number), ordinary
  efficiencies (0.5 to 1, a lossless mesh included) by default, as a symbol (possibly
  shared by meshes of equal efficiency), a number or a list of two, the links of
  revolutes and the gears of meshes in either order, optional ``at``, ``axis``,
  ``mesh``, ``internal: false``, ``reference``,
  ``format``, ``degrees_of_freedom``, comments and descriptions, and ``independent:``
  (left out, every size symbol but the dependent ones, or some of them; as a flow list,
  a block list or a single symbol written alone).

Every number is exact: the oracle's radii are module * teeth / 2 of the drawn values,
and the dependent symbols' values satisfy the loops, so the file's geometric
constraints hold whichever symbol the engine solves for.  `stepped_two_modules` builds
one train by hand: the stepped planet whose second module is the dependent symbol.
"""

from __future__ import annotations

import contextlib
import json
import random
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache

import sympy
import yaml
from hypothesis import assume
from hypothesis import strategies as st

from .balance import State
from .random_trains import HOUSING, RandomTrain, Spelling, TGear, TMember

F = Fraction

FAMILIES = ("pair", "chain", "planetary", "stepped", "double_pinion", "wolfrom", "tuplin", "simpson", "ravigneaux")
#: The families whose derivations take well under a second per state.
QUICK_FAMILIES = ("pair", "chain", "planetary", "stepped", "double_pinion", "wolfrom", "tuplin")
#: Module values drawn (a stepped planet's second module follows from its loop).
MODULES = (F(1), F(2), F(1, 2), F(3, 2), F(5, 2), F(3), F(4, 3), F(3, 4))

# -- names ----------------------------------------------------------------------------------

#: Link and gear names: ASCII letters, digits, spaces and _ / . + - (docs/topology.md).
LINK_NAME = r"[A-Za-z0-9_](?:[A-Za-z0-9_/.+ -]{0,12}[A-Za-z0-9_/.+-])?"
LINK_WORDS = (
    "0",
    "1",
    "2",
    "3/4",
    "5",
    "12",
    "frame",
    "housing",
    "Sun",
    "sun shaft",
    "ring.out",
    "q-2",
    "x+y",
    "arm",
    "Planet A",
    "p_1",
    "UP",
    "lower",
    "h/2",
    "_",
    "__init__",
    "1.5",
    "007",
    "true",
    "null",
    "NaN",
    "S",
    "s",
    "1e5",
    "2 + 2",
)
#: Coupling and state names: ASCII letters, digits and underscores.
COUPLING_NAME = r"[A-Za-z0-9_]{1,12}"
COUPLING_WORDS = (
    "A",
    "B",
    "In",
    "out",
    "1",
    "12",
    "007",
    "_",
    "__",
    "_a",
    "b1",
    "m1",
    "Z",
    "if",
    "None",
    "True",
    "self",
    "int",
    "NAN",
    "I",
    "end",
    "fn",
    "inf",
    "nan",
    "eta",
    "zeta",
    "T",
    "main",
    "yes",
    "on",
)
#: Symbol names: conventional ones, then ones that other languages or the engine's own
#: names might trip on (screw coordinates, torque and speed names, C, Rust, Julia and
#: Octave words, functions of <math.h>, the generated functions' names).
SYMBOL_WORDS = (
    "z1",
    "z2",
    "z3",
    "z4",
    "zs",
    "zp",
    "zr",
    "Z_sun",
    "m",
    "m1",
    "m2",
    "mod2",
    "r1",
    "rA",
    "R_ring",
    "k",
    "n_1",
    "N",
    "E",
    "I",
    "S",
    "Q",
    "O",
    "t",
    "u",
    "v",
    "w",
    "x",
    "y",
    "r",
    "s",
    "T_A",
    "w_A",
    "omega_A",
    "tau_A",
    "zeta_Q9",
    "sigma_Q9",
    "eta_Q9",
    "beta",
    "gamma",
    "alpha",
    "mu",
    "nu",
    "phi",
    "theta",
    "lam",
    "Lambda",
    "M_PI",
    "M_E",
    "pow",
    "fabs",
    "exp",
    "log",
    "fmin",
    "fmax",
    "copysign",
    "isnan",
    "EOF",
    "NULL",
    "errno",
    "y0",
    "j1",
    "end",
    "function",
    "elseif",
    "local",
    "Some",
    "Ok",
    "Err",
    "Vec",
    "f64",
    "i32",
    "usize",
    "Box",
    "String",
    "Option",
    "Result",
    "drop",
    "main",
    "printf",
    "double",
    "auto",
    "register",
    "restrict",
    "fn",
    "mut",
    "impl",
    "crate",
    "pub",
    "loop",
    "ret",
    "condition_1",
    "region_1",
    "variant_1",
    "efficiency_1",
    "efficiency_A",
    "speed_ratio_1",
    "sensitivity_z1",
    "reason",
    "holds_1",
    "agrees_1",
    "negative_1",
    "value_1",
    "from_A",
    "d_x",
    "a_1",
    "c_1",
    "input_port",
    "port",
    "numpy_",
    "jnp",
    "torch",
    "cp",
)
#: Prefixes of the symbols the engine names after couplings (docs/topology.md).
COUPLING_SYMBOL_PREFIXES = ("eta", "zeta", "sigma", "mu", "T", "w", "omega", "tau", "rho", "b", "D")


@cache
def _check_name() -> Callable[[str], str | None]:
    # The language's rule for symbol names (Python keywords, built-ins, the grammar's and
    # the formula modules' names are refused, each with a located message).
    from davies_sym.topology.expressions import check_name

    return check_name


def _symbol_ok(name: str) -> bool:
    return _check_name()(name) is None


def plain(name: str) -> bool:
    """Whether ``name`` reads back as itself written as a plain YAML scalar (a string, or
    an integer the loader takes as its digits), both as a value and as a key."""
    if name != name.strip() or not name:
        return False
    try:
        as_value = yaml.safe_load(f"[{name}]")
        as_key = yaml.safe_load(f"{name}: 1")
    except yaml.YAMLError:
        return False
    if not (isinstance(as_value, list) and len(as_value) == 1 and isinstance(as_key, dict) and len(as_key) == 1):
        return False
    for value in (as_value[0], next(iter(as_key))):
        if isinstance(value, bool) or not isinstance(value, (str, int)) or str(value) != name:
            return False
    return True


def quoted(text: str) -> str:
    """``text`` as a YAML double-quoted scalar: printable characters as they are, the rest
    (line breaks, controls, the quote and the backslash) escaped."""
    out = []
    for ch in text:
        code = ord(ch)
        if ch in '"\\':
            out.append("\\" + ch)
        elif (
            0x20 <= code <= 0x7E or 0xA0 <= code <= 0xD7FF or 0xE000 <= code <= 0xFFFD or code > 0xFFFF
        ) and code not in (
            0x2028,
            0x2029,
            0xFEFF,
        ):
            out.append(ch)
        elif code <= 0xFF:
            out.append(f"\\x{code:02x}")
        else:
            out.append(f"\\u{code:04x}")
    return '"' + "".join(out) + '"'


link_names = st.one_of(st.sampled_from(LINK_WORDS), st.from_regex(LINK_NAME, fullmatch=True))
coupling_names = st.one_of(st.sampled_from(COUPLING_WORDS), st.from_regex(COUPLING_NAME, fullmatch=True))
state_names = coupling_names
symbol_names = st.one_of(
    st.sampled_from(SYMBOL_WORDS),
    st.from_regex(r"[A-Za-z][A-Za-z0-9_]{0,10}", fullmatch=True),
).filter(_symbol_ok)

#: Free texts (the train's name, descriptions): any characters, some that comments of
#: generated code must keep inside them.
free_texts = st.one_of(
    st.sampled_from(
        ["planetary set", "Getriebe mit Stufenplanet \u00fc\u00df", "a */ b", "x\ny", "{-# #-}", "%", "\\"]
    ),
    st.text(min_size=1, max_size=20),
)


# -- sizes and skeletons --------------------------------------------------------------------


@dataclass
class Skeleton:
    """A family's members, gears (teeth, module group) and meshes in canonical names."""

    family: str
    members: list[TMember]
    teeth: dict[str, int]
    #: gear -> (member, internal)
    gear_members: dict[str, tuple[str, bool]]
    #: gear -> module group; group -> module
    group: dict[str, str]
    modules: dict[str, Fraction]
    meshes: list[tuple[str, str, str]]
    #: each loop of meshes: gear -> coefficient of its radius, the sum vanishing
    loops: list[dict[str, int]]
    #: members on the main axis that states hold, drive or take off (coaxial sets)
    central: tuple[str, ...] = ()
    #: port -> member where the family fixes them (fixed-axis trains, Simpson, Ravigneaux)
    ports: dict[str, str] = field(default_factory=dict)
    states: list[State] = field(default_factory=list)
    placement: bool = False
    fixed_axis: bool = False
    description: str = ""

    def radius(self, gear: str) -> Fraction:
        return self.modules[self.group[gear]] * self.teeth[gear] / 2

    def tgears(self) -> list[TGear]:
        return [TGear(g, m, self.radius(g), internal) for g, (m, internal) in self.gear_members.items()]


def _y(v: Fraction) -> tuple[Fraction, Fraction]:
    return (F(0), v)


modules = st.sampled_from(MODULES)


@st.composite
def _pair(draw: st.DrawFn) -> Skeleton:
    m = draw(modules)
    internal = draw(st.integers(0, 9)) < 3
    z1 = draw(st.integers(8, 60))
    z2 = z1 + draw(st.integers(6, 60)) if internal else draw(st.integers(8, 80))
    annulus_on_a = internal and draw(st.booleans())
    # (member of the pinion, member of the other gear)
    first, second = ("b", "a") if annulus_on_a else ("a", "b")
    distance = m * (z2 - z1) / 2 if internal else m * (z1 + z2) / 2
    members = [TMember(HOUSING, "housing"), TMember(first, "fixed"), TMember(second, "fixed", axis=_y(distance))]
    members = [members[0], *sorted(members[1:], key=lambda x: x.name)]
    inp = draw(st.sampled_from(["a", "b"]))
    return Skeleton(
        "pair",
        members,
        {"G1": z1, "G2": z2},
        {"G1": (first, False), "G2": (second, internal)},
        {"G1": "m1", "G2": "m1"},
        {"m1": m},
        [("C", "G1", "G2")],
        [],
        ports={"A": inp, "B": "b" if inp == "a" else "a"},
        fixed_axis=True,
        description="fixed-axis pair" + (" (annulus)" if internal else ""),
    )


@st.composite
def _chain(draw: st.DrawFn) -> Skeleton:
    k = draw(st.integers(3, 4))
    members = [TMember(HOUSING, "housing")]
    teeth: dict[str, int] = {}
    gear_members: dict[str, tuple[str, bool]] = {}
    group: dict[str, str] = {}
    mods: dict[str, Fraction] = {}
    meshes = []
    pos = F(0)
    for i in range(1, k):
        m = draw(modules)
        za, zb = draw(st.integers(8, 60)), draw(st.integers(8, 60))
        internal = za != zb and draw(st.integers(0, 9)) < 2
        a, b = f"G{i}b", f"G{i + 1}a"
        teeth[a], teeth[b] = za, zb
        gear_members[a] = (f"s{i}", internal and za > zb)
        gear_members[b] = (f"s{i + 1}", internal and zb > za)
        group[a] = group[b] = f"m{i}"
        mods[f"m{i}"] = m
        members.append(TMember(f"s{i}", "fixed", axis=_y(pos)))
        pos += m * (abs(za - zb) if internal else za + zb) / 2
        meshes.append((f"M{i}", a, b))
    members.append(TMember(f"s{k}", "fixed", axis=_y(pos)))
    ends = draw(st.permutations(["s1", f"s{k}"]))
    return Skeleton(
        "chain",
        members,
        teeth,
        gear_members,
        group,
        mods,
        meshes,
        [],
        ports={"A": ends[0], "B": ends[1]},
        fixed_axis=True,
        description=f"compound fixed-axis chain of {k} shafts",
    )


def _coaxial(names: Sequence[str]) -> list[TMember]:
    return [TMember(HOUSING, "housing")] + [TMember(n, "central") for n in names]


@st.composite
def _planetary(draw: st.DrawFn) -> Skeleton:
    m = draw(modules)
    zs, zp = draw(st.integers(8, 60)), draw(st.integers(8, 40))
    zr = zs + 2 * zp
    return Skeleton(
        "planetary",
        [*_coaxial(["s", "r", "c"]), TMember("p", "planet", "c", _y(m * (zs + zp) / 2))],
        {"S": zs, "P": zp, "R": zr},
        {"S": ("s", False), "P": ("p", False), "R": ("r", True)},
        {"S": "m1", "P": "m1", "R": "m1"},
        {"m1": m},
        [("C", "S", "P"), ("D", "R", "P")],
        [{"S": 1, "P": 2, "R": -1}],
        central=("s", "r", "c"),
        description="simple planetary",
    )


@st.composite
def _stepped(draw: st.DrawFn) -> Skeleton:
    m1 = draw(modules)
    zs, zp1, zp2 = draw(st.integers(8, 60)), draw(st.integers(8, 40)), draw(st.integers(8, 40))
    if draw(st.booleans()):
        # another module on the second gear and the ring: m2 (zr - zp2) = m1 (zs + zp1)
        d = draw(st.integers(8, 90).filter(lambda d: d != zs + zp1))
        zr, m2 = zp2 + d, m1 * (zs + zp1) / d
    else:
        zr, m2 = zs + zp1 + zp2, m1
    assume(m1 * zp1 != m2 * zp2)
    return Skeleton(
        "stepped",
        [*_coaxial(["s", "r", "c"]), TMember("p", "planet", "c", _y(m1 * (zs + zp1) / 2))],
        {"S": zs, "P1": zp1, "P2": zp2, "R": zr},
        {"S": ("s", False), "P1": ("p", False), "P2": ("p", False), "R": ("r", True)},
        {"S": "m1", "P1": "m1", "P2": "m2", "R": "m2"},
        {"m1": m1, "m2": m2},
        [("C", "S", "P1"), ("D", "R", "P2")],
        [{"S": 1, "P1": 1, "P2": 1, "R": -1}],
        central=("s", "r", "c"),
        description="stepped planet" + (" (two modules)" if m1 != m2 else ""),
    )


def _integral_triangles() -> list[tuple[Fraction, Fraction, Fraction, Fraction, Fraction]]:
    """Triangles O, p1 = (0, d1), p2 = (x, y) with whole sides d1, d2 = |p2|, d12 = |p2 - p1|
    and rational coordinates (random_trains.rational_triangle, every parameter of its grid)."""
    out = set()
    grid = sorted({F(a, b) for a in range(1, 10) for b in range(2, 11) if a < b})
    for t in grid:
        for s in grid:
            y, d2 = (1 - t * t) / (2 * t), (1 + t * t) / (2 * t)
            w, d12 = (1 - s * s) / (2 * s), (1 + s * s) / (2 * s)
            for d1 in (y + w, y - w):
                if d1 <= 0:
                    continue
                values = [d1, d2, d12, F(1), y]
                den = 1
                for v in values:
                    den = den * v.denominator // _gcd(den, v.denominator)
                values = [v * den for v in values]
                g = 0
                for v in values:
                    if v:
                        g = _gcd(g, int(v))
                d1_, d2_, d12_, x_, y_ = (v / (g or 1) for v in values)
                if 8 <= d1_ <= 200 and 8 <= d12_ <= 200 and 8 <= d2_ <= 300:
                    out.add((d1_, d2_, d12_, x_, y_))
    return sorted(out)


def _gcd(a: int, b: int) -> int:
    while b:
        a, b = b, a % b
    return abs(a)


@cache
def _double_pinion_layouts() -> list[tuple[tuple[Fraction, ...], list[Fraction]]]:
    out = []
    for tri in _integral_triangles():
        d1, d2, d12, _, _ = tri
        ok = [
            F(n, 2)
            for n in range(6, int(2 * min(d1, d12)))
            if d1 - F(n, 2) >= 4
            and d12 - F(n, 2) >= 3
            and d1 + F(n, 2) < d2 + d12 - F(n, 2)
            and d2 - (d12 - F(n, 2)) > d1 - F(n, 2)
        ]
        if ok:
            out.append((tri, ok))
    return out


@cache
def _ravigneaux_layouts() -> list[tuple[tuple[Fraction, ...], list[Fraction]]]:
    out = []
    for tri in _integral_triangles():
        d1, d2, d12, _, _ = tri
        ok = [
            F(n, 2)
            for n in range(6, int(2 * min(d12, d2)))
            if min(d12 - F(n, 2), d2 - F(n, 2), d1 - d12 + F(n, 2)) >= 3 and d1 + d12 - F(n, 2) < d2 + F(n, 2)
        ]
        if ok:
            out.append((tri, ok))
    return out


@st.composite
def _double_pinion(draw: st.DrawFn) -> Skeleton:
    (d1, d2, d12, x, y), choices = draw(st.sampled_from(_double_pinion_layouts()))
    rp1 = draw(st.sampled_from(choices))
    rs, rp2 = d1 - rp1, d12 - rp1
    rr = d2 + rp2
    m = draw(modules)
    return Skeleton(
        "double_pinion",
        [
            *_coaxial(["s", "r", "c"]),
            TMember("p1", "planet", "c", (F(0), m * d1)),
            TMember("p2", "planet", "c", (m * x, m * y)),
        ],
        {"S": int(2 * rs), "P1": int(2 * rp1), "P2": int(2 * rp2), "R": int(2 * rr)},
        {"S": ("s", False), "P1": ("p1", False), "P2": ("p2", False), "R": ("r", True)},
        {g: "m1" for g in ("S", "P1", "P2", "R")},
        {"m1": m},
        [("C", "S", "P1"), ("D", "P1", "P2"), ("E", "R", "P2")],
        [],
        central=("s", "r", "c"),
        placement=True,
        description="double-pinion planetary",
    )


@st.composite
def _wolfrom(draw: st.DrawFn) -> Skeleton:
    m1 = draw(modules)
    zs, zp1, zp2 = draw(st.integers(8, 50)), draw(st.integers(8, 40)), draw(st.integers(8, 40))
    zr1 = zs + 2 * zp1
    if draw(st.booleans()):
        d = draw(st.integers(8, 90).filter(lambda d: d != zs + zp1))
        zr2, m2 = zp2 + d, m1 * (zs + zp1) / d
    else:
        zr2, m2 = zs + zp1 + zp2, m1
    assume(m1 * zp1 != m2 * zp2)
    return Skeleton(
        "wolfrom",
        [*_coaxial(["s", "r1", "r2", "c"]), TMember("p", "planet", "c", _y(m1 * (zs + zp1) / 2))],
        {"S": zs, "P1": zp1, "R1": zr1, "P2": zp2, "R2": zr2},
        {"S": ("s", False), "P1": ("p", False), "R1": ("r1", True), "P2": ("p", False), "R2": ("r2", True)},
        {"S": "m1", "P1": "m1", "R1": "m1", "P2": "m2", "R2": "m2"},
        {"m1": m1, "m2": m2},
        [("C", "S", "P1"), ("D", "R1", "P1"), ("E", "R2", "P2")],
        [{"S": 1, "P1": 2, "R1": -1}, {"S": 1, "P1": 1, "P2": 1, "R2": -1}],
        central=("s", "r1", "r2"),
        description="Wolfrom, carrier free" + (" (two modules)" if m1 != m2 else ""),
    )


@st.composite
def _tuplin(draw: st.DrawFn) -> Skeleton:
    m1 = draw(modules)
    z3, z4 = draw(st.integers(8, 40)), draw(st.integers(8, 40))
    d1 = draw(st.integers(6, 60))
    if draw(st.booleans()):
        d2 = draw(st.integers(6, 60))
        m2 = m1 * d1 / d2
    else:
        d2, m2 = d1, m1
    assume(m1 * z3 != m2 * z4)
    return Skeleton(
        "tuplin",
        [*_coaxial(["1", "2", "5"]), TMember("3/4", "planet", "5", _y(m1 * d1 / 2))],
        {"1": z3 + d1, "2": z4 + d2, "3": z3, "4": z4},
        {"1": ("1", True), "2": ("2", True), "3": ("3/4", False), "4": ("3/4", False)},
        {"1": "m1", "3": "m1", "2": "m2", "4": "m2"},
        {"m1": m1, "m2": m2},
        [("C", "1", "3"), ("D", "2", "4")],
        [{"1": 1, "3": -1, "2": -1, "4": 1}],
        central=("1", "2", "5"),
        description="two annuli (Tuplin)" + (" (two modules)" if m1 != m2 else ""),
    )


SIMPSON_STATES = (
    State("first", "A", "B", brake=("c2",)),
    State("second", "A", "B", brake=("s",)),
    State("third", "A", "B", clutch=(("r1", "s"),)),
    State("reverse", "G", "B", brake=("c2",), free=("r1", "p1")),
)
RAVIGNEAUX_STATES = (
    State("reverse", "B", "D", brake=("c",), free=("s1", "ps")),
    State("first", "A", "D", brake=("c",), free=("s2",)),
    State("second", "A", "D", brake=("s2",)),
    State("third", "A", "D", clutch=(("s1", "s2"),)),
)


@st.composite
def _some_states(draw: st.DrawFn, states: Sequence[State]) -> list[State]:
    chosen = draw(st.lists(st.sampled_from(states), min_size=1, max_size=len(states), unique_by=lambda s: s.name))
    out = []
    for s in chosen:
        clutch = tuple(tuple(draw(st.permutations(pair))) for pair in s.clutch)
        out.append(State(s.name, s.input, s.output, s.brake, clutch, tuple(draw(st.permutations(s.free)))))
    return out


@st.composite
def _simpson(draw: st.DrawFn) -> Skeleton:
    m = draw(modules)
    zs, zp1, zp2 = draw(st.integers(12, 50)), draw(st.integers(8, 30)), draw(st.integers(8, 30))
    return Skeleton(
        "simpson",
        [
            *_coaxial(["s", "r1", "o", "c2"]),
            TMember("p1", "planet", "o", _y(m * (zs + zp1) / 2)),
            TMember("p2", "planet", "c2", _y(m * (zs + zp2) / 2)),
        ],
        {"S": zs, "P1": zp1, "R1": zs + 2 * zp1, "P2": zp2, "R2": zs + 2 * zp2},
        {"S": ("s", False), "P1": ("p1", False), "R1": ("r1", True), "P2": ("p2", False), "R2": ("o", True)},
        {g: "m1" for g in ("S", "P1", "R1", "P2", "R2")},
        {"m1": m},
        [("C", "S", "P1"), ("D", "R1", "P1"), ("E", "S", "P2"), ("F", "R2", "P2")],
        [{"S": 1, "P1": 2, "R1": -1}, {"S": 1, "P2": 2, "R2": -1}],
        ports={"A": "r1", "B": "o", "G": "s"},
        states=draw(_some_states(SIMPSON_STATES)),
        description="Simpson three-speed set",
    )


@st.composite
def _ravigneaux(draw: st.DrawFn) -> Skeleton:
    (d1, d2, d12, x, y), choices = draw(st.sampled_from(_ravigneaux_layouts()))
    rpl = draw(st.sampled_from(choices))
    rps, rs2 = d12 - rpl, d2 - rpl
    rs1, rr = d1 - rps, d2 + rpl
    m = draw(modules)
    return Skeleton(
        "ravigneaux",
        [
            *_coaxial(["s1", "s2", "c", "r"]),
            TMember("ps", "planet", "c", (F(0), m * d1)),
            TMember("pl", "planet", "c", (m * x, m * y)),
        ],
        {"S1": int(2 * rs1), "S2": int(2 * rs2), "PS": int(2 * rps), "PL": int(2 * rpl), "R": int(2 * rr)},
        {"S1": ("s1", False), "S2": ("s2", False), "PS": ("ps", False), "PL": ("pl", False), "R": ("r", True)},
        {g: "m1" for g in ("S1", "S2", "PS", "PL", "R")},
        {"m1": m},
        [("G1", "S1", "PS"), ("G2", "PS", "PL"), ("G3", "S2", "PL"), ("G4", "R", "PL")],
        [{"S2": 1, "PL": 2, "R": -1}],
        ports={"A": "s1", "B": "s2", "D": "r"},
        states=draw(_some_states(RAVIGNEAUX_STATES)),
        placement=True,
        description="Ravigneaux set",
    )


SKELETONS = {
    "pair": _pair,
    "chain": _chain,
    "planetary": _planetary,
    "stepped": _stepped,
    "double_pinion": _double_pinion,
    "wolfrom": _wolfrom,
    "tuplin": _tuplin,
    "simpson": _simpson,
    "ravigneaux": _ravigneaux,
}


# -- roles: which member is held, the ports and the states ----------------------------------


@dataclass
class Roles:
    """``hold``: ``housing`` (the held member's gears on the housing), ``brake`` (braked in
    one state), ``states`` (several states) or ``none`` (fixed-axis trains)."""

    hold: str
    ports: dict[str, str]
    input: str
    output: str
    held: str | None = None
    states: list[State] = field(default_factory=list)


@st.composite
def _roles(draw: st.DrawFn, sk: Skeleton) -> Roles:
    if sk.fixed_axis:
        return Roles("none", dict(sk.ports), "A", "B")
    if sk.states:
        first = sk.states[0]
        return Roles("states", dict(sk.ports), first.input, first.output, states=list(sk.states))
    hold = draw(st.sampled_from(["housing", "brake", "states"]))
    if hold != "states":
        held, inp, out = draw(st.permutations(sk.central))[:3]
        return Roles(hold, {"A": inp, "B": out}, "A", "B", held=held)
    port_names = ("A", "B", "G")
    ports = dict(zip(port_names, sk.central, strict=True))
    member_port = {m: p for p, m in ports.items()}
    states = []
    for i in range(draw(st.integers(1, 3))):
        third, inp, out = draw(st.permutations(sk.central))[:3]
        if draw(st.integers(0, 4)) == 0:
            # direct drive: the third member clutched to the input or the output
            partner = draw(st.sampled_from([inp, out]))
            pair = tuple(draw(st.permutations([third, partner])))
            states.append(State(f"st{i}", member_port[inp], member_port[out], clutch=(pair,)))  # type: ignore[arg-type]
        else:
            states.append(State(f"st{i}", member_port[inp], member_port[out], brake=(third,)))
    return Roles("states", ports, states[0].input, states[0].output, states=states)


# -- spelling ---------------------------------------------------------------------------------


def number_text(rnd: random.Random, v: Fraction) -> str:
    """One YAML spelling of the exact number ``v`` (> 0)."""
    options = []
    if v.denominator == 1:
        options += [str(v.numerator), f'"{v.numerator}"']
    den = v.denominator
    while den % 2 == 0:
        den //= 2
    while den % 5 == 0:
        den //= 5
    if den == 1 and v.denominator > 1:
        text = f"{float(v):.10f}".rstrip("0")
        options += [text, text + "0"]
    if v.denominator > 1:
        options += [f"{v.numerator}/{v.denominator}", f'"{v.numerator}/{v.denominator}"']
    options.append(f'"{v.numerator * 2}/{v.denominator * 2}"')
    return rnd.choice(options)


def _sym(name: str) -> sympy.Symbol:
    return sympy.Symbol(name, positive=True)


@dataclass
class Size:
    """How a gear's size is written: ``text`` (the entries), its radius as an exact sympy
    expression of the file's symbols, and the tooth symbol (for the search)."""

    entries: list[tuple[str, str]]
    expr: sympy.Expr
    tooth_symbol: str | None = None


@dataclass
class Drawn:
    """A drawn train: the oracle's canonical train and the file (``spelling``)."""

    train: RandomTrain
    spelling: Spelling
    #: tooth-number symbols -> their values
    teeth: dict[str, int]
    #: symbols of the sizes (geometry) -> values; the dependent ones `independent:` leaves
    geometry: dict[str, Fraction]
    independent: tuple[str, ...] | None
    dependent: tuple[str, ...]
    #: whether ``derive search`` applies: numeric efficiencies, every tooth symbol free or
    #: fixed by the geometry from the free ones
    searchable: bool
    features: tuple[str, ...]

    @property
    def yaml(self) -> str:
        return self.spelling.yaml

    @property
    def values(self) -> dict[str, Fraction]:
        return self.spelling.values

    def engine_states(self) -> list[str]:
        return [s for s in self.spelling.states.values() if s is not None]

    def __repr__(self) -> str:
        values = " ".join(f"{k}={v}" for k, v in sorted(self.values.items()))
        return f"Drawn({self.train.description}; {', '.join(self.features)})\n{self.yaml}# values: {values}\n"


@st.composite
def trains(
    draw: st.DrawFn,
    families: Sequence[str] = FAMILIES,
    search: bool = False,
) -> Drawn:
    """A valid train of one of ``families`` in a drawn spelling.  ``search``: tooth
    numbers as symbols, the free ones listed in ``independent:``, numeric efficiencies
    (what ``derive search`` needs)."""
    family = draw(st.sampled_from(list(families)))
    sk = draw(SKELETONS[family]())
    roles = draw(_roles(sk))
    return draw(_spelled(sk, roles, search))


@st.composite
def _spelled(draw: st.DrawFn, sk: Skeleton, roles: Roles, search: bool) -> Drawn:
    rnd = draw(st.randoms(use_true_random=True))
    features: list[str] = [sk.family, f"hold={roles.hold}", f"states={len(roles.states)}"]

    # members present as links: the held member's gears sit on the housing
    in_housing = roles.held if roles.hold == "housing" else None

    def member_of(m: str) -> str:
        return HOUSING if m == in_housing else m

    link_members = [m.name for m in sk.members if m.name != in_housing]
    names = draw(st.lists(link_names, min_size=len(link_members), max_size=len(link_members), unique=True))
    link = dict(zip(link_members, names, strict=True))
    gears = list(sk.gear_members)
    gear_name = dict(
        zip(gears, draw(st.lists(link_names, min_size=len(gears), max_size=len(gears), unique=True)), strict=True)
    )

    # couplings: a bearing per member on a fixed axis (ports first), a pin per planet, meshes
    port_of = {m: p for p, m in roles.ports.items()}
    letters = iter("KHJLNQUVWY")
    bearings: list[tuple[str, str, str]] = []  # (canonical, carrier side, member)
    for m in sk.members:
        if m.role == "housing" or m.name == in_housing:
            continue
        if m.role in ("central", "fixed"):
            bearings.append((port_of.get(m.name) or next(letters), HOUSING, m.name))
        else:
            bearings.append((next(letters), member_of(m.carrier or HOUSING), m.name))
    canonical_couplings = [b[0] for b in bearings] + [mesh[0] for mesh in sk.meshes]
    cnames = draw(
        st.lists(coupling_names, min_size=len(canonical_couplings), max_size=len(canonical_couplings), unique=True)
    )
    cname = dict(zip(canonical_couplings, cnames, strict=True))
    snames = draw(st.lists(state_names, min_size=len(roles.states) + 1, max_size=len(roles.states) + 1, unique=True))

    # symbols: a pool drawn once, names that could be read as a coupling's own symbols left out
    taken = {f"{p}_{c}" for p in COUPLING_SYMBOL_PREFIXES for c in cnames}
    drawn = [s for s in draw(st.lists(symbol_names, min_size=24, max_size=24, unique=True)) if s not in taken]
    pool = list(dict.fromkeys(drawn + [f"q{i}_" for i in range(40)]))
    pool.reverse()

    def new_symbol() -> str:
        return pool.pop()

    values: dict[str, Fraction] = {}
    geometry: dict[str, Fraction] = {}
    quote_all = draw(st.integers(0, 3)) == 0

    def scalar(name: str) -> str:
        if quote_all or not plain(name) or rnd.random() < 0.2:
            return quoted(name)
        return name

    # sizes
    style = "teeth" if search else draw(st.sampled_from(["teeth", "radius", "mixed"]))
    features.append(f"sizes={style}")
    module_text: dict[str, tuple[str, sympy.Expr]] = {}
    module_symbols_by_value: dict[Fraction, str] = {}
    module_symbols: set[str] = set()

    split_groups: set[str] = set()

    def module_of(group: str, gear: str) -> tuple[str, sympy.Expr]:
        """The module of ``gear``'s group as written: a number, the group's symbol, or now
        and then a symbol of the gear's own (of the same value: the language ties nothing)."""
        key = f"{group}.{gear}" if group in split_groups else group
        if key not in module_text:
            value = sk.modules[group]
            if draw(st.integers(0, 2)) > 0:
                if key == group and not search and draw(st.integers(0, 4)) == 0:
                    # (a search needs the modules of a mesh equal: the ratios then hold no module)
                    split_groups.add(group)
                    return module_of(group, gear)
                if value in module_symbols_by_value and draw(st.booleans()):
                    name = module_symbols_by_value[value]
                else:
                    name = new_symbol()
                    module_symbols_by_value[value] = name
                    module_symbols.add(name)
                    geometry[name] = value
                module_text[key] = (scalar(name), _sym(name))
            else:
                module_text[key] = (number_text(rnd, value), sympy.Rational(value.numerator, value.denominator))
        return module_text[key]

    sizes: dict[str, Size] = {}
    teeth_symbols: dict[str, int] = {}
    for g in gears:
        radius = sk.radius(g)
        kind = style
        if style == "mixed":
            kind = draw(st.sampled_from(["radius", "teeth", "radius_expr"]))
        if kind == "radius":
            how = draw(st.sampled_from(["symbol", "symbol", "number", "scaled"]))
            if how == "number":
                sizes[g] = Size(
                    [("radius", number_text(rnd, radius))], sympy.Rational(radius.numerator, radius.denominator)
                )
            elif how == "scaled":
                k = draw(st.sampled_from([F(2), F(1, 2), F(3, 2), F(3)]))
                name = new_symbol()
                geometry[name] = radius / k
                text = f"{k.numerator}*{name}" if k.denominator == 1 else f"{k.numerator}*{name}/{k.denominator}"
                sizes[g] = Size([("radius", text)], sympy.Rational(k.numerator, k.denominator) * _sym(name))
            else:
                name = new_symbol()
                geometry[name] = radius
                sizes[g] = Size([("radius", scalar(name))], _sym(name))
        elif kind == "radius_expr":
            mtext, mexpr = module_of(sk.group[g], g)
            name = new_symbol()
            geometry[name] = F(sk.teeth[g])
            text = f"{mexpr}*{name}/2"
            sizes[g] = Size([("radius", json.dumps(text))], mexpr * _sym(name) / 2)
        else:
            mtext, mexpr = module_of(sk.group[g], g)
            symbolic = (search and draw(st.integers(0, 5)) > 0) or (not search and draw(st.booleans()))
            if symbolic:
                name = new_symbol()
                geometry[name] = F(sk.teeth[g])
                teeth_symbols[name] = sk.teeth[g]
                sizes[g] = Size([("teeth", scalar(name)), ("module", mtext)], mexpr * _sym(name) / 2, name)
            else:
                sizes[g] = Size([("teeth", str(sk.teeth[g])), ("module", mtext)], mexpr * sk.teeth[g] / 2)
    if search and not teeth_symbols:
        g = gears[0]
        name = new_symbol()
        geometry[name] = F(sk.teeth[g])
        teeth_symbols[name] = sk.teeth[g]
        mtext, mexpr = module_of(sk.group[g], g)
        sizes[g] = Size([("teeth", scalar(name)), ("module", mtext)], mexpr * _sym(name) / 2, name)
    values.update(geometry)

    # independent: every size symbol but one per loop, or some of them, or left out
    independent, dependent, searchable = _independent(draw, sk, sizes, geometry, teeth_symbols, module_symbols, search)
    if independent is not None:
        features.append(f"independent={len(independent)}")
    if dependent:
        kinds = {d: "teeth" if d in teeth_symbols else "module" if d in module_symbols else "radius" for d in dependent}
        features.append("dependent=" + ",".join(kinds[d] for d in dependent))
    if len(set(sk.modules.values())) > 1 or len(module_symbols) > 1:
        features.append("modules=several")
    if split_groups:
        features.append("modules=per-gear")

    # efficiencies
    etas: dict[str, Fraction] = {}
    eta_entries: dict[str, list[tuple[str, str]]] = {}
    shared: dict[Fraction, str] = {}
    for mesh, _, _ in sk.meshes:
        eta = draw(
            st.one_of(
                st.integers(9000, 9999).map(lambda n: F(n, 10000)),
                st.integers(50, 99).map(lambda n: F(n, 100)),
                st.just(F(1)),
            )
        )
        how = "number" if search else draw(st.sampled_from(["default", "default", "symbol", "number", "pair"]))
        if how == "symbol" and shared and draw(st.booleans()):
            eta, name = next(iter(shared.items()))
            eta_entries[mesh] = [("efficiency", scalar(name))]
            how = "shared"
        elif how == "default":
            values[f"eta_{cname[mesh]}"] = eta
            eta_entries[mesh] = []
        elif how == "symbol":
            name = new_symbol()
            values[name] = eta
            shared[eta] = name
            eta_entries[mesh] = [("efficiency", scalar(name))]
        elif how == "number":
            eta_entries[mesh] = [("efficiency", number_text(rnd, eta))]
        else:
            text = number_text(rnd, eta) if draw(st.booleans()) else None
            if text is None:
                name = new_symbol()
                values[name] = eta
                text = scalar(name)
            eta_entries[mesh] = [("efficiency", f"[{text}, {text}]")]
        features.append(f"eta={how}")
        etas[mesh] = eta

    # the file

    def mapping(entries: list[tuple[str, str]], indent: str, flow: bool) -> list[str]:
        """``entries`` as a flow mapping (one line) or a block (lines below the key)."""
        if flow:
            return ["{" + ", ".join(f"{k}: {v}" for k, v in entries) + "}"]
        return [f"{indent}{k}: {v}" for k, v in entries]

    def entry(key: str, entries: list[tuple[str, str]]) -> list[str]:
        entries = list(entries)
        rnd.shuffle(entries)
        if rnd.random() < 0.7:
            return [f"  {key}: " + mapping(entries, "", True)[0]]
        return [f"  {key}:", *mapping(entries, "    ", False)]

    def seq(items: Sequence[str]) -> str:
        return "[" + ", ".join(items) + "]"

    geared = {member_of(m) for g, (m, _) in sk.gear_members.items()}
    housing = link[HOUSING]
    sections: dict[str, list[str]] = {}

    # links
    order = list(link_members)
    rnd.shuffle(order)
    form = draw(st.sampled_from(["flow", "block", "mapping"]))
    if form == "flow":
        sections["links"] = ["links: " + seq([scalar(link[m]) for m in order])]
    elif form == "block":
        sections["links"] = ["links:"] + [f"  - {scalar(link[m])}" for m in order]
    else:
        lines = ["links:"]
        for m in order:
            how = rnd.choice(["description", "empty", "null"])
            if how == "description":
                lines.append(f"  {scalar(link[m])}: {{description: {quoted(draw(free_texts))}}}")
            elif how == "empty":
                lines.append(f"  {scalar(link[m])}: {{}}")
            else:
                lines.append(f"  {scalar(link[m])}:")
        sections["links"] = lines

    # gears
    gear_lines = []
    gear_order = list(gears)
    rnd.shuffle(gear_order)
    for g in gear_order:
        m, internal = sk.gear_members[g]
        entries = [("link", scalar(link[member_of(m)])), *sizes[g].entries]
        if internal:
            entries.append(("internal", "true"))
        elif rnd.random() < 0.15:
            entries.append(("internal", "false"))
        gear_lines += entry(scalar(gear_name[g]), entries)
    sections["gears"] = ["gears:", *gear_lines]

    # couplings
    orientation: dict[str, int] = {}
    coupling_lines: list[list[str]] = []
    flips = 0
    for canonical, a, b in bearings:
        member = next(x for x in sk.members if x.name == b)
        flip = draw(st.booleans())
        flips += flip
        pair = [link[b], link[a]] if flip else [link[a], link[b]]
        entries = [("type", "revolute"), ("links", seq([scalar(x) for x in pair]))]
        if member.role == "central":
            # without `at` a geared member of a housing without gears sits where its meshes
            # put it, and the loops then tie nothing: a search needs them
            needed = HOUSING not in geared and (b not in geared or search)
            if needed or rnd.random() < 0.3:
                entries.append(("at", "0"))
        elif member.role == "planet" and (a in geared or rnd.random() < 0.2):
            entries.append(("axis", scalar(link[b])))
        coupling_lines.append(entry(scalar(cname[canonical]), entries))
        orientation[canonical] = -1 if flip else 1
    if sk.fixed_axis and rnd.random() < 0.3:
        # one shaft placed by `at` (the others follow from the meshes)
        k = rnd.randrange(len(coupling_lines))
        line = coupling_lines[k]
        at = number_text(rnd, F(rnd.choice([0, 0, 5, 12])))
        coupling_lines[k] = [line[0][:-1] + f", at: {at}}}"] if len(line) == 1 else [*line, f"    at: {at}"]
        features.append("at=fixed-axis")
    for mesh, ga, gb in sk.meshes:
        reverse = draw(st.booleans())
        pair = [gear_name[gb], gear_name[ga]] if reverse else [gear_name[ga], gear_name[gb]]
        entries = [("type", "mesh"), ("gears", seq([scalar(x) for x in pair]))] + eta_entries[mesh]
        if rnd.random() < 0.15:
            internal = sk.gear_members[ga][1] or sk.gear_members[gb][1]
            entries.append(("mesh", "internal" if internal else "external"))
        coupling_lines.append(entry(scalar(cname[mesh]), entries))
    if flips:
        features.append("flipped")
    rnd.shuffle(coupling_lines)
    sections["couplings"] = ["couplings:"] + [line for lines in coupling_lines for line in lines]

    sections["ports"] = (
        [f"ports: {{input: {scalar(cname[roles.input])}, output: {scalar(cname[roles.output])}}}"]
        if rnd.random() < 0.7
        else ["ports:", f"  output: {scalar(cname[roles.output])}", f"  input: {scalar(cname[roles.input])}"]
    )

    # states
    engine_states: dict[str, str | None] = {}
    oracle_states: list[State] = []
    if roles.hold == "brake":
        name = snames[0]
        brake = scalar(link[roles.held or ""])
        entries = [
            ("input", scalar(cname[roles.input])),
            ("output", scalar(cname[roles.output])),
            ("brake", brake if rnd.random() < 0.5 else seq([brake])),
        ]
        sections["states"] = ["states:", *entry(scalar(name), entries)]
        engine_states["run"] = name
    elif roles.states:
        lines = ["states:"]
        state_order = list(enumerate(roles.states))
        rnd.shuffle(state_order)
        for i, s in state_order:
            entries = [("input", scalar(cname[s.input])), ("output", scalar(cname[s.output]))]
            if s.brake:
                items = [scalar(link[x]) for x in s.brake]
                entries.append(("brake", items[0] if len(items) == 1 and rnd.random() < 0.5 else seq(items)))
            if s.clutch:
                entries.append(("clutch", seq([seq([scalar(link[x]) for x in p]) for p in s.clutch])))
                features.append("clutch")
            if s.free:
                items = [scalar(link[x]) for x in s.free]
                entries.append(("free", items[0] if len(items) == 1 and rnd.random() < 0.5 else seq(items)))
                features.append("free")
            if rnd.random() < 0.2:
                entries.append(("description", quoted(draw(free_texts))))
            lines += entry(scalar(snames[i]), entries)
            engine_states[s.name] = snames[i]
        sections["states"] = lines
        oracle_states = list(roles.states)
    else:
        engine_states["run"] = None

    if independent is not None:
        items = list(independent)
        form = draw(st.sampled_from(["flow", "block", "alone"] if len(items) == 1 else ["flow", "block"]))
        features.append(f"independent-{form}")
        if form == "alone":
            sections["independent"] = [f"independent: {scalar(items[0])}"]
        elif form == "flow":
            sections["independent"] = ["independent: " + seq([scalar(x) for x in items])]
        else:
            sections["independent"] = ["independent:"] + [f"  - {scalar(x)}" for x in items]

    if sk.placement or rnd.random() < 0.1:
        options = ["[0, 1]", "[3, 4]", "[1, 0]", "[-1, 2]", "[0, -1]", "90", "30", "45", "135", "[1, sqrt(3)]"]
        sections["placement"] = [f"placement: {draw(st.sampled_from(options))}"]
        features.append("placement" if sk.placement else "placement=1-D")
    if rnd.random() < 0.6:
        sections["reference"] = [f"reference: {scalar(housing)}"]
    if rnd.random() < 0.5:
        sections["format"] = ["format: 1"]
    if roles.hold in ("housing", "none") and rnd.random() < 0.3:
        sections["degrees_of_freedom"] = ["degrees_of_freedom: 1"]
    sections["name"] = [f"name: {quoted(draw(free_texts.filter(lambda t: any(c.isalnum() for c in t))))}"]
    if rnd.random() < 0.2:
        sections["notes"] = [f"notes: {quoted(draw(free_texts))}"]
    keys = list(sections)
    rnd.shuffle(keys)
    lines = []
    for key in keys:
        if rnd.random() < 0.15:
            lines.append("# " + sk.description)
        lines += sections[key]

    train = RandomTrain(
        sk.family,
        0,
        sk.members,
        sk.tgears(),
        {mesh: (a, b, etas[mesh]) for mesh, a, b in sk.meshes},
        dict(roles.ports),
        roles.input,
        roles.output,
        held=roles.held,
        states=oracle_states,
        placement=sk.placement,
        description=sk.description,
    )
    spelling = Spelling(
        "drawn",
        "\n".join(lines) + "\n",
        values,
        {p: cname[p] for p in roles.ports},
        engine_states,
        {p: orientation[p] for p in roles.ports},
    )
    for f in features:
        _event(f)
    return Drawn(train, spelling, teeth_symbols, geometry, independent, dependent, searchable, tuple(features))


def _event(text: str) -> None:
    """Count ``text`` in Hypothesis's statistics (``pytest --hypothesis-show-statistics``)."""
    from hypothesis import event
    from hypothesis.errors import InvalidArgument

    with contextlib.suppress(InvalidArgument):  # a draw outside a test
        event(text)


def _reduced(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` without its positive factors (the symbols, the numbers)."""
    expr = sympy.factor(sympy.together(expr))
    numerator = sympy.fraction(expr)[0]
    factors = numerator.args if numerator.is_Mul else (numerator,)
    kept = [f for f in factors if not (f.is_number or f.is_Symbol or (f.is_Pow and f.base.is_Symbol))]
    return sympy.Mul(*kept)


def _independent(
    draw: st.DrawFn,
    sk: Skeleton,
    sizes: dict[str, Size],
    geometry: dict[str, Fraction],
    teeth: dict[str, int],
    module_symbols: set[str],
    search: bool,
) -> tuple[tuple[str, ...] | None, tuple[str, ...], bool]:
    """The ``independent:`` list, the symbols it leaves dependent (one per loop that ties
    symbols), and whether the search applies."""
    constraints = []
    for loop in sk.loops:
        expr = _reduced(sum((c * sizes[g].expr for g, c in loop.items()), sympy.Integer(0)))
        if expr.free_symbols:
            constraints.append(expr)
    point = {_sym(n): sympy.Rational(v.numerator, v.denominator) for n, v in geometry.items()}
    assert all(sympy.simplify(c.subs(point)) == 0 for c in constraints), "drawn sizes break a loop"
    dependent: list[str] = []
    for c in constraints:
        candidates = sorted(str(s) for s in c.free_symbols if str(s) not in dependent)
        modules = [s for s in candidates if s in module_symbols]
        if modules and (search or draw(st.booleans())):
            # a module the dependent symbol (in a search a tooth number may depend on tooth
            # numbers only: the modules first)
            candidates = modules
        if not candidates:
            return None, (), False
        dependent.append(draw(st.sampled_from(candidates)))
    if dependent:
        jacobian = sympy.Matrix([[sympy.diff(c, _sym(d)) for d in dependent] for c in constraints])
        if jacobian.subs(point).det() == 0:
            return None, (), False
    rest = [s for s in geometry if s not in dependent]
    mode = "all" if search else draw(st.sampled_from(["omit", "all", "all", "some"]))
    if mode == "omit" or not rest:
        independent = None
    elif mode == "some":
        independent = tuple(draw(st.lists(st.sampled_from(rest), min_size=1, max_size=len(rest), unique=True)))
    else:
        independent = tuple(draw(st.permutations(rest)))
    searchable = False
    if search and independent is not None and any(t in independent for t in teeth):
        solution = sympy.solve(constraints, [_sym(d) for d in dependent], dict=True) if dependent else [{}]
        searchable = len(solution) == 1 and all(
            {str(s) for s in expr.free_symbols} <= set(independent) & set(teeth)
            for sym, expr in solution[0].items()
            if str(sym) in teeth
        )
    return independent, tuple(dependent), searchable


# -- one train written by hand ----------------------------------------------------------------

STEPPED_TWO_MODULES = """\
format: 1
name: stepped planet, the ring and the second gear in another module
links: [0, s, p, c]
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
  SP: {{type: mesh, gears: [S, P1], efficiency: {eta_sp}}}
  PR: {{type: mesh, gears: [P2, R], efficiency: {eta_pr}}}
ports: {{input: A, output: B}}
independent: {independent}
"""


def stepped_two_modules(independent: str = "[z1, z2, z3, z4, m1]", numeric_efficiency: bool = False) -> Drawn:
    """The stepped planetary with m1 on the sun and the first planet gear, m2 on the second
    planet gear and the ring (the ring held, sun in, carrier out): z1 = 20, z2 = 30,
    z3 = 18, z4 = 68, m1 = 2, so m2 (z4 - z3) = m1 (z1 + z2) gives m2 = 2.  The default
    ``independent`` leaves m2 the dependent symbol."""
    z1, z2, z3, z4, m1 = 20, 30, 18, 68, F(2)
    m2 = m1 * (z1 + z2) / (z4 - z3)
    etas = {"SP": F(49, 50), "PR": F(99, 100)}
    text = STEPPED_TWO_MODULES.format(
        independent=independent,
        eta_sp="0.98" if numeric_efficiency else "eta_SP",
        eta_pr="0.99" if numeric_efficiency else "eta_PR",
    )
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("c", "central"),
        TMember("r", "central"),
        TMember("p", "planet", "c", _y(m1 * (z1 + z2) / 2)),
    ]
    gears = [
        TGear("S", "s", m1 * z1 / 2),
        TGear("P1", "p", m1 * z2 / 2),
        TGear("P2", "p", m2 * z3 / 2),
        TGear("R", "r", m2 * z4 / 2, True),
    ]
    train = RandomTrain(
        "stepped",
        0,
        members,
        gears,
        {"SP": ("S", "P1", etas["SP"]), "PR": ("R", "P2", etas["PR"])},
        {"A": "s", "B": "c"},
        "A",
        "B",
        held="r",
        description="stepped planet, two modules, the ring held",
    )
    geometry = {"z1": F(z1), "z2": F(z2), "z3": F(z3), "z4": F(z4), "m1": m1, "m2": m2}
    values = dict(geometry)
    if not numeric_efficiency:
        values.update({"eta_SP": etas["SP"], "eta_PR": etas["PR"]})
    listed = tuple(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", independent))
    spelling = Spelling("stepped_two_modules", text, values, {"A": "A", "B": "B"}, {"run": None}, {"A": 1, "B": 1})
    dependent = tuple(s for s in geometry if s not in listed)
    teeth = {"z1": z1, "z2": z2, "z3": z3, "z4": z4}
    searchable = numeric_efficiency and set(dependent) <= {"m1", "m2"}
    return Drawn(train, spelling, teeth, geometry, listed, dependent, searchable, ("stepped", "two modules"))


def _by_hand(
    name: str,
    text: str,
    members: list[TMember],
    gears: list[TGear],
    meshes: dict[str, tuple[str, str]],
    ports: tuple[tuple[str, str, int], tuple[str, str, int]],
    held: str,
    values: dict[str, Fraction],
) -> Drawn:
    """A train written by hand: the held member in the housing, ``ports`` the input and the
    output as (member, coupling of the file, +1 or -1 as its links are written [housing,
    member] or reversed), every mesh of efficiency 49/50 (``eta_<mesh>``)."""
    (inp, inp_coupling, inp_sign), (out, out_coupling, out_sign) = ports
    train = RandomTrain(
        name,
        0,
        members,
        gears,
        {mesh: (a, b, F(49, 50)) for mesh, (a, b) in meshes.items()},
        {"A": inp, "B": out},
        "A",
        "B",
        held=held,
        description=name,
    )
    values = {**values, **{f"eta_{mesh}": F(49, 50) for mesh in meshes}}
    spelling = Spelling(
        name, text, values, {"A": inp_coupling, "B": out_coupling}, {"run": None}, {"A": inp_sign, "B": out_sign}
    )
    return Drawn(train, spelling, {}, {}, None, (), False, (name,))


def _central(*names: str) -> list[TMember]:
    return _coaxial(names)


def tuplin_by_teeth_and_radii() -> Drawn:
    """Tuplin's train with one annulus by teeth and a module symbol, the other sizes radii
    (one a number): the actions once failed with a KeyError on the tooth symbol."""
    text = """\
name: Tuplin, one annulus by teeth and a module symbol, a planet gear by a number
links: [1, 2, 3/4, 5]
reference: 1
gears:
  1: {link: 1, radius: r1, internal: true}
  2: {link: 2, teeth: z2, module: m2, internal: true}
  3: {link: 3/4, radius: r3}
  4: {link: 3/4, radius: 40}
couplings:
  A: {type: revolute, links: [1, 5]}
  B: {type: revolute, links: [1, 2]}
  C: {type: mesh, gears: [1, 3]}
  D: {type: mesh, gears: [2, 4]}
  E: {type: revolute, links: [3/4, 5]}
ports: {input: A, output: B}
"""
    return _by_hand(
        "tuplin_by_teeth_and_radii",
        text,
        [*_central("1", "2", "5"), TMember("3/4", "planet", "5", _y(F(20)))],
        [
            TGear("1", "1", F(55), True),
            TGear("2", "2", F(60), True),
            TGear("3", "3/4", F(35)),
            TGear("4", "3/4", F(40)),
        ],
        {"C": ("1", "3"), "D": ("2", "4")},
        (("5", "A", 1), ("2", "B", 1)),
        "1",
        {"r1": F(55), "r3": F(35), "z2": F(30), "m2": F(4)},
    )


def stepped_module_symbol_of_the_ring() -> Drawn:
    """A stepped planet (the sun held, the carrier in, the ring out) whose second module
    is a symbol and the ring's teeth a number, tooth symbols named ``a`` and ``b``: a
    sampled design once met the pole of the dependent module (ZeroDivisionError)."""
    text = """\
name: stepped planet, the sun held, the second module a symbol
links: [0, r, p, c]
reference: 0
gears:
  S: {link: 0, teeth: z1, module: 1}
  P1: {link: p, teeth: a, module: 1}
  P2: {link: p, teeth: b, module: m2}
  R: {link: r, teeth: 80, module: m2, internal: true}
couplings:
  A: {type: revolute, links: [0, c]}
  B: {type: revolute, links: [0, r]}
  D: {type: revolute, links: [c, p]}
  SP: {type: mesh, gears: [S, P1]}
  PR: {type: mesh, gears: [P2, R]}
ports: {input: A, output: B}
"""
    # m2 (80 - b) = z1 + a: z1 = 24, a = 30, b = 20 give m2 = 9/10
    return _by_hand(
        "stepped_module_symbol_of_the_ring",
        text,
        [*_central("s", "r", "c"), TMember("p", "planet", "c", _y(F(27)))],
        [TGear("S", "s", F(12)), TGear("P1", "p", F(15)), TGear("P2", "p", F(9)), TGear("R", "r", F(36), True)],
        {"SP": ("S", "P1"), "PR": ("R", "P2")},
        (("c", "A", 1), ("r", "B", 1)),
        "s",
        {"z1": F(24), "a": F(30), "b": F(20), "m2": F(9, 10)},
    )


def wolfrom_module_symbol() -> Drawn:
    """A Wolfrom set (the sun held, ring 1 in, ring 2 out) with one module symbol on the
    sun, the first planet gear and the first ring: with the sun's mesh named ``SP`` the
    dependent symbols were once solved over a quotient (PolynomialError)."""
    text = """\
name: Wolfrom set, the sun held, a module symbol L on the sun, the first planet gear and ring
links: [0, r1, r2, p, c]
reference: 0
gears:
  S: {link: 0, teeth: z1, module: L}
  P1: {link: p, teeth: z2, module: L}
  R1: {link: r1, teeth: r1, module: L, internal: true}
  P2: {link: p, teeth: i32, module: 1}
  R2: {link: r2, teeth: jnp, module: 1, internal: true}
couplings:
  H: {type: revolute, links: [c, p]}
  K: {type: revolute, links: [c, 0]}
  SP: {type: mesh, gears: [S, P1]}
  D: {type: mesh, gears: [R1, P1]}
  In: {type: revolute, links: [r1, 0]}
  E: {type: mesh, gears: [R2, P2]}
  Out: {type: revolute, links: [0, r2]}
ports: {input: In, output: Out}
independent: [i32, z2, jnp, z1]
"""
    # L = 1: r1 = z1 + 2 z2 = 61, jnp = i32 + z1 + z2 = 69
    return _by_hand(
        "wolfrom_module_symbol",
        text,
        [*_central("s", "r1", "r2", "c"), TMember("p", "planet", "c", _y(F(47, 2)))],
        [
            TGear("S", "s", F(33, 2)),
            TGear("P1", "p", F(7)),
            TGear("R1", "r1", F(61, 2), True),
            TGear("P2", "p", F(11)),
            TGear("R2", "r2", F(69, 2), True),
        ],
        {"SP": ("S", "P1"), "D": ("R1", "P1"), "E": ("R2", "P2")},
        (("r1", "In", -1), ("r2", "Out", 1)),
        "s",
        {"z1": F(33), "z2": F(14), "r1": F(61), "i32": F(22), "jnp": F(69), "L": F(1)},
    )


def planetary_named_after_rust() -> Drawn:
    """A simple planetary whose sun radius is named ``Some`` (a variant of Rust's prelude,
    which a parameter cannot shadow): its Rust code once did not compile."""
    text = """\
name: planetary, the sun radius named Some
links: [0, s, p, c]
reference: 0
gears:
  S: {link: s, radius: Some}
  P: {link: p, radius: rp}
  R: {link: 0, radius: rr, internal: true}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  D: {type: revolute, links: [c, p]}
  SP: {type: mesh, gears: [S, P]}
  PR: {type: mesh, gears: [P, R]}
ports: {input: A, output: B}
"""
    return _by_hand(
        "planetary_named_after_rust",
        text,
        [*_central("s", "r", "c"), TMember("p", "planet", "c", _y(F(30)))],
        [TGear("S", "s", F(20)), TGear("P", "p", F(10)), TGear("R", "r", F(40), True)],
        {"SP": ("S", "P"), "PR": ("R", "P")},
        (("s", "A", 1), ("c", "B", 1)),
        "r",
        {"Some": F(20), "rp": F(10), "rr": F(40)},
    )


#: Trains written by hand where drawn ones once failed (each an explicit example of the tests).
BY_HAND = (
    tuplin_by_teeth_and_radii,
    stepped_module_symbol_of_the_ring,
    wolfrom_module_symbol,
    planetary_named_after_rust,
)


__all__ = [
    "BY_HAND",
    "FAMILIES",
    "QUICK_FAMILIES",
    "Drawn",
    "plain",
    "stepped_two_modules",
    "trains",
]
