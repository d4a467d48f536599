"""One helix per gear: the meshes of a helical gear agree on its helix angle and hand.

Helical gears on parallel axes mesh with equal helix angles, of opposite hands on an
external mesh and of the same hand on an internal one.  A mesh entry gives the angle and
the hand of its first gear, so a gear in two meshes (a planet, an idler) is described
twice: both must name the same helix, and a helical gear cannot mesh a spur gear.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.entries import EntryReader

#: A gear's helix as one mesh describes it: (angle or None for spur teeth, hand, mesh).
_Helix = tuple[sympy.Expr | None, int, str]


def check_helices(couplings: Mapping[str, Coupling], reader: EntryReader) -> None:
    """Record a problem for each mesh that gives one of its gears another helix than an
    earlier mesh of that gear."""
    seen: dict[str, _Helix] = {}
    for mesh in gear_meshes(couplings.values()):
        angle = None if mesh.helix is None else mesh.helix.angle
        second_hand = mesh.hand if mesh.internal else -mesh.hand
        for gear, hand in zip(mesh.gears, (mesh.hand, second_hand), strict=True):
            earlier = seen.setdefault(gear, (angle, hand, mesh.name))
            if earlier[2] != mesh.name:
                _compare(gear, earlier, (angle, hand, mesh.name), reader)


def _compare(gear: str, earlier: _Helix, here: _Helix, reader: EntryReader) -> None:
    (angle0, hand0, mesh0), (angle, hand, mesh) = earlier, here
    path = f"couplings.{mesh}"
    if (angle0 is None) != (angle is None):
        helical, spur = (mesh0, mesh) if angle is None else (mesh, mesh0)
        reader.problem(
            f"{path}.helix_angle" if angle is not None else path,
            f"gear {gear!r} is helical in mesh {helical} but spur in mesh {spur}: give both meshes "
            "the same `helix_angle`, or neither",
        )
    elif angle is not None and sympy.expand(angle - angle0) != 0:
        reader.problem(
            f"{path}.helix_angle",
            f"gear {gear!r} has the helix angle {sympy.sstr(angle0)} in mesh {mesh0}: a gear has one helix; "
            "give this mesh the same `helix_angle`",
        )
    elif angle is not None and hand != hand0:
        words = {1: "right", -1: "left"}
        reader.problem(
            f"{path}.hand",
            f"gear {gear!r} is {words[hand0]}-handed in mesh {mesh0} but {words[hand]}-handed here (the hand "
            "names the first gear's; the second gear of an external mesh has the other): a gear has one helix",
        )
