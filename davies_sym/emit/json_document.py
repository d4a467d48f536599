"""The JSON document of ``derive FILE --json``: the train, its network and the
efficiency in friction coefficients."""

from __future__ import annotations

from typing import Any

import sympy

from davies_sym.algebra.radicals import restore
from davies_sym.network.analysis import Analysis
from davies_sym.topology.symbol_display import latex as display_latex
from davies_sym.topology.symbols import make_symbol

FRICTION_CONVENTION = (
    "Coulomb friction (default for gear meshes): friction torque T = -zeta |U| sign(t) about the "
    "relative-motion axis, zeta > 0 (Laus Table 2, eq. (10)); the signs are fixed with positive input "
    "power from the lossless solution, and a symbol sigma_X = +1 or -1 remains where the ports alone do "
    "not decide the sign (see sign_conditions). Linear law: T = zeta U with real zeta (Laus eqs. (63)-(64)). "
    "Viscous law: T = -b t (Laus Table 2, eq. (11))."
)


def _friction(coupling: Any) -> dict[str, str]:
    f = coupling.friction
    laws = {
        law: sympy.sstr(getattr(f, law))
        for law in ("coulomb", "linear", "viscous", "drag")
        if getattr(f, law) is not None
    }
    return laws | ({"pressed_by": f.pressed_by} if f.pressed_by is not None else {})


def _forms(analysis: Analysis) -> tuple[sympy.Expr, sympy.Expr]:
    """The speed ratio and the efficiency in the friction coefficients, radicals as roots."""
    radicals = analysis.network.layout.radicals
    return restore(analysis.speed_ratio().to_expr(), radicals), restore(analysis.efficiency, radicals)


def summary_document(analysis: Analysis, forms: tuple[sympy.Expr, sympy.Expr] | None = None) -> dict[str, Any]:
    """What the text summary prints (`text_summary`): the train, its mobility and screw
    system, the geometric constraints, the speed ratio and the efficiency in the friction
    coefficients (``forms``, when already formed), with nothing formed that it does not
    print."""
    train, net = analysis.train, analysis.network
    ratio, efficiency = forms or _forms(analysis)
    conditions = [
        {"symbol": str(s.symbol), "coupling": s.coupling, "equals": f"sign({sympy.sstr(s.expression)})"}
        for s in analysis.sign_conditions
    ]
    return {
        "name": train.name,
        "links": list(train.link_names),
        "reference": train.reference,
        "degrees_of_freedom": analysis.degrees_of_freedom,
        "screw_system_order": net.order,
        "screw_system": {
            "motion_coordinates": list(net.system.twist_names),
            "action_coordinates": list(net.system.wrench_names),
        },
        "geometric_constraints": [r.constraint for r in train.dependent or ()]
        + [str(c) for c in net.layout.constraints],
        "dependent_parameters": {str(r.symbol): sympy.sstr(r.expression) for r in train.dependent or ()},
        "speed_ratio": {"input": train.ports.input, "output": train.ports.output, "expression": sympy.sstr(ratio)},
        "efficiency_friction_form": {
            "input": train.ports.input,
            "output": train.ports.output,
            "expression": sympy.sstr(efficiency),
            "sign_conditions": conditions,
            "friction_convention": FRICTION_CONVENTION,
        },
    }


