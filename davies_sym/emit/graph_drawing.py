"""Drawing of a train's coupling graph G_C (Laus Fig. 6, 8, 10): links as nodes, couplings
as directed edges labelled with their name and kind; parallel edges are bent apart, the
ports and the reference link marked.  Node positions come from a seeded spring layout
(networkx), so the drawing is reproducible."""

from __future__ import annotations

from typing import Any

import networkx as nx

from davies_sym.emit.plots import new_figure
from davies_sym.topology.model import Train


def _kind(train: Train, name: str) -> str:
    """The coupling's type as the file writes it (``revolute``, ``mesh``, ``worm`` ...)."""
    return train.coupling(name).kind


def coupling_graph_figure(train: Train) -> Any:
    """A matplotlib figure of the coupling graph of ``train``."""
    graph = nx.MultiGraph()
    graph.add_nodes_from(train.link_names)
    for c in train.couplings:
        graph.add_edge(*c.links, key=c.name)
    positions = nx.spring_layout(nx.Graph(graph), seed=7, k=1.6)
    figure = new_figure(5.5, 4.2)
    axis = figure.subplots()
    axis.set_axis_off()
    pairs: dict[frozenset[str], int] = {}
    ports = {train.ports.input: "input", train.ports.output: "output"}
    for c in train.couplings:
        a, b = c.links
        key = frozenset((a, b))
        index = pairs.get(key, 0)
        pairs[key] = index + 1
        bend = 0.0 if index == 0 else (0.25 * ((index + 1) // 2) * (1 if index % 2 else -1))
        colour = "tab:red" if c.name in ports else ("tab:blue" if c.noun == "mesh" else "dimgray")
        axis.annotate(
            "",
            xy=positions[b],
            xytext=positions[a],
            arrowprops={
                "arrowstyle": "-|>",
                "color": colour,
                "shrinkA": 16,
                "shrinkB": 16,
                "connectionstyle": f"arc3,rad={bend}",
                "linewidth": 1.6,
            },
        )
        (xa, ya), (xb, yb) = positions[a], positions[b]
        mx, my = (xa + xb) / 2, (ya + yb) / 2
        # The label sits on the bent edge: the midpoint pushed along the normal.
        nx_, ny_ = -(yb - ya), xb - xa
        mx, my = mx + bend * nx_ * 0.5, my + bend * ny_ * 0.5
        text = f"{c.name} ({_kind(train, c.name)}" + (f", {ports[c.name]})" if c.name in ports else ")")
        axis.text(
            mx,
            my,
            text,
            fontsize=8,
            ha="center",
            va="center",
            color=colour,
            bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.85},
        )
    for link, (x, y) in positions.items():
        reference = link == train.reference
        axis.scatter([x], [y], s=700, color="#f0f0f0" if not reference else "#d0d0d0", edgecolors="black", zorder=3)
        axis.text(x, y, link, fontsize=10, ha="center", va="center", zorder=4, fontweight="bold")
    axis.set_title("coupling graph (links; couplings as edges; grey: reference link)", fontsize=9)
    axis.margins(0.15)
    return figure
