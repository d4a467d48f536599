"""From a graph to a drawable train: the main axis, which link holds each axis, and the
gears of every gear pair (suns, rings, planet gears) with their symbolic radii.

A displacement graph fixes which links turn about which axes and which mesh; it does
not say which central gear is a sun and which a ring, nor whether a planet carries one
gear or a stepped pair. The atlas draws every graph the same documented way (the
classical realisation of the literature's sketches):

- the *main axis* is the axis of the most links (frame, input and output turn about it);
  ties go to the lowest axis number of the canonical labelling;
- relative to the carrier of a gear pair, a gear on the carrier's own axis is *central*
  and a gear on an axis the carrier holds is a *planet*;
- a planet's first mesh with a central gear is with a sun, its later ones with rings;
  the sun and the first ring share one planet gear (the simple planetary's S-P-R), each
  further ring meshes a planet gear of its own (the Wolfrom train's stepped planet); a
  planet-planet mesh is external and uses the planet's first gear. No gear meshes two
  gears on one axis alike (two suns, two rings, two planets on one pin, or a central
  gear two planets on one pin), whose equal centre distances would force equal radii
  and lock two links together: the link gets a gear for each.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property

import networkx as nx

from davies_sym.atlas.enumeration import gear_axes
from davies_sym.atlas.graphs import GearPair, TrainGraph

#: Names of the axes in the train files and the docs: a is the main axis.
AXIS_LETTERS = "abcdefghijklmnopqrstuvwxyz"


@dataclass(frozen=True)
class GearSpec:
    """One gear of the drawn train: on ``link``, turning about ``axis``."""

    name: str
    link: int
    axis: int
    internal: bool


@dataclass(frozen=True)
class MeshSpec:
    """The gears a gear pair meshes, in the order (central or lower link, other)."""

    pair: GearPair
    first: str
    second: str


@dataclass(frozen=True)
class Realisation:
    """A graph drawn as a train: the main axis, the rooted tree of axes, the gears.

    Without a ``frame`` the train is drawn in a housing that holds one member of the main
    axis in each state; with one, that link (a member of the main axis) is the frame and
    every state drives and loads two links that turn in its bearings, coaxial or not."""

    graph: TrainGraph
    main_axis: int
    frame: int | None = None

    @cached_property
    def parent_axis(self) -> dict[int, int]:
        """The axis each link turns about towards the main axis (its own axis)."""
        tree = self.graph.incidence
        parents = nx.bfs_predecessors(tree, ("a", self.main_axis))
        return {node[1]: parent[1] for node, parent in parents if node[0] == "l"}

    @cached_property
    def holder(self) -> dict[int, int]:
        """The link that holds each axis other than the main one (its carrier)."""
        tree = self.graph.incidence
        parents = nx.bfs_predecessors(tree, ("a", self.main_axis))
        return {node[1]: parent[1] for node, parent in parents if node[0] == "a"}

    def axis_name(self, axis: int) -> str:
        """a for the main axis, then b, c, ... in the order of the canonical labelling."""
        others = [k for k in range(len(self.graph.axes)) if k != self.main_axis]
        return AXIS_LETTERS[0 if axis == self.main_axis else 1 + others.index(axis)]

    def is_central(self, link: int, axis: int, carrier: int) -> bool:
        """A gear of ``link`` about ``axis`` is central for ``carrier`` when the carrier
        turns about that axis too (the axis is not one the carrier holds)."""
        return self.holder.get(axis) != carrier and link != carrier

    @cached_property
    def meshes(self) -> tuple[MeshSpec, ...]:
        """Every gear pair with the gears it meshes (rules in the module docstring)."""
        return self._gears[1]

    @cached_property
    def gears(self) -> tuple[GearSpec, ...]:
        """Every gear, in the order of the links and then of their meshes."""
        return self._gears[0]

    @cached_property
    def _gears(self) -> tuple[tuple[GearSpec, ...], tuple[MeshSpec, ...]]:
        named = _GearNames(self)
        meshes = tuple(named.mesh(pair) for pair in self.graph.gear_pairs)
        ordered = tuple(sorted(named.specs.values(), key=lambda g: (g.link, g.axis, g.name)))
        return ordered, meshes

    def about(self, gear: GearSpec) -> int | None:
        """The link whose axis a gear is centred on when it is not its own link's (a gear
        fixed to a carrier about a pin it holds: a link turning on that pin), or None."""
        if gear.axis == self.parent_axis.get(gear.link, gear.axis):
            return None
        return min(x for x in self.graph.axes[gear.axis] if x != gear.link)


class _GearNames:
    """The gears of a drawing, named as its gear pairs are met (rules in the module
    docstring): one name per link, axis and suffix."""

    def __init__(self, drawn: Realisation):
        self.drawn = drawn
        self.specs: dict[str, GearSpec] = {}
        self.central: dict[tuple[int, int, bool], list[str]] = defaultdict(list)
        self.planet_gears: dict[tuple[int, int], list[dict[str, int]]] = defaultdict(list)
        # The axes of the gears each gear meshes, and whether the mesh is internal: a gear
        # meshing two gears on one axis alike (both external, or both internal) would force
        # their radii equal and lock their links together (a train of fewer links).
        self.partners: dict[str, set[tuple[int, bool]]] = defaultdict(set)
        #: The meshes of each planet (link, axis) with a central gear so far.
        self.suns_of: dict[tuple[int, int], int] = defaultdict(int)

    def name(self, link: int, axis: int, suffix: str) -> str:
        return f"G{link}{self.drawn.axis_name(axis)}{suffix}"

    def gear(self, link: int, axis: int, internal: bool, suffix: str, partner: tuple[int, bool]) -> str:
        name = self.name(link, axis, suffix)
        self.specs.setdefault(name, GearSpec(name, link, axis, internal))
        self.partners[name].add(partner)
        return name

    def central_gear(self, link: int, axis: int, internal: bool, partner: tuple[int, bool]) -> str:
        """One central gear per link and kind, another where it meshes a gear on the
        partner's axis alike already (two planets on one pin)."""
        suffixes = self.central[(link, axis, internal)]
        for suffix in suffixes:
            if partner not in self.partners[self.name(link, axis, suffix)]:
                return self.gear(link, axis, internal, suffix, partner)
        suffixes.append(("r" if internal else "") + (str(len(suffixes) + 1) if suffixes else ""))
        return self.gear(link, axis, internal, suffixes[-1], partner)

    def planet_gear(self, link: int, axis: int, role: str, partner: tuple[int, bool]) -> str:
        """The first gear of the planet without a mesh of this role (nor one with a gear
        on the partner's axis) takes it."""
        steps = self.planet_gears[(link, axis)]
        for index, used in enumerate(steps):
            suffix = "" if index == 0 else str(index + 1)
            if partner in self.partners[self.name(link, axis, suffix)]:
                continue
            if used.get(role, 0) == 0 or role == "planet":
                used[role] = used.get(role, 0) + 1
                return self.gear(link, axis, False, suffix, partner)
        steps.append({role: 1})
        return self.gear(link, axis, False, "" if len(steps) == 1 else str(len(steps)), partner)

    def mesh(self, pair: GearPair) -> MeshSpec:
        """The gears ``pair`` meshes: a central gear and a planet's (a sun, then rings),
        or two planets' gears."""
        drawn = self.drawn
        first_central = drawn.is_central(pair.first, pair.first_axis, pair.carrier)
        if not (first_central or drawn.is_central(pair.second, pair.second_axis, pair.carrier)):
            return MeshSpec(
                pair,
                self.planet_gear(pair.first, pair.first_axis, "planet", (pair.second_axis, False)),
                self.planet_gear(pair.second, pair.second_axis, "planet", (pair.first_axis, False)),
            )
        hub, hub_axis, planet, planet_axis = (
            (pair.first, pair.first_axis, pair.second, pair.second_axis)
            if first_central
            else (pair.second, pair.second_axis, pair.first, pair.first_axis)
        )
        ring = self.suns_of[(planet, planet_axis)] > 0
        self.suns_of[(planet, planet_axis)] += 1
        return MeshSpec(
            pair,
            self.central_gear(hub, hub_axis, ring, (planet_axis, ring)),
            self.planet_gear(planet, planet_axis, "ring" if ring else "sun", (hub_axis, ring)),
        )


def main_axis(graph: TrainGraph) -> int:
    """The axis of the most links; the lowest number among equals."""
    return max(range(len(graph.axes)), key=lambda k: (len(graph.axes[k]), -k))


def realisations(graph: TrainGraph) -> Iterator[Realisation]:
    """The ways the atlas draws a graph, in the order it tries them: in a housing about
    the axis of the most links when it has three or more (frame, input and output
    coaxial), then with each link as the frame (the links with the most neighbours
    first), about the axis of its gears (or its first axis when it has none)."""
    main = main_axis(graph)
    if len(graph.axes[main]) >= 3:
        yield Realisation(graph, main)
    geared = gear_axes(graph)
    for frame in sorted(range(graph.links), key=lambda x: (-len(graph.neighbours(x)), x)):
        if len(graph.neighbours(frame)) < 2:
            continue
        own = geared.get(frame, ())
        yield Realisation(graph, own[0] if len(own) == 1 else graph.axes_of(frame)[0], frame)
