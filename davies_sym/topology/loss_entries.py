"""Loss entries of a topology file: the friction laws of a coupling (Laus Table 2), a
journal bearing's Coulomb law (App. D) and a mesh's efficiencies from its tooth
geometry (App. A), read into laws and the definitions of their coefficients."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import sympy

from davies_sym.losses.definitions import Definition
from davies_sym.losses.journal_bearing import CONTACT_LAWS, friction_circle_radius
from davies_sym.losses.tooth_contact import contact_lengths, spur_mesh_efficiency
from davies_sym.topology.entries import describe
from davies_sym.topology.gear import Gear
from davies_sym.topology.schema import BEARING, FRICTION, THRUST, TOOTH_CONTACT, Field
from davies_sym.topology.symbols import train_symbol

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class Friction:
    """Friction laws of one coupling (Laus Table 2); ``None`` means the law is absent."""

    coulomb: sympy.Expr | None = None
    linear: sympy.Expr | None = None
    viscous: sympy.Expr | None = None
    #: Constant torque against the relative motion (a dependent source).
    drag: sympy.Expr | None = None
    #: Coefficients a loss model defines (a journal's friction-circle radius, App. D).
    definitions: tuple[Definition, ...] = ()
    #: The reaction of a bearing that loads its Coulomb law: ``radial`` (a journal) or
    #: ``axial`` (a thrust face).
    load: str = "radial"
    #: The mesh whose separating tooth force loads a guide's Coulomb law, if any.
    pressed_by: str | None = None

    @property
    def lossless(self) -> bool:
        return self.coulomb is None and self.linear is None and self.viscous is None and self.drag is None

    @property
    def loaded(self) -> tuple[str, sympy.Expr] | None:
        """The load-dependent law, ``("coulomb", coefficient)`` or else ``("linear", ...)``,
        the one a transmitted action loads (Laus Table 2); None when there is neither."""
        if self.coulomb is not None:
            return "coulomb", self.coulomb
        if self.linear is not None:
            return "linear", self.linear
        return None


def read_friction(
    value: Any,
    path: str,
    reader: EntryReader,
    default: Friction,
    name: str = "",
    on: Literal["", "bearing", "guide"] = "",
) -> Friction:
    """Read a ``friction`` entry of coupling ``name``: ``none``, or a mapping of laws to
    coefficients (``on`` a ``"bearing"``, a revolute, the ``bearing`` key gives the Coulomb
    law of a journal, Laus App. D, and ``thrust`` that of a thrust face; on a ``"guide"``, a
    prismatic pair, ``pressed_by`` names the mesh whose separating force loads its Coulomb
    law)."""
    if value is None:
        return default
    if isinstance(value, str) and value.strip().lower() == "none":
        return Friction()
    entry = reader.mapping(value, path)
    if entry is None:
        return default
    reader.check_keys(entry, path, FRICTION)
    laws: dict[str, sympy.Expr | None] = {}
    pressed_by = _read_pressed_by(entry, path, reader, on == "guide")
    for f in FRICTION:
        if f.key in entry and f.key not in (*_BEARING_LAWS, "pressed_by"):
            role = "viscous" if f.key == "viscous" else "friction"
            laws[f.key] = reader.quantity(entry[f.key], f"{path}.{f.key}", role)
    definitions: tuple[Definition, ...] = ()
    given = [k for k in _BEARING_LAWS if k in entry]
    if given and on != "bearing":
        reader.problem(f"{path}.{given[0]}", f"`{given[0]}` is a law of a bearing: write it on a revolute coupling")
        given = []
    if len(given) == 2:
        reader.problem(
            path,
            "one load-dependent law per bearing: `bearing` (loaded by the radial reaction) or `thrust` "
            "(loaded by the axial reaction), not both",
        )
    elif given:
        key = given[0]
        if "coulomb" in laws or "linear" in laws:
            reader.problem(path, f"`{key}` gives the bearing's Coulomb law: write it without `coulomb` or `linear`")
        reading = _read_bearing if key == "bearing" else _read_thrust
        law = reading(entry[key], f"{path}.{key}", reader, name)
        if law is not None:
            laws["coulomb"], definitions = law.symbol, (law,)
    if "coulomb" in laws and "linear" in laws:
        reader.problem(path, "choose one load-dependent law: `coulomb` or `linear`, not both")
    if pressed_by is not None and "coulomb" not in laws:
        reader.problem(f"{path}.pressed_by", "the separating force loads a Coulomb law: give `coulomb` too")
    load = "axial" if "thrust" in given else "radial"
    return Friction(**laws, definitions=definitions, load=load, pressed_by=pressed_by)


def _read_pressed_by(entry: Mapping[str, Any], path: str, reader: EntryReader, guide: bool) -> str | None:
    """The mesh named by a guide's ``pressed_by`` (checked to be such a mesh by the network)."""
    if "pressed_by" not in entry:
        return None
    if not guide:
        reader.problem(f"{path}.pressed_by", "`pressed_by` loads a guide: write it on a prismatic coupling")
        return None
    return reader.name(entry["pressed_by"], f"{path}.pressed_by")


