"""A planetary gear train as a graph: links, the axes they turn about, and gear pairs.

The turning pairs of a train are written as *axes*: an axis is the set of links that
turn about one line (all coaxial with each other). This is the displacement graph of
the literature with each level's clique of coaxial links kept as one set, so the choice
of which coaxial links carry the bearings, arbitrary in the classical graph, does not
exist here (no pseudo-isomorphic graphs). Links and axes form a tree (the bipartite
incidence graph): the turning pairs of Tsai's graph are a spanning tree.

A gear pair (i, j) meshes two links on different axes that are both fixed in one link
k, the *carrier* (transfer vertex) of the pair: the path from i to j in the tree is
i - axis - k - axis - j (Tsai's rule: one transfer vertex per fundamental circuit, the
edges on each side of it on one level).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import networkx as nx


@dataclass(frozen=True)
class GearPair:
    """A gear pair and where it lies: the gear of ``first`` turns about ``first_axis``,
    that of ``second`` about ``second_axis``, both axes fixed in ``carrier``."""

    first: int
    second: int
    first_axis: int
    second_axis: int
    carrier: int


@dataclass(frozen=True)
class TrainGraph:
    """A train of ``links`` links (0 .. links-1): ``axes`` are sets of coaxial links
    (each of at least two, sorted), ``gears`` the meshing link pairs (i < j)."""

    links: int
    axes: tuple[tuple[int, ...], ...]
    gears: tuple[tuple[int, int], ...]

    @cached_property
    def incidence(self) -> nx.Graph:
        """The tree of links ("l", i) and axes ("a", k), an edge where a link turns about an axis."""
        tree = nx.Graph()
        tree.add_nodes_from(("l", i) for i in range(self.links))
        for k, axis in enumerate(self.axes):
            tree.add_edges_from((("a", k), ("l", i)) for i in axis)
        return tree

    def is_tree(self) -> bool:
        """Links and axes form a tree: every link turns relative to every other through
        one chain of bearings, and there are L - 1 turning pairs."""
        return bool(nx.is_tree(self.incidence))

    def pair(self, first: int, second: int) -> GearPair | None:
        """Where a gear pair between ``first`` and ``second`` would lie, or None when no
        link holds both their axes (the path between them is not link - axis - carrier -
        axis - link)."""
        path = nx.shortest_path(self.incidence, ("l", first), ("l", second))
        if len(path) != 5 or path[1] == path[3]:
            return None
        return GearPair(first, second, path[1][1], path[3][1], path[2][1])

    @cached_property
    def gear_pairs(self) -> tuple[GearPair, ...]:
        """Every gear pair with its axes and carrier, in the order of ``gears``."""
        found = []
        for i, j in self.gears:
            located = self.pair(i, j)
            if located is None:
                raise ValueError(f"gear pair ({i}, {j}) has no carrier holding both axes")
            found.append(located)
        return tuple(found)

    def axes_of(self, link: int) -> tuple[int, ...]:
        """The axes a link turns about (a carrier holds several)."""
        return tuple(k for k, axis in enumerate(self.axes) if link in axis)

    def neighbours(self, link: int) -> tuple[int, ...]:
        """The links that turn about an axis with ``link`` (in its bearings or it in theirs)."""
        return tuple(sorted({y for k in self.axes_of(link) for y in self.axes[k]} - {link}))
