"""Every coupling kind a topology file may name in ``type:``, by that name."""

from __future__ import annotations

from collections.abc import Mapping

from davies_sym.topology.couplings import Coupling, GearMesh, Prismatic, Revolute, ScrewCoupling
from davies_sym.topology.skew_mesh import CrossedHelicalMesh, WormMesh

KINDS: Mapping[str, type[Coupling]] = {
    k.kind: k for k in (Revolute, GearMesh, WormMesh, CrossedHelicalMesh, Prismatic, ScrewCoupling)
}
