"""The train file of an atlas graph: symbolic radii, a housing that holds one coaxial
member in each state, ports for the first admissible choice and every held / input /
output choice as a state.

The coaxial members (the links on the main axis) turn in bearings of the housing, as in
the catalog's Ravigneaux and Simpson sets; each state brakes one of them to the housing,
drives a second and takes the output off a third. The choices whose speed ratio is not a
finite, non-zero function of the radii are left out (`admissible_choices`).

A train file is a frozen value (`TrainFile`): the atlas builds its trains from the
mapping it writes (`TrainFile.train`, no YAML between them) and writes YAML text only for
the user's files (`train_text`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import yaml

from davies_sym.atlas.realisation import GearSpec, Realisation
from davies_sym.topology.loader import load_mapping
from davies_sym.topology.model import Train

#: Name of the housing link in the train files.
HOUSING = "housing"


@dataclass(frozen=True)
class Choice:
    """One use of the train: ``held`` is braked to the housing, ``input`` driven,
    ``output`` taken off (links of the graph)."""

    held: int
    input: int
    output: int

    @property
    def name(self) -> str:
        return f"h{self.held}_i{self.input}_o{self.output}"

    @property
    def use(self) -> tuple[int, int, int]:
        """The held member and the two ports, the lower first: the use in either
        direction (as `davies_sym.atlas.idle_meshes.loadable_uses` lists them)."""
        return (self.held, min(self.input, self.output), max(self.input, self.output))


def link_name(link: int) -> str:
    return f"l{link}"


def bearing_name(link: int) -> str:
    """The bearing of a member of the main axis in the housing (or the frame)."""
    return f"B{link}"


def port_name(drawn: Realisation, link: int) -> str:
    """The bearing that drives or loads ``link``: in the housing (or the frame) for a
    member of the main axis, else the frame's bearing on the axis they share."""
    if link in drawn.graph.axes[drawn.main_axis]:
        return bearing_name(link)
    shared = next(k for k in drawn.graph.axes_of(link) if drawn.holder.get(k) == drawn.frame)
    return f"J{drawn.axis_name(shared)}{link}"


def radius_symbol(gear: str) -> str:
    return "r" + gear[1:]


def _description(drawn: Realisation, link: int) -> str:
    held = sorted(k for k, holder in drawn.holder.items() if holder == link)
    own = drawn.parent_axis[link]
    words = "coaxial member" if own == drawn.main_axis else f"turns about axis {drawn.axis_name(own)}"
    if held:
        words += ", carrier of axis " + ", ".join(drawn.axis_name(k) for k in held)
    return words


def distance_symbol(drawn: Realisation, axis: int) -> str:
    """The distance of ``axis`` from the main axis where the drawing leaves it free: e
    (eccentricity) and the axis letter."""
    return "e" + drawn.axis_name(axis)


def _axis_bearings(drawn: Realisation, free_axes: tuple[int, ...]) -> dict[str, dict[str, Any]]:
    """The bearings of every axis but the main one: the first link about it turns in a
    bearing of the axis's holder (on its own axis), every other one in a bearing of that
    first link on the first link's axis (`axis:`), so the layout reads which links are
    coaxial from the file and never has to guess it from the meshes. On an axis the frame
    holds every link turns in a bearing of the frame (their ports), the others on the
    first one's axis (`axis:` a third link). The first bearing of each of ``free_axes``
    places it at its symbolic distance from the main axis (`at:`)."""
    bearings: dict[str, dict[str, Any]] = {}
    for axis, links in enumerate(drawn.graph.axes):
        if axis == drawn.main_axis:
            continue
        holder = drawn.holder[axis]
        name = drawn.axis_name(axis)
        turning = [x for x in links if x != holder]
        for x in turning:
            bearing: dict[str, Any] = {"type": "revolute", "links": [link_name(holder), link_name(x)]}
            if x != turning[0]:
                if holder != drawn.frame:
                    bearing["links"] = [link_name(turning[0]), link_name(x)]
                bearing["axis"] = link_name(turning[0])
            if axis in free_axes and x == turning[0]:
                bearing["at"] = distance_symbol(drawn, axis)
            bearings[f"J{name}{x}"] = bearing
    return bearings


@dataclass(frozen=True)
class ToothedForm:
    """A train file for a search: tooth numbers (module 1) instead of radii, and every
    mesh's ordinary efficiency fixed (external and internal meshes)."""

    external: str
    internal: str


def tooth_symbol(gear: str) -> str:
    return "z" + gear[1:]


def _gear_entry(drawn: Realisation, gear: GearSpec, toothed: ToothedForm | None) -> dict[str, Any]:
    name = gear.name
    size = {"radius": radius_symbol(name)} if toothed is None else {"teeth": tooth_symbol(name), "module": 1}
    about = drawn.about(gear)
    return (
        {"link": link_name(gear.link), **size}
        | ({"internal": True} if gear.internal else {})
        | ({"about": link_name(about)} if about is not None else {})
    )


