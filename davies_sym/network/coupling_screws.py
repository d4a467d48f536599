"""The screws each coupling kind contributes to the network, for a given layout.

One writer per coupling kind (Laus Tables 3-4, 12-13, 14-15): a revolute is a
rotation about its axis, a mesh a rotation about the pitch line with the tooth force
along the common tangent (pressure angle zero, Laus section 3.3.1), a skew mesh a point
contact with its normal force and its sliding friction, a prismatic pair a
translation, and the low-level kind its screws as written.  Adding
a coupling kind means one writer here, registered in ``WRITERS``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.algebra.radicals import has_square_root
from davies_sym.algebra.screws import (
    AXES,
    UNIT,
    NamedScrew,
    Vector,
    axis_letter,
    cross,
    force_magnitude_name,
    force_wrench,
    rotation_magnitude_name,
    rotation_twist,
    torque_magnitude_name,
    torque_wrench,
    translation_magnitude_name,
    translation_twist,
    vector,
)
from davies_sym.errors import DerivationError
from davies_sym.geometry.layout import Layout
from davies_sym.topology.couplings import Coupling, GearMesh, Prismatic, Revolute, ScrewCoupling
from davies_sym.topology.skew_mesh import CrossedHelicalMesh, SkewMesh, WormMesh


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


def _point_constraints(
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


def _revolute(c: Revolute, layout: Layout) -> CouplingScrews:
    """A bearing: one rotation about its axis; forces and torques elsewhere."""
    point, axis = layout.coupling_points[c.name], layout.coupling_axes.get(c.name, layout.axis)
    motion = NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point))
    return CouplingScrews((motion,), (), _point_constraints(point, axis=axis))


def _mesh(c: GearMesh, layout: Layout) -> CouplingScrews:
    """A mesh: rotation about the pitch line, tooth force along the common tangent first;
    the separating motion along the centre line is a secondary freedom (kept in planar
    systems of order 3).  Where the gears carry thrust or the layout is spatial the teeth
    touch at the pitch point only: the translation along the axis and the tilts about the
    tangent and the centre line are freedoms too, so the bearings alone hold the gears
    out of their plane.  Helical teeth (`_helical`) slide along the tooth line instead of
    the axis."""
    point, axis = layout.coupling_points[c.name], layout.coupling_axes.get(c.name, layout.axis)
    tangent, normal = layout.mesh_tangents[c.name], layout.mesh_normals[c.name]
    motion = NamedScrew(rotation_magnitude_name(axis), rotation_twist(axis, point))
    if c.helix is not None:
        return _helical(c, layout, motion)
    separating = [NamedScrew(translation_magnitude_name(normal), translation_twist(normal))]
    if layout.spatial or layout.thrust:
        separating += [
            NamedScrew(translation_magnitude_name(axis), translation_twist(axis)),
            NamedScrew(rotation_magnitude_name(tangent), rotation_twist(tangent, point)),
            NamedScrew(rotation_magnitude_name(normal), rotation_twist(normal, point)),
        ]
    return CouplingScrews((motion,), tuple(separating), _point_constraints(point, (tangent,)))


def _helical(c: GearMesh, layout: Layout, motion: NamedScrew) -> CouplingScrews:
    """A helical mesh on parallel axes, pressure angle zero as for spur gears.

    On the first gear's pitch cylinder the tooth line of a right-hand helix runs along
    ``sin(beta) e_theta + cos(beta) e_z`` (``e_theta`` the direction of the gear's
    rotation about its axis at the pitch point); the tooth force is normal to it in the
    pitch plane, ``cos(beta) e_theta - sin(beta) e_z``.  Its magnitude is counted by the
    tangential part, so the wrench is the tangential unit force plus ``tan(beta)`` of it
    along the axis: the mesh law and its efficiency keep their meaning, and the thrust
    reaches the bearings.  Sliding along the tooth line and tilting about the tangent
    are freedoms the screw system must hold, or the thrust would have nowhere to go."""
    assert c.helix is not None
    point, axis = layout.coupling_points[c.name], layout.coupling_axes.get(c.name, layout.axis)
    tangent, normal = layout.mesh_tangents[c.name], layout.mesh_normals[c.name]
    centre = layout.gear_centres[c.gears[0]]
    # +1 when the tangent is the first gear's e_theta at the pitch point, -1 when opposite.
    along = sympy.cancel(
        sum(
            a * b
            for a, b in zip(
                tangent, cross(axis, vector([p - q for p, q in zip(point, centre, strict=True)])), strict=True
            )
        )
    )
    orientation = sympy.sign(along)
    if orientation not in (1, -1):
        raise DerivationError(f"mesh {c.name}: the sense of its first gear's rotation at the pitch point is unknown")
    lean = -int(orientation) * c.hand  # the axial part of e_theta-normal, per unit along the tangent
    cos, sin = c.helix.cos, c.helix.sin
    force = vector([t + lean * sin / cos * a for t, a in zip(tangent, axis, strict=True)])
    tooth_line = vector([-lean * sin * t + cos * a for t, a in zip(tangent, axis, strict=True)])
    sliding = NamedScrew("q", translation_twist(tooth_line))
    tilt = NamedScrew(rotation_magnitude_name(tangent), rotation_twist(tangent, point))
    secondary = (
        NamedScrew(translation_magnitude_name(normal), translation_twist(normal)),
        sliding,
        tilt,
        NamedScrew(rotation_magnitude_name(normal), rotation_twist(normal, point)),
    )
    pressing = NamedScrew(force_magnitude_name(tangent), force_wrench(force, point))
    return CouplingScrews((motion,), secondary, (pressing, *_point_constraints(point)), spans=(sliding, tilt))


def _skew_mesh(c: SkewMesh, layout: Layout) -> CouplingScrews:
    """A skew mesh: a point contact at the pitch point.  The sliding along the tooth line
    is the first motion (the one its friction opposes); the sliding across it and the
    rotations about lines through the pitch point are the other four freedoms; the normal
    force is the action, and the friction force acts along the tooth line at the pitch
    point."""
    point, tooth_line, normal = (
        layout.coupling_points[c.name],
        layout.mesh_tangents[c.name],
        layout.mesh_normals[c.name],
    )
    sliding = NamedScrew("q", translation_twist(tooth_line))
    across = NamedScrew("q", translation_twist(cross(normal, tooth_line)))
    tilts = tuple(NamedScrew(rotation_magnitude_name(UNIT[a]), rotation_twist(UNIT[a], point)) for a in AXES)
    friction = NamedScrew("F", force_wrench(tooth_line, point))
    pressing = NamedScrew("N", force_wrench(normal, point))
    return CouplingScrews((sliding,), (across, *tilts), (pressing, *_point_constraints(point)), friction)


def _prismatic(c: Prismatic, layout: Layout) -> CouplingScrews:
    """A slider: one translation along its direction."""
    motion = NamedScrew(translation_magnitude_name(c.direction), translation_twist(c.direction))
    return CouplingScrews((motion,), (), _point_constraints(vector((0, 0, 0))))


def _written(c: ScrewCoupling, layout: Layout) -> CouplingScrews:
    """The low-level kind: the screws as written (Laus App. B, C)."""
    return CouplingScrews(c.motion_screws, (), c.action_screws)


WRITERS: Mapping[type[Coupling], Callable[..., CouplingScrews]] = {
    Revolute: _revolute,
    GearMesh: _mesh,
    WormMesh: _skew_mesh,
    CrossedHelicalMesh: _skew_mesh,
    Prismatic: _prismatic,
    ScrewCoupling: _written,
}


def written_square_root(screws: CouplingScrews) -> bool:
    """Whether a square root is written in the screws (a low-level coupling's), which
    the layout's radical table must absorb."""
    return any(
        has_square_root(x) for group in (screws.motions, screws.constraints) for named in group for x in named.screw
    )


def coupling_screws(coupling: Coupling, layout: Layout) -> CouplingScrews:
    """The unit twists and candidate unit wrenches of ``coupling`` in ``layout``."""
    return WRITERS[type(coupling)](coupling, layout)
