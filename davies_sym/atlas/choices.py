"""Which coaxial members a train can hold, drive and take the output off.

A state holds one coaxial member and connects two others, one the input and one the
output; its variants cover both directions of the power (Laus Tables 5 and 6: the
output becomes the input), so the choice of which of the two is written as the input
only names the state. A choice is *admissible* when the speed ratio between the two
members is a finite, non-zero function of the radii: a constant ratio would mean the
two members turn as one (or one stands still) whatever the gears.

The choices are read from a drawing that some positive radii build: a layout whose
loops of meshes ask for a radius that is not positive is redrawn (`_way_to_draw`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import combinations, permutations

import sympy

from davies_sym.algebra.linear_regions import Requirement, empty_region
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.atlas.idle_meshes import loadable_uses
from davies_sym.atlas.realisation import Realisation
from davies_sym.atlas.train_file import Choice, TrainFile, distance_symbol
from davies_sym.errors import BeyondWorkBound, DaviesError, GeometryError
from davies_sym.geometry import train_layout
from davies_sym.geometry.layout import Layout, polynomial_part
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
    #: The axes whose distances from the main axis are free parameters.
    free_axes: tuple[int, ...] = ()
    #: The order the meshes are written (and placed) in, or None: that of the gear pairs.
    order: tuple[int, ...] | None = None


@dataclass(frozen=True)
class _Way:
    """One way of writing a drawn train: on a line or in 2-D, a free axis distance or
    none, the meshes in an order (None: that of the gear pairs)."""

    planar: bool
    free_axes: tuple[int, ...] = ()
    order: tuple[int, ...] | None = None


#: A way of writing a train, with the train so written.
_Written = tuple[_Way, Train]


def _written(drawn: Realisation, candidates: tuple[Choice, ...], way: _Way) -> Train:
    return TrainFile(drawn, "choices", "atlas", candidates, way.planar, way.free_axes, order=way.order).train()


def admits_positive_radii(train: Train, layout: Layout) -> bool:
    """False where no design of positive radii satisfies the geometric constraints of the
    layout (its loops of meshes, Laus section 3.4.1.6) with every fact of the layout
    positive (an annulus larger than its pinion, a triangle of planet axes that closes):
    the linear constraints solved exactly, the emptiness of what is left proved by
    Fourier-Motzkin elimination over the rationals (`empty_region`); True otherwise, also
    where the proof is out of its reach (a constraint of higher degree is left out)."""
    positive = [sympy.sympify(g.radius) for g in train.gears] + [sympy.sympify(f) for f in layout.positive_facts]
    symbols = sorted(set().union(*(e.free_symbols for e in positive)), key=str)
    linear = [e for c in layout.constraints if (e := polynomial_part(c.expression)).is_polynomial(*symbols)]
    linear = [e for e in linear if sympy.Poly(e, *symbols).total_degree() <= 1]
    solutions = sympy.linsolve(linear, symbols) if linear else sympy.FiniteSet(tuple(symbols))
    if not solutions:
        return False
    (solution,) = solutions
    solved = dict(zip(symbols, solution, strict=True))
    return empty_region([Requirement(sympy.expand(e.xreplace(solved)), ">") for e in positive]) is None


def _drawing(drawn: Realisation, candidates: tuple[Choice, ...], way: _Way) -> Train | GeometryError | None:
    """The train written ``way`` when its layout draws it with positive radii; the
    geometry's error when it cannot be drawn; None when its loops of meshes ask for a
    radius that is not positive."""
    train = _written(drawn, candidates, way)
    try:
        layout = train_layout(train)
    except GeometryError as exc:
        return exc
    return train if admits_positive_radii(train, layout) else None


def _ordered(drawn: Realisation, candidates: tuple[Choice, ...], way: _Way) -> _Written | GeometryError | None:
    """The train written ``way``, with the meshes in the order of the gear pairs; where
    that drawing asks for a radius that is not positive (on a line: a planet placed
    outward of the planet it meshes where it lies inward), in the first other order (of
    the permutations, lexicographic) that draws it without. The geometry's error where
    the order of the gear pairs cannot be drawn (no other is tried: a line that cannot
    be drawn gives way to 2-D); None where no order draws it."""
    found = _drawing(drawn, candidates, way)
    if found is not None:
        return (way, found) if isinstance(found, Train) else found
    identity = tuple(range(len(drawn.meshes)))
    for order in permutations(identity):
        other = replace(way, order=order)
        if order != identity and isinstance(train := _drawing(drawn, candidates, other), Train):
            return other, train
    return None


def _free_drawing(drawn: Realisation, candidates: tuple[Choice, ...]) -> _Written | None:
    """The first planet axis (in the order of the labelling), else the first pair of them,
    whose distances from the main axis, left free, let the 2-D placement close every loop
    of meshes, with the train so written; None when none does. A loop of four planet axes
    and the main one (two planets each meshing a coaxial gear and both meshing a third
    planet) keeps one free shape: the distance of the third planet's axis; a loop of five
    keeps two. The efficiency depends on none (the tangential tooth forces balance each
    planet whatever the angles, Laus eq. (2))."""
    planets = [axis for axis in range(len(drawn.graph.axes)) if axis != drawn.main_axis]
    for free_axes in (*((a,) for a in planets), *combinations(planets, 2)):
        found = _ordered(drawn, candidates, _Way(True, free_axes))
        if not isinstance(found, tuple):
            continue
        layout = train_layout(found[1])
        free = {distance_symbol(drawn, axis) for axis in free_axes}
        if not any(free & set(map(str, c.expression.free_symbols)) for c in layout.constraints):
            return found
    return None


def _way_to_draw(drawn: Realisation, candidates: tuple[Choice, ...]) -> _Written | str:
    """How the train is written: on a line; in 2-D (`placement:`) where the meshes between
    planets close loops a line cannot, or where no order of the meshes draws the line
    with positive radii; in 2-D with a free axis distance where the placement keeps a free
    shape. The reason where none draws it."""
    line = _ordered(drawn, candidates, _Way(False))
    if isinstance(line, tuple):
        return line
    planar = _ordered(drawn, candidates, _Way(True))
    if isinstance(planar, tuple):
        return planar
    free = _free_drawing(drawn, candidates)
    if free is not None:
        return free
    why = planar.problems[0].message if planar is not None else "no order of its meshes gives positive radii"
    return f"neither a line nor 2-D placement draws it ({why})"


def admissible_choices(drawn: Realisation) -> Admissible:
    """The choices whose speed ratio is finite, non-zero and depends on the radii, read
    from the motions of the train written with every choice as a state, drawn as
    `_way_to_draw` says."""
    candidates = every_choice(drawn)
    if not candidates:
        return Admissible((), False)
    found = _way_to_draw(drawn, candidates)
    if isinstance(found, str):
        return Admissible((), True, (), found)
    way, train = found
    kept, loaded = [], []
    drawing_fails: GeometryError | None = None
    read = _Readings(train, candidates, frozenset(loadable_uses(drawn.graph)))
    for choice in candidates:
        try:
            reading = read.choice(choice)
        except BeyondWorkBound:
            raise  # not a choice the motions refuse: the train is listed with the reason
        except GeometryError as exc:
            # The radii solved from the loops of meshes draw the train again (a planet
            # can land on nested square roots): a reason, where no choice is kept.
            drawing_fails = drawing_fails or exc
            continue
        except (DaviesError, ZeroDivisionError):
            continue
        if reading.kept:
            kept.append(choice)
            if reading.loaded:
                loaded.append(choice)
    if not kept and drawing_fails is not None:
        why = drawing_fails.problems[0].message
        return Admissible((), way.planar, reason=f"its radii, solved from the loops of meshes, cannot be drawn ({why})")
    return Admissible(tuple(kept), way.planar, tuple(loaded), free_axes=way.free_axes, order=way.order)


class _Readings:
    """The choices of one written train read from their motions and lossless actions.

    The choices that hold one member and drive the first of the others are analysed
    (`analyse`); a choice between two later members is read from two of those by
    superposition, without an analysis of its own: with the member held, the motion is
    one, so its speed ratio is the ratio of the two members' speeds in either analysis;
    the lossless actions are linear in the ports' torques, so the difference of the two
    analyses' (each per unit torque on the first member) is an equilibrium with no
    torque on the first member, the choice's own (Laus eq. (2)).  Where either analysis
    fails, the choice is analysed itself.  The lossless actions are read only for the
    choices among the ``loadable`` uses (`davies_sym.atlas.idle_meshes`): any other
    idles a gear whatever the radii.
    """

    def __init__(self, train: Train, candidates: tuple[Choice, ...], loadable: frozenset[tuple[int, int, int]]):
        self.train = train
        self.loadable = loadable
        self.states = dict(zip(candidates, train.states, strict=True))
        self.first: dict[int, int] = {}
        for choice in candidates:
            self.first.setdefault(choice.held, choice.input)
        self.analysed: dict[Choice, Analysis | Exception] = {}

    def choice(self, choice: Choice) -> _Reading:
        """Whether the choice's speed ratio depends on the radii, and whether every mesh
        carries a tooth force; the analysis's error where it fails."""
        first = self.first[choice.held]
        loadable = choice.use in self.loadable
        if choice.input != first:
            to_input, to_output = Choice(choice.held, first, choice.input), Choice(choice.held, first, choice.output)
            read = self._superposed(to_input, to_output, loadable)
            if read is not None:
                return read
        analysis = self._analysis(choice)
        if isinstance(analysis, Exception):
            raise analysis
        if not _radii_set(analysis.speed_ratio()):
            return _Reading(False, False)
        return _Reading(True, loadable and _every_mesh_loaded(analysis))

    def _analysis(self, choice: Choice) -> Analysis | Exception:
        known = self.analysed.get(choice)
        if known is None:
            try:
                known = analyse(train_in_state(self.train, self.states[choice]))
            except BeyondWorkBound:
                raise
            except (DaviesError, ZeroDivisionError) as exc:
                known = exc
            self.analysed[choice] = known
        return known

    def _superposed(self, to_input: Choice, to_output: Choice, loadable: bool) -> _Reading | None:
        """The reading of the choice between the outputs of ``to_input`` and
        ``to_output`` (both driving the first member; ``loadable``: whether its actions
        are read); None where either analysis or its lossless actions fail, or their
        meshes' actions differ."""
        a, b = self._analysis(to_input), self._analysis(to_output)
        if isinstance(a, Exception) or isinstance(b, Exception):
            return None
        try:
            speeds = a.motion_coefficients
            into, out_of = (speeds[_port_motion(a, x.train.ports.output)] for x in (a, b))
            if out_of.is_zero():
                raise ZeroDivisionError("the output does not turn")
            if not _radii_set(into / out_of):
                return _Reading(False, False)
            if not loadable:
                return _Reading(True, False)
            forces = (a.lossless_action_coefficients, b.lossless_action_coefficients)
            names = [_mesh_actions(x) for x in (a, b)]
        except BeyondWorkBound:
            raise
        except (DaviesError, ZeroDivisionError):
            return None
        if names[0] != names[1]:
            return None
        loaded = all(any(not (forces[0][n] - forces[1][n]).is_zero() for n in mesh) for mesh in names[0])
        return _Reading(True, loaded)


