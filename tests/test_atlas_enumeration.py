"""The atlas of 1-DOF planetary gear trains (davies_sym.atlas.enumeration, .canonical).

Published counts: Yang and Ding, "The Complete Set of One-Degree-of-Freedom Planetary Gear
Trains With Up to Nine Links", J. Mech. Des. 141(4) 043301 (2019): 27 rotation graphs and
81 displacement graphs of 6 links, 152 and 647 of 7 links, 1070 and 6360 of 8 links. The
counts of 3, 4 and 5 links are this package's definition's (docs/atlas_definitions.md), not
published ones. The 1-DOF check here is an independent one (exact rational arithmetic),
not the enumeration's own modular test.
"""

from __future__ import annotations

import random
from fractions import Fraction
from itertools import combinations

import networkx as nx
import pytest

from davies_sym.atlas.canonical import canonical_code, canonical_form, rotation_code, rotation_graph
from davies_sym.atlas.enumeration import (
    atlas,
    displacement_graphs,
    gear_axes,
    gears_on_two_axes,
    is_one_dof,
    main_axes,
)
from davies_sym.atlas.graphs import TrainGraph

#: Yang and Ding (2019), Table of results: links -> (r-graphs, d-graphs).
PUBLISHED = {6: (27, 81), 7: (152, 647), 8: (1070, 6360)}
#: This definition's counts below six links (docs/atlas_definitions.md); Tsai (1987) lists 2 and 6 graphs.
OWN = {3: (1, 1), 4: (2, 3), 5: (6, 13)}


def _rank_and_null(rows: list[list[Fraction]], columns: int) -> tuple[int, list[list[Fraction]]]:
    """Rank of a rational matrix and a basis of its null space (Gauss-Jordan, exact)."""
    rows = [r[:] for r in rows]
    pivots: list[int] = []
    for column in range(columns):
        at = next((r for r in range(len(pivots), len(rows)) if rows[r][column] != 0), None)
        if at is None:
            continue
        top = len(pivots)
        rows[top], rows[at] = rows[at], rows[top]
        rows[top] = [x / rows[top][column] for x in rows[top]]
        for r in range(len(rows)):
            if r != top and rows[r][column] != 0:
                rows[r] = [x - rows[r][column] * y for x, y in zip(rows[r], rows[top], strict=True)]
        pivots.append(column)
    null = []
    for free in (c for c in range(columns) if c not in pivots):
        vector = [Fraction(0)] * columns
        vector[free] = Fraction(1)
        for r, pivot in enumerate(pivots):
            vector[pivot] = -rows[r][free]
        null.append(vector)
    return len(pivots), null


def _independently_one_dof(graph: TrainGraph, seed: int) -> bool:
    """Willis' relations w_i - w_k = -n (w_j - w_k) at random rational ratios: rank L - 2 and,
    at a random solution, all link speeds different (no link locked to another)."""
    rng = random.Random(seed)
    rows = []
    for pair in graph.gear_pairs:
        n = Fraction(rng.randrange(7, 10**6), rng.randrange(7, 10**6))
        row = [Fraction(0)] * graph.links
        row[pair.first] += 1
        row[pair.second] += n
        row[pair.carrier] -= 1 + n
        rows.append(row)
    rank, null = _rank_and_null(rows, graph.links)
    weights = [rng.randrange(1, 10**6) for _ in null]
    speeds = [sum(w * v[i] for w, v in zip(weights, null, strict=True)) for i in range(graph.links)]
    return rank == graph.links - 2 and len(set(speeds)) == graph.links


def _relabelled(graph: TrainGraph, rng: random.Random) -> TrainGraph:
    """The same train with links permuted, axes and gear pairs shuffled."""
    perm = list(range(graph.links))
    rng.shuffle(perm)
    axes = [tuple(sorted(perm[i] for i in axis)) for axis in graph.axes]
    gears = [tuple(sorted((perm[i], perm[j]))) for i, j in graph.gears]
    rng.shuffle(axes)
    rng.shuffle(gears)
    return TrainGraph(graph.links, tuple(axes), tuple((i, j) for i, j in gears))


