"""Seeded random planar parallel-axis gear trains, each as an oracle description
(:mod:`balance`) and as YAML text in several spellings of the topology language.

Families (all radii satisfy the coaxial conditions of their family):

* ``pair``: two gears on fixed axes (external, or pinion and annulus).
* ``chain``: compound fixed-axis chain of 3-4 shafts (some meshes internal).
* ``planetary``: sun, planet, ring, carrier; r_R = r_S + 2 r_P.
* ``stepped``: sun - P1, P2 - ring on one compound planet; r_S + r_P1 = r_R - r_P2.
* ``double_pinion``: sun - P1 - P2 - ring, both planets on one carrier, laid out in 2-D
  (``placement``) on a triangle with rational sides and coordinates.
* ``wolfrom``: sun - P1 - ring 1, P2 - ring 2; the carrier runs free.
* ``tuplin``: two annuli on one compound planet; r_1 - r_3 = r_2 - r_4 (Laus Fig. 7).
* ``simpson``: two planetary sets on one sun, front carrier = rear ring; four states.
* ``ravigneaux``: small sun - short planet - long planet - large sun and ring; four states.

For the families without states, one of the central members is held (in the catalog's
spelling its gears sit on the housing; in the ``brake`` spelling it is braked in a state)
and the input and output are two of the others.

Spellings: ``catalog`` (symbolic radii, the catalog's style: ``at: 0`` on every bearing
between the housing and a member on the main axis), ``minimal`` (``at`` only where
neither link carries a gear, as the language allows), ``numeric`` (radii as
numbers), ``reversed`` (the two gears of every mesh swapped), ``flipped`` (the two links
of every revolute swapped; the engine's port speed changes sign with it),
``shuffled`` (entries of links, gears and couplings in random order), ``renamed``
(other names for members, gears, couplings, states and symbols), ``teeth``
(teeth + module), ``brake`` (the held member braked in a state), ``combined``
(reversed + flipped + shuffled + renamed + teeth, another placement direction).
"""

from __future__ import annotations

import json
import random
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from fractions import Fraction

from .balance import Gear, Member, Mesh, State, TrainSpec

FAMILIES = ("pair", "chain", "planetary", "stepped", "double_pinion", "wolfrom", "tuplin", "simpson", "ravigneaux")
SPELLINGS = (
    "catalog",
    "minimal",
    "numeric",
    "reversed",
    "flipped",
    "shuffled",
    "renamed",
    "teeth",
    "brake",
    "combined",
)
HOUSING = "0"
RUN = "run"

F = Fraction


@dataclass(frozen=True)
class TGear:
    name: str
    member: str
    radius: Fraction
    internal: bool = False


@dataclass(frozen=True)
class TMember:
    """``role``: housing, central (main axis), fixed (another axis fixed in the housing)
    or planet (``carrier`` holds it)."""

    name: str
    role: str
    carrier: str | None = None
    axis: tuple[Fraction, Fraction] = (F(0), F(0))


@dataclass
class RandomTrain:
    """A generated train in canonical names (ports are the bearings ``A``, ``B``, ...)."""

    family: str
    seed: int
    members: list[TMember]
    gears: list[TGear]
    #: name -> (first gear, second gear, eta)
    meshes: dict[str, tuple[str, str, Fraction]]
    #: port coupling name -> member (the other side is the housing)
    ports: dict[str, str]
    input: str
    output: str
    #: the central member held (single-state families), braked in state ``run``
    held: str | None = None
    states: list[State] = field(default_factory=list)
    placement: bool = False
    description: str = ""

    # -- oracle --------------------------------------------------------------------------
    def oracle(self) -> TrainSpec:
        """The oracle description (the held member braked in state ``run``)."""
        members = tuple(Member(m.name, m.carrier, m.axis) for m in self.members)
        gears = tuple(Gear(g.name, g.member, g.radius, g.internal) for g in self.gears)
        meshes = tuple(Mesh(n, (a, b), eta) for n, (a, b, eta) in self.meshes.items())
        return TrainSpec(
            f"{self.family}-{self.seed}",
            members,
            gears,
            meshes,
            HOUSING,
            dict(self.ports),
            self.input,
            self.output,
            tuple(self.oracle_states()),
        )

    def oracle_states(self) -> list[State]:
        if self.states:
            return self.states
        brake = (self.held,) if self.held else ()
        return [State(RUN, self.input, self.output, brake=brake)]

    def cases(self) -> list[tuple[str, str, str]]:
        """(state, input port, output port) of every comparison: each state, both directions."""
        out = []
        for st in self.oracle_states():
            out += [(st.name, st.input, st.output), (st.name, st.output, st.input)]
        return out

    def member(self, name: str) -> TMember:
        return next(m for m in self.members if m.name == name)

    def gear(self, name: str) -> TGear:
        return next(g for g in self.gears if g.name == name)


