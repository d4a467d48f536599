"""Which uses of a train can have every gear pair carry a tooth force, read from the
pairs' speed relations at generic ratios before the train is drawn.

Hold member h: the train moves as one where the relations B (Willis' equations of the
L - 2 gear pairs, and w_h = 0) have rank L - 1.  Without the relation of pair m, the
speeds form a plane.  By virtual power, the tooth force of m in a lossless equilibrium
between torques on members a and b is zero exactly where the speeds of a and b stay
proportional over that plane (the ports need nothing of the pair; Laus eq. (2) solved
for its action): the 2 x 2 determinant of (w_a, w_b) over a basis of the plane vanishes.

A zero at generic ratios is an identity of polynomials (every minor of order L of
[B without m; e_a; e_b] vanishes), so it holds at every special value where the train
still moves as one with h held: drawn with any radii, the pair idles too.  A use this
module rules out therefore has an idle gear in every drawing (a train of fewer links,
listed there); the converse is not claimed (a drawing's radii may make a generic force
vanish), and the atlas's choices decide it from the drawn train
(`davies_sym.atlas.choices`).  The ratios are the enumeration's (`enumeration.PRIME`:
a false zero needs a polynomial of low degree to vanish at them, probability < 1e-16).
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations

from davies_sym.atlas.enumeration import PRIME, echelon_with, speed_relation
from davies_sym.atlas.graphs import TrainGraph


def _plane(rows: Sequence[list[int]], links: int) -> list[list[int]] | None:
    """A basis of the speeds that satisfy ``rows`` (modulo `PRIME`) when they leave two
    free, else None."""
    basis: list[tuple[int, list[int]]] = []
    for row in rows:
        extended = echelon_with(basis, row)
        if extended is None:
            return None  # dependent: more than a plane of speeds
        basis = extended
    pivots = {p for p, _ in basis}
    free = [c for c in range(links) if c not in pivots]
    if len(free) != 2:
        return None
    vectors = []
    for c in free:
        speeds = [0] * links
        speeds[c] = 1
        for pivot, row in basis:
            speeds[pivot] = -row[c] % PRIME
        vectors.append(speeds)
    return vectors


def loadable_uses(graph: TrainGraph) -> tuple[tuple[int, int, int], ...]:
    """Every use (held, a, b), a < b, of two members turning in the bearings of the held
    one (every choice of every drawing of `davies_sym.atlas.choices` is one) in which
    every gear pair carries a tooth force at generic ratios; a use not listed idles a
    gear however the train is drawn."""
    links = graph.links
    relations = [speed_relation(links, pair) for pair in graph.gear_pairs]
    found = []
    for held in range(links):
        stop = [0] * links
        stop[held] = 1
        planes = []
        for m in range(len(relations)):
            plane = _plane([*relations[:m], *relations[m + 1 :], stop], links)
            if plane is None:
                break  # the train does not move as one with this member held
            planes.append(plane)
        else:
            for a, b in combinations(graph.neighbours(held), 2):
                if all((u[a] * v[b] - u[b] * v[a]) % PRIME for u, v in planes):
                    found.append((held, a, b))
    return tuple(found)
