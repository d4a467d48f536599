"""Text, JSON and ``--eval`` answers of a train driven on several shafts: the speeds in
the input speeds, the speed conditions, and per power-flow region the driving gear of
each mesh, the ports that put power in and take it out, every port torque in the load
torque and the efficiency (Mantriota and Pennestri 2003, eq. (6))."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy

from davies_sym.efficiency.power_flow_regions import OperatingPoint
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, Region, SeveralInputs, speed_symbol
from davies_sym.emit.force_conditions import force_conditions, force_text
from davies_sym.topology.coupling_kinds import as_toothed_mesh
from davies_sym.topology.symbol_display import latex as display_latex


def condition_text(si: SeveralInputs, region: Region) -> list[str]:
    """The region's speed conditions, e.g. ``omega_A - omega_K > 0``."""
    return [f"{sympy.sstr(c.form)} {'>' if region.signs[c.name] > 0 else '<'} 0" for c in si.conditions]


def region_forces(region: Region) -> list[tuple[str, sympy.Expr, int]]:
    """Where the region holds beyond its speed conditions: each loaded force (tooth force,
    bearing reaction) with the sign the region gives it."""
    return force_conditions(region.loaded_forces, region.first_drives, region.reversed)


def region_force_text(region: Region) -> list[str]:
    """`region_forces` as text, e.g. ``tooth force of M1: ... > 0``."""
    return force_text(region_forces(region))


def drivers(si: SeveralInputs, region: Region, words: bool = False) -> list[tuple[str, str, str]]:
    """(mesh, driving member, driven member) of every mesh in the region: their names, or
    with ``words`` as the reports name them (``gear 1``)."""
    out = []
    for name, first in region.first_drives.items():
        mesh = as_toothed_mesh(si.train.coupling(name))
        assert mesh is not None  # the regions decide the meshes with ordinary efficiencies
        members = mesh.sides if words else mesh.members
        driver, driven = members if first else members[::-1]
        out.append((name, driver, driven))
    return out


def mesh_text(si: SeveralInputs, region: Region) -> list[str]:
    """Which gear drives in each mesh, e.g. ``M1: gear 1 drives gear 2``."""
    return [f"{mesh}: {driver} drives {driven}" for mesh, driver, driven in drivers(si, region, words=True)]


def several_inputs_document(si: SeveralInputs) -> dict[str, Any]:
    """The JSON document: kinematics, conditions and regions with their closed forms."""
    train = si.train
    return {
        "status": "ok",
        "name": train.name,
        "source": train.source,
        "file": train.path,
        "inputs": list(train.ports.inputs),
        "output": train.ports.output,
        "input_speeds": [str(s) for s in si.speeds],
        "load_torque": str(LOAD_TORQUE),
        "port_speeds": {p: sympy.sstr(v.to_expr()) for p, v in si.port_speeds.items()},
        "load_dependent": any(r.reversed for r in si.regions),
        "speed_conditions": [
            {"name": c.name, "expression": sympy.sstr(c.form), "decides": list(c.decides)} for c in si.conditions
        ],
        "regions": [
            {
                "number": r.number,
                "conditions": condition_text(si, r),
                "meshes": mesh_text(si, r),
                "power_in": list(r.inputs),
                "power_out": list(r.outputs),
                "reversed": sorted(r.reversed),
                "forces": region_force_text(r),
                "torques": {p: sympy.sstr(t.to_expr()) for p, t in r.torques.items()},
                "efficiency": sympy.sstr(r.efficiency),
                "latex": display_latex(r.efficiency),
            }
            for r in si.regions
        ],
    }


def several_inputs_text(document: Mapping[str, Any]) -> str:
    """Plain text of `several_inputs_document`."""
    lines = [
        document["name"],
        f"  inputs {', '.join(document['inputs'])} (speeds {', '.join(document['input_speeds'])}), output "
        f"{document['output']} (load torque {document['load_torque']}, resisting its motion)",
    ]
    lines += [
        f"  speed of {p}: {speed_symbol(p)} = {v}"
        for p, v in document["port_speeds"].items()
        if str(speed_symbol(p)) not in document["input_speeds"]
    ]
    for c in document["speed_conditions"]:
        lines.append(f"  speed condition {c['name']}: sign of {c['expression']} ({'; '.join(c['decides'])})")
    for r in document["regions"]:
        reversed_text = f"; the losses reverse the force in {', '.join(r['reversed'])}" if r["reversed"] else ""
        lines.append(
            f"  ({r['number']}) where {' and '.join(r['conditions'])}{reversed_text}: without losses power "
            f"in at {', '.join(r['power_in'])}, out at {', '.join(r['power_out'])}"
        )
        if document["load_dependent"]:
            lines += [f"      holds where the {f}" for f in r["forces"]]
        lines += [f"      {m}" for m in r["meshes"]]
        lines += [f"      T_{p} = {t}" for p, t in r["torques"].items()]
        lines.append(f"      eta = {r['efficiency']}")
    return "\n".join(lines)


@dataclass(frozen=True)
class SeveralEvaluation:
    """The answer of ``--eval``: the operating point and the region's speed conditions."""

    point: OperatingPoint
    conditions: tuple[str, ...]

    @property
    def region(self) -> Region:
        return self.point.region

    @property
    def torques(self) -> Mapping[str, sympy.Expr]:
        return self.point.torques

    @property
    def efficiency(self) -> sympy.Expr:
        return self.point.efficiency

    @property
    def powers(self) -> Mapping[str, sympy.Expr]:
        return self.point.powers

    @property
    def inputs(self) -> tuple[str, ...]:
        return self.point.inputs

    @property
    def outputs(self) -> tuple[str, ...]:
        return self.point.outputs

    def document(self) -> dict[str, object]:
        return {
            "status": "ok",
            "region": self.region.number,
            "conditions": list(self.conditions),
            "power_in": list(self.inputs),
            "power_out": list(self.outputs),
            "powers": {p: float(v) for p, v in self.powers.items()},
            "torques": {p: float(t) for p, t in self.torques.items()},
            "efficiency": float(self.efficiency),
            "efficiency_exact": sympy.sstr(self.efficiency),
        }

    def text(self) -> str:
        torques = ", ".join(f"T_{p} = {float(t)!r}" for p, t in self.torques.items())
        return (
            f"region ({self.region.number}): power in at {', '.join(self.inputs)}, out at "
            f"{', '.join(self.outputs)}\n{torques}\n{float(self.efficiency)!r}\n"
        )


def evaluate_several(si: SeveralInputs, values: Mapping[str, sympy.Expr]) -> SeveralEvaluation:
    """The answer of ``--eval`` for a train with several inputs (``values`` by name):
    `SeveralInputs.design_point`, the decision every entry point shares."""
    point = si.design_point(values)
    return SeveralEvaluation(point, tuple(condition_text(si, point.region)))