@dataclass(frozen=True)
class _Reading:
    """What a choice's motions and lossless actions say: whether its speed ratio
    depends on the radii (it is kept), and whether every mesh carries a tooth force."""

    kept: bool
    loaded: bool


def _port_motion(analysis: Analysis, coupling: str) -> str:
    """The motion variable of a bearing in ``analysis``."""
    return analysis.network.coupling_motions(coupling)[0].name


def _radii_set(ratio: RationalFunction) -> bool:
    """Whether a speed ratio depends on the radii (a constant: the members turn as one,
    or one stands still, whatever the gears)."""
    return ratio.num.total_degree() > 0 or ratio.den.total_degree() > 0


def _mesh_actions(analysis: Analysis) -> list[tuple[str, ...]]:
    """The lossless actions of each mesh (its tooth force, Laus eq. (2))."""
    network = analysis.network
    return [
        tuple(a.name for a in network.coupling_actions(mesh.name, lossless=True))
        for mesh in gear_meshes(analysis.train.couplings)
    ]


def _every_mesh_loaded(analysis: Analysis) -> bool:
    """Every mesh carries a tooth force (Laus eq. (2), the lossless actions): where one
    carries none, its gears turn idle and the use is that of a train of fewer links,
    which the atlas lists there."""
    actions = analysis.lossless_action_coefficients
    return all(any(not actions[n].is_zero() for n in mesh) for mesh in _mesh_actions(analysis))
