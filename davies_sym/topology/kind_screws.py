"""What a coupling kind reads of the layout to write its screws, and what it writes.

`Placement` is the part of the geometry stage's `Layout` a kind reads (a structural
type: the layout satisfies it without this stage importing the geometry); `CouplingScrews`
is what each kind's ``screws`` method returns to the network (Laus Tables 3-4, 12-13).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

import sympy

from davies_sym.algebra.screws import (
    AXES,
    UNIT,
    NamedScrew,
    Vector,
    axis_letter,
    cross,
    force_magnitude_name,
    force_wrench,
    torque_magnitude_name,
    torque_wrench,
)


class Placement(Protocol):
    """Where the layout puts the couplings: points, axes, mesh tangents and normals."""

    @property
    def gear_centres(self) -> Mapping[str, Vector]: ...

    @property
    def coupling_points(self) -> Mapping[str, Vector]: ...

    @property
    def mesh_tangents(self) -> Mapping[str, Vector]: ...

    @property
    def mesh_normals(self) -> Mapping[str, Vector]: ...

    @property
    def axis(self) -> Vector: ...

    @property
    def coupling_axes(self) -> Mapping[str, Vector]: ...

    @property
    def gear_axes(self) -> Mapping[str, Vector]: ...

    @property
    def spatial(self) -> bool: ...

    @property
    def thrust(self) -> bool: ...

    @property
    def frame(self) -> tuple[sympy.Expr, sympy.Expr]:
        """The unit placement direction (x, y) of a 2-D drawing: a chain's strand runs along it."""
        ...


@dataclass(frozen=True)
class CouplingScrews:
    """What a coupling contributes to the network, in full 6-D coordinates.

    ``motions`` span its freedoms; ``secondary`` are freedoms kept only when the screw
    system of the whole network holds them (e.g. the separating motion of a mesh in a
    planar train drawn on one line); ``constraints`` are candidate unit wrenches in the
    order of preference, from which the screw-system reduction picks an independent set
    reciprocal to the kept freedoms.
    """

    motions: tuple[NamedScrew, ...]
    secondary: tuple[NamedScrew, ...]
    constraints: tuple[NamedScrew, ...]
    #: The unit wrench of the coupling's friction where it is not the action along its
    #: first motion (the sliding force of a skew mesh acts at the pitch point).
    friction: NamedScrew | None = None
    #: Secondary freedoms the screw system must hold, whatever the other couplings do
    #: (a helical mesh's sliding along its teeth: the thrust needs it).
    spans: tuple[NamedScrew, ...] = ()


def point_constraints(
    point: Vector, forces_first: tuple[Vector, ...] = (), axis: Vector | None = None
) -> tuple[NamedScrew, ...]:
    """Candidate constraint wrenches at ``point``: given forces, then forces along the
    axes, then torques about the axes, then torques normal to a bearing's ``axis``
    (a tilted planet bearing carries the torque P_G of Laus eq. (81))."""
    out = [NamedScrew(force_magnitude_name(d), force_wrench(d, point)) for d in forces_first]
    out += [NamedScrew(force_magnitude_name(UNIT[a]), force_wrench(UNIT[a], point)) for a in AXES]
    out += [NamedScrew(torque_magnitude_name(UNIT[a]), torque_wrench(UNIT[a])) for a in AXES]
    if axis is not None and axis_letter(axis) is None:
        for a in AXES:
            normal = cross(axis, UNIT[a])
            if any(sympy.expand(x) != 0 for x in normal):
                out.append(NamedScrew(torque_magnitude_name(normal), torque_wrench(normal)))
    return tuple(out)
