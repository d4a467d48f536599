"""Motions of links relative to a chosen link (Laus section 3.1.1).

Two routes give the motion screw ``^i$_L`` of every link L as seen from link i:

* the pseudo-inverse of the reduced incidence matrix, ``M_i = -M A_i^+`` (eqs. (6)-(7));
* a walk in the coupling graph from i to L, adding each edge's motion screw with +1 when
  the walk follows the edge and -1 against it (eq. (85)).

The edge ``X: p -> q`` carries the motion of q relative to p, so both routes agree
(a test checks it on every catalog train).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from itertools import pairwise
from typing import TYPE_CHECKING

import networkx as nx
import sympy

from davies_sym.algebra.polynomials import RationalFunction

if TYPE_CHECKING:
    from davies_sym.network.analysis import Analysis

Twist = list[RationalFunction]


def reduced_incidence_pseudoinverse(incidence: sympy.Matrix) -> sympy.Matrix:
    """Moore-Penrose pseudo-inverse ``A_i^T (A_i A_i^T)^-1`` of a reduced incidence
    matrix (eq. (7)); exact, since A_i has full row rank n - 1."""
    gram = incidence * incidence.T
    return incidence.T * gram.inv()


def _zero(analysis: Analysis) -> Twist:
    zero = RationalFunction.polynomial(analysis.ring, analysis.ring.zero)
    return [zero for _ in range(analysis.network.order)]


def absolute_motions(analysis: Analysis, reference: str) -> dict[str, Twist]:
    """``^i$_L`` for every link L (the reference gets zero), by eqs. (6)-(7)."""
    graph = analysis.network.graph
    pinv = reduced_incidence_pseudoinverse(graph.reduced_incidence_matrix(reference))
    twists = {e: analysis.coupling_twist(e) for e in graph.edges}
    others = [link for link in graph.links if link != reference]
    out: dict[str, Twist] = {reference: _zero(analysis)}
    for k, link in enumerate(others):
        total = _zero(analysis)
        for j, edge in enumerate(graph.edges):
            weight = pinv[j, k]
            if weight != 0:
                w = analysis.ring.rational(-weight)
                total = [a + b * w for a, b in zip(total, twists[edge], strict=True)]
        out[link] = total
    return out


def walk_path(analysis: Analysis, start: str, end: str) -> list[tuple[str, int]]:
    """A shortest walk from ``start`` to ``end``: (edge, +1 along / -1 against)."""
    graph = analysis.network.graph
    undirected = graph.undirected
    nodes = nx.shortest_path(undirected, start, end)
    steps = []
    for u, v in pairwise(nodes):
        edge = sorted(undirected.get_edge_data(u, v))[0]
        steps.append((edge, 1 if graph.ends[edge] == (u, v) else -1))
    return steps


def motion_along_path(analysis: Analysis, steps: Sequence[tuple[str, int]]) -> Twist:
    """Sum of the edges' motion screws along a walk (eq. (85))."""
    total = _zero(analysis)
    for edge, sign in steps:
        twist = analysis.coupling_twist(edge)
        total = [a + b if sign > 0 else a - b for a, b in zip(total, twist, strict=True)]
    return total


def relative_motions(analysis: Analysis, reference: str) -> dict[str, Twist]:
    """``^i$_L`` for every link L by walking the coupling graph from the reference."""
    return {
        link: motion_along_path(analysis, walk_path(analysis, reference, link)) for link in analysis.network.graph.links
    }


def twists_equal(a: Mapping[str, Twist], b: Mapping[str, Twist]) -> bool:
    """Exact equality of two link -> twist maps."""
    return a.keys() == b.keys() and all(x == y for link in a for x, y in zip(a[link], b[link], strict=True))
