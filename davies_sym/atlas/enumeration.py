"""Every non-isomorphic one-degree-of-freedom planetary gear train of N links.

A train is a `TrainGraph`: links, the axes they turn about (sets of coaxial links) and gear
pairs. Its displacement graph (d-graph) is the train itself; its rotation graph (r-graph)
forgets the axes (`davies_sym.atlas.canonical`). The rules (docs/atlas_definitions.md):

1. Buchsbaum and Freudenstein (1970), Tsai (2001): L links, L - 1 turning pairs forming a
   spanning tree (links and axes form a tree, every axis holds at least two links) and
   L - 2 gear pairs.
2. Tsai (2001): one transfer vertex per fundamental circuit, the turning edges on each
   side of it on one level and the two levels different: a gear pair meshes two links that
   turn about two different axes of a third link, its carrier (`TrainGraph.pair`).
3. Mobility one, and no degenerate train: at generic tooth ratios the L - 2 speed relations
   w_i - w_k = -n_ij (w_j - w_k) are independent (rank L - 2) and no two links keep equal
   speeds (no link is locked to another; this also rejects a link in no relation).

Nothing else is rejected: these rules alone reproduce the published numbers of d-graphs and
r-graphs of 6 and 7 links (Yang and Ding, J. Mech. Des. 141(4) 043301, 2019).

Generation: the link/axis trees of `nx.nonisomorphic_trees` with axes of degree >= 2, then,
tree by tree, every set of L - 2 independent admissible gear pairs (depth first, a pair kept
only when its relation is independent of those chosen), deduplicated by canonical code.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import cache

import networkx as nx

from davies_sym.atlas.canonical import (
    RotationGraph,
    canonical,
    canonical_code,
    canonical_rotation,
    rotation_code,
    rotation_graph,
)
from davies_sym.atlas.graphs import GearPair, TrainGraph

#: The prime field of the generic rank tests (a Mersenne prime: a false answer needs a
#: polynomial of degree <= L in the ratios to vanish at them, probability < 1e-16).
PRIME = 2**61 - 1


def _ratio(first: int, second: int, carrier: int) -> int:
    """A generic tooth ratio for the pair (first, second) on ``carrier``: splitmix64 of the
    labels (distinct for labels below 2**16), so the same in every run and every Python
    version (no ``hash``, no ``random``)."""
    z = (0x9E3779B97F4A7C15 * (1 + first + (second << 16) + (carrier << 32))) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
    return 2 + (z ^ (z >> 31)) % (PRIME - 3)


def speed_relation(links: int, pair: GearPair) -> list[int]:
    """The speed relation of a gear pair, Willis' equation (w_i - w_k) + n (w_j - w_k) = 0,
    as a row over the link speeds modulo `PRIME`."""
    n = _ratio(pair.first, pair.second, pair.carrier)
    row = [0] * links
    row[pair.first] += 1
    row[pair.second] += n
    row[pair.carrier] -= 1 + n
    return [x % PRIME for x in row]


def _reduce(row: list[int], basis: Sequence[tuple[int, list[int]]]) -> list[int]:
    """``row`` less its components along an echelon basis of (pivot, row with 1 at pivot)."""
    for pivot, base in basis:
        factor = row[pivot]
        if factor:
            row = [(x - factor * y) % PRIME for x, y in zip(row, base, strict=True)]
    return row


def echelon_with(basis: list[tuple[int, list[int]]], row: list[int]) -> list[tuple[int, list[int]]] | None:
    """The echelon basis extended by ``row``, or None when ``row`` depends on it."""
    row = _reduce(row, basis)
    pivot = next((c for c, x in enumerate(row) if x), None)
    if pivot is None:
        return None
    inverse = pow(row[pivot], PRIME - 2, PRIME)
    row = [x * inverse % PRIME for x in row]
    reduced = [(p, [(x - b[pivot] * y) % PRIME for x, y in zip(b, row, strict=True)]) for p, b in basis]
    return [*reduced, (pivot, row)]


def _no_locked_links(links: int, basis: Sequence[tuple[int, list[int]]]) -> bool:
    """No two links keep equal speeds for every solution of the relations (reduced echelon
    ``basis``): a generic combination of the null space has all entries different."""
    pivots = {p for p, _ in basis}
    free = [c for c in range(links) if c not in pivots]
    weights = [_ratio(links, c, links + 1) for c in free]
    speeds = [0] * links
    for c, weight in zip(free, weights, strict=True):
        speeds[c] = weight
    for pivot, row in basis:
        speeds[pivot] = -sum(row[c] * w for c, w in zip(free, weights, strict=True)) % PRIME
    return len(set(speeds)) == links


def is_one_dof(graph: TrainGraph) -> bool:
    """Rule 3 (Buchsbaum and Freudenstein 1970; Tsai 2001, degenerate trains): the gear
    pairs' speed relations at generic ratios have rank L - 2 (mobility L - 1 - rank = 1)
    and leave no two links locked together; False too when rules 1 or 2 fail (no tree,
    a gear pair without a carrier holding both its axes, a gear count other than L - 2)."""
    if len(set(graph.gears)) != graph.links - 2 or len(graph.gears) != graph.links - 2 or not graph.is_tree():
        return False
    if any(graph.pair(i, j) is None for i, j in graph.gears):
        return False
    basis: list[tuple[int, list[int]]] | None = []
    for pair in graph.gear_pairs:
        assert basis is not None
        basis = echelon_with(basis, speed_relation(graph.links, pair))
        if basis is None:
            return False
    return _no_locked_links(graph.links, basis or [])


def link_axis_trees(links: int) -> Iterator[TrainGraph]:
    """Rule 1: every non-isomorphic tree of ``links`` link nodes and axis nodes, each axis
    on at least two links (its two colour classes of `nx.nonisomorphic_trees`), no gears."""
    for axes in range(1, links):
        for tree in nx.nonisomorphic_trees(links + axes):
            colour = nx.bipartite.color(tree)
            for side in (0, 1):
                link_nodes = sorted(v for v in tree if colour[v] == side)
                axis_nodes = sorted(v for v in tree if colour[v] != side)
                if len(link_nodes) != links or any(tree.degree(a) < 2 for a in axis_nodes):
                    continue
                label = {v: i for i, v in enumerate(link_nodes)}
                yield TrainGraph(links, tuple(tuple(sorted(label[u] for u in tree[a])) for a in axis_nodes), ())


def admissible_pairs(tree: TrainGraph) -> tuple[GearPair, ...]:
    """Rule 2: every gear pair the tree allows, a link on one axis of a carrier meshing a
    link on another (tree path link - axis - carrier - axis - link), in label order."""
    found = []
    for carrier in range(tree.links):
        held = tree.axes_of(carrier)
        for n, a in enumerate(held):
            for b in held[n + 1 :]:
                for i in tree.axes[a]:
                    for j in tree.axes[b]:
                        if carrier not in (i, j):
                            found.append(GearPair(i, j, a, b, carrier) if i < j else GearPair(j, i, b, a, carrier))
    return tuple(sorted(found, key=lambda p: (p.first, p.second, p.carrier)))


def _gear_sets(tree: TrainGraph) -> Iterator[TrainGraph]:
    """Every train on ``tree`` with L - 2 gear pairs passing rule 3 (depth first over the
    admissible pairs: a pair is taken only when its relation is independent of the others)."""
    links, wanted = tree.links, tree.links - 2
    pairs = admissible_pairs(tree)
    rows = [speed_relation(links, p) for p in pairs]
    reach = [{p.first, p.second, p.carrier} for p in pairs]

    def extend(
        start: int, chosen: list[int], basis: list[tuple[int, list[int]]], seen: set[int]
    ) -> Iterator[TrainGraph]:
        left = wanted - len(chosen)
        if left == 0:
            if len(seen) == links and _no_locked_links(links, basis):
                yield TrainGraph(links, tree.axes, tuple((pairs[n].first, pairs[n].second) for n in chosen))
            return
        if links - len(seen) > 3 * left:
            return
        for n in range(start, len(pairs) - left + 1):
            grown = echelon_with(basis, rows[n])
            if grown is not None:
                yield from extend(n + 1, [*chosen, n], grown, seen | reach[n])

    yield from extend(0, [], [], set())


@cache
def _displacement_graphs(links: int) -> tuple[TrainGraph, ...]:
    found: dict[str, TrainGraph] = {}
    for tree in link_axis_trees(links):
        for train in _gear_sets(tree):
            code, form = canonical(train)
            found.setdefault(code, form)
    return tuple(found[code] for code in sorted(found))


def displacement_graphs(links: int) -> tuple[TrainGraph, ...]:
    """Every non-isomorphic displacement graph (train) of ``links`` links under rules 1-3,
    each in its canonical labelling, sorted by canonical code."""
    if links < 3:
        raise ValueError(f"a planetary gear train has at least 3 links, not {links}")
    return _displacement_graphs(links)


def main_axes(graph: TrainGraph) -> tuple[tuple[int, ...], ...]:
    """The candidate main axes: the axes of at least three links, which can carry frame,
    input and output coaxially (a 1-DOF PGT used as a transmission needs one)."""
    return tuple(axis for axis in graph.axes if len(axis) >= 3)


def gear_axes(graph: TrainGraph) -> dict[int, tuple[int, ...]]:
    """For every link with gears, the axes its gears turn about (`GearPair.first_axis` of
    the pairs where it is ``first``, ``second_axis`` where it is ``second``)."""
    axes: dict[int, set[int]] = {}
    for p in graph.gear_pairs:
        axes.setdefault(p.first, set()).add(p.first_axis)
        axes.setdefault(p.second, set()).add(p.second_axis)
    return {link: tuple(sorted(axes[link])) for link in sorted(axes)}


def gears_on_two_axes(graph: TrainGraph) -> tuple[int, ...]:
    """The links whose gears turn about two or more different axes (a carrier with teeth
    of its own about one axis meshing across another, for instance)."""
    return tuple(link for link, axes in gear_axes(graph).items() if len(axes) > 1)


@dataclass(frozen=True)
class Displacement:
    """One d-graph of the atlas: the train in its canonical labelling, its canonical code,
    its candidate main axes and the links whose gears lie on two axes or more."""

    graph: TrainGraph
    code: str
    main_axes: tuple[tuple[int, ...], ...]
    gears_on_two_axes: tuple[int, ...]


@dataclass(frozen=True)
class RotationClass:
    """One r-graph of the atlas (canonical labelling and code) and its d-graphs."""

    code: str
    rotation: RotationGraph
    displacements: tuple[Displacement, ...]

    @property
    def codes(self) -> tuple[str, ...]:
        """The canonical codes of the d-graphs, in order."""
        return tuple(d.code for d in self.displacements)

    @property
    def graphs(self) -> tuple[TrainGraph, ...]:
        """The d-graphs (trains in canonical labelling), in order."""
        return tuple(d.graph for d in self.displacements)


@dataclass(frozen=True)
class Atlas:
    """Every 1-DOF train of ``links`` links, the d-graphs grouped by r-graph (r-graphs
    sorted by code, the d-graphs of each sorted by code)."""

    links: int
    rotation_graphs: tuple[RotationClass, ...]

    @property
    def displacements(self) -> tuple[Displacement, ...]:
        """Every d-graph, r-graph by r-graph."""
        return tuple(d for r in self.rotation_graphs for d in r.displacements)

    @property
    def rotation_count(self) -> int:
        """The number of non-isomorphic r-graphs."""
        return len(self.rotation_graphs)

    @property
    def displacement_count(self) -> int:
        """The number of non-isomorphic d-graphs."""
        return sum(len(r.displacements) for r in self.rotation_graphs)

    @property
    def two_axis_gear_count(self) -> int:
        """The number of d-graphs with a link whose gears lie on two axes or more."""
        return sum(1 for d in self.displacements if d.gears_on_two_axes)

    @property
    def main_axis_histogram(self) -> dict[int, int]:
        """Number of candidate main axes -> number of d-graphs with that many."""
        return dict(sorted(Counter(len(d.main_axes) for d in self.displacements).items()))


def atlas(links: int) -> Atlas:
    """The atlas of 1-DOF trains of ``links`` links: every d-graph, grouped by r-graph."""
    groups: dict[str, list[Displacement]] = {}
    for graph in displacement_graphs(links):
        entry = Displacement(graph, canonical_code(graph), main_axes(graph), gears_on_two_axes(graph))
        groups.setdefault(rotation_code(graph), []).append(entry)
    return Atlas(
        links,
        tuple(
            RotationClass(
                code, canonical_rotation(rotation_graph(group[0].graph)), tuple(sorted(group, key=lambda d: d.code))
            )
            for code, group in sorted(groups.items())
        ),
    )