def train_document(analysis: Analysis) -> dict[str, Any]:
    """Everything ``derive --json`` prints, as plain JSON-ready data: the summary, and
    every coupling's screws, every motion and action magnitude and the LaTeX of the
    speed ratio and the efficiency."""
    train, net = analysis.train, analysis.network
    ratio, efficiency = _forms(analysis)
    summary = summary_document(analysis, (ratio, efficiency))
    couplings = []
    for c in train.couplings:
        entry: dict[str, Any] = {"name": c.name, "type": c.kind, "links": list(c.links)}
        entry.update(c.report_fields())
        if c.located:
            point = net.layout.coupling_points[c.name]
            entry["position"] = [sympy.sstr(v) for v in point]
        entry["friction"] = _friction(c)
        entry["motions"] = {v.name: [sympy.sstr(x) for x in v.twist] for v in net.coupling_motions(c.name)}
        entry["actions"] = {
            v.name: {"role": v.role, "wrench": [sympy.sstr(x) for x in v.wrench]} for v in net.coupling_actions(c.name)
        }
        couplings.append(entry)
    return {
        "name": train.name,
        "source": train.source,
        "file": train.path,
        "links": summary["links"],
        "reference": train.reference,
        "gears": [
            {"name": g.name, "link": g.link, "radius": sympy.sstr(g.radius), "internal": g.internal}
            for g in train.gears
        ],
        "couplings": couplings,
        "ports": {"input": train.ports.input, "output": train.ports.output},
        "degrees_of_freedom": summary["degrees_of_freedom"],
        "screw_system_order": summary["screw_system_order"],
        "screw_system": summary["screw_system"],
        "spanning_tree": list(net.tree),
        "geometric_constraints": summary["geometric_constraints"],
        "dependent_parameters": summary["dependent_parameters"],
        "motion_magnitudes": {k: sympy.sstr(v.to_expr()) for k, v in analysis.motion_magnitudes.items()},
        "action_magnitudes": {k: sympy.sstr(v.to_expr()) for k, v in analysis.action_magnitudes.items()},
        "speed_ratio": _with_latex(summary["speed_ratio"], ratio),
        "efficiency_friction_form": _with_latex(summary["efficiency_friction_form"], efficiency),
    }


def _with_latex(entry: dict[str, Any], expr: sympy.Expr) -> dict[str, Any]:
    """``entry`` with the LaTeX of ``expr`` after its ``expression``."""
    out: dict[str, Any] = {}
    for key, value in entry.items():
        out[key] = value
        if key == "expression":
            out["latex"] = display_latex(expr)
    return out


def text_summary(document: dict[str, Any]) -> str:
    """A short human-readable summary of the document."""
    eff = document["efficiency_friction_form"]
    lines = [
        f"{document['name']}",
        f"  links: {', '.join(document['links'])}; reference: {document['reference']}",
        f"  degrees of freedom: {document['degrees_of_freedom']}; screw system order: "
        f"{document['screw_system_order']} {{{', '.join(document['screw_system']['motion_coordinates'])}}}",
    ]
    dependent = document.get("dependent_parameters", {})
    solved = iter(dependent.items())
    for c in document["geometric_constraints"]:
        given = next(solved, None)
        lines.append(f"  geometric constraint: {c}" + (f", so {given[0]} = {given[1]}" if given else ""))
    ratio = document["speed_ratio"]
    lines.append(f"  speed ratio ({ratio['input']} over {ratio['output']} speed) = {ratio['expression']}")
    lines.append(f"  efficiency ({eff['input']} -> {eff['output']}) = {eff['expression']}")
    for s in eff["sign_conditions"]:
        lines.append(f"    where {s['symbol']} = {s['equals']} (not decided by the ports alone)")
    return "\n".join(lines)


def kinematics_document(analysis: Analysis) -> dict[str, Any]:
    """Motions of a train with several degrees of freedom in its primary speeds (eq. (1));
    the efficiency with several inputs is not derived."""
    basis = analysis.motion_basis
    primaries = sorted({f for combo in basis.values() for f in combo}, key=list(basis).index)
    relations = {}
    for name, combo in basis.items():
        if name in primaries:
            continue
        expr = sympy.Add(*(c.to_expr() * make_symbol(f, "magnitude") for f, c in combo.items()))
        relations[name] = sympy.sstr(expr)
    return {
        "name": analysis.train.name,
        "source": analysis.train.source,
        "file": analysis.train.path,
        "degrees_of_freedom": analysis.degrees_of_freedom,
        "primary_speeds": primaries,
        "kinematics": relations,
    }


def kinematics_text(document: dict[str, Any]) -> str:
    lines = [
        document["name"],
        f"  degrees of freedom: {document['degrees_of_freedom']}; primary speeds: "
        f"{', '.join(document['primary_speeds'])}",
    ]
    lines += [f"  {name} = {expr}" for name, expr in document["kinematics"].items()]
    lines.append(
        f"  (no efficiency: a train of {document['degrees_of_freedom']} degrees of freedom needs as many "
        "input ports; list them in ports.input, e.g. input: [A, K])"
    )
    return "\n".join(lines)
