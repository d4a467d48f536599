"""Singular positions passed between two time steps of a task.

A singular position where a path merely passes (between two samples) leaves no trace in
either sample's solution, yet the machine on the far side is not the machine on the
near side: a limb through a dead-centre position, or the two contacts of a split slider
(Laus sec. 4.1.1 and 4.3.2) sliding past each other, so that the slider has come
apart.  Each is told by a sign that changes only through such a position: the
determinant of the motion and of the frictionless action system (a rank drop of one),
and the separation of a split slider's two contacts along its axis (a rank drop of two,
which leaves the determinant's sign alone).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from davies_sym.machines.linear import orientation
from davies_sym.machines.machine_model import Coupling
from davies_sym.machines.network import Network

#: Couplings that are one contact of a slider split in two (Laus sec. 4.3.2).
SLIDER_CONTACTS = ("square_annulus", "round_annulus")


def split_sliders(couplings: Sequence[Coupling]) -> list[tuple[Coupling, Coupling]]:
    """Pairs of slider contacts between the same two links."""
    contacts = [c for c in couplings if c.kind in SLIDER_CONTACTS]
    return [(a, b) for i, a in enumerate(contacts) for b in contacts[i + 1 :] if set(a.links) == set(b.links)]


def signs(
    network: Network,
    couplings: Sequence[Coupling],
    action_system: np.ndarray,
    known_motions: Mapping[str, float],
    known_actions: Mapping[str, float],
) -> dict[str, float]:
    """The signs that change only through a singular position, each keyed by what its
    change means."""
    determinant = "the determinant of the {} equations changes sign"
    out = {
        determinant.format("motion"): orientation(network.motion_matrix, network.motions, known_motions),
        determinant.format("action"): orientation(action_system, network.actions, known_actions),
    }
    for a, b in split_sliders(couplings):
        axis = np.asarray(a.axis if a.axis is not None else (0.0, 0.0, 1.0), dtype=float)
        gap = float(np.dot(np.asarray(b.at, dtype=float) - np.asarray(a.at, dtype=float), axis))
        out[f"the contacts {a.name} and {b.name} of one slider pass each other (the slider comes apart)"] = float(
            np.sign(gap)
        )
    return out


def passed(before: Mapping[str, float], after: Mapping[str, float]) -> list[str]:
    """What changed sign between two neighbouring positions."""
    return [what for what, sign in after.items() if sign * before.get(what, 0.0) < 0]