@dataclass(frozen=True)
class TrainFile:
    """The train file of a drawn graph as a value: ``choices`` as its states (the first
    one's ports as the train's), drawn in 2-D when ``planar``, with the distance of
    each of ``free_axes`` from the main axis a symbol (`distance_symbol`) where the meshes
    leave it free, tooth numbers when ``toothed`` and the free ones listed in ``independent``; the
    meshes written in ``order`` (indices of the drawing's meshes; None: in the order of
    the gear pairs), which is the order the layout places them in.

    The atlas builds the `Train` from it (`train`) and writes YAML only for the user's
    files (`text`)."""

    drawn: Realisation
    title: str
    source: str
    choices: tuple[Choice, ...]
    planar: bool = False
    free_axes: tuple[int, ...] = ()
    toothed: ToothedForm | None = None
    independent: tuple[str, ...] | None = None
    order: tuple[int, ...] | None = None

    def document(self) -> dict[str, Any]:
        """The train file as a mapping (YAML-ready), in the order a person reads it."""
        if not self.choices:
            raise ValueError("a train file needs at least one admissible choice")
        drawn = self.drawn
        housed = drawn.frame is None
        reference = HOUSING if drawn.frame is None else link_name(drawn.frame)
        couplings: dict[str, Any] = {
            bearing_name(x): {"type": "revolute", "links": [reference, link_name(x)], "axis": reference}
            for x in drawn.graph.axes[drawn.main_axis]
            if link_name(x) != reference
        }
        couplings |= _axis_bearings(drawn, self.free_axes)
        couplings |= _meshes(drawn, self.toothed, self.order)
        first = self.choices[0]
        states = {
            c.name: {
                "description": f"{link_name(c.held)} held, {link_name(c.input)} in, {link_name(c.output)} out",
                "input": port_name(drawn, c.input),
                "output": port_name(drawn, c.output),
            }
            | ({"brake": [link_name(c.held)]} if housed else {})
            for c in self.choices
        }
        return {
            "format": 1,
            "name": self.title,
            "source": self.source,
            # Meshes between planets of one carrier that a line cannot close: drawn in 2-D.
            **({"placement": [0, 1]} if self.planar else {}),
            "links": _links(drawn),
            "reference": reference,
            "gears": {g.name: _gear_entry(drawn, g, self.toothed) for g in drawn.gears},
            "couplings": couplings,
            "ports": {"input": port_name(drawn, first.input), "output": port_name(drawn, first.output)},
            "states": states,
            **({"independent": list(self.independent)} if self.independent is not None else {}),
        }

    def train(self) -> Train:
        """The train this file describes, built from `document` (no YAML text)."""
        return load_mapping(self.document())

    def text(self, comment: str) -> str:
        """The train file as YAML text under ``comment`` (`train_text`)."""
        return train_text(self.document(), comment)


def _links(drawn: Realisation) -> dict[str, Any]:
    """The links with their descriptions: the housing first when there is one."""
    links: dict[str, Any] = (
        {HOUSING: {"description": "housing (reference), holds one coaxial member per state"}}
        if drawn.frame is None
        else {}
    )
    links |= {link_name(i): {"description": _description(drawn, i)} for i in range(drawn.graph.links)}
    if drawn.frame is not None:
        links[link_name(drawn.frame)]["description"] += " (the frame, reference)"
    return links


def _meshes(drawn: Realisation, toothed: ToothedForm | None, order: tuple[int, ...] | None) -> dict[str, Any]:
    """The meshes, named M0, M1, ... in ``order`` (the layout places them in the order of
    their names: on a line, a mesh between two planets of one carrier puts the planet it
    places outward of the other), with their ordinary efficiencies when ``toothed``."""
    internal = {g.name for g in drawn.gears if g.internal}
    written = drawn.meshes if order is None else tuple(drawn.meshes[k] for k in order)
    meshes: dict[str, Any] = {}
    for index, m in enumerate(written):
        mesh: dict[str, Any] = {"type": "mesh", "gears": [m.first, m.second]}
        if toothed is not None:
            mesh["efficiency"] = toothed.internal if internal & {m.first, m.second} else toothed.external
        meshes[f"M{index}"] = mesh
    return meshes


class _Entry(dict[str, Any]):
    """An entry written on one line (a YAML flow mapping), as in the catalog files."""


class _Dumper(yaml.SafeDumper):
    pass


_Dumper.add_representer(
    _Entry, lambda dumper, data: dumper.represent_mapping("tag:yaml.org,2002:map", data, flow_style=True)
)


def train_text(document: dict[str, Any], comment: str) -> str:
    """The YAML text: a comment block, then the document with one line per link, gear,
    coupling and state."""
    lines = "".join(f"# {line}\n" if line else "#\n" for line in comment.splitlines())
    flowing = {
        key: {name: _Entry(entry) for name, entry in value.items()}
        if key in ("links", "gears", "couplings", "states")
        else (_Entry(value) if isinstance(value, dict) else value)
        for key, value in document.items()
    }
    body = yaml.dump(flowing, Dumper=_Dumper, sort_keys=False, width=200, allow_unicode=True)
    return lines + body
