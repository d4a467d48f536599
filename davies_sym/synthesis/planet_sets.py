"""The planet sets of a train and the two conditions N equally spaced planets impose.

A *planet* is a link pivoted on a moving link, its *carrier*, at a point off the
carrier's own axis; planets of one carrier that mesh each other form one group (the two
planets of a double-planet set), copied N times around the axis.  The gears the group
meshes on other links are its *central* gears (suns and rings).  Which link carries which
planet is the geometry stage's bearing tree and axis classes
(`davies_sym.geometry.axes.axis_structure`, from the topology alone), the same carriers
the layout and the virtual power of the meshes use; the conditions below are those of
gears on parallel axes, so a planet whose gears the layout tilts (a bevel planet) forms
no set here.

**Assembly** (equal spacing).  Hold the first central gear G1 and turn the carrier by
1/N of a revolution: the first planet group moves to the second position, and every
other central gear Gi turns by (1 - rho_i)/N revolutions, rho_i being the ratio of Gi's to
G1's speed relative to the carrier (the fixed-carrier train G1 -> planets -> Gi).  A
second group fits at that position iff each Gi's turn is a whole number of its teeth,
once each planet of the group may be put in turned by whole teeth of the gear by which it
is reached (k_j teeth of planet j shift Gi by a fixed fraction of its teeth):

    z_i (1 - rho_i)/N + sum_j k_j s_ij  is whole for every i, for some whole k_j.

For a simple set this is (z_s + z_r)/N whole; for a stepped (compound) planet with gears
p1, p2 meshing centrals z1, z2 it is (z1 p2 -+ z2 p1)/(N gcd(p1, p2)) whole; for a
double-planet set (z_r - z_s)/N whole: the conditions of the gear-design literature, here
from one derivation.

**Tip clearance**.  Neighbouring copies of a planet, at orbit radius a, have their
centres 2 a sin(pi/N) apart; their tip circles (diameter m (z + 2), the standard addendum
of one module) must not touch: 2 a sin(pi/N) > m (z + 2) for every gear of the planet.
Planets of different links in one group are not checked against each other's copies.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.algebra.screws import cross
from davies_sym.geometry.axes import AxisStructure, axis_structure
from davies_sym.geometry.layout import Layout
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.model import Train

#: The most re-phasings of a planet group tried for the assembly condition (the product
#: of the planets' tooth periods; a group beyond it is reported, not assumed to fit).
MAX_PHASINGS = 100_000


@dataclass(frozen=True)
class Step:
    """One mesh on the way from the first central gear: ``gear`` (on ``link``) reached
    from ``previous`` (a gear on the link before), external or not."""

    previous: str
    gear: str
    internal: bool


@dataclass(frozen=True)
class PlanetSet:
    """A planet group of one carrier: its planets, each one's pivot coupling, the central
    gears it meshes and the path of meshes from the first central gear to each gear."""

    carrier: str
    planets: tuple[str, ...]
    pivots: Mapping[str, str]
    centrals: tuple[str, ...]
    #: For each planet and each further central gear: the meshes from the first central gear.
    paths: Mapping[str, tuple[Step, ...]]
    #: The gear each planet is reached by (its phase is counted in this gear's teeth).
    entry: Mapping[str, str]
    #: Each planet's distance from the carrier's axis.
    orbit: Mapping[str, sympy.Expr]

    @property
    def name(self) -> str:
        return f"carrier {self.carrier}: planets {', '.join(self.planets)}; central gears {', '.join(self.centrals)}"


def planet_sets(train: Train, layout: Layout) -> tuple[PlanetSet, ...]:
    """Every planet group of ``train`` (with its layout), carriers in name order."""
    pivots = _pivots(train, axis_structure(train), layout)
    meshes = [c.gears for c in train.couplings if c.gears is not None]
    gear_link = {g.name: g.link for g in train.gears}
    out = []
    for carrier in sorted({c for c, _ in pivots.values()}):
        planets = sorted(p for p, (c, _) in pivots.items() if c == carrier)
        groups: list[set[str]] = []
        for p in planets:
            joined = [g for g in groups if any(_meshing(meshes, gear_link, p, q) for q in g)]
            merged = {p}.union(*joined)
            groups = [g for g in groups if g not in joined] + [merged]
        for group in sorted(groups, key=lambda g: sorted(g)):
            out.append(_planet_set(train, layout, carrier, tuple(sorted(group)), pivots))
    return tuple(out)


def _pivots(train: Train, structure: AxisStructure, layout: Layout) -> dict[str, tuple[str, str]]:
    """Planet -> (its carrier, the bearing that pins it there): every link that a moving
    link holds in the bearing tree off the holder's own axis, the bearing being the one of
    the tree (the first by name between the two).  All of a planet's bearings lie on its
    own axis (a link that also holds links off its axis is their carrier, not a planet),
    and no other bearing of the carrier lies there; a planet on a coaxial planet's pin
    turns about that planet's axis and is no planet of its own; a planet whose gears turn
    about axes the layout tilts is left out (see the module's docstring)."""
    revolutes = bearings(train.couplings)
    out = {}
    for planet, carrier in sorted(structure.parent.items()):
        axis = structure.axis[planet]
        if train.reference in (planet, carrier) or structure.axis[carrier] == axis:
            continue
        on_axis = {c.name: structure.bearing_axis[c.name] == axis for c in revolutes}
        if not all(on_axis[c.name] for c in revolutes if planet in c.links):
            continue
        if any(on_axis[c.name] for c in revolutes if carrier in c.links and planet not in c.links):
            continue
        if any(not _parallel(layout, g.name) for g in train.gears if g.link == planet):
            continue
        pivot = min(c.name for c in revolutes if set(c.links) == {planet, carrier})
        out[planet] = (carrier, pivot)
    return out


def _parallel(layout: Layout, gear: str) -> bool:
    """Whether ``gear`` turns about an axis parallel to the layout's main axis."""
    axis = layout.gear_axes.get(gear, layout.axis)
    return all(sympy.expand(x) == 0 for x in cross(axis, layout.axis))


def _meshing(meshes: list[tuple[str, str]], gear_link: Mapping[str, str], a: str, b: str) -> bool:
    return any({gear_link[x], gear_link[y]} == {a, b} for x, y in meshes)


def _planet_set(
    train: Train, layout: Layout, carrier: str, group: tuple[str, ...], pivots: Mapping[str, tuple[str, str]]
) -> PlanetSet:
    """The group's central gears, the paths of meshes to its planets and further central
    gears from the first central gear, and each planet's orbit about the carrier's axis."""
    gear_link = {g.name: g.link for g in train.gears}
    internal = {g.name: g.internal for g in train.gears}
    meshes = [c.gears for c in train.couplings if c.gears is not None]
    on_planet = {g for g, link in gear_link.items() if link in group}
    centrals = sorted({y for x, y in (*meshes, *((b, a) for a, b in meshes)) if x in on_planet and y not in on_planet})
    paths: dict[str, tuple[Step, ...]] = {}
    entry: dict[str, str] = {}
    if centrals:
        # Breadth first from the first central gear through the group's meshes.
        frontier: list[tuple[str, tuple[Step, ...]]] = [(centrals[0], ())]
        seen_links = set()
        while frontier:
            gear, path = frontier.pop(0)
            for x, y in (*meshes, *((b, a) for a, b in meshes)):
                if x != gear:
                    continue
                link = gear_link[y]
                step = Step(gear, y, internal[x] or internal[y])
                if link in group and link not in seen_links:
                    seen_links.add(link)
                    entry[link] = y
                    here = (*path, step)
                    paths[link] = here
                    for sibling in sorted(g for g, owner in gear_link.items() if owner == link):
                        frontier.append((sibling, here))
                elif link not in group and y != centrals[0] and y not in paths and gear in on_planet:
                    paths[y] = (*path, step)
    centre = layout.coupling_points
    carrier_axis = _carrier_axis(layout, centrals)
    orbit = {
        p: sympy.sqrt(sum((a - b) ** 2 for a, b in zip(centre[pivots[p][1]], carrier_axis, strict=True))) for p in group
    }
    return PlanetSet(carrier, group, {p: pivots[p][1] for p in group}, tuple(centrals), paths, entry, orbit)


def _carrier_axis(layout: Layout, centrals: list[str]) -> tuple[sympy.Expr, ...]:
    """The point the carrier turns about: the centre of a central gear (coaxial with it)."""
    if centrals:
        return tuple(layout.gear_centres[centrals[0]])
    return tuple(sympy.Integer(0) for _ in range(3))


def _ratio_rows(
    steps: tuple[Step, ...], teeth: Mapping[str, NDArray[np.int64]]
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """The speed of the last gear's link over the first gear's, relative to the carrier, at
    every row: numerator and (positive) denominator arrays."""
    size = len(next(iter(teeth.values())))
    num, den = np.ones(size, dtype=np.int64), np.ones(size, dtype=np.int64)
    for s in steps:
        num = num * teeth[s.previous] * (1 if s.internal else -1)
        den = den * teeth[s.gear]
        g = np.gcd(num, den)
        num, den = num // g, den // g
    return num, den


def assembles(pset: PlanetSet, teeth: Mapping[str, int], n: int) -> bool | None:
    """Whether ``n`` equally spaced copies of the group can be assembled at one design
    (None: more re-phasings than `MAX_PHASINGS` would have to be tried)."""
    fits, tried = _assembly(pset, {g: np.array([z], dtype=np.int64) for g, z in teeth.items()}, n)
    return bool(fits[0]) if tried[0] else None


def assembles_rows(pset: PlanetSet, teeth: Mapping[str, NDArray[np.int64]], n: int) -> NDArray[np.bool_]:
    """`assembles` at every row of ``teeth`` (arrays by gear name); a row whose periods
    exceed `MAX_PHASINGS` counts as not assembling."""
    return _assembly(pset, teeth, n)[0]


def _assembly(
    pset: PlanetSet, teeth: Mapping[str, NDArray[np.int64]], n: int
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Where the group assembles, and where that was decided (within `MAX_PHASINGS`), at
    every row, vectorised: for each re-phasing k (up to each planet's largest tooth
    period) the residues z_i (1 - rho_i)/n + sum_j k_j s_ij are tested on all rows at once."""
    size = len(next(iter(teeth.values())))
    if len(pset.centrals) < 2:
        return np.ones(size, dtype=bool), np.ones(size, dtype=bool)
    constants = []  # (numerator, denominator) of z_i (1 - rho_i)/n
    shifts = []  # per central: (numerator, denominator) per planet
    for central in pset.centrals[1:]:
        path = pset.paths[central]
        num, den = _ratio_rows(path, teeth)
        z = teeth[central]
        constants.append((z * (den - num), den * n))
        row = []
        for planet in pset.planets:
            mine = pset.paths.get(planet)
            if mine is None or path[: len(mine)] != mine or len(path) == len(mine):
                row.append((np.zeros(size, dtype=np.int64), np.ones(size, dtype=np.int64)))
                continue
            rest_num, rest_den = _ratio_rows(path[len(mine) :], teeth)
            row.append((rest_num * z, rest_den * teeth[pset.entry[planet]]))
        shifts.append(row)
    periods = []
    for j in range(len(pset.planets)):
        period = np.ones(size, dtype=np.int64)
        for row in shifts:
            num, den = row[j]
            period = np.lcm(period, den // np.gcd(num, den))
        periods.append(period)
    total = np.ones(size, dtype=np.int64)
    for p in periods:
        total = total * p
    fits = np.zeros(size, dtype=bool)
    tried = total <= MAX_PHASINGS
    largest = [int(p[tried].max()) if tried.any() else 1 for p in periods]
    if math.prod(largest) > MAX_PHASINGS:
        return fits, np.zeros(size, dtype=bool)
    for ks in itertools.product(*(range(p) for p in largest)):
        ok = tried & ~fits
        for (cn, cd), row in zip(constants, shifts, strict=True):
            # c + sum k_j s_j whole: put everything over one denominator.
            num, den = cn.copy(), cd.copy()
            for k, (sn, sd) in zip(ks, row, strict=True):
                if k:
                    num, den = num * sd + k * sn * den, den * sd
                    g = np.gcd(num, den)
                    num, den = num // g, den // g
            ok &= num % den == 0
        fits |= ok
        if fits[tried].all():
            break
    return fits, tried
