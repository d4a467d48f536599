"""How a derived efficiency shows itself in a notebook (``_repr_latex_``,
``_repr_html_``): each variant's formula with the turning conditions, input and output
where it holds, as Laus Tables 5 and 6 list them."""

from __future__ import annotations

import html
from collections.abc import Sequence

from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.efficiency.variant_result import Variant
from davies_sym.topology.symbol_display import latex


def _expressions(conditions: Sequence[TurningCondition]) -> dict[str, str]:
    """Each turning condition's expression as LaTeX, by name."""
    return {c.name: latex(c.simplified) for c in conditions}


def variant_latex(conditions: Sequence[TurningCondition], variant: Variant) -> str:
    """``$$\\eta_{(n)} = ... \\quad (A \\to B,\\ conditions)$$``."""
    return variant.equation_latex(_expressions(conditions))


def variant_set_html(name: str, conditions: Sequence[TurningCondition], variants: Sequence[Variant]) -> str:
    """A table of the variants: number, ports, where each holds, and its formula (LaTeX
    for the notebook's math renderer)."""
    rows = []
    expressions = _expressions(conditions)
    for v in variants:
        where = ", ".join(v.where_latex(expressions)) or "always"
        rows.append(
            f"<tr><td>({v.number})</td><td>{html.escape(v.input)} &rarr; {html.escape(v.output)}</td>"
            f"<td>\\({html.escape(where)}\\)</td><td>\\(\\eta = {html.escape(latex(v.efficiency))}\\)"
            "</td></tr>"
        )
    head = "<tr><th>variant</th><th>ports</th><th>holds where</th><th>efficiency</th></tr>"
    return f"<p><b>{html.escape(name)}</b>: {len(variants)} variants</p><table>{head}{''.join(rows)}</table>"
