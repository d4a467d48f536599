"""Coupling kinds as written in a topology file: what each joins, its parameters, its friction.

A coupling kind is a frozen dataclass with a ``from_entry`` constructor that reads its
entry of the topology file and its ``FIELDS`` for the schema.  Adding a kind means a
class here (or in a module of its own, such as `davies_sym.topology.skew_mesh`),
registered in `davies_sym.topology.coupling_kinds.KINDS`, and its screws in
`davies_sym.network.coupling_screws` (Laus Tables 3-4, 12-13).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from davies_sym.algebra.screws import TWIST_COORDINATES, UNIT, WRENCH_COORDINATES, NamedScrew, Vector, vector
from davies_sym.errors import shortened
from davies_sym.losses.definitions import Definition
from davies_sym.topology.angles import AngleFunctions
from davies_sym.topology.entries import describe
from davies_sym.topology.expressions import check_name
from davies_sym.topology.gear import Gear
from davies_sym.topology.loss_entries import Friction, read_friction, tooth_contact
from davies_sym.topology.mesh_entries import annulus_larger, read_efficiencies, read_gear_pair, read_helix
from davies_sym.topology.schema import COUPLING_COMMON, Field

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


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
    def angles(self) -> tuple[AngleFunctions, ...]:
        """The angles of its geometry whose cos and sin are symbols (a helix angle)."""
        return ()

    @property
    def definitions(self) -> tuple[Definition, ...]:
        """Symbols of this coupling's laws that a loss model defines."""
        return self.friction.definitions

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        """The quantities its entry writes besides its friction laws: a position, a
        direction, screws, ordinary efficiencies."""
        return ()

    #: What the reports call it: ``mesh`` for a coupling of two gears.
    noun: ClassVar[str] = "coupling"
    #: Whether the reports give its point of the layout (a bearing's, a mesh's pitch point).
    located: ClassVar[bool] = False

    def report_fields(self) -> dict[str, Any]:
        """What the JSON report says of it besides its name, type, links and laws."""
        return {}


def _read_links(entry: Mapping[str, Any], path: str, reader: EntryReader) -> tuple[str, str] | None:
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


@dataclass(frozen=True)
class Revolute(Coupling):
    """A revolute pair (bearing): one rotation about the axis through its point."""

    at: sympy.Expr | None = None
    axis: str | None = None

    kind: ClassVar[str] = "revolute"
    located: ClassVar[bool] = True
    DOC: ClassVar[str] = (
        "Revolute pair between two links. Its axis is parallel to the gear "
        "axes; its position is that of the gears of either link, or `at`."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links; the edge goes from the first to the second."),
        Field(
            "at",
            "number or expression",
            False,
            "Position of the axis on the layout line (y), needed only when neither link carries a gear.",
        ),
        Field(
            "axis",
            "link",
            False,
            "The link whose gear axis this bearing is on, when both links carry gears but are not "
            "coaxial (a planet pin in a carrier that also has teeth). Default: the two links are coaxial.",
        ),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> Revolute | None:
        links = _read_links(entry, path, reader)
        at = reader.quantity(entry["at"], f"{path}.at", "position") if "at" in entry else None
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name, bearing=True)
        axis = reader.name(entry["axis"], f"{path}.axis") if "axis" in entry else None
        if links is not None and axis is not None and axis not in links:
            reader.problem(f"{path}.axis", f"{shortened(axis)} is not one of the coupling's links {list(links)}")
            axis = None
        return None if links is None else cls(name, links, friction, at, axis)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return () if self.at is None else (self.at,)


