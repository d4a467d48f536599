"""Standalone LaTeX document of a train's efficiency variants (``derive FILE --latex``).

Like Laus Tables 5 and 6: the turning conditions with the meshes they decide, a table
of variants (input, output, sign of every condition, driving gear of every mesh) and
every formula as a numbered equation, broken into lines that fit the page
(`davies_sym.emit.latex_lines`).  Symbols are typeset as the references write them
(`davies_sym.topology.symbol_display`: ``rp1`` is `r_{p1}`).  pdflatex with
amsmath, booktabs, geometry, tabularx and array (all in a TeX Live base and recommended
install) compiles it.
"""

from __future__ import annotations

import sympy

from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.latex_lines import LINE_WIDTH, display, fits, numbered
from davies_sym.emit.variant_report import variant_forces
from davies_sym.topology.symbol_display import latex

# "<" and ">" print as inverted punctuation in the default text font: they need commands.
_SPECIAL = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
    "<": r"\textless{}",
    ">": r"\textgreater{}",
}


def escape(text: str) -> str:
    """Plain text safe for LaTeX."""
    return "".join(_SPECIAL.get(ch, ch) for ch in text)


def force_latex(conditions: list[tuple[str, sympy.Expr, int]]) -> list[str]:
    """Each loaded-force condition (`davies_sym.emit.force_conditions`) as a
    displayed inequality after its name, broken into lines when long."""
    out = []
    for what, force, sign in conditions:
        relation = ">" if sign > 0 else "<"
        out += [rf"\noindent Holds where the {escape(what)}:", *display("", force, tail=f" {relation} 0")]
    return out


def inline_or_display(expr: sympy.Expr) -> list[str]:
    """``expr`` as inline mathematics when it fits a line, else displayed and broken."""
    text = latex(expr)
    return [f"${text}$"] if fits(text, LINE_WIDTH) else display("", expr)


def definitions_latex(definitions: list[tuple[sympy.Symbol, sympy.Expr, str, str]]) -> list[str]:
    """Each defined symbol (symbol, expression, meaning, source) as a displayed equation
    after its meaning, broken into lines when long."""
    out = []
    for symbol, expression, meaning, source in definitions:
        out += [
            rf"\noindent where ${latex(symbol)}$ is the {escape(meaning)} ({escape(source)}):",
            *display(latex(symbol), expression),
        ]
    return out


def _latex_notes(variant: Variant) -> list[str]:
    """`davies_sym.emit.variant_report.notes` with the expressions as mathematics
    (no program syntax such as ``r1**2`` in the prose), one paragraph line each."""
    out = []
    if not variant.feasible:
        out.append(r"\noindent Infeasible: no sampled admissible geometry satisfies its conditions.\\")
    out.append(rf"\noindent Partial derivatives in the mesh efficiencies: {escape(variant.derivative_check)}.\\")
    if variant.self_locking_point is not None:
        point = ", ".join(
            f"${latex(k)} = {latex(v)}$"
            for k, v in sorted(variant.self_locking_point.items(), key=lambda kv: str(kv[0]))
        )
        out.append(rf"\noindent Self-locking: the efficiency is outside $(0, 1]$ at the sampled point {point}.\\")
    if variant.locking_expression is not None:
        sign = inline_or_display(variant.locking_expression)
        if len(sign) == 1:
            out.append(
                rf"\noindent The efficiency has the sign of {sign[0]}; the train self-locks where that is "
                r"$\le 0$.\\"
            )
        else:
            out += [
                r"\noindent The efficiency has the sign of",
                *sign,
                r"\noindent and the train self-locks where that is $\le 0$.\\",
            ]
    return out


#: The relations of a requirement as LaTeX.
_RELATION_LATEX = {">": ">", ">=": r"\ge", "<": "<"}


def never_holds_latex(variant: ExcludedVariant) -> list[str]:
    """Why no admissible design reaches ``variant``: its conditions and the facts of the
    geometry they contradict, each displayed (broken into lines when long)."""
    out = [r"\noindent Never holds, so not derived: no admissible design satisfies"]
    for r in variant.conditions:
        out += display("", r.factored(), tail=f" {_RELATION_LATEX[r.relation]} 0")
    out.append(r"\noindent together with the facts of the admissible geometry")
    for r in variant.facts:
        note = rf"\quad\text{{({escape(r.description)})}}" if r.description else ""
        out += display("", r.factored(), tail=f" {_RELATION_LATEX[r.relation]} 0{note}")
    return out


def _sign(sign: int) -> str:
    return "$> 0$" if sign > 0 else "$< 0$"


#: Packages of TeX Live base and recommended only; ``L`` is a ragged-right ``tabularx`` column.
PREAMBLE = [
    r"\documentclass[11pt]{article}",
    "% Compile with pdflatex; needs amsmath, booktabs, geometry, tabularx and array (TeX Live base and recommended).",
    r"\usepackage{amsmath}",
    r"\usepackage{booktabs}",
    r"\usepackage{array}",
    r"\usepackage{tabularx}",
    r"\usepackage[a4paper,margin=2cm]{geometry}",
    r"\allowdisplaybreaks",
    r"\newcolumntype{L}{>{\raggedright\arraybackslash}X}",
    r"\begin{document}",
]


def latex_document(variants: VariantSet) -> str:
    """The whole document of one train (or one state) as a string."""
    return "\n".join([*PREAMBLE, *_section(variants), r"\end{document}", ""])


def latex_states_document(sets: list[VariantSet]) -> str:
    """One document with a section per operating state."""
    body = [line for vs in sets for line in [*_section(vs), r"\clearpage"]]
    return "\n".join([*PREAMBLE, *body[:-1], r"\end{document}", ""])


