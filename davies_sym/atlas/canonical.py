"""Canonical forms of a train's displacement graph and of its rotation graph.

Two trains are isomorphic when a permutation of their links maps the axes (sets of
coaxial links) of one onto those of the other and its gear pairs onto the other's. The
canonical code is the lexicographically smallest encoding of the train over the
labellings that an individualisation-refinement search reaches (the method of McKay's
canonical labelling, without automorphism pruning): colour refinement (1-dimensional
Weisfeiler-Leman) of the link/axis/gear graph, then, cell by cell, each member of the
first non-singleton cell individualised in turn. Refinement and the choice of cell depend
on the structure alone, so every labelling of a train reaches the same set of leaves up to
the isomorphism and the smallest encoding is the same: a true canonical form, never a hash.

The rotation graph (Yang and Ding, J. Mech. Des. 140(1) 012303, 2018) keeps what a train's
speeds depend on and forgets where the axes lie: the links, and for each gear pair the two
meshing links with the carrier both turn about (its gear edge and the two rotation edges
carrier - gear of its fundamental circuit, without edge levels). Adding the levels (which
axis of the carrier each gear turns about, and which links share an axis) gives back the
displacement graph, the `TrainGraph`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TypeVar

from davies_sym.atlas.graphs import TrainGraph

#: A train's encoding: its axes and its gear pairs as sorted tuples of link labels.
TrainKey = tuple[tuple[tuple[int, ...], ...], tuple[tuple[int, int], ...]]
#: A rotation graph's encoding: its gear pairs as sorted (gear, gear, carrier) triples.
RotationKey = tuple[tuple[int, int, int], ...]
K = TypeVar("K", TrainKey, RotationKey)


def refine(colours: list[int], neighbours: Sequence[Sequence[tuple[int, int]]]) -> list[int]:
    """Colour refinement to the coarsest equitable partition finer than ``colours``.

    A node's new colour is its rank among the distinct (old colour, sorted multiset of
    (edge type, neighbour colour)) signatures, so the old order of the cells is kept and
    nothing but the structure decides the colours."""
    count = len(set(colours))
    while True:
        signatures = [
            (colours[v], tuple(sorted((kind, colours[u]) for u, kind in neighbours[v]))) for v in range(len(colours))
        ]
        rank = {signature: r for r, signature in enumerate(sorted(set(signatures)))}
        colours = [rank[signature] for signature in signatures]
        if len(rank) == count:
            return colours
        count = len(rank)


def canonical_labelling(
    colours: Sequence[int], edges: Sequence[tuple[int, int, int]], encode: Callable[[list[int]], K]
) -> tuple[K, list[int]]:
    """The smallest ``encode(labels)`` over the leaves of the individualisation-refinement
    search of a coloured graph, and the labels (node -> position) that give it.

    ``colours`` are the initial colours of nodes 0..n-1 (an isomorphism-invariant kind),
    ``edges`` are (u, v, edge type), undirected. ``encode`` receives a bijection node ->
    0..n-1 that keeps the initial colour order and must encode the graph relabelled by it."""
    neighbours: list[list[tuple[int, int]]] = [[] for _ in colours]
    for u, v, kind in edges:
        neighbours[u].append((v, kind))
        neighbours[v].append((u, kind))
    best: list[tuple[K, list[int]]] = []

    def search(current: list[int]) -> None:
        current = refine(current, neighbours)
        cells: dict[int, list[int]] = {}
        for v, colour in enumerate(current):
            cells.setdefault(colour, []).append(v)
        target = next((cells[c] for c in sorted(cells) if len(cells[c]) > 1), None)
        if target is None:
            key = encode(current)
            if not best or key < best[0][0]:
                best[:] = [(key, current)]
            return
        for chosen in target:
            search([2 * c + (1 if c == current[chosen] and v != chosen else 0) for v, c in enumerate(current)])

    search(list(colours))
    return best[0]


def _train_key(graph: TrainGraph, labels: Sequence[int]) -> TrainKey:
    axes = tuple(sorted(tuple(sorted(labels[i] for i in axis)) for axis in graph.axes))
    gears = tuple(sorted((min(labels[i], labels[j]), max(labels[i], labels[j])) for i, j in graph.gears))
    return axes, gears


def _train_search(graph: TrainGraph) -> tuple[TrainKey, list[int]]:
    """The canonical key of a train and a labelling of its links that gives it."""
    links = graph.links
    colours = [0] * links + [1] * len(graph.axes)
    edges = [(i, links + k, 0) for k, axis in enumerate(graph.axes) for i in axis]
    edges += [(i, j, 1) for i, j in graph.gears]
    key, labels = canonical_labelling(colours, edges, lambda labels: _train_key(graph, labels))
    return key, labels[:links]


def _train_text(links: int, key: TrainKey) -> str:
    axes, gears = key
    return (
        f"L{links}|"
        + ",".join(".".join(map(str, axis)) for axis in axes)
        + "|"
        + ",".join(f"{i}-{j}" for i, j in gears)
    )


def canonical(graph: TrainGraph) -> tuple[str, TrainGraph]:
    """The canonical code of a train and the train relabelled into its canonical labelling
    (one search for both)."""
    key, _ = _train_search(graph)
    return _train_text(graph.links, key), TrainGraph(graph.links, *key)


def canonical_form(graph: TrainGraph) -> TrainGraph:
    """The train relabelled into its canonical labelling (axes and gear pairs sorted): two
    isomorphic trains give equal results."""
    return canonical(graph)[1]


def canonical_code(graph: TrainGraph) -> str:
    """The canonical code of a train's displacement graph: ``L<links>|<axes>|<gear pairs>``
    of its canonical labelling, e.g. ``L4|0.1.2,0.3|1-3,2-3`` for the simple planetary
    (carrier 0, sun 1, ring 2, planet 3). Equal codes if and only if the trains are
    isomorphic (a permutation of links maps axes onto axes and gear pairs onto gear pairs)."""
    key, _ = _train_search(graph)
    return _train_text(graph.links, key)


@dataclass(frozen=True)
class RotationGraph:
    """The rotation graph of a train (Yang and Ding 2018): links 0..links-1 and, for every
    gear pair, the triple (gear, gear, carrier): a gear edge between the two meshing links
    and the rotation edges carrier - gear of its fundamental circuit, with no edge levels."""

    links: int
    meshes: tuple[tuple[int, int, int], ...]

    @property
    def rotation_edges(self) -> tuple[tuple[int, int], ...]:
        """The thin edges (carrier, gear) without levels, each once, sorted."""
        return tuple(sorted({(min(g, c), max(g, c)) for i, j, c in self.meshes for g in (i, j)}))

    @property
    def gear_edges(self) -> tuple[tuple[int, int], ...]:
        """The thick edges (gear, gear), sorted."""
        return tuple(sorted((min(i, j), max(i, j)) for i, j, _ in self.meshes))


def rotation_graph(graph: TrainGraph) -> RotationGraph:
    """The rotation graph of a train: its displacement graph with the edge levels (axes)
    forgotten, each gear pair kept with its carrier (Tsai (2001): the transfer vertex of the
    pair's fundamental circuit)."""
    meshes = tuple(sorted((min(p.first, p.second), max(p.first, p.second), p.carrier) for p in graph.gear_pairs))
    return RotationGraph(graph.links, meshes)


def _rotation_key(rotation: RotationGraph, labels: Sequence[int]) -> RotationKey:
    return tuple(
        sorted((min(labels[i], labels[j]), max(labels[i], labels[j]), labels[c]) for i, j, c in rotation.meshes)
    )


def canonical_rotation(rotation: RotationGraph) -> RotationGraph:
    """The rotation graph relabelled into its canonical labelling. Nodes: links, then one per
    gear pair, joined to its two gears (mesh edges) and to its carrier (a carrier edge)."""
    links = rotation.links
    colours = [0] * links + [1] * len(rotation.meshes)
    edges = [(u, links + n, 0) for n, (i, j, _) in enumerate(rotation.meshes) for u in (i, j)]
    edges += [(c, links + n, 1) for n, (_, _, c) in enumerate(rotation.meshes)]
    key, _ = canonical_labelling(colours, edges, lambda labels: _rotation_key(rotation, labels))
    return RotationGraph(links, key)


def rotation_code(graph: TrainGraph | RotationGraph) -> str:
    """The canonical code of a train's rotation graph: ``R<links>|<i>-<j>@<carrier>,...``.
    Equal codes if and only if the rotation graphs are isomorphic."""
    rotation = graph if isinstance(graph, RotationGraph) else rotation_graph(graph)
    canonical = canonical_rotation(rotation)
    return f"R{canonical.links}|" + ",".join(f"{i}-{j}@{c}" for i, j, c in canonical.meshes)
