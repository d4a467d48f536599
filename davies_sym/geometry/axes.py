"""Which links turn about one axis, read from the topology alone (no radii, no word order).

Every link is held by a bearing: walking the revolutes from the reference gives a
tree, and each link turns about its own axis relative to the link that holds it (a
planet about its pin on the carrier, a shaft about its bearing in the housing); a
revolute is on the axis of the link it holds.  The meshes then decide which axes
coincide (Willis, Laus section 3.4.1): the two gears of a mesh keep their centre
distance only if one link (the mesh's carrier) holds both gear axes, so either both
links are held by the same link (a fixed-axis pair in its frame), or one of them (the
planet) is held by the carrier and the other turns about the carrier's own axis.  The
two gears of a mesh are never coaxial.  Among the choices that satisfy every mesh, the
planet is the link farther from the reference (ties by name), so the result depends on
the topology and the names only, never on the order in which entries are written.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from itertools import product

from davies_sym.errors import GeometryError, Problem
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.couplings import AxisSpacing
from davies_sym.topology.link_groups import link_classes
from davies_sym.topology.model import Train
from davies_sym.topology.revolute import Revolute


@dataclass(frozen=True)
class MeshFrame:
    """The link holding both gear axes of a mesh, and which gear's link is its planet.

    ``planet`` is the index (0 or 1, in the mesh's gear order) of the gear whose link the
    carrier holds off the carrier's own axis; None when the carrier holds both links on
    axes of their own (a fixed-axis pair in the carrier's frame)."""

    carrier: str
    planet: int | None


@dataclass(frozen=True)
class AxisStructure:
    """The axes of a train as the topology fixes them.

    ``axis`` names the axis class of every link (links turning about one axis share it);
    ``bearing_axis`` the class of every revolute; ``root`` the class drawn at the origin
    (the main axis)."""

    parent: Mapping[str, str]
    depth: Mapping[str, int]
    axis: Mapping[str, str]
    bearing_axis: Mapping[str, str]
    meshes: Mapping[str, MeshFrame]
    root: str
    #: How each coupling that places two gears' axes spaces them (`spacings`), in the
    #: train's order: what the layouts place the axes by.
    spacings: tuple[AxisSpacing, ...] = ()
    #: The meshes whose second gear turns on a planet axis.
    planet_second: frozenset[str] = frozenset()

    def classes(self) -> list[str]:
        """Every axis class, sorted."""
        return sorted(set(self.axis.values()))


def spacings(train: Train) -> list[AxisSpacing]:
    """How each coupling that places two gears' axes spaces them (meshes, chains), in the
    train's order."""
    gears = {g.name: g for g in train.gears}
    found = (c.spacing(gears) for c in train.couplings)
    return [s for s in found if s is not None]


def axis_structure(train: Train, spaced: Sequence[AxisSpacing] | None = None) -> AxisStructure:
    """The bearing tree, the mesh carriers and the axis classes of ``train`` (``spaced``:
    its `spacings`, where the caller has them already)."""
    spaced = tuple(spacings(train) if spaced is None else spaced)
    revolutes = sorted(bearings(train.couplings), key=lambda c: c.name)
    meshes = sorted(spaced, key=lambda c: c.name)
    parent, depth, tree = _bearing_tree(train, revolutes)
    coaxial, bearing_on = _coaxial(train, revolutes, tree)
    _check_meshes_apart(train, meshes, revolutes, tree, coaxial)
    holders = _axis_holders(parent, coaxial)
    frames, axis = _mesh_frames(train, meshes, holders, depth, revolutes, tree, coaxial)
    bearing_axis = {name: axis[link] for name, link in bearing_on.items()}
    return AxisStructure(
        parent=parent,
        depth=depth,
        axis=axis,
        bearing_axis=bearing_axis,
        meshes=frames,
        root=_root(train, axis, bearing_axis),
        spacings=spaced,
        planet_second=frozenset(name for name, frame in frames.items() if frame.planet == 1),
    )


def _axis_holders(parent: Mapping[str, str], coaxial: Mapping[str, str]) -> dict[str, str]:
    """The link that holds each link's axis: its parent in the bearing tree, or, for a
    link held on its parent's own axis (a planet turning on a coaxial planet), the holder
    of that parent's axis, so that the carrier of both is found for its meshes
    (``coaxial``: each link's axis class)."""
    holders: dict[str, str] = {}
    for link, holder in parent.items():
        while coaxial[holder] == coaxial[link] and holder in parent:
            holder = parent[holder]
        holders[link] = holder
    return holders


def _bearing_tree(train: Train, revolutes: Sequence[Revolute]) -> tuple[dict[str, str], dict[str, int], dict[str, str]]:
    """Breadth-first tree of the revolutes from the reference (neighbours by name):
    parent and depth of every link, and tree revolute -> the link it holds.  Links no
    bearing chain reaches start trees of their own."""
    parent: dict[str, str] = {}
    depth: dict[str, int] = {}
    tree: dict[str, str] = {}
    neighbours: dict[str, list[tuple[str, str]]] = {link: [] for link in train.link_names}
    for c in revolutes:
        a, b = c.links
        neighbours[a].append((b, c.name))
        neighbours[b].append((a, c.name))
    for start in [train.reference, *sorted(train.link_names)]:
        if start in depth:
            continue
        depth[start] = 0
        queue = deque([start])
        while queue:
            link = queue.popleft()
            for other, name in sorted(neighbours[link]):
                if other not in depth:
                    depth[other] = depth[link] + 1
                    parent[other] = link
                    tree[name] = other
                    queue.append(other)
    return parent, depth, tree


Choice = tuple[MeshFrame, tuple[str, str] | None]


def axis_links(train: Train, mesh: AxisSpacing) -> tuple[str, str]:
    """The links whose axes the two gears of ``mesh`` turn about: their own links, or the
    link a gear names with ``about`` (a gear fixed to a carrier about a pin it holds)."""
    first, second = (train.gear(name).axis_link for name in mesh.gears)
    return first, second


def _options(
    train: Train,
    mesh: AxisSpacing,
    parent: Mapping[str, str],
    depth: Mapping[str, int],
    coaxial: Mapping[str, str],
) -> list[Choice]:
    """The ways ``mesh`` can keep its centre distance: (frame, the two links it makes
    coaxial), those the bearings make coaxial already (``coaxial``: each link's class)
    first."""
    a, b = axis_links(train, mesh)
    pa, pb = parent.get(a), parent.get(b)
    if pa is not None and pa == pb:
        return [(MeshFrame(pa, None), None)]
    if pa == b:  # a planet meshing a gear of its own carrier
        return [(MeshFrame(b, 0), None)]
    if pb == a:
        return [(MeshFrame(a, 1), None)]
    options: list[tuple[int, str, MeshFrame, tuple[str, str]]] = []
    if pa is not None:
        options.append((-depth[a], a, MeshFrame(pa, 0), (b, pa)))
    if pb is not None:
        options.append((-depth[b], b, MeshFrame(pb, 1), (a, pb)))
    # A gear turning about the other gear's holder's own axis already (a planet's gear
    # meshing a ring on a pin of the same carrier) names that holder first; else the
    # planet is the link farther from the reference; ties by name.
    return [
        (frame, equal)
        for _, _, frame, equal in sorted(options, key=lambda o: (coaxial[o[3][0]] != coaxial[o[3][1]], o[0], o[1]))
    ]


def _coaxial(
    train: Train,
    revolutes: Sequence[Revolute],
    tree: Mapping[str, str],
    without: str | None = None,
    equals: Sequence[tuple[str, str]] = (),
) -> tuple[dict[str, str], dict[str, str]]:
    """The links that turn about one axis (each link's class, named by its first link),
    and the link each bearing is on (``without``: that bearing's `axis:` left out, to find
    which entry makes two links coaxial; ``equals``: pairs of links the meshes make
    coaxial besides)."""
    joined: list[tuple[str, str]] = list(equals)
    bearing_on: dict[str, str] = {}
    for c in revolutes:
        a, b = c.links
        axis = None if c.name == without else c.axis
        if c.name in tree:
            child = tree[c.name]
            holder = a if child == b else b
            if axis == holder:  # the bearing is on the holder's axis: the two turn about one axis
                joined.append((child, holder))
            elif axis is not None and axis not in c.links:  # on a third link's axis
                joined.append((child, axis))
            bearing_on[c.name] = child
        elif axis is not None:
            bearing_on[c.name] = axis
        else:  # a second bearing between two held links: they turn about one axis
            joined.append((a, b))
            bearing_on[c.name] = a
    return link_classes(train.link_names, joined), bearing_on


def _check_meshes_apart(
    train: Train,
    meshes: Sequence[AxisSpacing],
    revolutes: Sequence[Revolute],
    tree: Mapping[str, str],
    coaxial: Mapping[str, str],
) -> None:
    """No mesh joins two links that turn about one axis; the problem is filed at the
    bearing whose `axis:` makes them coaxial where one does, else at the mesh."""
    for mesh in meshes:
        a, b = axis_links(train, mesh)
        if coaxial[a] != coaxial[b]:
            continue
        cause = next(
            (
                c
                for c in revolutes
                if c.axis is not None and (groups := _coaxial(train, revolutes, tree, c.name)[0])[a] != groups[b]
            ),
            None,
        )
        if cause is None:
            problem = Problem(
                f"couplings.{mesh.name}",
                f"links {a!r} and {b!r} turn about one axis (their bearings make them coaxial), so their gears "
                f"cannot {_joined(mesh)}; {_apart(mesh)}",
            )
        else:
            problem = Problem(
                f"couplings.{cause.name}.axis",
                f"`axis: {cause.axis}` puts links {a!r} and {b!r} on one axis, so their {mesh.noun} "
                f"{mesh.name!r} cannot turn; `axis:` names the link whose axis the bearing is on: write "
                f"`axis: {tree.get(cause.name, cause.links[1])}` for a planet on its pin, or leave `axis:` out",
            )
        raise GeometryError([problem], train.file_lines)


def _joined(mesh: AxisSpacing) -> str:
    """What two coaxial gears cannot do in a problem: mesh, or be joined by a chain."""
    return "mesh" if mesh.noun == "mesh" else f"be joined by a {mesh.noun}"


def _apart(mesh: AxisSpacing) -> str:
    """How to keep two coaxial links' gears apart, in a problem."""
    if mesh.noun == "mesh":
        return "name the planet of a pin with `axis:` on its revolute"
    return f"a {mesh.noun} joins two axes that one link holds apart: join each link to it by its own revolute"


def _mesh_frames(
    train: Train,
    meshes: Sequence[AxisSpacing],
    parent: Mapping[str, str],
    depth: Mapping[str, int],
    revolutes: Sequence[Revolute],
    tree: Mapping[str, str],
    coaxial: Mapping[str, str],
) -> tuple[dict[str, MeshFrame], dict[str, str]]:
    """The first choice of a carrier per mesh (in order of preference) under which no mesh
    joins two coaxial links, and the axis classes of the links with the axes it makes
    coaxial (each link's class, named by its first link); the ``revolutes`` (``tree``:
    the bearing tree) make links coaxial before the meshes do."""
    ends = {m.name: axis_links(train, m) for m in meshes}
    choices = [_options(train, m, parent, depth, coaxial) for m in meshes]
    for assignment in _assignments(choices):
        equals = [equal for _, equal in assignment if equal is not None]
        groups = _coaxial(train, revolutes, tree, equals=equals)[0]
        if all(groups[ends[m.name][0]] != groups[ends[m.name][1]] for m in meshes):
            return {m.name: frame for m, (frame, _) in zip(meshes, assignment, strict=True)}, groups
    problems = [
        Problem(
            f"couplings.{m.name}",
            f"no link holds both gear axes of this {m.noun} together with "
            "the other meshes: the planet's carrier must turn about the axis of the gear it "
            "meshes",
        )
        for m, c in zip(meshes, choices, strict=True)
        if len(c) != 1
    ]
    raise GeometryError(
        problems or [Problem("couplings", "the meshes cannot all keep their centre distances")], train.file_lines
    )


def _assignments(choices: Sequence[list[Choice]]) -> Iterator[tuple[Choice, ...]]:
    """Every combination of the choices, the preferred ones first."""
    if any(not c for c in choices):
        return iter(())
    return product(*choices)


def _root(train: Train, axis: Mapping[str, str], bearing_axis: Mapping[str, str]) -> str:
    """The class drawn at the origin, from the file's own statements, never from its ports:
    the reference's axis when gears turn about it; else, where a bearing gives a geared
    axis its `at`, the reference's axis too (the origin the `at` values are measured from),
    so that every `at` is kept as written; else the first geared class (by name)."""
    geared = {axis[g.axis_link] for g in train.gears}
    if axis[train.reference] in geared:
        return axis[train.reference]
    stated = any(c.at is not None and bearing_axis.get(c.name) in geared for c in bearings(train.couplings))
    if stated or not geared:
        return axis[train.reference]
    return min(geared)
