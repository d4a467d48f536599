"""Which coaxial members a train can hold, drive and take the output off.

A state holds one coaxial member and connects two others, one the input and one the
output; its variants cover both directions of the power (Laus Tables 5 and 6: the
output becomes the input), so the choice of which of the two is written as the input
only names the state. A choice is *admissible* when the speed ratio between the two
members is a finite, non-zero function of the radii: a constant ratio would mean the
two members turn as one (or one stands still) whatever the gears.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from davies_sym.atlas.realisation import Realisation
from davies_sym.atlas.train_file import Choice, TrainFile, distance_symbol
from davies_sym.errors import DaviesError, GeometryError
from davies_sym.geometry import train_layout
from davies_sym.network.analysis import Analysis, analyse
from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state


def every_choice(drawn: Realisation) -> tuple[Choice, ...]:
    """In a housing: every held member of the main axis with every pair of two other
    members; with a frame: every pair of links turning in the frame's bearings (the
    lower link written as the input)."""
    graph = drawn.graph
    if drawn.frame is not None:
        return tuple(Choice(drawn.frame, a, b) for a, b in combinations(graph.neighbours(drawn.frame), 2))
    coaxial = graph.axes[drawn.main_axis]
    return tuple(Choice(held, a, b) for held in coaxial for a, b in combinations([x for x in coaxial if x != held], 2))


@dataclass(frozen=True)
class Admissible:
    """The admissible choices of a drawn train, whether it must be drawn in 2-D, and the
    choices in which every mesh carries a tooth force."""

    choices: tuple[Choice, ...]
    planar: bool
    loaded: tuple[Choice, ...] = ()
    #: Why there is no choice when the layout cannot be drawn.
    reason: str | None = None
    #: The axis whose distance from the main axis is a free parameter, or None.
    free_axis: int | None = None


def _written(drawn: Realisation, candidates: tuple[Choice, ...], planar: bool, free_axis: int | None = None) -> Train:
    return TrainFile(drawn, "choices", "atlas", candidates, planar, free_axis).train()


def _free_drawing(drawn: Realisation, candidates: tuple[Choice, ...]) -> tuple[int, Train] | None:
    """The first planet axis (in the order of the labelling) whose distance from the main
    axis, left free, lets the 2-D placement close every loop of meshes, with the train so
    written; None when none does. A loop of four planet axes and the main one (two planets
    each meshing a coaxial gear and both meshing a third planet) keeps one free shape: the
    distance of the third planet's axis, on which the efficiency does not depend (the
    tangential tooth forces balance each planet whatever the angles, Laus eq. (2))."""
    for axis in range(len(drawn.graph.axes)):
        if axis == drawn.main_axis:
            continue
        train = _written(drawn, candidates, True, axis)
        try:
            layout = train_layout(train)
        except GeometryError:
            continue
        free = distance_symbol(drawn, axis)
        if not any(free in map(str, c.expression.free_symbols) for c in layout.constraints):
            return axis, train
    return None


def admissible_choices(drawn: Realisation) -> Admissible:
    """The choices whose speed ratio is finite, non-zero and depends on the radii, read
    from the motions of the train written with every choice as a state; drawn on a line,
    or in 2-D (`placement:`) when the meshes between planets close loops a line cannot."""
    candidates = every_choice(drawn)
    if not candidates:
        return Admissible((), False)
    planar, free_axis = False, None
    train = _written(drawn, candidates, planar)
    try:
        train_layout(train)
    except GeometryError:
        planar = True
        train = _written(drawn, candidates, planar)
        try:
            train_layout(train)
        except GeometryError as exc:
            free = _free_drawing(drawn, candidates)
            if free is None:
                reason = f"neither a line nor 2-D placement draws it ({exc.problems[0].message})"
                return Admissible((), planar, (), reason)
            free_axis, train = free
    kept, loaded = [], []
    for choice, state in zip(candidates, train.states, strict=True):
        try:
            analysis = analyse(train_in_state(train, state))
            ratio = analysis.speed_ratio()
            if ratio.num.total_degree() > 0 or ratio.den.total_degree() > 0:
                kept.append(choice)
                if _every_mesh_loaded(analysis):
                    loaded.append(choice)
        except (DaviesError, ZeroDivisionError):
            continue
    return Admissible(tuple(kept), planar, tuple(loaded), free_axis=free_axis)


def _every_mesh_loaded(analysis: Analysis) -> bool:
    """Every mesh carries a tooth force (Laus eq. (2), the lossless actions): where one
    carries none, its gears turn idle and the use is that of a train of fewer links,
    which the atlas lists there."""
    actions = analysis.lossless_action_coefficients
    network = analysis.network
    return all(
        any(not actions[a.name].is_zero() for a in network.coupling_actions(mesh.name, lossless=True))
        for mesh in gear_meshes(analysis.train.couplings)
    )
