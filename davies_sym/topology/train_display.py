"""How a train shows itself in a notebook (``Train._repr_html_``): its name and source,
ports, links and couplings, as the topology file declares them."""

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
