"""The four d-graphs (in two r-graphs) of 9 links that can be listed twice: where the
atlas's 9-link counts (8652 r-graphs, 71833 d-graphs) and the published ones (Yang and
Ding, J. Mech. Des. 141(4) 043301, 2019: 8654 / 71837) differ by 2 and 4.

A d-graph is read as the graph of its links, its axes and its gear pairs (an edge from each
link to each axis it turns about, an edge between the two links of each gear pair), as in
`davies_sym.atlas.canonical`. Colour refinement (1-dimensional Weisfeiler-Leman) of that
graph gives two links that an automorphism maps onto each other the same colour. When the
converse also holds (the colour classes of the links are their orbits), a code read from
one branch of the search (refine, individualise the first link of the first class with more
than one member in the order the links were given, refine again, ...) does not depend on
that order. Where it fails, the code of a train depends on how the train was labelled, and
one train can be listed under two codes; the atlas's `canonical_code` takes the smallest
code over every branch and is not affected.

Checks:

1. every d-graph of the atlas of each link count given (default 3 to 8): the d-graphs whose
   refined colours are not their orbits, and those whose branches give different codes;
2. the four 9-link d-graphs of `NINE`: each passes the rules (`is_one_dof`) and is in
   canonical form; refinement leaves links of two different orbits in one colour class;
   relabelled at random, each gives two one-branch codes and one canonical code; the four
   lie in two r-graphs, two in each;
3. with ``--nine``, every d-graph of the 9-link atlas (about 13 minutes on one core): check
   1 finds exactly the four d-graphs of `NINE`.

    python benchmarks/atlas_nine_difference.py             # checks 1 (3-8 links) and 2
    python benchmarks/atlas_nine_difference.py 6 7 8       # check 1 for chosen link counts
    python benchmarks/atlas_nine_difference.py --nine      # checks 1, 2 and 3
"""

from __future__ import annotations

import operator
import random
import sys
import time

import networkx as nx
from networkx.algorithms.isomorphism import GraphMatcher

from davies_sym.atlas.canonical import canonical_code, refine, rotation_code
from davies_sym.atlas.enumeration import displacement_graphs, is_one_dof
from davies_sym.atlas.graphs import TrainGraph

#: The four 9-link d-graphs (canonical codes): one carrier, link 0, holding every axis;
#: the first two share one r-graph, the last two another.
NINE = (
    "L9|0.1.2.5,0.3.4.6,0.7.8|1-7,2-8,3-7,4-8,5-6,5-7,6-8",
    "L9|0.1.2.5,0.3.4.6,0.7,0.8|1-7,2-8,3-7,4-8,5-6,5-7,6-8",
    "L9|0.1.2.3,0.4.5.6,0.7,0.8|1-7,2-7,3-8,4-7,5-8,6-8,7-8",
    "L9|0.1.2,0.3.4,0.5.6,0.7,0.8|1-7,2-7,3-7,4-8,5-8,6-8,7-8",
)

#: Yang and Ding (2019): links -> (r-graphs, d-graphs).
PUBLISHED = {6: (27, 81), 7: (152, 647), 8: (1070, 6360), 9: (8654, 71837)}


def parse(code: str) -> TrainGraph:
    """The train of a code ``L<links>|<axis>,...|<i>-<j>,...``."""
    links, axes, gears = code.split("|")
    return TrainGraph(
        int(links[1:]),
        tuple(tuple(int(x) for x in axis.split(".")) for axis in axes.split(",")),
        tuple((int(i), int(j)) for i, j in (pair.split("-") for pair in gears.split(","))),
    )


def relabel(train: TrainGraph, new: list[int]) -> TrainGraph:
    """The train with link ``i`` renamed ``new[i]``."""
    return TrainGraph(
        train.links,
        tuple(sorted(tuple(sorted(new[i] for i in axis)) for axis in train.axes)),
        tuple(sorted((min(new[i], new[j]), max(new[i], new[j])) for i, j in train.gears)),
    )


def structure(train: TrainGraph) -> tuple[list[int], list[list[tuple[int, int]]]]:
    """The graph of a d-graph: nodes 0..L-1 the links (colour 0), then one node per axis
    (colour 1); edges link - axis (kind 0) and gear pair (kind 1), as neighbour lists."""
    links = train.links
    colours = [0] * links + [1] * len(train.axes)
    neighbours: list[list[tuple[int, int]]] = [[] for _ in colours]
    edges = [(i, links + k, 0) for k, axis in enumerate(train.axes) for i in axis]
    edges += [(i, j, 1) for i, j in train.gears]
    for u, v, kind in edges:
        neighbours[u].append((v, kind))
        neighbours[v].append((u, kind))
    return colours, neighbours


def individualise(colours: list[int], chosen: int) -> list[int]:
    """The colouring with ``chosen`` put in a class of its own, just before the rest of its class."""
    return [2 * c + (1 if c == colours[chosen] and v != chosen else 0) for v, c in enumerate(colours)]


def first_class(colours: list[int]) -> list[int] | None:
    """The nodes of the first colour class (in colour order) with more than one member."""
    classes: dict[int, list[int]] = {}
    for v, c in enumerate(colours):
        classes.setdefault(c, []).append(v)
    return next((classes[c] for c in sorted(classes) if len(classes[c]) > 1), None)


def leaf_code(train: TrainGraph, colours: list[int]) -> str:
    """The code of the train relabelled by a discrete colouring (links ranked by colour)."""
    order = sorted(range(train.links), key=lambda i: colours[i])
    new = [0] * train.links
    for position, link in enumerate(order):
        new[link] = position
    form = relabel(train, new)
    return (
        f"L{form.links}|"
        + ",".join(".".join(map(str, axis)) for axis in form.axes)
        + "|"
        + ",".join(f"{i}-{j}" for i, j in form.gears)
    )


