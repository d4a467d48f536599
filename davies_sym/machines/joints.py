"""Unit motion and action screws of the couplings of a machine (Laus Tables 7-10).

Each kind allows some freedoms (unit twists, axis formation) and transmits the
constraint actions reciprocal to them (unit wrenches, ray formation), chosen along the
coupling's frame: its ``axis`` a, its ``normal`` n and b = a x n (for a universal joint
the two pin axes and their cross product, as Laus Table 10 with e1, e3, e5).  A coupling
with friction adds one friction action per freedom that slides or turns on a pin, its
magnitude fixed by a constitutive equation (`friction_laws`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import sympy

from davies_sym.algebra.screws import cross, force_wrench, rotation_twist, torque_wrench, translation_twist
from davies_sym.machines.machine_model import Coupling
from davies_sym.machines.vectors import AXES, Vector

#: Screws and vectors hold sympy expressions (closed forms) or floats (numeric solution).
Screw = tuple[Any, ...]
ZeroTest = Callable[[Any], bool]


def exactly_zero(value: Any) -> bool:
    return bool(sympy.expand(value) == 0)


def numerically_zero(value: Any) -> bool:
    return abs(float(value)) < 1e-12


#: Multipliers of the friction coefficient for a pin (Laus App. D): a force across the
#: pin presses a half cylinder (Table 16 with 2 beta = pi), one along it a flat face
#: (eqs. (145) and (146) with no inner radius).
#: ``clearance``: a pin with clearance touches its bore along one line, the
#: friction-circle model (multiplier 1).
PIN_MULTIPLIERS = {
    "worn": {"across": 4 / sympy.pi, "along": sympy.Integer(1)},
    "new": {"across": sympy.pi / 2, "along": sympy.Rational(2, 3)},
    "clearance": {"across": sympy.Integer(1), "along": sympy.Integer(1)},
}
_FLOAT_MULTIPLIERS = {law: {k: float(v) for k, v in m.items()} for law, m in PIN_MULTIPLIERS.items()}
_ROTATION_LETTERS = {"x": "r", "y": "s", "z": "t"}
_TRANSLATION_LETTERS = {"x": "u", "y": "v", "z": "w"}
_NEXT_AXIS = {"x": "y", "y": "z", "z": "x"}


def axis_name(direction: Vector) -> str | None:
    """``x``, ``y`` or ``z`` when ``direction`` is that coordinate axis."""
    return next((name for name, axis in AXES.items() if tuple(direction) == axis), None)


@dataclass(frozen=True)
class FrictionAction:
    """A friction action opposing one freedom: its magnitude is
    ``-coefficient * sign(freedom) * N`` with ``N`` formed from the ``load`` actions,
    each weighted (a sum of magnitudes, or their resultant)."""

    name: str
    coupling: str
    screw: Screw
    freedom: str
    coefficient: sympy.Expr
    load: tuple[tuple[str, sympy.Expr], ...]
    resultant: bool
    #: A slider of some height: the friction acts on the face its one load presses, half
    #: the height off the axis (Laus sec. 4.1.1, Fig. 14); the wrench is ``screw +
    #: sign(load) * shift``.
    shift: Screw | None = None


@dataclass(frozen=True)
class JointScrews:
    """The unit screws of one coupling."""

    coupling: str
    freedoms: tuple[tuple[str, Screw], ...]
    constraints: tuple[tuple[str, Screw], ...]
    friction: tuple[FrictionAction, ...]


class _Names:
    """Laus's naming: coordinate letters for coordinate axes (t_A, U_B), p/q and P/Q
    numbered within the coupling otherwise (p_A1, Q_A2)."""

    def __init__(self, coupling: str):
        self.coupling = coupling
        self.counts: dict[str, int] = {}

    def plan(self, letters: list[str]) -> list[str]:
        totals = {letter: letters.count(letter) for letter in letters}
        out = []
        for letter in letters:
            self.counts[letter] = self.counts.get(letter, 0) + 1
            number = str(self.counts[letter]) if totals[letter] > 1 else ""
            out.append(f"{letter}_{self.coupling}{number}")
        return out


def _letter(direction: Vector, coordinate: dict[str, str], general: str, coordinate_names: bool) -> str:
    name = axis_name(direction) if coordinate_names else None
    return coordinate[name] if name is not None else general


def frame(coupling: Coupling) -> tuple[Vector, Vector, Vector]:
    """The coupling's axis a, normal n and b = a x n (a coordinate axis gets the next
    coordinate axis as its default normal)."""
    a = coupling.axis if coupling.axis is not None else AXES["z"]
    n = coupling.normal
    if n is None:
        n = AXES[_NEXT_AXIS[axis_name(a) or "z"]]
    return a, n, cross(a, n)


Directions = list[tuple[str, Vector]]


@dataclass(frozen=True)
class JointKind:
    """A joint kind (Laus Tables 7-10): its freedoms (``R`` a rotation, ``T`` a
    translation) and held actions (``F`` a force, ``M`` a moment) in the coupling's frame
    ``a, n, b``; ``journal``: a pin radius gives it journal-bearing friction; ``virtual``:
    the free coupling of Laus sec. 4.3.1, which moves along the coordinate axes."""

    screws: Callable[[Vector, Vector, Vector], tuple[Directions, Directions]]
    journal: bool = False
    virtual: bool = False


_X, _Y, _Z = AXES["x"], AXES["y"], AXES["z"]

#: Every joint kind a machine file may name, by that name, with the freedoms it allows
#: (Laus sec. 4.1.1 and 4.3.2).
JOINT_KINDS: Mapping[str, JointKind] = {
    "revolute": JointKind(
        lambda a, n, b: ([("R", a)], [("F", a), ("F", n), ("F", b), ("M", n), ("M", b)]), journal=True
    ),
    "prismatic": JointKind(lambda a, n, b: ([("T", a)], [("F", n), ("F", b), ("M", a), ("M", n), ("M", b)])),
    "cylindrical": JointKind(
        lambda a, n, b: ([("T", a), ("R", a)], [("F", n), ("F", b), ("M", n), ("M", b)]), journal=True
    ),
    "universal": JointKind(
        lambda a, n, b: ([("R", a), ("R", n)], [("M", b), ("F", a), ("F", n), ("F", b)]), journal=True
    ),
    "spherical": JointKind(lambda a, n, b: ([("R", _X), ("R", _Y), ("R", _Z)], [("F", _X), ("F", _Y), ("F", _Z)])),
    "square_annulus": JointKind(lambda a, n, b: ([("T", a), ("R", n), ("R", b)], [("M", a), ("F", n), ("F", b)])),
    "round_annulus": JointKind(lambda a, n, b: ([("T", a), ("R", a), ("R", n), ("R", b)], [("F", n), ("F", b)])),
    "free": JointKind(
        lambda a, n, b: ([("R", _X), ("R", _Y), ("R", _Z), ("T", _X), ("T", _Y), ("T", _Z)], []), virtual=True
    ),
}


def joint_screws(coupling: Coupling, coordinate_names: bool = True, zero: ZeroTest = exactly_zero) -> JointScrews:
    """Freedoms, constraint actions and friction actions of ``coupling`` (Laus Tables 7-10).

    ``coordinate_names``: a planar machine names magnitudes by coordinate (``t_A``,
    ``U_B``, Laus Tables 7 and 8); a spatial one p, q, P, Q numbered per coupling
    (``p_A1``, ``Q_A2``, Table 10).  ``zero`` tests a coordinate for zero (exact for
    closed forms, to rounding for the numeric solution)."""
    p = coupling.at
    kind = JOINT_KINDS[coupling.kind]
    free, held = kind.screws(*frame(coupling))
    # A free (virtual) coupling moves along the coordinate axes: Laus's r_M ... w_M.
    coordinate_names = coordinate_names or kind.virtual
    names = _Names(coupling.name)
    motion_names = names.plan(
        [
            _letter(d, _ROTATION_LETTERS, "p", coordinate_names)
            if k == "R"
            else _letter(d, _TRANSLATION_LETTERS, "q", coordinate_names)
            for k, d in free
        ]
    )
    freedoms = tuple(
        (name, rotation_twist(d, p) if k == "R" else translation_twist(d))
        for name, (k, d) in zip(motion_names, free, strict=True)
    )
    action_names = _Names(coupling.name).plan(
        [
            _letter(d, {c: _ROTATION_LETTERS[c].upper() for c in "xyz"}, "P", coordinate_names)
            if k == "M"
            else _letter(d, {c: _TRANSLATION_LETTERS[c].upper() for c in "xyz"}, "Q", coordinate_names)
            for k, d in held
        ]
    )
    constraints = tuple(
        (name, torque_wrench(d) if k == "M" else force_wrench(d, p))
        for name, (k, d) in zip(action_names, held, strict=True)
    )
    forces = [(name, d) for name, (k, d) in zip(action_names, held, strict=True) if k == "F"]
    return JointScrews(coupling.name, freedoms, constraints, _friction(coupling, free, freedoms, forces, zero))


def _friction(
    coupling: Coupling,
    free: list[tuple[str, Vector]],
    freedoms: tuple[tuple[str, Screw], ...],
    forces: list[tuple[str, Vector]],
    zero: ZeroTest,
) -> tuple[FrictionAction, ...]:
    law = coupling.friction
    if law is None:
        return ()
    out = []
    sliding = [(name, d) for (k, d), (name, _) in zip(free, freedoms, strict=True) if k == "T"]
    turning = [(name, d) for (k, d), (name, _) in zip(free, freedoms, strict=True) if k == "R"]
    resultant = law.load == "resultant"
    for freedom, d in sliding:
        load: tuple[tuple[str, Any], ...] = tuple((name, 1) for name, fd in forces if not _parallel(fd, d, zero))
        base = force_wrench(d, coupling.at)
        if law.height is None:
            out.append(FrictionAction(friction_name(freedom), coupling.name, base, freedom, law.mu, load, resultant))
            continue
        # One friction force per pressed face: the normal force along n_k presses the face
        # at sign(Q_k) h/2 along n_k, where the friction force acts (Laus Fig. 14).
        normals = {name: fd for name, fd in forces}
        for i, (name, weight) in enumerate(load, start=1):
            half = law.height / 2
            moment = cross(normals[name], d)
            shift = (half * moment[0], half * moment[1], half * moment[2], 0, 0, 0)
            label = friction_name(freedom) + (str(i) if len(load) > 1 else "")
            out.append(FrictionAction(label, coupling.name, base, freedom, law.mu, ((name, weight),), resultant, shift))
    if law.pin_radius is not None and JOINT_KINDS[coupling.kind].journal:
        exact = zero is exactly_zero
        multipliers = (PIN_MULTIPLIERS if exact else _FLOAT_MULTIPLIERS)[law.surfaces]
        for freedom, d in turning:
            load = tuple(
                (name, multipliers["along"] if _parallel(fd, d, zero) else multipliers["across"]) for name, fd in forces
            )
            out.append(
                FrictionAction(
                    friction_name(freedom),
                    coupling.name,
                    torque_wrench(d),
                    freedom,
                    law.mu * law.pin_radius,
                    load,
                    resultant,
                )
            )
    return tuple(out)


def friction_name(freedom: str) -> str:
    """``t_A`` -> ``T_AF``, ``p_A1`` -> ``P_AF1`` (Laus Table 10)."""
    letter, _, rest = freedom.partition("_")
    digits = rest[len(rest.rstrip("0123456789")) :]
    return f"{letter.upper()}_{rest[: len(rest) - len(digits)]}F{digits}"


def _parallel(u: Vector, v: Vector, zero: ZeroTest) -> bool:
    return all(zero(c) for c in cross(u, v))
