"""How Davies' method runs on a train: the choices `Analysis` takes besides the train."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy

from davies_sym.geometry.layout import Layout
from davies_sym.network.friction_laws import CoulombSigns


@dataclass(frozen=True)
class AnalysisOptions:
    """The choices of one analysis, travelling together (see `Analysis` for each).

    ``tree`` and ``action_tree`` pick the spanning trees of the motion and action
    networks; ``coulomb_signs`` how the Coulomb signs are fixed; ``extra_symbols`` join
    the polynomial ring; ``layout`` replaces the one derived from the train;
    ``reversed_coulomb`` names bearings whose resolved Coulomb sign is taken the other way.
    """

    tree: Sequence[str] | None = None
    action_tree: Sequence[str] | None = None
    coulomb_signs: CoulombSigns | str = CoulombSigns.RESOLVE
    extra_symbols: Sequence[sympy.Symbol] = ()
    layout: Layout | None = None
    reversed_coulomb: frozenset[str] = frozenset()
