"""The planet sets of a train and their assembly condition (`davies_sym.synthesis.planet_sets`),
checked against closed forms derived here by hand, by brute force over small tooth-number
ranges and N = 2 to 6 equally spaced planets; `assembles` (one design) and `assembles_rows`
(the same designs as arrays) must both answer as the closed form does at every point.

The derivation used for every closed form below (the classical one of the gear-design
literature, e.g. Müller, Epicyclic Drive Trains, 1982, ch. 3; Niemann and Winter,
Maschinenelemente II, 1983, section 24.2): put the first planet group in, hold one central
gear G1 still and turn the carrier by 2 pi/N, so that the group moves to the next position.
Seen from the carrier every gear turns about a fixed axis, so each other central gear Gi
turns by a known angle; a second group fits at the first group's old place iff that angle is a
whole number of Gi's tooth pitches, once each planet of the group may first be turned by a
whole number of pitches of the gear that meshes the gear it is reached by (this keeps that
mesh and shifts Gi by a known fraction of its pitch).  None of these closed forms uses the
coaxiality of the set (they hold for any tooth numbers, e.g. profile-shifted gears), so the
brute force runs over tooth numbers that need not be coaxial: a wider check.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pytest
import sympy

import davies_sym
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.synthesis.planet_sets import PlanetSet, assembles, assembles_rows, planet_sets

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
CATALOG = ROOT / "catalog"

#: The planet counts tried at every point.
PLANET_COUNTS = (2, 3, 4, 5, 6)


def sets_of(path: Path) -> tuple[PlanetSet, ...]:
    """The planet sets of the train file at ``path`` (dependent tooth numbers resolved)."""
    train = resolved_train(davies_sym.load(path))
    return planet_sets(train, train_layout(train))


def only_set(path: Path) -> PlanetSet:
    sets = sets_of(path)
    assert len(sets) == 1, [s.name for s in sets]
    return sets[0]


# --- the closed forms, each derived in its docstring ------------------------------------------------------------


def simple_set(zs: int, zp: int, zr: int, n: int) -> bool:
    """Sun zs, planet zp, ring zr: (zs + zr)/N whole (Müller 1982, ch. 3; Niemann and Winter, 24.2).

    Hold the sun, turn the carrier by 1/N revolution.  Seen from the carrier the sun turns by
    -1/N, the planet by +(zs/zp)/N (external mesh), the ring by +(zp/zr)(zs/zp)/N = +(zs/zr)/N
    (internal mesh); absolutely the ring turns by 1/N + zs/(N zr) = (zr + zs)/(N zr) revolution,
    i.e. (zs + zr)/N of its pitches.  Turning the planet by one of its pitches (it keeps the
    sun's mesh) turns the ring by one of the ring's pitches, a whole number: no help.  Hence
    (zs + zr)/N whole; zp does not enter.
    """
    return (zs + zr) % n == 0


def stepped_two_suns(z1: int, p1: int, p2: int, z2: int, n: int) -> bool:
    """Stepped planet, gear p1 meshing sun z1, gear p2 meshing sun z2 (both external):
    (z1 p2 - z2 p1)/(N gcd(p1, p2)) whole.

    Hold sun 1, turn the carrier by 1/N.  Seen from the carrier sun 1 turns by -1/N, the
    planet by +(z1/p1)/N, sun 2 by -(p2/z2)(z1/p1)/N; absolutely sun 2 turns by
    1/N - z1 p2/(N p1 z2) = (p1 z2 - z1 p2)/(N p1 z2) revolution, (p1 z2 - z1 p2)/(N p1) of
    its pitches.  Turning the planet by k pitches of p1 (it keeps sun 1's mesh) turns sun 2 by
    -k p2/p1 of its pitches.  A second planet fits iff for some whole k

        (p1 z2 - z1 p2 - k N p2)/(N p1)  is whole,  i.e.  p1 z2 - z1 p2 = k N p2 (mod N p1).

    The multiples of N p2 modulo N p1 are exactly the multiples of gcd(N p2, N p1) = N gcd(p1, p2),
    hence the condition.
    """
    return (z1 * p2 - z2 * p1) % (n * math.gcd(p1, p2)) == 0


def stepped_sun_ring(z1: int, p1: int, p2: int, z2: int, n: int) -> bool:
    """Stepped planet, gear p1 meshing the sun z1 (external), gear p2 meshing the ring z2
    (internal): (z1 p2 + z2 p1)/(N gcd(p1, p2)) whole.

    As for two suns, with the internal mesh keeping the sense of rotation: hold the sun, turn
    the carrier by 1/N; seen from the carrier the planet turns by +(z1/p1)/N and the ring by
    +(p2/z2)(z1/p1)/N, absolutely by (p1 z2 + z1 p2)/(N p1 z2) revolution, (p1 z2 + z1 p2)/(N p1)
    of its pitches.  k pitches of p1 turn the ring by +k p2/p1 of its pitches:
    p1 z2 + z1 p2 + k N p2 = 0 (mod N p1) for some whole k iff N gcd(p1, p2) divides z1 p2 + z2 p1.
    """
    return (z1 * p2 + z2 * p1) % (n * math.gcd(p1, p2)) == 0


def double_planet(zs: int, za: int, zb: int, zr: int, n: int) -> bool:
    """Double-planet set, sun zs - planet a (za) - planet b (zb) - ring zr: (zr - zs)/N whole
    (the pair of planets is copied as a whole; their relative place is fixed by the geometry).

    Hold the sun, turn the carrier by 1/N.  Seen from the carrier the sun turns by -1/N,
    planet a by +(zs/za)/N, planet b by -(za/zb)(zs/za)/N = -(zs/zb)/N, the ring (internal
    mesh, same sense as b) by -(zs/zr)/N; absolutely the ring turns by (zr - zs)/(N zr)
    revolution, (zr - zs)/N of its pitches.  Turning planet a by one pitch (keeps the sun's
    mesh) turns b by one of b's pitches and the ring by one of its pitches; turning b by one
    pitch (keeps a's mesh) turns the ring by one pitch: whole numbers, no help.
    Hence (zr - zs)/N whole; za and zb do not enter.
    """
    return (zr - zs) % n == 0


def wolfrom(zs: int, zp1: int, zr1: int, zp2: int, zr2: int, n: int) -> bool:
    """Wolfrom train: planet gear P1 (zp1) meshes the sun (zs) and ring 1 (zr1), gear P2 (zp2)
    meshes ring 2 (zr2): (zs + zr1)/N whole and (zr1 zp2 - zr2 zp1)/(N gcd(zp1, zp2)) whole.

    Sun, P1 and ring 1 form a simple set: (zs + zr1)/N whole, and turning the planet by one
    pitch of P1 shifts the sun by one pitch (no help there).  Ring 1 - P1 - P2 - ring 2 is a
    stepped planet between two internal gears: hold ring 1, turn the carrier by 1/N; seen
    from the carrier ring 1 turns by -1/N, the planet by -(zr1/zp1)/N, ring 2 by
    -(zp2/zr2)(zr1/zp1)/N; absolutely ring 2 turns by (zp1 zr2 - zr1 zp2)/(N zp1 zr2)
    revolution; k pitches of P1 turn ring 2 by k zp2/zp1 of its pitches; as for two suns,
    N gcd(zp1, zp2) must divide zr1 zp2 - zr2 zp1.  The k is free for ring 2 since it changes
    the sun's condition by whole pitches only.
    """
    return (zs + zr1) % n == 0 and (zr1 * zp2 - zr2 * zp1) % (n * math.gcd(zp1, zp2)) == 0


def ravigneaux(zs1: int, zps: int, zpl: int, zs2: int, zr: int, n: int) -> bool:
    """Ravigneaux set: small sun zs1 - short planet zps - long planet zpl - ring zr, and the
    large sun zs2 meshing the long planet: (zs2 + zr)/N whole and (zr - zs1)/N whole.

    Large sun, long planet and ring form a simple set: (zs2 + zr)/N.  Small sun, short
    planet, long planet and ring form a double-planet set: (zr - zs1)/N.  Turning either planet
    by one pitch shifts every central gear by a whole number of pitches (one each), so the two
    conditions are independent of the planets' phases and both must hold.
    """
    return (zs2 + zr) % n == 0 and (zr - zs1) % n == 0


# --- the brute force ---------------------------------------------------------------------------------------------


def check_condition(
    pset: PlanetSet, gears: Sequence[str], ranges: Sequence[Sequence[int]], condition: Callable[..., bool]
) -> None:
    """At every point of the product of ``ranges`` (tooth numbers of ``gears``, in order) and every
    N of `PLANET_COUNTS`: `assembles` is ``condition`` (True or False, never None) and
    `assembles_rows` on the points as arrays gives the same; each N has designs that fit and
    designs that do not (the comparison decides something)."""
    points = list(itertools.product(*ranges))
    columns = {g: np.array([p[k] for p in points], dtype=np.int64) for k, g in enumerate(gears)}
    for n in PLANET_COUNTS:
        expected = [condition(*p, n) for p in points]
        assert any(expected) and not all(expected), f"N = {n}: the ranges decide nothing"
        wrong = []
        for p, e in zip(points, expected, strict=True):
            got = assembles(pset, dict(zip(gears, p, strict=True)), n)
            if got is not e:
                wrong.append((dict(zip(gears, p, strict=True)), n, e, got))
        assert not wrong, f"{len(wrong)} disagreements (teeth, N, expected, got), e.g. {wrong[:5]}"
        rows = assembles_rows(pset, columns, n)
        assert rows.dtype == np.bool_ and rows.shape == (len(points),)
        wrong_rows = [
            (dict(zip(gears, p, strict=True)), n, e, bool(r))
            for p, e, r in zip(points, expected, rows, strict=True)
            if bool(r) is not e
        ]
        assert not wrong_rows, f"{len(wrong_rows)} row disagreements, e.g. {wrong_rows[:5]}"


def test_simple_set_assembles_as_zs_plus_zr_over_n() -> None:
    """Simple set (tests/data/search_planetary.yaml): `simple_set` at every sun 15-26, planet
    9-13 (any, not only the coaxial one) and ring 45-57."""
    pset = only_set(DATA / "search_planetary.yaml")
    check_condition(pset, ("sun", "planet", "ring"), (range(15, 27), range(9, 14), range(45, 58)), simple_set)


#: Planet step tooth numbers with many common divisors between them (gcd 1, 2, 3, 4, 5, 6, 7, 8, 12).
STEP_1 = (12, 15, 16, 18, 21)
STEP_2 = (8, 9, 10, 14, 24)


def test_stepped_planet_between_two_suns() -> None:
    """Stepped planet between two external suns (tests/data/search_stepped_suns.yaml, as the SR20
    differential): `stepped_two_suns` at suns 17-26 and the planet steps `STEP_1` x `STEP_2`."""
    pset = only_set(DATA / "search_stepped_suns.yaml")
    check_condition(pset, ("S1", "P1", "P2", "S2"), (range(17, 27), STEP_1, STEP_2, range(17, 27)), stepped_two_suns)


def test_stepped_planet_between_two_suns_either_way_round() -> None:
    """The same set with the suns' names swapped (the search starts from the first central gear
    by name): the condition is symmetric in the two suns up to sign, so nothing changes."""
    text = (DATA / "search_stepped_suns.yaml").read_text(encoding="utf-8")
    swapped = text.replace("S1:", "TMP:").replace("S2:", "S1:").replace("TMP:", "S2:")
    swapped = swapped.replace("[S1, P1]", "[S2, P1]").replace("[S2, P2]", "[S1, P2]")
    train = resolved_train(davies_sym.loads(swapped, "swapped.yaml"))
    (pset,) = planet_sets(train, train_layout(train))
    assert pset.centrals == ("S1", "S2")
    # Now S2 (zs1) meshes P1 and S1 (zs2) meshes P2.
    check_condition(pset, ("S2", "P1", "P2", "S1"), (range(17, 27), STEP_1, STEP_2, range(17, 27)), stepped_two_suns)


def test_sr20_published_teeth() -> None:
    """The SR20 differential's published teeth 36, 32 / 20, 45 (catalog/sr20_differential.yaml):
    (36 * 20 - 45 * 32)/(N gcd(32, 20)) = -720/(4 N) = -180/N, whole for N = 2 to 6."""
    pset = only_set(CATALOG / "sr20_differential.yaml")
    teeth = {"1": 36, "2": 32, "3": 20, "4": 45}
    for n in PLANET_COUNTS:
        assert stepped_two_suns(36, 32, 20, 45, n)
        assert assembles(pset, teeth, n) is True, n
    assert assembles(pset, teeth, 7) is False  # 180/7 is not whole


def test_stepped_planet_between_a_sun_and_a_ring() -> None:
    """Stepped planet between a sun and a ring (tests/data/search_stepped_sun_ring.yaml):
    `stepped_sun_ring` at suns 17-26, rings 60-71 and the planet steps `STEP_1` x `STEP_2`."""
    pset = only_set(DATA / "search_stepped_sun_ring.yaml")
    check_condition(pset, ("S", "P1", "P2", "R"), (range(17, 27), STEP_1, STEP_2, range(60, 72)), stepped_sun_ring)


def test_double_planet_set() -> None:
    """Double-planet set (tests/data/search_double_planet.yaml): `double_planet` at suns 17-28,
    planets a 11-13 and b 14-15, rings 70-83."""
    pset = only_set(DATA / "search_double_planet.yaml")
    gears = ("SUN", "PA", "PB", "RING")
    check_condition(pset, gears, (range(17, 29), range(11, 14), range(14, 16), range(70, 84)), double_planet)


@pytest.mark.slow
def test_wolfrom_stepped_planet_with_three_central_gears() -> None:
    """Wolfrom train (catalog/wolfrom.yaml, radii in the file, tooth numbers given here by gear
    name): `wolfrom`, two conditions sharing one planet."""
    pset = only_set(CATALOG / "wolfrom.yaml")
    assert set(pset.centrals) == {"S", "R1", "R2"}
    ranges = (range(17, 23), (12, 15, 16), range(48, 54), (10, 12, 14), range(44, 50))
    check_condition(pset, ("S", "P1", "R1", "P2", "R2"), ranges, wolfrom)


def test_ravigneaux_set() -> None:
    """Ravigneaux set (catalog/ravigneaux.yaml): `ravigneaux`; the ZF 3HP12's published teeth
    25, 32, 64 fit three planets ((32 + 64)/3 = 32, (64 - 25)/3 = 13) but not two ((64 - 25)/2)."""
    pset = only_set(CATALOG / "ravigneaux.yaml")
    ranges = (range(22, 28), (15, 16, 17), (15, 16), range(30, 35), range(62, 68))
    check_condition(pset, ("S1", "PS", "PL", "S2", "R"), ranges, ravigneaux)
    published = {"S1": 25, "PS": 16, "PL": 16, "S2": 32, "R": 64}
    assert assembles(pset, published, 3) is True
    assert assembles(pset, published, 2) is False


# --- which links and gears form the planet sets ------------------------------------------------------------------


def test_simple_set_is_found() -> None:
    """tests/data/search_planetary.yaml: carrier C holds planet P (pivot JP) meshing the ring and
    the sun; the orbit is the centre distance m (zs + zp)/2 = (zs + zr)/2 with m = 2 and
    zp = (zr - zs)/2."""
    pset = only_set(DATA / "search_planetary.yaml")
    assert (pset.carrier, pset.planets, set(pset.centrals)) == ("C", ("P",), {"sun", "ring"})
    assert dict(pset.pivots) == {"P": "JP"}
    orbit = pset.orbit["P"]
    assert {str(s) for s in orbit.free_symbols} == {"zs", "zr"}
    for zs, zr in ((20, 70), (17, 61), (33, 99)):
        assert orbit.subs({s: {"zs": zs, "zr": zr}[str(s)] for s in orbit.free_symbols}) == sympy.Rational(zs + zr, 2)


@pytest.mark.parametrize(
    ("name", "carrier", "planets", "centrals"),
    [
        ("search_stepped_suns", "c", ("p",), {"S1", "S2"}),
        ("search_stepped_sun_ring", "c", ("p",), {"S", "R"}),
        ("search_double_planet", "c", ("a", "b"), {"SUN", "RING"}),
    ],
)
def test_planets_and_central_gears(name: str, carrier: str, planets: tuple[str, ...], centrals: set[str]) -> None:
    """Each test train's carrier, its planets (a stepped planet is one link with two gears; the
    double planet two links meshing each other, one group) and the central gears they mesh, as
    the files' comments state."""
    pset = only_set(DATA / f"{name}.yaml")
    assert (pset.carrier, tuple(sorted(pset.planets)), set(pset.centrals)) == (carrier, planets, centrals)


def test_catalog_planet_sets() -> None:
    """The catalog's planetary trains: SR20 (carrier c, compound planet p, gears 1 and 4);
    Wolfrom (carrier c, stepped planet p, sun and both rings); Ravigneaux (one carrier c, short
    and long planets as one group, both suns and the ring); Simpson, two sets sharing the sun:
    carrier o (the front carrier, also ring 2) with p1 meshing S and R1, carrier c2 with p2
    meshing S and R2."""
    found = {
        "sr20_differential": [("c", ("p",), {"1", "4"})],
        "wolfrom": [("c", ("p",), {"S", "R1", "R2"})],
        "ravigneaux": [("c", ("pl", "ps"), {"S1", "S2", "R"})],
        "simpson": [("c2", ("p2",), {"S", "R2"}), ("o", ("p1",), {"S", "R1"})],
    }
    for name, expected in found.items():
        sets = sets_of(CATALOG / f"{name}.yaml")
        got = sorted((s.carrier, tuple(sorted(s.planets)), set(s.centrals)) for s in sets)
        assert got == sorted(expected), name


def test_simpson_test_train_has_the_catalog_sets() -> None:
    """tests/data/search_simpson.yaml (teeth instead of radii) has the catalog's two sets."""
    got = sorted((s.carrier, s.planets, set(s.centrals)) for s in sets_of(DATA / "search_simpson.yaml"))
    assert got == [("c2", ("p2",), {"S", "R2"}), ("o", ("p1",), {"S", "R1"})]


@pytest.mark.parametrize("path", [CATALOG / "simple_pair.yaml", DATA / "search_layshaft.yaml"])
def test_no_planet_set_on_fixed_axes(path: Path) -> None:
    """A simple external pair and a layshaft train: every gear turns about an axis fixed in the
    housing, so there is no planet and no planet set."""
    assert sets_of(path) == ()
