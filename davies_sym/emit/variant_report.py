"""Variants as JSON-ready data and as plain text (``derive FILE [--json]``)."""

from __future__ import annotations

from typing import Any

import sympy

from davies_sym.efficiency.turning_conditions import MeshRole
from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.force_conditions import force_conditions, force_text
from davies_sym.topology.symbol_display import latex as display_latex


def condition_text(variants: VariantSet, variant: Variant | ExcludedVariant) -> list[str]:
    """``"r2 - r1 > 0"`` for every turning condition of ``variant``."""
    out = []
    for c in variants.conditions:
        out.append(f"{sympy.sstr(c.simplified)} {'>' if variant.signs[c.name] > 0 else '<'} 0")
    return out


def variant_forces(variants: VariantSet, variant: Variant) -> list[tuple[str, sympy.Expr, int]]:
    """Where ``variant`` holds beyond its turning conditions: each mesh power and bearing
    reaction the losses can reverse, with the sign it needs."""
    return force_conditions(variant.loaded_forces, {r.coupling for r in variants.roles}, variant.reversed_forces)


def mesh_text(variants: VariantSet, variant: Variant | ExcludedVariant) -> list[str]:
    """``"C: gear 1 drives gear 3 (eta_C)"`` for every mesh (an idle one says so)."""
    out = []
    for role in variants.roles:
        if role.idle:
            out.append(
                f"{role.coupling}: carries no power ({role.flow.pair_words}; its set is locked or unloaded), no loss"
            )
            continue
        first = variant.first_drives[role.coupling]
        driver, driven = role.flow.sides if first else role.flow.sides[::-1]
        eta = role.efficiencies[0 if first else 1]
        out.append(f"{role.coupling}: {driver} drives {driven} ({sympy.sstr(eta)}), carrier {role.flow.carrier}")
    return out


def notes(variant: Variant) -> list[str]:
    """Feasibility, partial-derivative check and self-locking of a variant."""
    out = []
    if not variant.feasible:
        out.append("infeasible: no sampled admissible geometry satisfies its conditions")
    out.append(f"partial derivatives in the mesh efficiencies: {variant.derivative_check}")
    if variant.self_locking_point is not None:
        point = ", ".join(f"{k}={v}" for k, v in sorted(variant.self_locking_point.items(), key=lambda kv: str(kv[0])))
        out.append(f"self-locking: efficiency outside (0, 1] at sampled point {point}")
    if variant.locking_expression is not None:
        out.append(
            f"the efficiency has the sign of {sympy.sstr(variant.locking_expression)}; it self-locks where that is <= 0"
        )
    return out


def variants_document(variants: VariantSet) -> dict[str, Any]:
    """The ``turning_conditions``, ``meshes`` and ``variants`` entries of the JSON document."""
    conditions = [
        {
            "name": c.name,
            "expression": sympy.sstr(c.expression),
            "simplified": sympy.sstr(c.simplified),
            "latex": display_latex(c.simplified),
        }
        for c in variants.conditions
    ]
    meshes = [_mesh_entry(variants, r) for r in variants.roles]
    items = [
        _excluded_entry(variants, v) if isinstance(v, ExcludedVariant) else _variant_entry(variants, v)
        for v in variants.listed
    ]
    definitions = [
        {
            "symbol": str(d.symbol),
            "expression": sympy.sstr(d.expression),
            "latex": display_latex(d.expression),
            "meaning": d.meaning,
            "source": d.source,
        }
        for d in variants.train.definitions
    ]
    return {"turning_conditions": conditions, "meshes": meshes, "variants": items, "definitions": definitions}


def _mesh_entry(variants: VariantSet, r: MeshRole) -> dict[str, Any]:
    """One mesh of the ``meshes`` entry: its gears, virtual power and when its first gear drives."""
    return {
        "coupling": r.coupling,
        "carrier": r.flow.carrier,
        "gears": list(r.flow.gears),
        "virtual_power_per_input_power": sympy.sstr(r.flow.flow_ratio.to_expr()),
        "efficiency_symbols": [sympy.sstr(e) for e in r.efficiencies],
        "decided": r.condition is None,
        "carries_power": not r.idle,
        "first_gear_drives_when": "no power crosses the mesh"
        if r.idle
        else (
            ("always" if r.fixed and r.fixed > 0 else "never") + f" (input {variants.train.ports.input})"
            if r.condition is None
            else f"{r.condition} {'>' if r.orientation > 0 else '<'} 0 (input {variants.train.ports.input})"
        ),
    }


def _variant_entry(variants: VariantSet, v: Variant) -> dict[str, Any]:
    """One derived variant of the ``variants`` entry: its efficiency and what was checked of it."""
    return {
        **_common_entry(variants, v),
        "efficiency": sympy.sstr(v.efficiency),
        "latex": display_latex(v.efficiency),
        "feasible": v.feasible,
        "derivative_check": v.derivative_check,
        "self_locking_sampled": v.self_locking_point is not None,
        "sign_expression": None if v.locking_expression is None else sympy.sstr(v.locking_expression),
        "reversed_forces": sorted(v.reversed_forces),
        "loaded_forces": [
            {"force": what, "expression": sympy.sstr(force), "sign": sign}
            for what, force, sign in variant_forces(variants, v)
        ],
    }


def _common_entry(variants: VariantSet, v: Variant | ExcludedVariant) -> dict[str, Any]:
    """What every row of the variants table has: number, name, ports, condition signs
    and the driving gear of every mesh."""
    return {
        "number": v.number,
        "name": v.name,
        "input": v.input,
        "output": v.output,
        "conditions": [
            {"condition": c.name, "expression": sympy.sstr(c.simplified), "sign": v.signs[c.name]}
            for c in variants.conditions
        ],
        "meshes": mesh_text(variants, v),
    }


def _excluded_entry(variants: VariantSet, v: ExcludedVariant) -> dict[str, Any]:
    """A combination no admissible design reaches: no formula, the proof's requirements."""
    return {
        **_common_entry(variants, v),
        "efficiency": None,
        "feasible": False,
        "never_holds": {
            "reason": v.reason,
            "conditions": [str(r) for r in v.conditions],
            "facts": [str(r) for r in v.facts],
        },
    }


def variants_text(variants: VariantSet) -> str:
    """Plain-text table of conditions and variants."""
    lines = []
    for c in variants.conditions:
        lines.append(
            f"  turning condition {c.name}: sign of {sympy.sstr(c.simplified)}"
            + (f" (derived: {sympy.sstr(c.expression)})" if c.expression != c.simplified else "")
        )
    for v in variants.listed:
        where = "; ".join(condition_text(variants, v)) or "always"
        lines.append(f"  ({v.number}) input {v.input}, output {v.output}, where {where}:")
        if isinstance(v, ExcludedVariant):
            lines.append(f"      never holds: {v.reason}")
            lines += [f"      {m}" for m in mesh_text(variants, v)]
            continue
        lines.append(f"      eta = {sympy.sstr(v.efficiency)}")
        for f in force_text(variant_forces(variants, v)):
            lines.append(f"      holds where the {f}")
        for m in mesh_text(variants, v):
            lines.append(f"      {m}")
        for n in notes(v):
            lines.append(f"      {n}")
    for d in variants.train.definitions:
        lines.append(f"  where {d.symbol} ({d.meaning}, {d.source}):")
        lines.append(f"      {d.symbol} = {sympy.sstr(d.expression)}")
    return "\n".join(lines)
