"""Every coupling kind a topology file may name in ``type:``, by that name, and the
queries the later stages ask of a train's couplings by kind.

The kind classes (`davies_sym.topology.couplings`, `davies_sym.topology.skew_mesh`) and
this registry are the only modules that test a coupling's class: the stages ask for the
meshes, bearings or sliders of a train here, and everything else of a kind through its
own members (`Coupling.written_quantities`, `Coupling.noun`, ...).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from davies_sym.topology.chain_drive import BeltDrive, ChainDrive
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.gear_mesh import GearMesh
from davies_sym.topology.prismatic import Prismatic
from davies_sym.topology.rack_mesh import RackMesh
from davies_sym.topology.revolute import Revolute
from davies_sym.topology.screw_coupling import ScrewCoupling
from davies_sym.topology.skew_mesh import CrossedHelicalMesh, SkewMesh, WormMesh
from davies_sym.topology.toothed_mesh import ToothedMesh

KINDS: Mapping[str, type[Coupling]] = {
    k.kind: k
    for k in (
        Revolute,
        GearMesh,
        WormMesh,
        CrossedHelicalMesh,
        Prismatic,
        ScrewCoupling,
        RackMesh,
        ChainDrive,
        BeltDrive,
    )
}


def gear_meshes(couplings: Iterable[Coupling]) -> list[GearMesh]:
    """The meshes of gears on parallel or intersecting axes (spur, helical, bevel), in order."""
    return [c for c in couplings if isinstance(c, GearMesh)]


def as_gear_mesh(coupling: Coupling) -> GearMesh | None:
    """``coupling`` if it is a mesh of gears on parallel or intersecting axes, else None."""
    return coupling if isinstance(coupling, GearMesh) else None


def toothed_meshes(couplings: Iterable[Coupling]) -> list[ToothedMesh]:
    """The meshes whose losses are ordinary efficiencies (gear pairs, a rack and its
    pinion), in order: what the efficiency stage's power flow reads."""
    return [c for c in couplings if isinstance(c, ToothedMesh)]


def as_toothed_mesh(coupling: Coupling) -> ToothedMesh | None:
    """``coupling`` if its losses are an ordinary efficiency, else None."""
    return coupling if isinstance(coupling, ToothedMesh) else None


def skew_meshes(couplings: Iterable[Coupling]) -> list[SkewMesh]:
    """The meshes of gears on skew axes (worm and wheel, crossed helical), in order."""
    return [c for c in couplings if isinstance(c, SkewMesh)]


def as_skew_mesh(coupling: Coupling) -> SkewMesh | None:
    return coupling if isinstance(coupling, SkewMesh) else None


def bearings(couplings: Iterable[Coupling]) -> list[Revolute]:
    """The revolute pairs, in order."""
    return [c for c in couplings if isinstance(c, Revolute)]


def as_bearing(coupling: Coupling) -> Revolute | None:
    return coupling if isinstance(coupling, Revolute) else None


def sliders(couplings: Iterable[Coupling]) -> list[Prismatic]:
    """The prismatic pairs, in order."""
    return [c for c in couplings if isinstance(c, Prismatic)]


@dataclass(frozen=True)
class CouplingsByKind:
    """A train's couplings split by kind once, each group in the train's order: what a
    stage that asks several of the queries above reads instead of asking each."""

    toothed: tuple[ToothedMesh, ...]
    gear: tuple[GearMesh, ...]
    skew: tuple[SkewMesh, ...]
    bearings: tuple[Revolute, ...]


def by_kind(couplings: Iterable[Coupling]) -> CouplingsByKind:
    """``couplings`` split by kind: toothed meshes, gear meshes, skew meshes, bearings."""
    couplings = tuple(couplings)
    return CouplingsByKind(
        toothed=tuple(toothed_meshes(couplings)),
        gear=tuple(gear_meshes(couplings)),
        skew=tuple(skew_meshes(couplings)),
        bearings=tuple(bearings(couplings)),
    )


def as_written_screws(coupling: Coupling) -> ScrewCoupling | None:
    """``coupling`` if it is written as its screws (the low-level kind), else None."""
    return coupling if isinstance(coupling, ScrewCoupling) else None
