"""Guides pressed by a mesh's separating force: a rack's guide carries the tooth force's
component along the line of centres, tan(alpha) times the tangential force U, so its
Coulomb law reads F = -mu tan(alpha) |U| sign(v) (Laus Table 2, eq. (10), loaded by the
mesh's transmitted action instead of the guide's own reaction)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from davies_sym.errors import Problem, TopologyError
from davies_sym.network.friction_laws import FrictionLaw
from davies_sym.topology.model import Train


def pressed_laws(train: Train, laws: Sequence[FrictionLaw]) -> tuple[FrictionLaw, ...]:
    """``laws`` with each pressed guide's Coulomb law loaded by its mesh's tooth force."""
    tooth_force = {law.coupling: law for law in laws if law.load_dependent and train.coupling(law.coupling).meshing}
    names = {c.name for c in train.couplings}
    out = []
    problems = []
    for law in laws:
        guide = train.coupling(law.coupling)
        pressing = guide.friction.pressed_by
        if pressing is None or not law.load_dependent:
            out.append(law)
            continue
        entry = f"couplings.{law.coupling}.friction.pressed_by"
        mesh = train.coupling(pressing) if pressing in names else None
        if mesh is None or mesh.separating is None or pressing not in tooth_force:
            why = (
                f"no coupling {pressing!r} in this train"
                if pressing not in names
                else f"{pressing} is no mesh with a `pressure_angle` (and a friction law), so it presses no guide"
            )
            problems.append(Problem(entry, f"{why}: name the mesh of the rack this guide holds"))
            continue
        if not set(mesh.links) & set(guide.links):
            problems.append(Problem(entry, f"mesh {pressing} moves neither link of this guide, so it cannot press it"))
            continue
        coefficient = law.coefficient * mesh.separating
        out.append(replace(law, coefficient=coefficient, transmitted=tooth_force[pressing].transmitted))
    if problems:
        raise TopologyError(problems, train.file_lines)
    return tuple(out)