#: The friction keys that give a bearing's Coulomb law through its own model.
_BEARING_LAWS = ("bearing", "thrust")


def _bearing_entry(
    value: Any, path: str, reader: EntryReader, fields: tuple[Field, ...]
) -> tuple[Mapping[str, Any], sympy.Expr, sympy.Expr] | None:
    """A bearing law's mapping with its friction coefficient ``mu`` and its ``radius``."""
    entry = reader.mapping(value, path)
    if entry is None:
        return None
    reader.check_keys(entry, path, fields)
    if "mu" not in entry or "radius" not in entry:
        return None  # reported as missing required keys
    mu = reader.quantity(entry["mu"], f"{path}.mu", "friction")
    radius = reader.quantity(entry["radius"], f"{path}.radius", "length")
    return None if mu is None or radius is None else (entry, mu, radius)


def _read_thrust(value: Any, path: str, reader: EntryReader, name: str) -> Definition | None:
    """The friction radius of a thrust face as a definition: its torque is mu r |F_axial|."""
    read = _bearing_entry(value, path, reader, THRUST)
    if read is None:
        return None
    _, mu, radius = read
    return Definition(
        _defined_symbol(f"zeta_{name}", "friction", reader),
        mu * radius,
        f"friction radius of the thrust face of bearing {name}",
        "Coulomb friction of a thrust face",
        _units((mu, "1"), (radius, "length (one unit for all)")),
    )


def _read_bearing(value: Any, path: str, reader: EntryReader, name: str) -> Definition | None:
    """The friction-circle radius of a journal bearing as a definition (Laus App. D)."""
    read = _bearing_entry(value, path, reader, BEARING)
    if read is None:
        return None
    entry, mu, radius = read
    contact = entry.get("contact", "catalogue")
    if contact not in CONTACT_LAWS:
        reader.problem(f"{path}.contact", f"expected one of {', '.join(CONTACT_LAWS)}, got {describe(contact)}")
        return None
    return Definition(
        _defined_symbol(f"zeta_{name}", "friction", reader),
        friction_circle_radius(mu, radius, contact),
        f"friction-circle radius of journal bearing {name} ({contact} contact)",
        "Laus App. D, Table 16",
        _units((mu, "1"), (radius, "length (one unit for all)")),
    )


