"""One atlas entry per displacement graph: the graph drawn as a train, its admissible
choices, and its train file; written by worker processes and read back as plain data."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

from davies_sym.atlas.choices import admissible_choices
from davies_sym.atlas.graphs import TrainGraph
from davies_sym.atlas.realisation import Realisation, main_axis, realisations
from davies_sym.atlas.train_file import Choice, TrainFile, distance_symbol, link_name
from davies_sym.errors import BeyondWorkBound
from davies_sym.topology.model import Train

#: Where the counts are published (the docs compare them with the atlas's).
PUBLISHED = "Yang & Ding, J. Mech. Des. 141(4) 043301 (2019)"
PUBLISHED_COUNTS = {6: (27, 81), 7: (152, 647), 8: (1070, 6360), 9: (8654, 71837)}


@dataclass(frozen=True)
class GraphPlace:
    """Where a displacement graph stands in the atlas of ``links`` links: rotation graph
    ``rotation`` (1-based), number ``index`` among its displacement graphs, both codes;
    the task a worker turns into an `Entry`."""

    links: int
    rotation: int
    index: int
    code: str
    rotation_code: str
    graph: TrainGraph

    @property
    def name(self) -> str:
        """The train's name in files: atlas6_r03_d2."""
        return f"atlas{self.links}_r{self.rotation:02d}_d{self.index}"


@dataclass(frozen=True)
class Entry(GraphPlace):
    """A displacement graph of the atlas at its place, the train drawn from it and the
    admissible choices (None: the language cannot draw it)."""

    choices: tuple[Choice, ...]
    #: Why the topology language cannot write the train, or None.
    not_drawable: str | None
    #: Drawn in 2-D (`placement:`): meshes between planets close loops a line cannot.
    planar: bool = False
    #: How the train is drawn (None: it is not).
    drawing: Realisation | None = None
    #: The choices in which every mesh carries a tooth force (no gear idle).
    loaded: tuple[Choice, ...] = ()
    #: The axes whose distances from the main axis the meshes leave free (parameters of
    #: the train file the efficiency does not depend on).
    free_axes: tuple[int, ...] = ()
    #: The order the train file writes its meshes in (the layout places them so), or
    #: None: that of the gear pairs.
    order: tuple[int, ...] | None = None

    @property
    def drawn(self) -> Realisation:
        """How the train is drawn; the housing about the main axis when it is not."""
        return self.drawing or Realisation(self.graph, main_axis(self.graph))

    def document(self) -> dict[str, Any]:
        """The entry in ``derive atlas --json``."""
        drawn = self.drawn
        levels = {drawn.axis_name(k): list(axis) for k, axis in enumerate(self.graph.axes)}
        gears = [
            {
                "links": [p.first, p.second],
                "carrier": p.carrier,
                "axes": [drawn.axis_name(p.first_axis), drawn.axis_name(p.second_axis)],
            }
            for p in self.graph.gear_pairs
        ]
        return {
            "name": self.name,
            "code": self.code,
            "rotation_graph": self.rotation,
            "rotation_code": self.rotation_code,
            "levels": dict(sorted(levels.items())),
            "gears": gears,
            "coaxial": list(self.graph.axes[drawn.main_axis]),
            # None: a housing holds one coaxial member per state; else the link that is the frame.
            "frame": drawn.frame if self.drawing is not None else None,
            "held": sorted({c.held for c in self.choices}),
            # A state's variants run both ways: a member that can be driven can be taken off.
            "driven_or_taken_off": sorted({x for c in self.choices for x in (c.input, c.output)}),
            "choices": [
                {"held": c.held, "between": [c.input, c.output], "every_mesh_loaded": c in self.loaded}
                for c in self.choices
            ],
            "train_file": None if self.not_drawable else f"{self.name}.yaml",
            "not_drawable": self.not_drawable,
        }

    def train_file(self) -> TrainFile:
        """The train file (the entry must be drawable and have a choice)."""
        drawn = self.drawn
        title = (
            f"Atlas of {self.links}-link planetary trains: "
            f"rotation graph {self.rotation}, displacement graph {self.index}"
        )
        coaxial = ", ".join(link_name(x) for x in self.graph.axes[drawn.main_axis])
        source = f"derive atlas --links {self.links}: {self.name}, coaxial members {coaxial}"
        return TrainFile(drawn, title, source, self.choices, self.planar, self.free_axes, order=self.order)

    def train(self) -> Train:
        """The train of `train_file`, built without YAML."""
        return self.train_file().train()

    def train_text(self) -> str:
        """The train file as YAML text (``derive atlas --out DIR``), under a comment that
        says where it comes from."""
        drawn = self.drawn
        written = self.train_file()
        comment = (
            f"{written.title}.\n"
            f"Canonical code {self.code}.\n"
            + (
                "Written by derive atlas: symbolic radii; the housing holds one coaxial member in each state;\n"
                if drawn.frame is None
                else f"Written by derive atlas: symbolic radii; link l{drawn.frame} is the frame;\n"
            )
            + "the ports are those of the first state. Suns, rings and planet gears as in docs/atlas.md."
            + _free_shapes(drawn, self.free_axes)
        )
        return written.text(comment)


def _free_shapes(drawn: Realisation, axes: tuple[int, ...]) -> str:
    """The comment's lines on the axis distances the meshes leave free, if any."""
    if not axes:
        return ""
    if len(axes) == 1:
        return (
            f"\nThe meshes leave the distance {distance_symbol(drawn, axes[0])} of axis "
            f"{drawn.axis_name(axes[0])} from the main axis free: any value that closes the\n"
            "triangles of its planets draws the train; the efficiency does not depend on it."
        )
    symbols = " and ".join(distance_symbol(drawn, a) for a in axes)
    names = " and ".join(drawn.axis_name(a) for a in axes)
    return (
        f"\nThe meshes leave the distances {symbols} of axes {names} from the main axis free:\n"
        "any values that close the triangles of its planets draw the train; the efficiency does\n"
        "not depend on them."
    )


def places(links: int) -> list[GraphPlace]:
    """Every displacement graph of ``links`` links, in the order of the codes."""
    from davies_sym.atlas.enumeration import atlas

    return [
        GraphPlace(links, r + 1, d + 1, code, group.code, graph)
        for r, group in enumerate(atlas(links).rotation_graphs)
        for d, (code, graph) in enumerate(zip(group.codes, group.graphs, strict=True))
    ]


def entry(place: GraphPlace) -> Entry:
    """The entry of one displacement graph: drawn the first way of `realisations` that
    leaves a choice (the choices read from the train's motions), or the reason none does."""
    where: dict[str, Any] = {f.name: getattr(place, f.name) for f in fields(GraphPlace)}
    reasons: list[str | None] = []
    for drawn in realisations(place.graph):
        try:
            found = admissible_choices(drawn)
        except BeyondWorkBound as exc:
            reasons.append(f"its choices are not read: {exc}")
            continue
        reasons.append(found.reason)
        if found.choices:
            return Entry(
                **where,
                choices=found.choices,
                not_drawable=None,
                planar=found.planar,
                drawing=drawn,
                loaded=found.loaded,
                free_axes=found.free_axes,
                order=found.order,
            )
    reason = next((r for r in reasons if r), "no held member leaves two others turning at a ratio set by the gears")
    return Entry(**where, choices=(), not_drawable=reason)