@pytest.mark.parametrize("links", [6, 7])
def test_counts_match_yang_and_ding_2019(links: int) -> None:
    """Yang and Ding, J. Mech. Des. 141(4) 043301 (2019): 6 links 27 r-graphs / 81 d-graphs,
    7 links 152 / 647."""
    found = atlas(links)
    assert (found.rotation_count, found.displacement_count) == PUBLISHED[links]
    assert len(displacement_graphs(links)) == PUBLISHED[links][1]


@pytest.mark.parametrize("links", [3, 4, 5])
def test_counts_below_six_links_are_this_definitions(links: int) -> None:
    found = atlas(links)
    assert (found.rotation_count, found.displacement_count) == OWN[links]


@pytest.mark.slow
def test_counts_of_eight_links_match_yang_and_ding_2019() -> None:
    """Yang and Ding (2019): 8 links, 1070 r-graphs and 6360 d-graphs (about a minute)."""
    found = atlas(8)
    assert (found.rotation_count, found.displacement_count) == PUBLISHED[8]


@pytest.mark.parametrize("links", [4, 5, 6, 7])
def test_every_displacement_graph_follows_the_rules(links: int) -> None:
    for n, graph in enumerate(displacement_graphs(links)):
        assert graph.is_tree(), graph
        assert all(len(axis) >= 2 for axis in graph.axes)
        assert len(graph.gears) == links - 2 and len(set(graph.gears)) == links - 2
        assert len(graph.gear_pairs) == links - 2  # each pair has its carrier (raises otherwise)
        assert _independently_one_dof(graph, seed=n), graph


@pytest.mark.parametrize("links", [5, 6, 7])
def test_codes_are_sorted_distinct_and_of_canonical_graphs(links: int) -> None:
    graphs = displacement_graphs(links)
    codes = [canonical_code(g) for g in graphs]
    assert codes == sorted(codes) and len(set(codes)) == len(codes)
    assert all(canonical_form(g) == g for g in graphs)
    assert displacement_graphs(links) is graphs  # computed once


def test_canonical_codes_survive_random_relabelling() -> None:
    rng = random.Random(20190401)
    for links in (5, 6, 7):
        graphs = displacement_graphs(links)
        for graph in rng.sample(graphs, min(60, len(graphs))):
            for _ in range(3):
                other = _relabelled(graph, rng)
                assert canonical_code(other) == canonical_code(graph)
                assert canonical_form(other) == graph
                assert rotation_code(other) == rotation_code(graph)


def test_different_codes_are_non_isomorphic_trains() -> None:
    """networkx's own isomorphism test agrees: no two 6-link d-graphs are isomorphic."""

    def coloured(graph: TrainGraph) -> nx.Graph:
        out = nx.Graph()
        out.add_nodes_from((("l", i), {"kind": "link"}) for i in range(graph.links))
        for k, axis in enumerate(graph.axes):
            out.add_node(("a", k), kind="axis")
            out.add_edges_from(((("a", k), ("l", i)) for i in axis), kind="turn")
        out.add_edges_from(((("l", i), ("l", j)) for i, j in graph.gears), kind="gear")
        return out

    same = nx.algorithms.isomorphism.categorical_node_match("kind", None)
    edges = nx.algorithms.isomorphism.categorical_edge_match("kind", None)
    graphs = [coloured(g) for g in displacement_graphs(6)]
    for a, b in combinations(graphs, 2):
        assert not nx.is_isomorphic(a, b, node_match=same, edge_match=edges)


def test_rotation_groups() -> None:
    found = atlas(6)
    for group in found.rotation_graphs:
        assert [rotation_code(d.graph) for d in group.displacements] == [group.code] * len(group.displacements)
        assert rotation_code(group.rotation) == group.code
        assert group.codes == tuple(sorted(group.codes))
    assert [g.code for g in found.rotation_graphs] == sorted(g.code for g in found.rotation_graphs)
    assert found.main_axis_histogram == {0: 15, 1: 48, 2: 18}
    assert found.two_axis_gear_count == 9
    assert atlas(7).two_axis_gear_count == 111


