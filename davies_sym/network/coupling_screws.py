"""The screws each coupling contributes to the network, for a given layout: each kind
writes its own (``Coupling.screws``, Laus Tables 3-4, 12-13); square roots written in a
low-level coupling's screws are found here for the layout's radical table.
"""

from __future__ import annotations

from davies_sym.algebra.radicals import has_square_root
from davies_sym.geometry.layout import Layout
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.kind_screws import CouplingScrews


def written_square_root(screws: CouplingScrews) -> bool:
    """Whether a square root is written in the screws (a low-level coupling's), which
    the layout's radical table must absorb."""
    return any(
        has_square_root(x) for group in (screws.motions, screws.constraints) for named in group for x in named.screw
    )


def coupling_screws(coupling: Coupling, layout: Layout) -> CouplingScrews:
    """The unit twists and candidate unit wrenches of ``coupling`` in ``layout``."""
    return coupling.screws(layout)