# -- random geometry helpers ----------------------------------------------------------------


def _eta(rng: random.Random) -> Fraction:
    return F(rng.randint(9000, 9999), 10000)


def _radius(rng: random.Random, lo: int, hi: int) -> Fraction:
    """A radius on a half-tooth grid (module 1): n/2 with lo <= n/2 <= hi."""
    return F(rng.randint(2 * lo, 2 * hi), 2)


def _y(v: Fraction) -> tuple[Fraction, Fraction]:
    return (F(0), v)


def rational_triangle(rng: random.Random) -> tuple[Fraction, Fraction, Fraction, Fraction, Fraction]:
    """A triangle O, p1 = (0, d1), p2 = (x, y) with rational sides d1, d2 = |p2|,
    d12 = |p2 - p1| and rational coordinates: two rational right triangles glued along
    the common leg x (t, s parametrise the rational points of the unit circle).
    Returns (d1, d2, d12, x, y), scaled to integers."""
    while True:
        t = F(rng.randint(1, 9), rng.randint(2, 10))
        s = F(rng.randint(1, 9), rng.randint(2, 10))
        if not (0 < t < 1 and 0 < s < 1):
            continue
        y, d2 = (1 - t * t) / (2 * t), (1 + t * t) / (2 * t)
        w, d12 = (1 - s * s) / (2 * s), (1 + s * s) / (2 * s)
        d1 = y + w if rng.random() < 0.7 else y - w
        if d1 <= 0:
            continue
        x = F(1)
        den = 1
        for v in (y, d2, w, d12, d1):
            den = den * v.denominator // _gcd(den, v.denominator)
        scale = F(den)
        d1, d2, d12, x, y = (v * scale for v in (d1, d2, d12, x, y))
        g = _gcd_all([int(v) for v in (d1, d2, d12, x, y) if v != 0])
        d1, d2, d12, x, y = (v / g for v in (d1, d2, d12, x, y))
        if 8 <= d1 <= 400 and 8 <= d12 <= 400 and 8 <= d2 <= 600:
            return d1, d2, d12, x, y


def _gcd(a: int, b: int) -> int:
    while b:
        a, b = b, a % b
    return abs(a)


def _gcd_all(values: list[int]) -> int:
    g = 0
    for v in values:
        g = _gcd(g, v)
    return g or 1


# -- families -----------------------------------------------------------------------------


def _planetary_roles(rng: random.Random, central: list[str]) -> tuple[str, str, str]:
    held = rng.choice(central)
    rest = [c for c in central if c != held]
    rng.shuffle(rest)
    return held, rest[0], rest[1]


def _pair(rng: random.Random, seed: int) -> RandomTrain:
    internal = rng.random() < 0.3
    r1, r2 = _radius(rng, 8, 40), _radius(rng, 8, 40)
    if internal:
        r1, r2 = sorted((r1, r2))
        if r1 == r2:
            r2 += 5
    members = [
        TMember(HOUSING, "housing"),
        TMember("a", "fixed"),
        TMember("b", "fixed", axis=_y(r2 - r1 if internal else r1 + r2)),
    ]
    gears = [TGear("G1", "a", r1), TGear("G2", "b", r2, internal)]
    inp, out = ("a", "b") if rng.random() < 0.5 else ("b", "a")
    return RandomTrain(
        "pair",
        seed,
        members,
        gears,
        {"C": ("G1", "G2", _eta(rng))},
        {"A": inp, "B": out},
        "A",
        "B",
        description="fixed-axis pair" + (" (annulus)" * internal),
    )


