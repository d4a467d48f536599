"""A machine's closed forms as a standalone LaTeX document (Laus sec. 4.2): the friction
laws, the friction modes, and per input every variant of the efficiency with the
region where its signs hold (eqs. (110)-(117)), then the cycle efficiency (eqs. (120)
and (123)).  Long formulas are broken to the page by the gear trains' line breaker."""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.emit.latex import PREAMBLE, escape
from davies_sym.emit.latex_lines import aligned, display, numbered
from davies_sym.machines.closed_form import ClosedForms, DirectionForms, FrictionMode
from davies_sym.machines.cycle import CycleEfficiency
from davies_sym.machines.joints import FrictionAction
from davies_sym.topology.symbol_display import latex


def _name(name: str) -> str:
    """A magnitude's name in mathematics: ``U_DF`` -> ``U_{DF}``."""
    return latex(sympy.Symbol(name))


def _friction_law(f: FrictionAction) -> str:
    """Laus eq. (98)/(127)-(129) (a sum of magnitudes) or (133) (a resultant)."""
    weighted = [(latex(sympy.sympify(w)) + " " if w != 1 else "", _name(n)) for n, w in f.load]
    if f.resultant:
        load = r"\sqrt{" + " + ".join(f"({w}{n})^2" for w, n in weighted) + "}"
    else:
        load = " + ".join(f"{w}\\lvert {n} \\rvert" for w, n in weighted)
        load = f"\\left({load}\\right)" if len(weighted) > 1 else load
    coefficient = latex(sympy.sympify(f.coefficient))
    return f"{_name(f.name)} = -{coefficient} \\operatorname{{sign}}({_name(f.freedom)})\\, {load}"


def _mode(m: FrictionMode) -> str:
    if m.motion is None:
        return rf"{latex(m.symbol)} = \operatorname{{sign}}({_name(m.load)})"
    return rf"{latex(m.symbol)} = \operatorname{{sign}}({_name(m.motion)}) \operatorname{{sign}}({_name(m.load)})"


def _signs(signs: tuple[tuple[sympy.Symbol, int], ...]) -> str:
    return ", ".join(f"${latex(s)} = {'+1' if v > 0 else '-1'}$" for s, v in signs) or "no friction"


def _direction(direction: DirectionForms, cycle: CycleEfficiency | None, first_tag: int) -> list[str]:
    out = [rf"\subsection*{{Input {escape(direction.input)}, output {escape(direction.output)}}}"]
    given = [k for k, v in direction.motions.items() if v == sympy.Symbol(k, real=True) or str(v) == k]
    found = [(_name(k), v) for k, v in direction.motions.items() if k not in given]
    out += [rf"\noindent Motions, from ${', '.join(_name(k) for k in given)}$:", *aligned(found)]
    for tag, variant in enumerate(direction.variants, start=first_tag):
        out.append(rf"\paragraph{{Variant ({tag})}} Friction mode {_signs(variant.signs)}; it holds where")
        if variant.conditions:
            for condition in variant.conditions:
                negated = condition.could_extract_minus_sign()
                out += display("", -condition if negated else condition, tail=" < 0" if negated else " > 0")
        else:
            out.append("every position.")
        out += numbered(r"\eta", variant.abbreviated, tag)
        if variant.abbreviated != variant.efficiency:
            out += [r"\noindent that is,", *display(r"\eta", variant.efficiency)]
    if cycle is not None:
        role = "input" if cycle.steady_is_input else "output"
        out.append(
            rf"\paragraph{{Over one cycle}} of ${latex(cycle.variable)}$, the {role} "
            rf"{escape(cycle.steady)}'s power constant ({cycle.equation}):"
        )
        if cycle.closed is not None:
            out += display(r"\bar{\eta}", cycle.closed)
        else:
            out.append("no closed form (derive --eval integrates it numerically).")
    return out


def machine_latex_document(forms: ClosedForms, cycles: Mapping[str, CycleEfficiency]) -> str:
    """The whole document of one machine's closed forms."""
    machine = forms.machine
    out = [*PREAMBLE, rf"\section*{{{escape(machine.name)}}}"]
    if machine.source:
        out.append(rf"\noindent Source: {escape(machine.source)}.\\")
    ports = ", ".join(f"{escape(p.name)} (coupling {escape(p.coupling)})" for p in machine.ports)
    links = escape(", ".join(machine.links))
    out.append(rf"Links: {links}; reference link {escape(machine.reference)}. Ports: {ports}.")
    friction = list(forms.network.friction)
    if friction:
        out.append(r"\par\noindent Friction (Coulomb, against the relative motion):")
        for f in friction:
            out += [r"\begin{equation*}", _friction_law(f), r"\end{equation*}"]
    if forms.abbreviations:
        out += [r"\noindent Geometry:", *aligned([(latex(k), v) for k, v in forms.abbreviations.items()])]
    if forms.modes:
        out.append(
            r"\noindent Friction modes (Laus eqs. (98) and (107)): "
            + ", ".join(f"${_mode(m)}$" for m in forms.modes)
            + "."
        )
    tag = 1
    for direction in forms.directions:
        out += _direction(direction, cycles.get(direction.input), tag)
        tag += len(direction.variants)
    return "\n".join([*out, r"\end{document}", ""])
