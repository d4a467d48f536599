"""The base of the coupling kinds, and what every kind's entry shares.

A coupling kind is a frozen dataclass in a module of its own (`davies_sym.topology.revolute`,
`.gear_mesh`, `.prismatic`, `.screw_coupling`, `.skew_mesh`): a ``from_entry`` constructor
that reads its entry of the topology file, its ``FIELDS`` for the schema, the screws it
contributes to the network where the layout puts it (``screws``, Laus Tables 3-4,
12-13) and what the reports say of it.  Adding a kind means its module, registered in
`davies_sym.topology.coupling_kinds.KINDS`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import UNIT, Vector, vector
from davies_sym.losses.definitions import Definition
from davies_sym.topology.angles import AngleFunctions
from davies_sym.topology.entries import describe
from davies_sym.topology.gear import Gear
from davies_sym.topology.kind_screws import CouplingScrews, Placement
from davies_sym.topology.loss_entries import Friction
from davies_sym.topology.schema import COUPLING_COMMON, Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class AxisSpacing:
    """How a coupling that joins two gears places their axes, as the layouts read it: the
    distance between the axes along the line the layout draws them on (r_g + r_h of an
    external mesh, R - r of an internal one, Laus section 3.4.1.6; a free length of a
    chain), how far the second axis lies across that line, and where the pitch point is.

    A mesh's distance is fixed by the radii: a loop of couplings it closes gives a
    geometric constraint, and its pitch point lies on the line of centres, on the pitch
    circle of ``pitch[0]`` (the annulus of an internal mesh, else the first gear).  A
    distance written in ``free`` symbols is a length the formulas must not depend on (a
    chain's centre distance): it places an axis but closes no loop, and the coupling
    locates itself from the placed centres (`ToothedMesh.locate`)."""

    #: The coupling's name and its two gears (first, second) as the file writes them.
    name: str
    gears: tuple[str, str]
    distance: sympy.Expr
    #: (the gear whose pitch circle holds the pitch point, the other gear).
    pitch: tuple[str, str]
    #: The gears turn the same way in the coupling's carrier with the first or second an
    #: annulus (R - r > 0 is then a fact of the layout).
    internal: bool = False
    #: The second gear's axis lies this far across the line of placement from the first's
    #: (on the side of the drawing's tangent direction, right of the placement direction).
    across: sympy.Expr = sympy.S.Zero
    #: The symbols of a distance the coupling leaves free (a chain's centre distance).
    free: tuple[sympy.Symbol, ...] = ()
    #: Whether the gears may turn about intersecting axes (bevel gears); a chain or a belt
    #: joins parallel axes only.
    intersecting: bool = True
    #: What the coupling is called in a problem of the layout: ``mesh``, ``chain drive``.
    noun: str = "mesh"

    @property
    def fixed(self) -> bool:
        """Whether the radii fix the distance: it then closes loops and triangles."""
        return not self.free


@dataclass(frozen=True)
class Coupling:
    """Base of the coupling kinds: a named edge from ``links[0]`` to ``links[1]``."""

    name: str
    links: tuple[str, str]
    friction: Friction

    kind: ClassVar[str] = ""
    FIELDS: ClassVar[tuple[Field, ...]] = ()
    DOC: ClassVar[str] = ""

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> Coupling | None:
        """The coupling its entry describes, or None when ``reader`` holds the problems
        (``gears``: the train's gears by name, for the kinds that join gears)."""
        raise NotImplementedError

    @property
    def gears(self) -> tuple[str, str] | None:
        return None

    @property
    def free_lengths(self) -> tuple[sympy.Symbol, ...]:
        """Symbols of a length its layout leaves free (a chain's centre distance): no formula
        holds them, so the formula modules do not take them."""
        return ()

    @property
    def separating(self) -> sympy.Expr | None:
        """The push of its transmitted force off its line, per unit of it, where a guide's
        friction may be loaded by it (tan of a rack's pressure angle); None where it has none."""
        return None

    def spacing(self, gears: Mapping[str, Gear]) -> AxisSpacing | None:
        """How it places the axes of the two gears it joins, where the layouts place them
        from it (a mesh on parallel or intersecting axes, a chain); None for a coupling the
        layouts place otherwise (a bearing on its link's axis, a rack beside its pinion, a
        worm across its wheel)."""
        return None

    @property
    def angles(self) -> tuple[AngleFunctions, ...]:
        """The angles of its geometry whose cos and sin are symbols (a helix angle)."""
        return ()

    @property
    def definitions(self) -> tuple[Definition, ...]:
        """Symbols of this coupling's laws that a loss model defines."""
        return self.friction.definitions

    def screws(self, place: Placement) -> CouplingScrews:
        """The unit twists and candidate unit wrenches it contributes where ``place``
        puts it (Laus Tables 3-4, 12-13)."""
        raise NotImplementedError

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        """The quantities its entry writes besides its friction laws: a position, a
        direction, screws, ordinary efficiencies."""
        return ()

    @property
    def named_links(self) -> tuple[tuple[str, str], ...]:
        """The links its entry names besides ``links``, with the key that names each
        (checked against the train's links on load)."""
        return ()

    #: What the reports call it: ``mesh`` for a coupling of two gears.
    noun: ClassVar[str] = "coupling"
    #: Whether the reports give its point of the layout (a bearing's, a mesh's pitch point).
    located: ClassVar[bool] = False
    #: Teeth in contact: several freedoms, its friction opposing the first and loaded by
    #: the tooth force; no port sits on it.
    meshing: ClassVar[bool] = False
    #: The unit of its Coulomb or linear coefficient: a length where the friction is a
    #: torque loaded by a force (a bearing, a mesh), 1 where it is a force (a slider).
    load_dependent_unit: ClassVar[str] = "length"

    def report_fields(self) -> dict[str, Any]:
        """What the JSON report says of it besides its name, type, links and laws."""
        return {}


def read_links(entry: Mapping[str, Any], path: str, reader: EntryReader) -> tuple[str, str] | None:
    if "links" not in entry:
        return None  # reported as a missing required key
    links = entry["links"]
    if not isinstance(links, list) or len(links) != 2:
        reader.problem(f"{path}.links", "expected a list of two link names")
        return None
    a = reader.name(links[0], f"{path}.links[0]")
    b = reader.name(links[1], f"{path}.links[1]")
    if a is None or b is None:
        return None
    if a == b:
        reader.problem(f"{path}.links", f"a coupling must join two different links, got {a!r} twice")
        return None
    return (a, b)


def axis_direction(value: Any) -> Vector | None:
    """The unit vector of an axis letter, ``x``, ``y``, ``z`` or ``-x`` ...; None for anything else."""
    if isinstance(value, str) and value in UNIT:
        return UNIT[value]
    if isinstance(value, str) and value.startswith("-") and value[1:] in UNIT:
        return vector([-v for v in UNIT[value[1:]]])
    return None


def read_direction(value: Any, path: str, reader: EntryReader) -> Vector | None:
    """A direction: ``x``, ``y``, ``z`` (``-x`` ...), or a list of three quantities."""
    axis = axis_direction(value)
    if axis is not None:
        return axis
    if isinstance(value, list) and len(value) == 3:
        parts = [reader.quantity(v, f"{path}[{i}]", "position", roots=True) for i, v in enumerate(value)]
        if any(p is None for p in parts):
            return None
        if all(p == 0 for p in parts):
            reader.problem(path, "the direction must not be zero")
            return None
        return vector(parts)
    reader.problem(path, f"expected x, y, z or a list of three numbers, got {describe(value)}")
    return None


def coupling_fields(kind: type[Coupling]) -> tuple[Field, ...]:
    """Every key a coupling entry of ``kind`` may hold."""
    return COUPLING_COMMON + kind.FIELDS