def one_branch_code(train: TrainGraph) -> str:
    """Refine, then individualise the first node (lowest label) of the first non-singleton
    class and refine again, until every class is a singleton: one branch, no backtracking."""
    colours, neighbours = structure(train)
    colours = refine(colours, neighbours)
    while (target := first_class(colours)) is not None:
        colours = refine(individualise(colours, target[0]), neighbours)
    return leaf_code(train, colours)


def branch_codes(train: TrainGraph) -> set[str]:
    """The codes at every leaf of the search (each member of the first non-singleton class
    individualised in turn): one code when no input order can change the one-branch code."""
    colours, neighbours = structure(train)
    found: set[str] = set()

    def search(current: list[int]) -> None:
        current = refine(current, neighbours)
        target = first_class(current)
        if target is None:
            found.add(leaf_code(train, current))
            return
        for chosen in target:
            search(individualise(current, chosen))

    search(colours)
    return found


def link_classes(train: TrainGraph) -> list[list[int]]:
    """The links grouped by their refined colour."""
    colours, neighbours = structure(train)
    colours = refine(colours, neighbours)
    classes: dict[int, list[int]] = {}
    for link in range(train.links):
        classes.setdefault(colours[link], []).append(link)
    return sorted(classes.values())


def link_orbits(train: TrainGraph) -> list[list[int]]:
    """The links grouped by the automorphisms of the train (permutations of the links
    mapping axes onto axes and gear pairs onto gear pairs)."""
    colours, neighbours = structure(train)
    graph = nx.Graph()
    graph.add_nodes_from((v, {"c": c}) for v, c in enumerate(colours))
    graph.add_edges_from((u, v, {"k": kind}) for u in range(len(colours)) for v, kind in neighbours[u])
    orbit = list(range(train.links))
    for mapping in GraphMatcher(graph, graph, node_match=operator.eq, edge_match=operator.eq).isomorphisms_iter():
        for link in range(train.links):
            orbit[link] = min(orbit[link], mapping[link])
    changed = True
    while changed:
        changed = False
        for link in range(train.links):
            if orbit[orbit[link]] != orbit[link]:
                orbit[link] = orbit[orbit[link]]
                changed = True
    groups: dict[int, list[int]] = {}
    for link in range(train.links):
        groups.setdefault(orbit[link], []).append(link)
    return sorted(groups.values())


def scan(links: int) -> tuple[int, int, list[str], list[str]]:
    """Over the atlas of ``links`` links: the numbers of r-graphs and d-graphs, the d-graphs
    whose refined colours are not their orbits, and those with more than one branch code."""
    trains = displacement_graphs(links)
    rotations = {rotation_code(train) for train in trains}
    not_orbits, two_codes = [], []
    for train in trains:
        code = canonical_code(train)
        if link_classes(train) != link_orbits(train):
            not_orbits.append(code)
        if len(branch_codes(train)) > 1:
            two_codes.append(code)
    return len(rotations), len(trains), not_orbits, two_codes


def check_atlas(link_counts: list[int]) -> dict[int, list[str]]:
    """Check 1 (and 3 when 9 is among ``link_counts``)."""
    print("links  r-graphs  d-graphs  published      colours not orbits  several branch codes  time")
    found = {}
    for links in link_counts:
        start = time.perf_counter()
        rotations, displacements, not_orbits, two_codes = scan(links)
        published = "/".join(map(str, PUBLISHED[links])) if links in PUBLISHED else "-"
        print(
            f"{links:>5} {rotations:>9} {displacements:>9}  {published:<13} {len(not_orbits):>19}"
            f" {len(two_codes):>21}  {time.perf_counter() - start:.0f} s"
        )
        for code in sorted(set(not_orbits) | set(two_codes)):
            print(f"      {code}")
        found[links] = sorted(set(not_orbits) | set(two_codes))
    return found


def check_nine() -> None:
    """Check 2: the four 9-link d-graphs written out in `NINE`."""
    rotations: dict[str, list[str]] = {}
    rng = random.Random(0)
    for code in NINE:
        train = parse(code)
        assert is_one_dof(train), code
        assert canonical_code(train) == code, code
        classes, orbits = link_classes(train), link_orbits(train)
        assert classes != orbits, code
        one_branch, canonical = set(), set()
        for _ in range(200):
            new = list(range(train.links))
            rng.shuffle(new)
            shuffled = relabel(train, new)
            one_branch.add(one_branch_code(shuffled))
            canonical.add(canonical_code(shuffled))
        assert canonical == {code} and len(one_branch) == 2, (code, one_branch)
        assert len(branch_codes(train)) == 2, code
        rotations.setdefault(rotation_code(train), []).append(code)
        print(code)
        print(f"    r-graph {rotation_code(train)}")
        print(f"    refined link classes {classes}")
        print(f"    link orbits          {orbits}")
        for other in sorted(one_branch):
            print(f"    one-branch code      {other}")
    assert sorted(len(codes) for codes in rotations.values()) == [2, 2]
    print(f"{len(NINE)} d-graphs in {len(rotations)} r-graphs; 8652 + 2 = 8654, 71833 + 4 = 71837")


def main(arguments: list[str]) -> None:
    nine = "--nine" in arguments
    link_counts = [int(a) for a in arguments if a != "--nine"] or [3, 4, 5, 6, 7, 8]
    if nine and 9 not in link_counts:
        link_counts.append(9)
    found = check_atlas(link_counts)
    for links, codes in found.items():
        assert codes == (sorted(NINE) if links == 9 else []), (links, codes)
    check_nine()


if __name__ == "__main__":
    main(sys.argv[1:])