def _chain(rng: random.Random, seed: int) -> RandomTrain:
    k = rng.choice((3, 4))
    members = [TMember(HOUSING, "housing")]
    gears: list[TGear] = []
    meshes: dict[str, tuple[str, str, Fraction]] = {}
    pos = F(0)
    for i in range(1, k):
        # mesh M<i> between gear G<i>b on shaft s<i> and gear G<i+1>a on shaft s<i+1>
        ra, rb = _radius(rng, 6, 35), _radius(rng, 6, 35)
        internal = rng.random() < 0.25 and ra != rb
        ga = TGear(f"G{i}b", f"s{i}", ra, internal and ra > rb)
        gb = TGear(f"G{i + 1}a", f"s{i + 1}", rb, internal and rb > ra)
        members.append(TMember(f"s{i}", "fixed", axis=_y(pos)))
        pos += abs(ra - rb) if internal else ra + rb
        gears += [ga, gb]
        meshes[f"M{i}"] = (ga.name, gb.name, _eta(rng))
    members.append(TMember(f"s{k}", "fixed", axis=_y(pos)))
    ends = ["s1", f"s{k}"]
    rng.shuffle(ends)
    return RandomTrain(
        "chain",
        seed,
        members,
        gears,
        meshes,
        {"A": ends[0], "B": ends[1]},
        "A",
        "B",
        description=f"compound fixed-axis chain of {k} shafts",
    )


def _three_shaft(
    family: str,
    rng: random.Random,
    seed: int,
    members: list[TMember],
    gears: list[TGear],
    meshes: dict[str, tuple[str, str, Fraction]],
    central: list[str],
    description: str,
    placement: bool = False,
) -> RandomTrain:
    held, inp, out = _planetary_roles(rng, central)
    return RandomTrain(
        family,
        seed,
        members,
        gears,
        meshes,
        {"A": inp, "B": out},
        "A",
        "B",
        held=held,
        placement=placement,
        description=f"{description}; {held} held, {inp} in, {out} out",
    )


def _planetary(rng: random.Random, seed: int) -> RandomTrain:
    rs, rp = _radius(rng, 6, 40), _radius(rng, 5, 30)
    rr = rs + 2 * rp
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("r", "central"),
        TMember("c", "central"),
        TMember("p", "planet", "c", _y(rs + rp)),
    ]
    gears = [TGear("S", "s", rs), TGear("P", "p", rp), TGear("R", "r", rr, True)]
    meshes = {"C": ("S", "P", _eta(rng)), "D": ("R", "P", _eta(rng))}
    return _three_shaft("planetary", rng, seed, members, gears, meshes, ["s", "r", "c"], "simple planetary")


def _stepped(rng: random.Random, seed: int) -> RandomTrain:
    while True:
        rs, rp1, rp2 = _radius(rng, 6, 40), _radius(rng, 5, 30), _radius(rng, 5, 30)
        rr = rs + rp1 + rp2
        if rp1 != rp2:
            break
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("r", "central"),
        TMember("c", "central"),
        TMember("p", "planet", "c", _y(rs + rp1)),
    ]
    gears = [TGear("S", "s", rs), TGear("P1", "p", rp1), TGear("P2", "p", rp2), TGear("R", "r", rr, True)]
    meshes = {"C": ("S", "P1", _eta(rng)), "D": ("R", "P2", _eta(rng))}
    return _three_shaft("stepped", rng, seed, members, gears, meshes, ["s", "r", "c"], "stepped planet")


def _double_pinion(rng: random.Random, seed: int) -> RandomTrain:
    while True:
        d1, d2, d12, x, y = rational_triangle(rng)
        rp1 = F(rng.randint(1, int(min(d1, d12)) * 2 - 1), 2)
        rs, rp2 = d1 - rp1, d12 - rp1
        rr = d2 + rp2
        if rs > 0 and rp2 > 0 and d1 + rp1 < rr and d2 - rp2 > rs and rs >= 4 and rp1 >= 3 and rp2 >= 3:
            break
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("r", "central"),
        TMember("c", "central"),
        TMember("p1", "planet", "c", (F(0), d1)),
        TMember("p2", "planet", "c", (x, y)),
    ]
    gears = [TGear("S", "s", rs), TGear("P1", "p1", rp1), TGear("P2", "p2", rp2), TGear("R", "r", rr, True)]
    meshes = {"C": ("S", "P1", _eta(rng)), "D": ("P1", "P2", _eta(rng)), "E": ("R", "P2", _eta(rng))}
    return _three_shaft(
        "double_pinion", rng, seed, members, gears, meshes, ["s", "r", "c"], "double-pinion planetary", placement=True
    )