def test_simple_planetary_and_its_rotation_graph() -> None:
    """Carrier 0, sun 1, ring 2, planet 3. Its r-graph is shared with the three-gear train
    on a carrier (gear 1 meshing gears 2 and 3, each on its own axis of carrier 0)."""
    planetary = TrainGraph(4, ((0, 1, 2), (0, 3)), ((1, 3), (2, 3)))
    fixed_axes = TrainGraph(4, ((0, 1), (0, 2), (0, 3)), ((1, 2), (1, 3)))
    codes = {canonical_code(g) for g in displacement_graphs(4)}
    assert canonical_code(planetary) in codes and canonical_code(fixed_axes) in codes
    assert rotation_code(planetary) == rotation_code(fixed_axes)
    assert main_axes(planetary) == ((0, 1, 2),) and main_axes(fixed_axes) == ()
    assert rotation_graph(planetary).gear_edges == ((1, 3), (2, 3))
    assert rotation_graph(planetary).rotation_edges == ((0, 1), (0, 2), (0, 3))


def test_wolfrom_train() -> None:
    """Carrier 0, sun 1, ring 1 = 2, ring 2 = 3, stepped planet 4 meshing all three."""
    wolfrom = TrainGraph(5, ((0, 1, 2, 3), (0, 4)), ((1, 4), (2, 4), (3, 4)))
    assert canonical_code(wolfrom) in {canonical_code(g) for g in displacement_graphs(5)}


def test_ravigneaux_set_with_a_member_held() -> None:
    """Small sun 0, large sun 1, carrier 2, short planet 3, long planet 4, ring 5; main axis
    {small sun, large sun, carrier, ring}."""
    ravigneaux = TrainGraph(6, ((0, 1, 2, 5), (2, 3), (2, 4)), ((0, 3), (3, 4), (1, 4), (4, 5)))
    assert is_one_dof(ravigneaux)
    assert canonical_code(ravigneaux) in {canonical_code(g) for g in displacement_graphs(6)}
    assert main_axes(ravigneaux) == ((0, 1, 2, 5),) and gears_on_two_axes(ravigneaux) == ()


def test_simpson_set_with_a_member_held() -> None:
    """Sun 0 (common), front planet 1, front ring 2, front carrier = rear ring 3, rear planet
    4, rear carrier 5."""
    simpson = TrainGraph(6, ((0, 2, 3, 5), (1, 3), (4, 5)), ((0, 1), (1, 2), (0, 4), (3, 4)))
    assert canonical_code(simpson) in {canonical_code(g) for g in displacement_graphs(6)}
    assert gears_on_two_axes(simpson) == ()


def test_a_link_with_gears_on_two_axes() -> None:
    """The one 5-link d-graph with such a link: link 2 turns about axes 0 (with link 0) and
    2 (with link 1); its gear about axis 0 meshes planet 3 of carrier 0, its gear about axis
    2 meshes planet 4 of carrier 1; links 0 and 1 mesh on carrier 2."""
    train = TrainGraph(5, ((0, 2), (0, 3), (1, 2), (1, 4)), ((0, 1), (2, 3), (2, 4)))
    assert train in displacement_graphs(5)
    assert gear_axes(train) == {0: (0,), 1: (2,), 2: (0, 2), 3: (1,), 4: (3,)}
    assert gears_on_two_axes(train) == (2,)
    assert atlas(5).two_axis_gear_count == 1


def test_degenerate_trains_are_rejected() -> None:
    """Two planets meshing the same sun and ring lock sun, ring, planets and carrier
    together (rank L - 2 but locked); five relations among five links are dependent; a
    missing gear pair leaves two freedoms; coaxial links cannot mesh."""
    locked = TrainGraph(6, ((0, 1, 2, 5), (0, 3), (0, 4)), ((1, 3), (2, 3), (1, 4), (2, 4)))
    assert not is_one_dof(locked) and not _independently_one_dof(locked, seed=1)
    dependent = TrainGraph(7, ((0, 1, 2, 3, 4), (0, 5), (0, 6)), ((1, 5), (1, 6), (2, 5), (2, 6), (5, 6)))
    assert not is_one_dof(dependent) and not _independently_one_dof(dependent, seed=2)
    assert not is_one_dof(TrainGraph(4, ((0, 1, 2), (0, 3)), ((1, 3),)))  # two freedoms
    assert not is_one_dof(TrainGraph(4, ((0, 1, 2), (0, 3)), ((1, 3), (1, 2))))  # coaxial gears
    with pytest.raises(ValueError):
        displacement_graphs(2)
