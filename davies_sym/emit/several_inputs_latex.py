"""Standalone LaTeX document of a train driven on several shafts (``derive FILE --latex``).

The speeds of the ports in the input speeds, the speed conditions (lines through the
origin of the plane of input speeds) with what each decides, a table of the power-flow
regions (sign of every condition, ports putting power in and taking it out, driving
gears) and, per region, the port torques in the load torque and Mantriota and
Pennestri's efficiency (eq. (6)) as numbered equations.  Same packages as the one-input
document, so pdflatex compiles it anywhere.
"""

from __future__ import annotations

import sympy

from davies_sym.efficiency.several_inputs import LOAD_TORQUE, SeveralInputs, speed_symbol
from davies_sym.emit.latex import PREAMBLE, escape, force_latex
from davies_sym.emit.several_inputs_report import drivers, mesh_text, region_forces


def _ports(names: tuple[str, ...]) -> str:
    return ", ".join(escape(p) for p in names) or "none"


def several_inputs_latex(si: SeveralInputs) -> str:
    """The whole document as a string."""
    train = si.train
    ports = train.ports
    out = [*PREAMBLE, rf"\section*{{{escape(train.name)}}}"]
    if train.source:
        out.append(rf"\noindent Source: {escape(train.source)}.\\")
    speeds = ", ".join(f"${sympy.latex(s)}$" for s in si.speeds)
    out.append(rf"Input ports {_ports(ports.inputs)} with speeds {speeds} (signed); output port "
               rf"{escape(ports.output)} with the load torque ${sympy.latex(LOAD_TORQUE)} > 0$ resisting its motion. "
               r"The efficiency is the output's power over the sum of the input shafts' powers (Mantriota and "
               r"Pennestri 2003, eq.~(6)); a shaft driven backwards by the others takes power and lowers that sum.")
    out += [r"\subsection*{Speeds}", r"\begin{align*}"]
    lines = [rf"{sympy.latex(speed_symbol(p))} &= {sympy.latex(v.to_expr())}" for p, v in si.port_speeds.items()
             if p not in ports.inputs]
    out += [r" \\ ".join(lines), r"\end{align*}"]
    out += [r"\subsection*{Speed conditions}", r"\begin{center}", r"\begin{tabular}{lll}", r"\toprule",
            r"Condition & Expression & Its sign decides \\", r"\midrule"]
    for c in si.conditions:
        out.append(rf"${c.name}$ & ${sympy.latex(c.form)}$ & {escape('; '.join(c.decides))} \\")
    out += [r"\bottomrule", r"\end{tabular}", r"\end{center}"]
    out += [r"\subsection*{Power-flow regions}", r"\begin{center}",
            r"\begin{tabular}{l" + "c" * len(si.conditions) + "lll}", r"\toprule",
            " & ".join(["Region", *(f"${c.name}$" for c in si.conditions), "Power in", "Power out",
                        "Driving gears"]) + r" \\", r"\midrule"]
    for r in si.regions:
        signs = ["$> 0$" if r.signs[c.name] > 0 else "$< 0$" for c in si.conditions]
        driving = ", ".join(escape(driver) for _, driver, _ in drivers(si, r))
        out.append(" & ".join([f"({r.number})", *signs, _ports(r.inputs), _ports(r.outputs), driving]) + r" \\")
    out += [r"\bottomrule", r"\end{tabular}", r"\end{center}"]
    load_dependent = any(r.reversed for r in si.regions)
    for r in si.regions:
        where = ", ".join(f"${c.name} {'>' if r.signs[c.name] > 0 else '<'} 0$" for c in si.conditions)
        out.append(rf"\paragraph{{Region ({r.number})}} Where {where}: "
                   + escape("; ".join(mesh_text(si, r))) + ".")
        if load_dependent:
            # Regions of one speed sector differ by the loaded forces' signs.
            out += force_latex(region_forces(r))
        torques = [rf"T_{{{escape(p)}}} &= {sympy.latex(t.to_expr())}" for p, t in r.torques.items()]
        out += [r"\begin{align*}", r" \\ ".join(torques), r"\end{align*}"]
        out += [r"\begin{equation}", rf"\eta^* = {sympy.latex(r.efficiency)}", rf"\tag{{{r.number}}}",
                r"\end{equation}"]
    for d in train.definitions:
        out += [rf"\noindent where ${sympy.latex(d.symbol)}$ is the {escape(d.meaning)} ({escape(d.source)}):",
                r"\begin{equation*}", rf"{sympy.latex(d.symbol)} = {sympy.latex(d.expression)}", r"\end{equation*}"]
    return "\n".join([*out, r"\end{document}", ""])