def _wolfrom(rng: random.Random, seed: int) -> RandomTrain:
    while True:
        rs, rp1, rp2 = _radius(rng, 6, 30), _radius(rng, 5, 25), _radius(rng, 5, 25)
        rr1 = rs + 2 * rp1
        rr2 = rr1 - rp1 + rp2
        if rp1 != rp2:
            break
    e = rs + rp1
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("r1", "central"),
        TMember("r2", "central"),
        TMember("c", "central"),
        TMember("p", "planet", "c", _y(e)),
    ]
    gears = [
        TGear("S", "s", rs),
        TGear("P1", "p", rp1),
        TGear("R1", "r1", rr1, True),
        TGear("P2", "p", rp2),
        TGear("R2", "r2", rr2, True),
    ]
    meshes = {"C": ("S", "P1", _eta(rng)), "D": ("R1", "P1", _eta(rng)), "E": ("R2", "P2", _eta(rng))}
    held = rng.choice(["r1", "r1", "r2", "s"])
    rest = [m for m in ("s", "r1", "r2") if m != held]
    rng.shuffle(rest)
    return RandomTrain(
        "wolfrom",
        seed,
        members,
        gears,
        meshes,
        {"A": rest[0], "B": rest[1]},
        "A",
        "B",
        held=held,
        description=f"Wolfrom, carrier free; {held} held, {rest[0]} in, {rest[1]} out",
    )


def _tuplin(rng: random.Random, seed: int) -> RandomTrain:
    while True:
        r3, r4 = _radius(rng, 5, 30), _radius(rng, 5, 30)
        e = _radius(rng, 5, 40)
        r1, r2 = e + r3, e + r4
        if r3 != r4:
            break
    members = [
        TMember(HOUSING, "housing"),
        TMember("1", "central"),
        TMember("2", "central"),
        TMember("5", "central"),
        TMember("3/4", "planet", "5", _y(e)),
    ]
    gears = [TGear("1", "1", r1, True), TGear("2", "2", r2, True), TGear("3", "3/4", r3), TGear("4", "3/4", r4)]
    meshes = {"C": ("1", "3", _eta(rng)), "D": ("2", "4", _eta(rng))}
    return _three_shaft("tuplin", rng, seed, members, gears, meshes, ["1", "2", "5"], "two annuli (Tuplin)")


def _simpson(rng: random.Random, seed: int) -> RandomTrain:
    rs, rp1, rp2 = _radius(rng, 8, 30), _radius(rng, 5, 20), _radius(rng, 5, 20)
    members = [
        TMember(HOUSING, "housing"),
        TMember("s", "central"),
        TMember("r1", "central"),
        TMember("o", "central"),
        TMember("c2", "central"),
        TMember("p1", "planet", "o", _y(rs + rp1)),
        TMember("p2", "planet", "c2", _y(rs + rp2)),
    ]
    gears = [
        TGear("S", "s", rs),
        TGear("P1", "p1", rp1),
        TGear("R1", "r1", rs + 2 * rp1, True),
        TGear("P2", "p2", rp2),
        TGear("R2", "o", rs + 2 * rp2, True),
    ]
    meshes = {
        "C": ("S", "P1", _eta(rng)),
        "D": ("R1", "P1", _eta(rng)),
        "E": ("S", "P2", _eta(rng)),
        "F": ("R2", "P2", _eta(rng)),
    }
    states = [
        State("first", "A", "B", brake=("c2",)),
        State("second", "A", "B", brake=("s",)),
        State("third", "A", "B", clutch=(("r1", "s"),)),
        State("reverse", "G", "B", brake=("c2",), free=("r1", "p1")),
    ]
    return RandomTrain(
        "simpson",
        seed,
        members,
        gears,
        meshes,
        {"A": "r1", "B": "o", "G": "s"},
        "A",
        "B",
        states=states,
        description="Simpson three-speed set",
    )


