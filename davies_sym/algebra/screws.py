"""Screws in Plücker coordinates (Laus section 2.2).

A motion screw (twist) is written in axis formation ``{r, s, t; u, v, w}``: angular
velocity, then velocity of the point of the body at the origin.  An action screw
(wrench) is written in ray formation ``{R, S, T; U, V, W}``: moment about the origin,
then force.  Power is their plain inner product (Laus eq. (5)).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy

Vector = tuple[sympy.Expr, sympy.Expr, sympy.Expr]
Screw = tuple[sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr]

#: Coordinate names of twists (axis formation) and wrenches (ray formation).
TWIST_COORDINATES = ("r", "s", "t", "u", "v", "w")
WRENCH_COORDINATES = ("R", "S", "T", "U", "V", "W")
AXES = ("x", "y", "z")

ORIGIN: Vector = (sympy.Integer(0), sympy.Integer(0), sympy.Integer(0))


def vector(values: Sequence[object]) -> Vector:
    """A 3-vector of sympy expressions."""
    x, y, z = (sympy.sympify(v) for v in values)
    return (x, y, z)


def cross(a: Vector, b: Vector) -> Vector:
    """Vector product a x b."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotation_twist(direction: Vector, point: Vector) -> Screw:
    """Unit twist of a rotation about the line through ``point`` along ``direction``.

    Axis formation: ``{p; q}`` with ``q = point x p``, the velocity of the body point
    at the origin (Laus Table 3: a rotation about z through y = r1 gives ``{1; r1}``).
    """
    q = cross(point, direction)
    return (*direction, *q)


def translation_twist(direction: Vector) -> Screw:
    """Unit twist of a pure translation (infinite pitch)."""
    return (*ORIGIN, *direction)


def force_wrench(direction: Vector, point: Vector) -> Screw:
    """Unit wrench of a force along ``direction`` through ``point``: ``{point x f; f}``."""
    return (*cross(point, direction), *direction)


def torque_wrench(direction: Vector) -> Screw:
    """Unit wrench of a pure torque (infinite pitch): ``{P; 0}``."""
    return (*direction, *ORIGIN)


def power(wrench: Sequence[sympy.Expr], twist: Sequence[sympy.Expr]) -> sympy.Expr:
    """Power of a wrench on a twist, the inner product ``rR + sS + tT + uU + vV + wW``
    (Laus eq. (5)); works on full or reduced coordinates alike."""
    if len(wrench) != len(twist):
        raise ValueError("wrench and twist must have the same number of coordinates")
    return sympy.Add(*(a * b for a, b in zip(wrench, twist, strict=True)))


def action_along_motion(twist: Screw) -> Screw:
    """The unit wrench that a port or a friction element applies along a motion.

    A rotation gets a pure torque about its direction (Laus eq. (9)); a translation a
    force along its direction through the origin.
    """
    angular = twist[:3]
    if any(c != 0 for c in angular):
        return torque_wrench(vector(angular))
    return (*ORIGIN, *twist[3:])


def axis_letter(direction: Vector) -> str | None:
    """'x', 'y' or 'z' if ``direction`` is the positive unit vector of that axis."""
    for index, name in enumerate(AXES):
        unit = [0, 0, 0]
        unit[index] = 1
        if all(d == u for d, u in zip(direction, unit, strict=True)):
            return name
    return None


def rotation_magnitude_name(direction: Vector) -> str:
    """Thesis naming of a rotation magnitude: ``r``, ``s`` or ``t`` about x, y, z, else ``p``."""
    letter = axis_letter(direction)
    return TWIST_COORDINATES[AXES.index(letter)] if letter else "p"


def translation_magnitude_name(direction: Vector) -> str:
    """``u``, ``v`` or ``w`` along x, y, z, else ``q``."""
    letter = axis_letter(direction)
    return TWIST_COORDINATES[3 + AXES.index(letter)] if letter else "q"


def torque_magnitude_name(direction: Vector) -> str:
    """``R``, ``S`` or ``T`` about x, y, z, else ``P``."""
    letter = axis_letter(direction)
    return WRENCH_COORDINATES[AXES.index(letter)] if letter else "P"


def force_magnitude_name(direction: Vector) -> str:
    """``U``, ``V`` or ``W`` along x, y, z, else ``F``."""
    letter = axis_letter(direction)
    return WRENCH_COORDINATES[3 + AXES.index(letter)] if letter else "F"


#: Unit vectors along the coordinate axes, by name.
UNIT: dict[str, Vector] = {name: vector([1 if i == k else 0 for i in range(3)]) for k, name in enumerate(AXES)}


@dataclass(frozen=True)
class NamedScrew:
    """A unit screw (6-D) and the base name of its magnitude, e.g. ``t`` or ``U``."""

    name: str
    screw: Screw