def drivers_latex(variants: VariantSet, variant: Variant | ExcludedVariant) -> str:
    """The driving gear of every mesh in ``variant``: ``C: 1$\\to$3`` (gear 1 drives gear
    3), ``idle`` for a mesh that carries no power."""
    out = []
    for role in variants.roles:
        if role.idle:
            out.append(f"{escape(role.coupling)}: idle")
            continue
        first = variant.first_drives[role.coupling]
        driver, driven = role.flow.gears if first else role.flow.gears[::-1]
        out.append(rf"{escape(role.coupling)}:~{escape(driver)}$\to${escape(driven)}")
    return ", ".join(out)


def _status(variant: Variant) -> str:
    status = "infeasible" if not variant.feasible else ("self-locks" if variant.self_locking_point is not None else "")
    if variant.reversed_forces:
        reversed_text = f"the losses reverse {escape(', '.join(sorted(variant.reversed_forces)))}"
        status = ", ".join(filter(None, [reversed_text, status]))
    return status


#: Rows per ``tabularx``: a table is one box that cannot break across pages, so a long
#: one is written as several of at most this many rows (each wrapped row up to four lines).
TABLE_ROWS = 8


def table(columns: str, header: list[str], rows: list[list[str]]) -> list[str]:
    """A full-width ``tabularx`` (``L``: a ragged-right column that wraps) of ``rows``
    under ``header``, in pieces of `TABLE_ROWS` rows that each repeat the header,
    so that a page break can fall between them."""
    out: list[str] = []
    for start in range(0, max(len(rows), 1), TABLE_ROWS):
        out += [
            r"\par\noindent",
            rf"\begin{{tabularx}}{{\linewidth}}{{{columns}}}",
            r"\toprule",
            " & ".join(header) + r" \\",
            r"\midrule",
        ]
        out += [" & ".join(cells) + r" \\" for cells in rows[start : start + TABLE_ROWS]]
        out += [r"\bottomrule", r"\end{tabularx}"]
    return out


def _conditions_table(variants: VariantSet) -> list[str]:
    """The turning conditions with the meshes each decides."""
    rows = []
    for c in variants.conditions:
        decided = [
            f"{escape(r.coupling)} when {'$>0$' if r.orientation > 0 else '$<0$'}"
            for r in variants.roles
            if r.condition == c.name
        ]
        rows.append([f"${c.name}$", f"${latex(c.simplified)}$", ", ".join(decided)])
    return [
        r"\subsection*{Turning conditions}",
        *table("lLL", ["Condition", "Expression", "Meshes (first gear drives, declared input)"], rows),
    ]


def variants_table(variants: VariantSet) -> list[str]:
    """Input, output, condition signs, driving gears (and status where any) per variant."""
    listed = variants.listed
    statuses = ["never holds" if isinstance(v, ExcludedVariant) else _status(v) for v in listed]
    extra = any(statuses)
    columns = "lll" + "c" * len(variants.conditions) + "L" + ("L" if extra else "")
    header = [
        "Variant",
        "Input",
        "Output",
        *(f"${c.name}$" for c in variants.conditions),
        r"Mesh: driving gear $\to$ driven gear",
        *(["Status"] if extra else []),
    ]
    rows = []
    for v, status in zip(listed, statuses, strict=True):
        cells = [f"({v.number})", escape(v.input), escape(v.output)]
        cells += [_sign(v.signs[c.name]) for c in variants.conditions] + [drivers_latex(variants, v)]
        rows.append(cells + ([status] if extra else []))
    return [r"\subsection*{Variants}", *table(columns, header, rows)]


def _section(variants: VariantSet) -> list[str]:
    """Title, conditions, variants table and formulas of one train."""
    train = variants.train
    out = [rf"\section*{{{escape(train.name)}}}"]
    if train.source:
        out.append(rf"\noindent Source: {escape(train.source)}.\\")
    out.append(
        rf"Ports: input {escape(train.ports.input)}, output {escape(train.ports.output)}; "
        rf"reference link {escape(train.reference)}. Ordinary efficiencies are those of each mesh "
        r"with its carrier held; swapping input and output reverses every mesh."
    )
    if variants.conditions:
        out += _conditions_table(variants)
    fixed = [r for r in variants.roles if r.condition is None and not r.idle]
    idle = [escape(r.coupling) for r in variants.roles if r.idle]
    if idle:
        out.append(
            rf"\par\noindent Meshes that carry no power (their set locked or unloaded; no loss): "
            rf"{', '.join(idle)}."
        )
    if fixed:
        text = "; ".join(
            f"{escape(r.coupling)}: {escape(r.flow.sides[0 if r.fixed and r.fixed > 0 else 1])} drives" for r in fixed
        )
        out.append(rf"\par\noindent Meshes whose direction the geometry fixes (declared input): {text}.")
    out += variants_table(variants)
    for v in variants.listed:
        out.append(
            rf"\paragraph{{Variant ({v.number})}} Input {escape(v.input)}, output {escape(v.output)}"
            + ("".join(f", ${c.name}$ {_sign(v.signs[c.name])}" for c in variants.conditions))
            + "."
        )
        if isinstance(v, ExcludedVariant):
            out += never_holds_latex(v)
            continue
        # The losses' say beyond the lossless turning conditions: each mesh power (and
        # bearing reaction) the losses can reverse, with the sign the variant needs.
        out += force_latex(variant_forces(variants, v))
        out += numbered(r"\eta", v.efficiency, v.number)
        out += _latex_notes(v)
    out += definitions_latex([(d.symbol, d.expression, d.meaning, d.source) for d in train.definitions])
    return out
