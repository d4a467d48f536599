"""Where a train written by hand lies in the atlas: its graph (which links turn about
which axis, which mesh), read from the file through the layout's axis structure.

A transmission written with a housing and every coaxial member in its bearings (the
catalog's Ravigneaux and Simpson sets) has two degrees of freedom; holding one member
(``held``) joins it to the housing and gives the one-degree-of-freedom train the atlas
counts.
"""

from __future__ import annotations

from collections import defaultdict

from davies_sym.atlas.graphs import TrainGraph
from davies_sym.geometry.axes import axis_structure
from davies_sym.topology.coupling_kinds import as_bearing, as_gear_mesh
from davies_sym.topology.model import Train


class OutsideAtlas(ValueError):
    """The train is not a planar gear train of revolutes and spur meshes."""


def train_graph(train: Train, held: str | None = None) -> TrainGraph:
    """The graph of ``train`` (its links numbered in name order), with ``held`` joined to
    the reference link when given."""
    structure = axis_structure(train)

    def merged(link: str) -> str:
        return train.reference if link == held else link

    spatial = {g.name for g in train.gears if g.axis is not None or g.tilted}
    axes: dict[str, set[str]] = defaultdict(set)
    gears: set[tuple[str, str]] = set()
    for c in train.couplings:
        mesh = as_gear_mesh(c)
        if as_bearing(c) is not None:
            axes[structure.bearing_axis[c.name]] |= {merged(x) for x in c.links}
        elif mesh is not None and not spatial & set(mesh.gears):
            a, b = sorted(merged(x) for x in c.links)
            gears.add((a, b))
        else:
            raise OutsideAtlas(
                f"coupling {c.name} (type: {c.kind}) is neither a revolute nor a mesh of parallel-axis gears, "
                "the pairs of the atlas's trains"
            )
    names = sorted({merged(x) for x in train.link_names})
    number = {name: k for k, name in enumerate(names)}
    sets = sorted({tuple(sorted(number[x] for x in members)) for members in axes.values() if len(members) > 1})
    return TrainGraph(len(names), tuple(sets), tuple(sorted((number[a], number[b]) for a, b in gears)))
