"""The mobility check of a train: its net degree of freedom F_N (the nullity of M_N,
Laus eq. (1)) against the input ports and the file's ``degrees_of_freedom``."""

from __future__ import annotations

from collections.abc import Sequence

import sympy

from davies_sym.errors import Problem
from davies_sym.geometry.layout import Layout
from davies_sym.network.matrices import Network
from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.model import Train


def mobility_problems(train: Train, network: Network, free: Sequence[int], input_index: int) -> list[Problem]:
    """What is wrong with the free motions ``free`` of Null(M_N) (indices into the
    network's motions; ``input_index`` is the input speed's), empty when nothing is."""
    dof = len(free)
    problems = []
    if dof == 0 and train.degrees_of_freedom is None:
        # One cause, one problem: the input cannot move because nothing can.
        port = train.ports.input
        return [
            Problem(
                "ports", f"the train has no degree of freedom (it is locked): the input coupling {port!r} cannot move"
            )
        ]
    if input_index not in free:
        hint = _ring_hint(train, network.layout)
        problems.append(
            Problem("ports.input", f"the input coupling {train.ports.input!r} cannot move: the train is locked{hint}")
        )
    if train.degrees_of_freedom is not None and dof != train.degrees_of_freedom:
        problems.append(
            Problem(
                "degrees_of_freedom",
                f"the train has {dof} degree(s) of freedom, the file says {train.degrees_of_freedom}",
            )
        )
    elif train.degrees_of_freedom is None and dof != len(train.ports.inputs):
        # Without a stated mobility, one degree of freedom per input port is expected.
        driven = {m.name for p in train.ports.inputs for m in network.coupling_motions(p)[:1]}
        extra = [network.motions[j].name for j in free if network.motions[j].name not in driven]
        inputs = len(train.ports.inputs)
        count = "one input port drives" if inputs == 1 else f"{inputs} input ports drive"
        text = f"the train has {dof} degrees of freedom but {count} it"
        if extra:
            text += f"; also free: {', '.join(extra)}"
        if dof == 0:
            text = "the train has no degree of freedom"
        problems.append(Problem("ports", text))
    return problems


def _ring_hint(train: Train, layout: Layout) -> str:
    """A locked train whose gear meshes two external gears on two other links about one
    axis: a ring gear written without ``internal: true`` (the planet then rolls between
    two equal external gears on one axis, which locks the set) is the usual cause.  Two
    partners on different axes (a planet between a sun and another planet) give no hint:
    such a train locks by its numbers, not by a missing ``internal``."""
    gears = {g.name: g for g in train.gears}
    partners: dict[str, list[str]] = {}
    for mesh in gear_meshes(train.couplings):
        if not all(name in gears for name in mesh.mesh_gears):
            continue
        a, b = (gears[name] for name in mesh.mesh_gears)
        if not (a.internal or b.internal) and a.link != b.link:
            partners.setdefault(a.name, []).append(b.name)
            partners.setdefault(b.name, []).append(a.name)
    for gear, others in partners.items():
        links = {gears[o].link for o in others}
        centres = {tuple(sympy.expand(x) for x in layout.gear_centres[o]) for o in others if o in layout.gear_centres}
        if len(others) >= 2 and len(links) >= 2 and len(centres) < len(others):
            shown = " and ".join(repr(o) for o in others[:2])
            return (
                f"; gear {gear!r} meshes {shown}, both external: if one is a ring gear (an annulus), "
                "write `internal: true` on it"
            )
    return ""
