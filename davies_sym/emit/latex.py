"""Standalone LaTeX document of a train's efficiency variants (``derive FILE --latex``).

Like Laus Tables 5 and 6: the turning conditions with the meshes they decide, a table
of variants (input, output, sign of every condition) and every formula as a numbered
equation.  Only ``amsmath``, ``booktabs`` and ``geometry`` are used, so any TeX
installation compiles it with pdflatex.
"""

from __future__ import annotations

import sympy

from davies_sym.efficiency.variant import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.variant_report import load_dependent, variant_forces

# "<" and ">" print as inverted punctuation in the default text font: they need commands.
_SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
            "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "<": r"\textless{}",
            ">": r"\textgreater{}"}


def escape(text: str) -> str:
    """Plain text safe for LaTeX."""
    return "".join(_SPECIAL.get(ch, ch) for ch in text)


def force_latex(conditions: list[tuple[str, sympy.Expr, int]]) -> list[str]:
    """Each loaded-force condition (:mod:`davies_sym.emit.force_conditions`) as a
    displayed inequality after its name."""
    out = []
    for what, force, sign in conditions:
        out += [rf"\noindent Holds where the {escape(what)}:", r"\begin{equation*}",
                rf"{sympy.latex(force)} {'>' if sign > 0 else '<'} 0", r"\end{equation*}"]
    return out


def _latex_notes(variant: Variant) -> list[str]:
    """:func:`davies_sym.emit.variant_report.notes` with the expressions as mathematics
    (no program syntax such as ``r1**2`` in the prose)."""
    out = []
    if not variant.feasible:
        out.append("Infeasible: no sampled admissible geometry satisfies its conditions")
    out.append(f"Partial derivatives in the mesh efficiencies: {escape(variant.derivative_check)}")
    if variant.self_locking_point is not None:
        point = ", ".join(f"{sympy.latex(k)} = {sympy.latex(v)}"
                          for k, v in sorted(variant.self_locking_point.items(), key=lambda kv: str(kv[0])))
        out.append(f"Self-locking: the efficiency is outside $(0, 1]$ at the sampled point ${point}$")
    if variant.locking_expression is not None:
        out.append(f"The efficiency has the sign of ${sympy.latex(variant.locking_expression)}$; the train "
                   "self-locks where that is $\\le 0$")
    return out


def _sign(sign: int) -> str:
    return "$> 0$" if sign > 0 else "$< 0$"


PREAMBLE = [r"\documentclass[11pt]{article}", r"\usepackage{amsmath}", r"\usepackage{booktabs}",
             r"\usepackage[margin=2cm]{geometry}", r"\allowdisplaybreaks", r"\begin{document}"]


def latex_document(variants: VariantSet) -> str:
    """The whole document of one train (or one state) as a string."""
    return "\n".join([*PREAMBLE, *_section(variants), r"\end{document}", ""])


def latex_states_document(sets: list[VariantSet]) -> str:
    """One document with a section per operating state."""
    body = [line for vs in sets for line in [*_section(vs), r"\clearpage"]]
    return "\n".join([*PREAMBLE, *body[:-1], r"\end{document}", ""])


def _section(variants: VariantSet) -> list[str]:
    """Title, conditions, variants table and formulas of one train."""
    train = variants.train
    out = [rf"\section*{{{escape(train.name)}}}"]
    if train.source:
        out.append(rf"\noindent Source: {escape(train.source)}.\\")
    out.append(rf"Ports: input {escape(train.ports.input)}, output {escape(train.ports.output)}; "
               rf"reference link {escape(train.reference)}. Ordinary efficiencies are those of each mesh "
               r"with its carrier held; swapping input and output reverses every mesh.")
    if variants.conditions:
        out += [r"\subsection*{Turning conditions}", r"\begin{center}", r"\begin{tabular}{lll}", r"\toprule",
                r"Condition & Expression & Meshes (first gear drives, declared input) \\", r"\midrule"]
        for c in variants.conditions:
            decided = [f"{escape(r.coupling)} when {'$>0$' if r.orientation > 0 else '$<0$'}"
                       for r in variants.roles if r.condition == c.name]
            out.append(rf"${c.name}$ & ${sympy.latex(c.simplified)}$ & {', '.join(decided)} \\")
        out += [r"\bottomrule", r"\end{tabular}", r"\end{center}"]
    fixed = [r for r in variants.roles if r.condition is None and not r.idle]
    idle = [escape(r.coupling) for r in variants.roles if r.idle]
    if idle:
        out.append(rf"\noindent Meshes that carry no power (their set locked or unloaded; no loss): {', '.join(idle)}.")
    if fixed:
        text = "; ".join(f"{escape(r.coupling)}: gear {escape(r.flow.gears[0 if r.fixed and r.fixed > 0 else 1])} "
                         "drives" for r in fixed)
        out.append(rf"\noindent Meshes whose direction the geometry fixes (declared input): {text}.")
    out += [r"\subsection*{Variants}", r"\begin{center}",
            r"\begin{tabular}{l" + "c" * (2 + len(variants.conditions)) + "l}", r"\toprule"]
    header = ["Variant", "Input", "Output"] + [f"${c.name}$" for c in variants.conditions] + ["Status"]
    out.append(" & ".join(header) + r" \\")
    out.append(r"\midrule")
    for v in variants.variants:
        status = "infeasible" if not v.feasible else ("self-locks" if v.self_locking_point is not None else "")
        if v.reversed_forces:
            status = ", ".join(filter(None, [f"light load: {escape(', '.join(sorted(v.reversed_forces)))} reversed",
                                             status]))
        cells = [f"({v.number})", escape(v.input), escape(v.output)]
        cells += [_sign(v.signs[c.name]) for c in variants.conditions] + [status]
        out.append(" & ".join(cells) + r" \\")
    out += [r"\bottomrule", r"\end{tabular}", r"\end{center}"]
    for v in variants.variants:
        out.append(rf"\paragraph{{Variant ({v.number})}} Input {escape(v.input)}, output {escape(v.output)}"
                   + ("".join(f", ${c.name}$ {_sign(v.signs[c.name])}" for c in variants.conditions)) + ".")
        if load_dependent(variants):
            # Variants of one input and turning-condition signs differ by the loaded forces' signs.
            out += force_latex(variant_forces(variants, v))
        out += [r"\begin{equation}", rf"\eta = {sympy.latex(v.efficiency)}", rf"\tag{{{v.number}}}",
                r"\end{equation}"]
        out += [rf"\noindent {n}.\\" for n in _latex_notes(v)]
    for d in variants.train.definitions:
        out += [rf"\noindent where ${sympy.latex(d.symbol)}$ is the {escape(d.meaning)} ({escape(d.source)}):",
                r"\begin{equation*}", rf"{sympy.latex(d.symbol)} = {sympy.latex(d.expression)}", r"\end{equation*}"]
    return out
