"""The coupling graph G_C and its matrices (Laus sections 2.1, 3.1.1 and App. E).

Links are nodes, couplings are directed edges (first link -> second link) of a
networkx ``MultiDiGraph`` keyed by coupling name, in declaration order.  For a spanning
tree it gives the fundamental circuit matrix B (one row per chord, oriented like the
chord), the fundamental cutset matrix Q (one row per branch, oriented like the branch),
the incidence matrix and the reduced incidence matrix A_i.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from functools import cached_property
from itertools import combinations, pairwise

import networkx as nx
import sympy


class CouplingGraph:
    """Directed multigraph of links and couplings with deterministic order."""

    def __init__(self, links: Sequence[str], edges: Sequence[tuple[str, str, str]]):
        self.links = tuple(links)
        self.edges = tuple(name for name, _, _ in edges)
        self.ends = {name: (a, b) for name, a, b in edges}
        self.graph = nx.MultiDiGraph()
        self.graph.add_nodes_from(self.links)
        for name, a, b in edges:
            self.graph.add_edge(a, b, key=name)

    @cached_property
    def undirected(self) -> nx.MultiGraph:
        """The same graph without directions, edges in declaration order: the walks
        between links follow it."""
        graph = nx.MultiGraph()
        graph.add_nodes_from(self.links)
        for name in self.edges:
            graph.add_edge(*self.ends[name], key=name)
        return graph

    def default_tree(self, root: str) -> tuple[str, ...]:
        """Spanning tree grown breadth-first from ``root``, edges in declaration order."""
        reached, tree, frontier = {root}, [], [root]
        while frontier:
            nxt = []
            for node in frontier:
                for name in self.edges:
                    a, b = self.ends[name]
                    other = b if a == node else a if b == node else None
                    if other is not None and other not in reached:
                        reached.add(other)
                        tree.append(name)
                        nxt.append(other)
            frontier = nxt
        return tuple(n for n in self.edges if n in tree)

    def spanning_trees(self) -> Iterator[tuple[str, ...]]:
        """Every spanning tree, as edge names in declaration order."""
        n = len(self.links)
        for subset in combinations(self.edges, n - 1):
            g = nx.Graph()
            g.add_nodes_from(self.links)
            g.add_edges_from(self.ends[e] for e in subset)
            if nx.is_tree(g):
                yield subset

    def is_spanning_tree(self, tree: Sequence[str]) -> bool:
        g = nx.Graph()
        g.add_nodes_from(self.links)
        g.add_edges_from(self.ends[e] for e in tree if e in self.ends)
        return len(tree) == len(self.links) - 1 and nx.is_tree(g)

    def chords(self, tree: Sequence[str]) -> tuple[str, ...]:
        return tuple(e for e in self.edges if e not in tree)

    def _tree_graph(self, tree: Sequence[str]) -> nx.MultiGraph:
        g = nx.MultiGraph()
        g.add_nodes_from(self.links)
        for e in tree:
            g.add_edge(*self.ends[e], key=e)
        return g

    def circuit_matrix(self, tree: Sequence[str]) -> sympy.Matrix:
        """Fundamental circuit matrix B (l x e): chord c, then the tree path back."""
        tg = self._tree_graph(tree)
        chords = self.chords(tree)
        B = sympy.zeros(len(chords), len(self.edges))
        for i, chord in enumerate(chords):
            a, b = self.ends[chord]
            B[i, self.edges.index(chord)] = 1
            path = nx.shortest_path(tg, b, a)
            for u, v in pairwise(path):
                name = next(iter(tg.get_edge_data(u, v)))
                B[i, self.edges.index(name)] = 1 if self.ends[name] == (u, v) else -1
        return B

    def cutset_matrix(self, tree: Sequence[str]) -> sympy.Matrix:
        """Fundamental cutset matrix Q (k x e): +1 for edges crossing like the branch."""
        Q = sympy.zeros(len(tree), len(self.edges))
        for i, branch in enumerate(tree):
            tg = self._tree_graph([e for e in tree if e != branch])
            tail, _ = self.ends[branch]
            tail_side = nx.node_connected_component(tg, tail)
            for j, name in enumerate(self.edges):
                a, b = self.ends[name]
                if (a in tail_side) != (b in tail_side):
                    Q[i, j] = 1 if a in tail_side else -1
        return Q

    def incidence_matrix(self) -> sympy.Matrix:
        """Incidence matrix (n x e): +1 where an edge starts, -1 where it ends."""
        A = sympy.zeros(len(self.links), len(self.edges))
        for j, name in enumerate(self.edges):
            a, b = self.ends[name]
            A[self.links.index(a), j] = 1
            A[self.links.index(b), j] = -1
        return A

    def reduced_incidence_matrix(self, reference: str) -> sympy.Matrix:
        """Incidence matrix without the row of the reference link (Laus eq. (66))."""
        A = self.incidence_matrix()
        A.row_del(self.links.index(reference))
        return A
