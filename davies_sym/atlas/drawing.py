"""Drawings of an atlas entry (``derive atlas --out DIR --draw``): its graph (links,
axes, gear pairs) and its train's layout seen along the axes, as SVG with the same
bytes from run to run."""

from __future__ import annotations

import math
import random

import networkx as nx
import sympy

from davies_sym.algebra.radicals import restore
from davies_sym.atlas.atlas_entries import Entry
from davies_sym.atlas.train_file import link_name
from davies_sym.emit.plots import figure_bytes, new_figure
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train

#: Colours of the links (cycled).
COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:olive")


def graph_svg(entry: Entry) -> str:
    """The graph: links as circles, axes as squares with their letters (a: the main
    axis), a thin edge where a link turns about an axis, a thick one per gear pair."""
    drawn = entry.drawn
    tree = entry.graph.incidence
    positions = nx.kamada_kawai_layout(tree)
    figure = new_figure(5.0, 4.2)
    axis = figure.subplots()
    axis.set_axis_off()
    axis.set_aspect("equal")
    for a, b in sorted(tree.edges):
        (xa, ya), (xb, yb) = positions[a], positions[b]
        axis.plot([xa, xb], [ya, yb], color="dimgray", linewidth=1.0, zorder=1)
    for p in entry.graph.gear_pairs:
        (xa, ya), (xb, yb) = positions[("l", p.first)], positions[("l", p.second)]
        axis.plot([xa, xb], [ya, yb], color="black", linewidth=3.2, zorder=2)
    for node in sorted(tree.nodes):
        x, y = positions[node]
        if node[0] == "l":
            label, marker, face = link_name(node[1]), "o", COLOURS[node[1] % len(COLOURS)]
        else:
            label, marker, face = drawn.axis_name(node[1]), "s", "white"
        axis.scatter([x], [y], s=520, marker=marker, color=face, edgecolors="black", zorder=3)
        axis.text(x, y, label, ha="center", va="center", fontsize=9, zorder=4)
    axis.set_title(f"{entry.name}: thick edges mesh, thin edges turn about an axis", fontsize=9)
    return figure_bytes(figure, ".svg").decode("utf-8")


def sample_radii(symbols: list[sympy.Symbol], positive: list[sympy.Expr]) -> dict[sympy.Symbol, int] | None:
    """Whole values up to 30 for the free symbols (radii, and a free axis distance) that
    make every expression of ``positive`` positive (the radii, the radicands of the 2-D
    placement's triangles): seeded tries, the same from run to run; None when none does."""
    chooser = random.Random(0)
    for _ in range(400):
        values = {s: chooser.randint(6, 30) for s in symbols}
        if all(sympy.sympify(r).subs(values) > 0 for r in positive):
            return values
    return None


def layout_svg(entry: Entry) -> str:
    """The train seen along its axes at whole sample sizes: each gear a circle about its
    axis, in its link's colour (a carrier has no circle; its axes are the planets'); a
    train drawn in 2-D shows its planets off the centre line."""
    train = resolved_train(entry.train())
    layout = train_layout(train)
    radii = [g.radius for g in train.gears if g.radius is not None]
    positive = radii + [r.radicand for r in layout.radicals]
    free = sorted(set().union(*(sympy.sympify(r).free_symbols for r in positive)), key=str)
    values = sample_radii(free, positive)
    figure = new_figure(5.0, 5.0)
    axis = figure.subplots()
    axis.set_aspect("equal")
    axis.set_axis_off()
    if values is None:
        axis.text(0.5, 0.5, "no whole sizes up to 30 draw the train", ha="center", transform=axis.transAxes)
        return figure_bytes(figure, ".svg").decode("utf-8")
    reach = 1.0
    links = list(train.link_names)
    for g in train.gears:
        x, y = (float(restore(sympy.sympify(c), layout.radicals).subs(values)) for c in layout.gear_centres[g.name][:2])
        radius = float(sympy.sympify(g.radius).subs(values))
        colour = COLOURS[links.index(g.link) % len(COLOURS)]
        axis.plot(*_circle(x, y, radius), color=colour, linewidth=2.4 if g.internal else 1.6)
        axis.text(x, y + radius, g.name, ha="center", va="bottom", fontsize=7, color=colour)
        reach = max(reach, math.hypot(x, y) + radius)
    axis.set_xlim(-1.1 * reach, 1.1 * reach)
    axis.set_ylim(-1.1 * reach, 1.1 * reach)
    shown = ", ".join(f"{s}={v}" for s, v in values.items())
    axis.set_title(f"{entry.name} at {shown}", fontsize=7)
    return figure_bytes(figure, ".svg").decode("utf-8")


def _circle(x: float, y: float, radius: float) -> tuple[list[float], list[float]]:
    steps = [2 * math.pi * k / 96 for k in range(97)]
    return [x + radius * math.cos(t) for t in steps], [y + radius * math.sin(t) for t in steps]