def tooth_contact(
    entry: Mapping[str, Any], path: str, reader: EntryReader, name: str, gears: tuple[Gear, Gear]
) -> tuple[Definition, ...]:
    """Both ordinary efficiencies of an external spur mesh from its tooth geometry (Laus
    App. A): eq. (136) with the approach and recess lengths of eqs. (134)-(135)."""
    reader.check_keys(entry, path, TOOTH_CONTACT)
    if any(g.internal for g in gears):
        reader.problem(
            path,
            "the tooth-contact model (Laus App. A) covers external spur meshes; give the "
            "ordinary efficiency of this internal mesh as a symbol or a number",
        )
        return ()
    if "mu" not in entry or "pressure_angle" not in entry:
        return ()  # reported as missing required keys
    mu = reader.quantity(entry["mu"], f"{path}.mu", "friction")
    degrees = _pressure_angle(entry, path, reader)
    lengths = [
        reader.quantity(entry[k], f"{path}.{k}", "length") if k in entry else None
        for k in ("addendum", "approach", "recess")
    ]
    addendum, approach, recess = lengths
    if ("approach" in entry) != ("recess" in entry):
        reader.problem(path, "give both `approach` and `recess`, or neither (they are then computed from the addenda)")
        return ()
    if addendum is None and "addendum" not in entry:
        modules = {g.module for g in gears}
        if len(modules) != 1 or None in modules:
            if approach is None:
                reader.problem(
                    path,
                    "the addendum defaults to the gears' module, but these gears do not share "
                    "one: give `addendum` (or `approach` and `recess`)",
                )
                return ()
        else:
            addendum = modules.pop()
    if mu is None or degrees is None or (approach is None and addendum is None):
        return ()
    contact = _ToothContact(mu, degrees * sympy.pi / 180, addendum, approach, recess)
    return tuple(
        contact.efficiency(name, driver, driven, driver is gears[0], reader) for driver, driven in (gears, gears[::-1])
    )


def _pressure_angle(entry: Mapping[str, Any], path: str, reader: EntryReader) -> sympy.Expr | None:
    """The ``pressure_angle`` of a tooth-contact entry in degrees, refused outside (0, 45)."""
    degrees = reader.quantity(entry["pressure_angle"], f"{path}.pressure_angle", "angle")
    if degrees is not None and not (degrees.is_number and 0 < degrees < 45):
        reader.problem(
            f"{path}.pressure_angle",
            f"expected a number of degrees between 0 and 45, got {describe(entry['pressure_angle'])}",
        )
        return None
    return degrees


@dataclass(frozen=True)
class _ToothContact:
    """A mesh's tooth contact as read: the friction coefficient ``mu``, the pressure
    ``angle`` (radians), and the ``addendum`` or the ``approach`` and ``recess`` lengths
    (given for the first gear driving)."""

    mu: sympy.Expr
    angle: sympy.Expr
    addendum: sympy.Expr | None
    approach: sympy.Expr | None
    recess: sympy.Expr | None

    def efficiency(self, name: str, driver: Gear, driven: Gear, first: bool, reader: EntryReader) -> Definition:
        """The ordinary efficiency of mesh ``name`` with ``driver`` driving ``driven``
        (``first``: the driver is the mesh's first gear), Laus eq. (136)."""
        if self.approach is not None and self.recess is not None:
            # Lengths are given for the first gear driving; the other way round the pitch
            # point splits the path of contact the other way.
            lengths_of = (self.approach, self.recess) if first else (self.recess, self.approach)
        else:
            assert self.addendum is not None
            lengths_of = contact_lengths(driver.radius, driven.radius, self.addendum, self.angle)
        symbol = _defined_symbol(f"eta_{name}_{driver.name}_{driven.name}", "efficiency", reader)
        given = (self.addendum, self.approach, self.recess)
        return Definition(
            symbol,
            spur_mesh_efficiency(driver.radius, driven.radius, self.angle, self.mu, *lengths_of),
            f"ordinary efficiency of mesh {name}, gear {driver.name} driving gear {driven.name}, "
            "from the tooth geometry",
            "Laus App. A, eqs. (134)-(136)",
            _units((self.mu, "1"), *((x, "length (one unit for all)") for x in given if x is not None)),
        )


def _defined_symbol(name: str, role: str, reader: EntryReader) -> sympy.Symbol:
    """The train's symbol ``name`` (gear names may hold characters a symbol may not)."""
    return train_symbol(re.sub(r"\W", "_", name, flags=re.ASCII), role, reader.symbols)


def _units(*given: tuple[sympy.Expr, str]) -> tuple[tuple[str, str], ...]:
    """(symbol name, unit) of every symbol in the given parameters."""
    return tuple((str(s), unit) for value, unit in given for s in sorted(value.free_symbols, key=str))
