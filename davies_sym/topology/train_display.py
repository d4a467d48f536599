"""How a train shows itself in a notebook (``Train._repr_html_``, ``_repr_latex_``): its
name and source, ports, links, gears and couplings, as the topology file declares them."""

from __future__ import annotations

import html
from collections.abc import Sequence


def _table(head: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    cells = "".join(f"<th>{html.escape(h)}</th>" for h in head)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><tr>{cells}</tr>{body}</table>"


def train_html(
    name: str, source: str, summary: str, links: Sequence[tuple[str, str]], couplings: Sequence[tuple[str, str, str]]
) -> str:
    """Name, source and the summary line (ports, reference link, mobility), then the links
    (name, description) and the couplings (name, kind, the links it joins)."""
    parts = [f"<p><b>{html.escape(name)}</b></p>"]
    if source:
        parts.append(f"<p>Source: {html.escape(source)}</p>")
    parts += [
        f"<p>{html.escape(summary)}</p>",
        _table(("link", "description"), links),
        _table(("coupling", "kind", "between"), couplings),
    ]
    return "".join(parts)


def train_latex(name: str, ports: tuple[str, str], gears: Sequence[tuple[str, str, str]]) -> str:
    """The name, the ports and each gear (name, its radius as LaTeX, its link) as one
    LaTeX array."""

    def text(value: str) -> str:
        return r"\text{" + value.replace("\\", "").replace("{", "").replace("}", "").replace("_", r"\_") + "}"

    rows = [rf"{text(name)} & {text(ports[0])} \to {text(ports[1])}"]
    rows += [rf"{text('gear ' + g)} & {radius} \quad {text('on link ' + link)}" for g, radius, link in gears]
    return r"$$\begin{array}{ll}" + r" \\ ".join(rows) + r"\end{array}$$"