@dataclass(frozen=True)
class GearMesh(Coupling):
    """A gear mesh between two gears on different links, external or internal.

    The relative motion is a rotation about the pitch line (Laus Table 3, coupling C);
    the transmitted action is the tooth force along the common tangent at the pitch
    point (pressure angle taken as zero, Laus section 3.3.1), and the friction is a
    torque about the pitch line (Theorem 1).  The separating motion along the centre
    line is a secondary freedom: it is kept in planar systems of order 3.

    Helical gears (``helix``) on parallel axes: the tooth force is normal to the tooth
    line, so besides its tangential part ``F`` it pushes the gears apart along their
    axes by ``F tan(beta)``, the thrust the bearings take; the teeth may slide along the
    tooth line.  ``hand`` is +1 when the first gear is right-handed (the second is then
    left-handed on an external mesh, right-handed on an internal one).
    """

    mesh_gears: tuple[str, str] = ("", "")
    internal: bool = False
    #: Ordinary efficiencies: (first gear drives, second gear drives), Laus eqs. (32), (34).
    efficiencies: tuple[sympy.Expr, sympy.Expr] | None = None
    #: The efficiencies as functions of the tooth geometry (Laus App. A), when given so.
    efficiency_definitions: tuple[Definition, ...] = ()
    #: cos and sin of the helix angle at the pitch radius (helical gears), else None.
    helix: AngleFunctions | None = None
    #: +1: the first gear is right-handed, -1: left-handed.
    hand: int = 1

    kind: ClassVar[str] = "mesh"
    noun: ClassVar[str] = "mesh"
    located: ClassVar[bool] = True
    DOC: ClassVar[str] = (
        "Gear mesh between two gears. The edge goes from the link of the first gear "
        "to the link of the second. External or internal is derived from the gears "
        "(`internal: true` marks an annulus); `mesh` may state it as a check."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("gears", "[gear, gear]", True, "The two meshing gears."),
        Field("mesh", "`external` or `internal`", False, "Checked against the gears."),
        Field(
            "efficiency",
            "symbol or number, a list of two, or a mapping",
            False,
            "Ordinary efficiency of the mesh (carrier held). One value serves both power "
            "directions; a list gives [first gear drives, second gear drives]; a mapping derives both "
            "from the tooth geometry of an external spur mesh (Laus App. A, eq. (136)): "
            "`eta_<coupling>_<gear>_<gear>` (driver first), see *Tooth contact*. "
            "Default: `eta_<coupling>`.",
        ),
        Field(
            "helix_angle",
            "symbol or number",
            False,
            "Helix angle beta of helical gears at the pitch radius, between 0 and 90 degrees (numbers are "
            "degrees, symbols radians): the tooth force then thrusts along the axes by F tan(beta), which "
            "the bearings take (see `thrust` friction). Default: spur gears.",
        ),
        Field(
            "hand",
            "`right` or `left`",
            False,
            "Hand of the first gear's helix (the second gear has the other hand on an external mesh, the "
            "same on an internal one); it sets the direction of the thrust. Default: `right`.",
        ),
    )

    @property
    def gears(self) -> tuple[str, str]:
        return self.mesh_gears

    @property
    def angles(self) -> tuple[AngleFunctions, ...]:
        return () if self.helix is None else (self.helix,)

    @property
    def definitions(self) -> tuple[Definition, ...]:
        angles = tuple(d for a in self.angles for d in a.definitions)
        return self.friction.definitions + self.efficiency_definitions + angles

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return () if self.efficiencies is None else tuple(self.efficiencies)

    def report_fields(self) -> dict[str, Any]:
        return {"gears": list(self.gears), "mesh": "internal" if self.internal else "external"}

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> GearMesh | None:
        pair = read_gear_pair(entry, path, reader, gears)
        if pair is None:
            return None
        g1, g2 = pair
        if g1.internal and g2.internal:
            reader.problem(f"{path}.gears", "two internal gears cannot mesh")
            return None
        internal = g1.internal or g2.internal
        if internal and not annulus_larger(g1 if g1.internal else g2, g2 if g1.internal else g1, path, reader):
            return None
        stated = entry.get("mesh")
        if stated is not None and stated not in ("external", "internal"):
            reader.problem(f"{path}.mesh", f"expected `external` or `internal`, got {shortened(str(stated))}")
        elif stated is not None and (stated == "internal") != internal:
            reader.problem(
                f"{path}.mesh",
                f"stated {shortened(str(stated))} but the gears make an {'internal' if internal else 'external'} mesh",
            )
        for own, meaning, role, given in (
            (f"zeta_{name}", "mesh friction coefficient", "friction", "friction" in entry),
            (f"eta_{name}", "ordinary efficiency", "efficiency", "efficiency" in entry),
        ):
            elsewhere = reader.written.get(own)
            if not given and elsewhere is not None and not elsewhere.startswith(path):
                # The mesh's own symbol, already written in another role (a radius called eta_G):
                # said once, where it was written.
                reader.problem(
                    elsewhere, f"{own} is the name of the {meaning} of mesh {name}; give this symbol another name"
                )
                reader.roles[own] = role
        default = Friction(coulomb=reader.quantity(f"zeta_{name}", path, "friction"))
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, default, name)
        value = entry.get("efficiency", f"eta_{name}")
        definitions: tuple[Definition, ...] = ()
        if isinstance(value, Mapping):
            definitions = tooth_contact(value, f"{path}.efficiency", reader, name, (g1, g2))
            efficiencies = (definitions[0].symbol, definitions[1].symbol) if definitions else None
        else:
            efficiencies = read_efficiencies(value, f"{path}.efficiency", reader)
        helix, hand = read_helix(entry, path, reader, name)
        return cls(
            name, (g1.link, g2.link), friction, (g1.name, g2.name), internal, efficiencies, definitions, helix, hand
        )


