"""Standalone LaTeX document of a train driven on several shafts (``derive FILE --latex``).

The speeds of the ports in the input speeds, the speed conditions (lines through the
origin of the plane of input speeds) with what each decides, a table of the power-flow
regions (sign of every condition, ports putting power in and taking it out, driving
gears) and, per region, the port torques in the load torque and Mantriota and
Pennestri's efficiency (eq. (6)) as numbered equations, broken into lines that fit the
page (`davies_sym.emit.latex_lines`).  Same preamble as the one-input document:
pdflatex with amsmath, booktabs, geometry, tabularx and array compiles it.
"""

from __future__ import annotations

from davies_sym.efficiency.several_inputs import LOAD_TORQUE, Region, SeveralInputs, speed_symbol
from davies_sym.emit.latex import PREAMBLE, definitions_latex, escape, force_latex, table
from davies_sym.emit.latex_lines import aligned, numbered
from davies_sym.emit.several_inputs_report import drivers, mesh_text, region_forces
from davies_sym.topology.symbol_display import latex


def _ports(names: tuple[str, ...]) -> str:
    return ", ".join(escape(p) for p in names) or "none"


def _drivers(si: SeveralInputs, region: Region) -> str:
    """``M1: 1$\\to$2, ...``: the driving and the driven gear of every mesh."""
    return ", ".join(
        rf"{escape(mesh)}:~{escape(driver)}$\to${escape(driven)}" for mesh, driver, driven in drivers(si, region)
    )


def _tables(si: SeveralInputs) -> list[str]:
    """The speed conditions with what each decides, and the power-flow regions."""
    conditions = [[f"${c.name}$", f"${latex(c.form)}$", escape("; ".join(c.decides))] for c in si.conditions]
    regions = [
        [
            f"({r.number})",
            *("$> 0$" if r.signs[c.name] > 0 else "$< 0$" for c in si.conditions),
            _ports(r.inputs),
            _ports(r.outputs),
            _drivers(si, r),
        ]
        for r in si.regions
    ]
    header = [
        "Region",
        *(f"${c.name}$" for c in si.conditions),
        "Power in",
        "Power out",
        r"Mesh: driving gear $\to$ driven gear",
    ]
    return [
        r"\subsection*{Speed conditions}",
        *table("llL", ["Condition", "Expression", "Its sign decides"], conditions),
        r"\subsection*{Power-flow regions}",
        *table("l" + "c" * len(si.conditions) + "llL", header, regions),
    ]


def several_inputs_latex(si: SeveralInputs) -> str:
    """The whole document as a string."""
    train = si.train
    ports = train.ports
    out = [*PREAMBLE, rf"\section*{{{escape(train.name)}}}"]
    if train.source:
        out.append(rf"\noindent Source: {escape(train.source)}.\\")
    speeds = ", ".join(f"${latex(s)}$" for s in si.speeds)
    out.append(
        rf"Input ports {_ports(ports.inputs)} with speeds {speeds} (signed); output port "
        rf"{escape(ports.output)} with the load torque ${latex(LOAD_TORQUE)} > 0$ resisting its motion. "
        r"The efficiency is the output's power over the sum of the input shafts' powers (Mantriota and "
        r"Pennestri 2003, eq.~(6)); a shaft driven backwards by the others takes power and lowers that sum."
    )
    speed_rows = [(latex(speed_symbol(p)), v.to_expr()) for p, v in si.port_speeds.items() if p not in ports.inputs]
    if speed_rows:
        out += [r"\subsection*{Speeds}", *aligned(speed_rows)]
    out += _tables(si)
    load_dependent = any(r.reversed for r in si.regions)
    for r in si.regions:
        where = ", ".join(f"${c.name} {'>' if r.signs[c.name] > 0 else '<'} 0$" for c in si.conditions)
        out.append(rf"\paragraph{{Region ({r.number})}} Where {where}: " + escape("; ".join(mesh_text(si, r))) + ".")
        if load_dependent:
            # Regions of one speed sector differ by the loaded forces' signs.
            out += force_latex(region_forces(r))
        out += aligned([(rf"T_{{{escape(p)}}}", t.to_expr()) for p, t in r.torques.items()])
        out += numbered(r"\eta^*", r.efficiency, r.number)
    out += definitions_latex([(d.symbol, d.expression, d.meaning, d.source) for d in train.definitions])
    return "\n".join([*out, r"\end{document}", ""])
