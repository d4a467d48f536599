"""Text and JSON of a machine's derivation: closed forms per friction mode, cycle
efficiencies, a position's solution and a task's energies (Laus ch. 4)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy

from davies_sym.machines.closed_form import ClosedForms, DirectionForms, ModeVariant
from davies_sym.machines.cycle import CycleEfficiency
from davies_sym.machines.joints import FrictionAction
from davies_sym.machines.machine_model import Machine
from davies_sym.machines.network import Network
from davies_sym.machines.task import TaskResult


def _sign_text(signs: tuple[tuple[sympy.Symbol, int], ...]) -> str:
    return ", ".join(f"{s} = {'+1' if v > 0 else '-1'}" for s, v in signs) or "no friction"


def machine_summary(machine: Machine, network: Network) -> list[str]:
    kinds = ", ".join(f"{c.name} {c.kind}" + (" (friction)" if c.friction else "") for c in machine.couplings)
    system = "planar, d = 3 {t; u, v}" if network.order == 3 else "spatial, d = 6"
    freedoms = len(network.motions) - network.motion_matrix.rows
    lines = [
        f"machine: {machine.name}" + (f" ({machine.source})" if machine.source else ""),
        f"links: {', '.join(machine.links)}; couplings: {kinds}",
        f"screw system: {system}; {len(network.motions)} motions in {network.motion_matrix.rows} circuit equations, "
        f"{len(network.actions)} actions in {network.action_matrix.rows} cutset equations",
        f"net degrees of freedom: {freedoms}; ports: " + ", ".join(f"{p.name} ({p.coupling})" for p in machine.ports),
    ]
    if network.friction:
        lines.append("friction: " + "; ".join(_friction_law(f) for f in network.friction))
    return lines


def _friction_law(f: FrictionAction) -> str:
    """Laus eq. (98)/(127)-(129) (a sum of magnitudes) or (133) (a resultant), as written."""

    def weighted(name: str, weight: sympy.Expr) -> str:
        return name if weight == 1 else f"{weight} {name}"

    if f.resultant:
        load = "|(" + ", ".join(weighted(n, w) for n, w in f.load) + ")|"
    else:
        load = " + ".join(f"|{weighted(n, w)}|" if w == 1 else f"{w} |{n}|" for n, w in f.load)
        load = f"({load})" if len(f.load) > 1 else load
    return f"{f.name} = -{f.coefficient} sign({f.freedom}) {load}"


def _condition(condition: sympy.Expr) -> str:
    """``c > 0``, written ``-c < 0`` when c is a negated expression."""
    if condition.could_extract_minus_sign():
        return f"{-condition} < 0"
    return f"{condition} > 0"


def _variant_lines(variant: ModeVariant) -> list[str]:
    where = " and ".join(_condition(c) for c in variant.conditions) or "everywhere"
    return [
        f"  variant {_sign_text(variant.signs)}, where {where}:",
        f"    eta = {variant.abbreviated}",
        f"        = {variant.efficiency}",
    ]


def closed_form_text(forms: ClosedForms, cycles: Mapping[str, CycleEfficiency]) -> str:
    lines = machine_summary(forms.machine, forms.network)
    if forms.abbreviations:
        lines.append("geometry: " + ", ".join(f"{k} = {v}" for k, v in forms.abbreviations.items()))
    lines.append(
        "friction modes: "
        + ", ".join(
            f"{m.symbol} = sign({m.motion}) sign({m.load})"
            if m.motion is not None
            else f"{m.symbol} = sign({m.load}) (the face it presses)"
            for m in forms.modes
        )
        + " (Laus eqs. (98) and (107))"
    )
    for direction in forms.directions:
        lines += ["", *_direction_lines(direction, cycles.get(direction.input))]
    return "\n".join(lines) + "\n"


def _direction_lines(direction: DirectionForms, cycle: CycleEfficiency | None) -> list[str]:
    lines = [f"input {direction.input}, output {direction.output}:"]
    lines.append("  motions: " + ", ".join(f"{k} = {v}" for k, v in direction.motions.items()))
    for variant in direction.variants:
        lines += _variant_lines(variant)
    if cycle is not None:
        role = "input" if cycle.steady_is_input else "output"
        lines.append(
            f"  cycle efficiency over {cycle.variable}, the {role} {cycle.steady}'s power constant ({cycle.equation}):"
        )
        lines.append(
            f"    eta = {cycle.closed}" if cycle.closed is not None else "    no closed form (--eval integrates it)"
        )
    return lines


def closed_form_json(forms: ClosedForms, cycles: Mapping[str, CycleEfficiency]) -> dict[str, Any]:
    return {
        "status": "ok",
        "machine": forms.machine.name,
        "source": forms.machine.source,
        "screw_system_order": forms.network.order,
        "motions": list(forms.network.motions),
        "actions": list(forms.network.actions),
        "geometry": {str(k): str(v) for k, v in forms.abbreviations.items()},
        "friction_modes": [
            {"symbol": str(m.symbol), "motion": m.motion, "load": m.load, "friction": m.friction} for m in forms.modes
        ],
        "directions": [
            {
                "input": d.input,
                "output": d.output,
                "motions": {k: str(v) for k, v in d.motions.items()},
                "actions": {k: str(v) for k, v in d.actions.items()},
                "variants": [
                    {
                        "signs": {str(s): v for s, v in variant.signs},
                        "conditions": [_condition(c) for c in variant.conditions],
                        "efficiency": str(variant.efficiency),
                        "efficiency_abbreviated": str(variant.abbreviated),
                    }
                    for variant in d.variants
                ],
                "cycle_efficiency": str(cycles[d.input].closed)
                if d.input in cycles and cycles[d.input].closed is not None
                else None,
            }
            for d in forms.directions
        ],
    }


def task_text(machine: Machine, result: TaskResult) -> str:
    total_lost = sum(result.lost.values())
    lines = [
        f"machine: {machine.name}; task {result.task}: {len(result.steps)} time samples "
        f"from {result.steps[0].time:g} s to {result.steps[-1].time:g} s",
        f"energy supplied by {', '.join(result.drivers)}: {result.supplied:.2f} J",
        f"energy delivered to {', '.join(result.loads)}: {result.delivered:.2f} J",
        f"energy lost: {total_lost:.2f} J",
    ]
    for coupling, lost in result.lost.items():
        share = lost / total_lost if total_lost > 0 else 0.0
        lines.append(f"  {coupling}: {lost:.3f} J ({100 * share:.2f} %)")
    by_kind = lost_by_kind(machine, result)
    if len(by_kind) > 1 and total_lost > 0:
        lines.append(
            "lost by coupling type: "
            + ", ".join(f"{kind} {100 * lost / total_lost:.2f} %" for kind, lost in by_kind.items())
        )
    closed = " (a closed path: the loads end where they started, all the energy supplied is lost)"
    note = closed if result.delivered == 0 else ""
    lines.append(f"task efficiency (delivered over supplied): {result.efficiency:.6g}{note}")
    lines.append(repr(result.efficiency))
    return "\n".join(lines) + "\n"


def lost_by_kind(machine: Machine, result: TaskResult) -> dict[str, float]:
    """The energy lost per coupling type (Laus sec. 4.3.4.2 gives the prismatic share),
    largest first."""
    out: dict[str, float] = {}
    for coupling, lost in result.lost.items():
        kind = machine.coupling(coupling).kind
        out[kind] = out.get(kind, 0.0) + lost
    return dict(sorted(out.items(), key=lambda item: -item[1]))


def task_json(machine: Machine, result: TaskResult) -> dict[str, Any]:
    return {
        "status": "ok",
        "machine": machine.name,
        "task": result.task,
        "drivers": list(result.drivers),
        "loads": list(result.loads),
        "supplied_energy": result.supplied,
        "delivered_energy": result.delivered,
        "lost_energy": result.lost,
        "lost_energy_by_type": lost_by_kind(machine, result),
        "efficiency": result.efficiency,
        "steps": [
            {
                "time": s.time,
                "port_power": s.port_power,
                "port_action": s.port_action,
                "port_speed": s.port_speed,
                "friction_power": s.friction_power,
            }
            for s in result.steps
        ],
    }