def _ravigneaux(rng: random.Random, seed: int) -> RandomTrain:
    while True:
        d1, d2, d12, x, y = rational_triangle(rng)
        rpl = F(rng.randint(1, int(min(d12, d2)) * 2 - 1), 2)
        rps, rs2 = d12 - rpl, d2 - rpl
        rs1, rr = d1 - rps, d2 + rpl
        if min(rps, rs2, rs1) >= 3 and rpl >= 3 and d1 + rps < rr:
            break
    members = [
        TMember(HOUSING, "housing"),
        TMember("s1", "central"),
        TMember("s2", "central"),
        TMember("c", "central"),
        TMember("r", "central"),
        TMember("ps", "planet", "c", (F(0), d1)),
        TMember("pl", "planet", "c", (x, y)),
    ]
    gears = [
        TGear("S1", "s1", rs1),
        TGear("S2", "s2", rs2),
        TGear("PS", "ps", rps),
        TGear("PL", "pl", rpl),
        TGear("R", "r", rr, True),
    ]
    meshes = {
        "G1": ("S1", "PS", _eta(rng)),
        "G2": ("PS", "PL", _eta(rng)),
        "G3": ("S2", "PL", _eta(rng)),
        "G4": ("R", "PL", _eta(rng)),
    }
    states = [
        State("reverse", "B", "D", brake=("c",), free=("s1", "ps")),
        State("first", "A", "D", brake=("c",), free=("s2",)),
        State("second", "A", "D", brake=("s2",)),
        State("third", "A", "D", clutch=(("s1", "s2"),)),
    ]
    return RandomTrain(
        "ravigneaux",
        seed,
        members,
        gears,
        meshes,
        {"A": "s1", "B": "s2", "D": "r"},
        "A",
        "D",
        states=states,
        placement=True,
        description="Ravigneaux set",
    )


_BUILDERS = {
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


def generate(family: str, seed: int) -> RandomTrain:
    """The train of ``family`` for ``seed`` (deterministic)."""
    rng = random.Random(f"{family}:{seed}")
    return _BUILDERS[family](rng, seed)


def trains(n: int, families: tuple[str, ...] = FAMILIES, start: int = 0) -> Iterator[RandomTrain]:
    """``n`` trains of each family, seeds ``start`` .. ``start + n - 1``."""
    for seed in range(start, start + n):
        for family in families:
            yield generate(family, seed)


# -- YAML spellings -------------------------------------------------------------------------


@dataclass
class Spelling:
    """One YAML text of a train and what is needed to evaluate it."""

    name: str
    yaml: str
    #: symbol name -> exact value (radii given as symbols, mesh efficiencies)
    values: dict[str, Fraction]
    #: canonical port / state name -> the name in this text
    ports: dict[str, str]
    states: dict[str, str | None]
    #: canonical port -> +1 when its revolute is written [housing, member], -1 reversed
    orientation: dict[str, int]

    def engine_state(self, state: str) -> str | None:
        return self.states[state]


_NAME_POOL = [
    "frame",
    "Sun",
    "shaft_in",
    "arm",
    "k1",
    "7",
    "3/4",
    "q-2",
    "ring.out",
    "Planet A",
    "m",
    "x9",
    "lower",
    "UP",
    "n_4",
    "w",
    "11",
    "h/2",
    "gamma",
    "t0",
]
_COUPLING_POOL = [
    "In",
    "Out",
    "b1",
    "b2",
    "b3",
    "b4",
    "m1",
    "m2",
    "m3",
    "m4",
    "Z",
    "X7",
    "pin",
    "g_a",
    "g_b",
    "Q",
    "brg",
    "r",
    "tooth",
    "ZZ",
]


def _scalar(name: str) -> str:
    """A YAML scalar for a name (quoted unless it is a plain word or number)."""
    if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*|[0-9]+|[0-9]+/[0-9]+", name) and name.lower() not in (
        "true",
        "false",
        "yes",
        "no",
        "on",
        "off",
        "null",
        "y",
        "n",
    ):
        return name
    return json.dumps(name)