@dataclass(frozen=True)
class Prismatic(Coupling):
    """A prismatic pair: one translation along ``direction``."""

    direction: Vector = (sympy.Integer(1), sympy.Integer(0), sympy.Integer(0))

    kind: ClassVar[str] = "prismatic"
    DOC: ClassVar[str] = "Prismatic pair between two links: one translation."
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links."),
        Field("direction", "`x`, `y`, `z` or [x, y, z]", True, "Direction of the translation."),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> Prismatic | None:
        links = _read_links(entry, path, reader)
        direction = read_direction(entry["direction"], f"{path}.direction", reader) if "direction" in entry else None
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name)
        if links is None or direction is None:
            return None
        return cls(name, links, friction, direction)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return tuple(self.direction)


def read_direction(value: Any, path: str, reader: EntryReader) -> Vector | None:
    """A direction: ``x``, ``y``, ``z`` (``-x`` ...), or a list of three quantities."""
    if isinstance(value, str) and value in UNIT:
        return UNIT[value]
    if isinstance(value, str) and value.startswith("-") and value[1:] in UNIT:
        return vector([-v for v in UNIT[value[1:]]])
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


@dataclass(frozen=True)
class ScrewCoupling(Coupling):
    """The low-level form: unit motion and action screws written out (Laus App. B, C)."""

    motion_screws: tuple[NamedScrew, ...] = ()
    action_screws: tuple[NamedScrew, ...] = ()

    kind: ClassVar[str] = "screws"
    DOC: ClassVar[str] = (
        "Low-level coupling with explicit unit screws, as in the tables of Laus "
        "appendices B and C. Coordinates not written are zero."
    )
    FIELDS: ClassVar[tuple[Field, ...]] = (
        Field("links", "[link, link]", True, "The two links."),
        Field("motions", "mapping", True, "Unit twists: magnitude name -> {r, s, t, u, v, w} (axis formation)."),
        Field(
            "actions",
            "mapping",
            True,
            "Unit wrenches transmitted: magnitude name -> {R, S, T, U, V, W} (ray formation).",
        ),
    )

    @classmethod
    def from_entry(
        cls, name: str, entry: Mapping[str, Any], path: str, reader: EntryReader, gears: Mapping[str, Gear]
    ) -> ScrewCoupling | None:
        links = _read_links(entry, path, reader)
        motions = (
            _read_screws(entry["motions"], f"{path}.motions", reader, TWIST_COORDINATES) if "motions" in entry else None
        )
        actions = _read_screws(entry.get("actions", {}), f"{path}.actions", reader, WRENCH_COORDINATES)
        friction = read_friction(entry.get("friction"), f"{path}.friction", reader, Friction(), name)
        if links is None or motions is None or actions is None:
            return None
        if not motions:
            reader.problem(f"{path}.motions", "a coupling needs at least one motion screw")
            return None
        return cls(name, links, friction, motions, actions)

    @property
    def written_quantities(self) -> tuple[sympy.Expr, ...]:
        return tuple(x for s in (*self.motion_screws, *self.action_screws) for x in s.screw)


def _read_screws(
    value: Any, path: str, reader: EntryReader, coordinates: tuple[str, ...]
) -> tuple[NamedScrew, ...] | None:
    entry = reader.mapping(value, path)
    if entry is None:
        return None
    out = []
    for label, coords in entry.items():
        cpath = f"{path}.{label}"
        # The label names the screw's magnitude, which becomes a symbol of the outputs.
        why = check_name(label)
        if why is not None:
            reader.problem(cpath, f"{why} (a magnitude such as t_C or U_C)")
            continue
        cmap = reader.mapping(coords, cpath)
        if cmap is None:
            continue
        screw = []
        for key in cmap:
            if key not in coordinates:
                reader.problem(f"{cpath}.{key}", f"unknown coordinate {shortened(key)} (use {', '.join(coordinates)})")
        for c in coordinates:
            q = reader.quantity(cmap[c], f"{cpath}.{c}", "position", roots=True) if c in cmap else sympy.Integer(0)
            screw.append(q if q is not None else sympy.Integer(0))
        if all(c == 0 for c in screw):
            reader.problem(cpath, "a unit screw must not be zero")
        base = label.split("_")[0] if "_" in label else label
        out.append(NamedScrew(base, tuple(screw)))
    return tuple(out)


def coupling_fields(kind: type[Coupling]) -> tuple[Field, ...]:
    """Every key a coupling entry of ``kind`` may hold."""
    return COUPLING_COMMON + kind.FIELDS
