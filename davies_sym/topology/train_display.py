"""How a train shows itself in a notebook (``Train._repr_html_``): its name and source,
ports, links and couplings, as the topology file declares them."""

from __future__ import annotations

import html
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the model imports this module; the types only for the checker
    from davies_sym.topology.model import Train


def _table(head: tuple[str, ...], rows: list[tuple[str, ...]]) -> str:
    cells = "".join(f"<th>{html.escape(h)}</th>" for h in head)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><tr>{cells}</tr>{body}</table>"


def train_html(train: Train) -> str:
    """Name, source, ports and degrees of freedom, then the links and the couplings."""
    ports = train.ports
    inputs = ", ".join(ports.inputs)
    summary = f"input {inputs}, output {ports.output}; reference link {train.reference}"
    if (train.degrees_of_freedom or 1) > 1:
        summary += f"; {train.degrees_of_freedom} degrees of freedom"
    links = [(link.name, link.description) for link in train.links]
    couplings = [(c.name, type(c).__name__, " \u2014 ".join(c.links)) for c in train.couplings]
    parts = [f"<p><b>{html.escape(train.name)}</b></p>"]
    if train.source:
        parts.append(f"<p>Source: {html.escape(train.source)}</p>")
    parts += [f"<p>{html.escape(summary)}</p>", _table(("link", "description"), links),
              _table(("coupling", "kind", "between"), couplings)]
    return "".join(parts)