def _number(v: Fraction) -> str:
    return str(v.numerator) if v.denominator == 1 else f'"{v.numerator}/{v.denominator}"'


def _flow(entries: list[tuple[str, str]]) -> str:
    return "{" + ", ".join(f"{k}: {v}" for k, v in entries) + "}"


def spelling(train: RandomTrain, name: str, rng: random.Random | None = None) -> Spelling:
    """``train`` written in the spelling ``name`` (see the module docstring); parts may be
    joined with ``+`` (``reversed+renamed``).  ``rng`` chooses the order of entries, the
    names and the tooth counts (default: seeded by the train and the spelling)."""
    rng = rng or random.Random(f"{train.family}:{train.seed}:{name}")
    parts = (
        set(name.split("+"))
        if name != "combined"
        else {"reversed", "flipped", "shuffled", "renamed", "teeth", "placement"}
    )
    if name == "catalog":
        parts = set()
    reverse = "reversed" in parts
    flip_links = "flipped" in parts
    shuffle = "shuffled" in parts
    rename = "renamed" in parts
    numeric = bool(parts & {"numeric", "teeth"})
    teeth = "teeth" in parts
    brake = "brake" in parts and train.held is not None and not train.states
    minimal = "minimal" in parts

    # names
    member_names = {m.name: m.name for m in train.members}
    gear_names = {g.name: g.name for g in train.gears}
    coupling_names: dict[str, str] = {}
    state_names = {s.name: s.name for s in train.states}
    if rename:
        pool = _NAME_POOL[:]
        rng.shuffle(pool)
        member_names = {m.name: pool[i] for i, m in enumerate(train.members)}
        gpool = [f"g{i}" for i in range(1, 20)] + ["Z1", "annulus", "pinion", "12"]
        rng.shuffle(gpool)
        gear_names = {g.name: gpool[i] for i, g in enumerate(train.gears)}
        state_names = {s.name: f"gear_{i + 1}" for i, s in enumerate(train.states)}
    cpool = _COUPLING_POOL[:]
    rng.shuffle(cpool)

    def cname(canonical: str) -> str:
        if canonical not in coupling_names:
            coupling_names[canonical] = cpool.pop() if rename else canonical
        return coupling_names[canonical]

    held_in_housing = train.held is not None and not brake and not train.states
    housing = member_names[HOUSING]

    def link(member: str) -> str:
        if held_in_housing and member == train.held:
            return housing
        return member_names[member]

    values: dict[str, Fraction] = {}
    # links
    links = [link(m.name) for m in train.members if not (held_in_housing and m.name == train.held)]
    if shuffle:
        rng.shuffle(links)
    # gears
    geared = {link(g.member) for g in train.gears}
    gear_lines = []
    for g in train.gears:
        entries = [("link", _scalar(link(g.member)))]
        if teeth:
            z = _teeth(rng, g.radius)
            entries += [("teeth", str(z)), ("module", _number(2 * g.radius / z))]
        elif numeric:
            entries.append(("radius", _number(g.radius)))
        else:
            symbol = "r" + re.sub(r"[^A-Za-z0-9]", "", gear_names[g.name]).lower()
            if symbol in values:
                symbol += "_" + str(len(values))
            values[symbol] = g.radius
            entries.append(("radius", symbol))
        if g.internal:
            entries.append(("internal", "true"))
        gear_lines.append(f"  {_scalar(gear_names[g.name])}: {_flow(entries)}")
    if shuffle:
        rng.shuffle(gear_lines)
    # couplings: port bearings, other bearings, meshes
    coupling_lines = []
    orientation: dict[str, int] = {}

    def revolute(canonical: str, a: str, b: str, at: bool, axis: str | None) -> None:
        flip = flip_links
        pair = [b, a] if flip else [a, b]
        entries = [("type", "revolute"), ("links", "[" + ", ".join(_scalar(x) for x in pair) + "]")]
        if at:
            entries.append(("at", "0"))
        if axis is not None:
            entries.append(("axis", _scalar(axis)))
        coupling_lines.append(f"  {_scalar(cname(canonical))}: {_flow(entries)}")
        orientation[canonical] = -1 if flip else 1

    port_of = {m: p for p, m in train.ports.items()}
    letters = iter(["K", "H", "J", "L", "N", "Q", "U", "V", "W", "Y"])
    for m in train.members:
        if m.role == "housing" or (held_in_housing and m.name == train.held):
            continue
        if m.role in ("central", "fixed"):
            canonical = port_of.get(m.name) or next(letters)
            needed = link(m.name) not in geared and housing not in geared
            revolute(canonical, housing, link(m.name), at=m.role == "central" and (needed or not minimal), axis=None)
        else:
            carrier = link(m.carrier or HOUSING)
            revolute(next(letters), carrier, link(m.name), at=False, axis=link(m.name) if carrier in geared else None)
    for mesh, (a, b, eta) in train.meshes.items():
        pair = [gear_names[b], gear_names[a]] if reverse else [gear_names[a], gear_names[b]]
        entries = [("type", "mesh"), ("gears", "[" + ", ".join(_scalar(x) for x in pair) + "]")]
        coupling_lines.append(f"  {_scalar(cname(mesh))}: {_flow(entries)}")
        values[f"eta_{cname(mesh)}"] = eta
    if shuffle:
        rng.shuffle(coupling_lines)
    # states
    state_lines = []
    engine_states: dict[str, str | None] = {}
    if train.states:
        for s in train.states:
            entries = [("input", _scalar(cname(s.input))), ("output", _scalar(cname(s.output)))]
            if s.brake:
                entries.append(("brake", "[" + ", ".join(_scalar(link(x)) for x in s.brake) + "]"))
            if s.clutch:
                entries.append(
                    (
                        "clutch",
                        "["
                        + ", ".join("[" + ", ".join(_scalar(link(x)) for x in pair) + "]" for pair in s.clutch)
                        + "]",
                    )
                )
            if s.free:
                entries.append(("free", "[" + ", ".join(_scalar(link(x)) for x in s.free) + "]"))
            state_lines.append(f"  {_scalar(state_names[s.name])}: {_flow(entries)}")
            engine_states[s.name] = state_names[s.name]
    elif brake:
        name_run = "hold" if rename else RUN
        entries = [
            ("input", _scalar(cname(train.input))),
            ("output", _scalar(cname(train.output))),
            ("brake", f"[{_scalar(link(train.held or ''))}]"),
        ]
        state_lines.append(f"  {_scalar(name_run)}: {_flow(entries)}")
        engine_states[RUN] = name_run
    else:
        engine_states[RUN] = None
    lines = [
        "format: 1",
        f"name: {json.dumps(f'random {train.family} {train.seed} ({name})')}",
        f"# {train.description}",
    ]
    if train.placement:
        lines.append("placement: [3, 4]" if "placement" in parts else "placement: [0, 1]")
    lines.append("links: [" + ", ".join(_scalar(x) for x in links) + "]")
    lines.append(f"reference: {_scalar(housing)}")
    lines.append("gears:")
    lines += gear_lines
    lines.append("couplings:")
    lines += coupling_lines
    lines.append(f"ports: {{input: {_scalar(cname(train.input))}, output: {_scalar(cname(train.output))}}}")
    if state_lines:
        lines.append("states:")
        lines += state_lines
    ports = {p: cname(p) for p in train.ports}
    return Spelling(name, "\n".join(lines) + "\n", values, ports, engine_states, orientation)


def _teeth(rng: random.Random, radius: Fraction) -> int:
    """A tooth count for ``radius``: module 1, 2 or 1/2 when that gives whole teeth, else any."""
    for module in rng.sample([F(1), F(2), F(1, 2)], 3):
        z = 2 * radius / module
        if z.denominator == 1 and 6 <= z <= 400:
            return int(z)
    return rng.randint(12, 90)


def spellings(train: RandomTrain, names: tuple[str, ...] = SPELLINGS) -> dict[str, Spelling]:
    """Every applicable spelling of ``train`` (``brake`` only for trains with a held member)."""
    out = {}
    for name in names:
        if name == "brake" and (train.held is None or train.states):
            continue
        out[name] = spelling(train, name)
    return out
