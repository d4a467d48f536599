"""The screws each coupling contributes to the network, and the screw work of a
multi-speed train, done once for the states that share a whole train.

Each kind writes its own screws for a given layout (``Coupling.screws``, Laus Tables
3-4, 12-13); square roots written in a low-level coupling's screws are found here for
the layout's radical table.  A state (`davies_sym.topology.states.train_in_state`) keeps the couplings of its whole
train with their ends renamed, and the layout of the whole (a brake or a clutch joins
members, it does not move an axis).  A coupling's screws read its name, gears and kind
from the coupling and its point, axis and tangent from the layout, never its ends, so
they are the same in every state: the unit screws (Laus Tables 3-4), the screw system
the kept couplings span (section 3.3.1) and each coupling reduced to it are worked out
once, kept in the whole train's ``memo``, and a brake or a clutch only changes which of
them a state takes.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import replace
from typing import Any, TypeVar, cast

import sympy

from davies_sym.algebra.radicals import has_square_root
from davies_sym.caches import IdentityCache
from davies_sym.geometry.layout import Layout
from davies_sym.network.screw_system import (
    ReducedCoupling,
    ScrewSystem,
    essential_twists,
    minimal_screw_system,
    reduce_coupling,
)
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.kind_screws import CouplingScrews
from davies_sym.topology.model import Train

T = TypeVar("T")


def written_square_root(screws: CouplingScrews) -> bool:
    """Whether a square root is written in the screws (a low-level coupling's), which
    the layout's radical table must absorb."""
    return any(
        has_square_root(x) for group in (screws.motions, screws.constraints) for named in group for x in named.screw
    )


def coupling_screws(coupling: Coupling, layout: Layout) -> CouplingScrews:
    """The unit twists and candidate unit wrenches of ``coupling`` in ``layout``."""
    return coupling.screws(layout)


class SharedScrews:
    """The coupling screws of a whole train and what the screw systems of its states
    make of them, each computed on first use.

    Screw systems are keyed by the couplings a state keeps (a state that drops
    couplings may span a smaller system); reduced couplings by the system and the
    coupling, so states whose systems agree share them.  ``layout`` is the whole train's.
    """

    def __init__(self, whole: Train, layout: Layout):
        self.layout = layout
        self.couplings = {c.name: c for c in whole.couplings}
        self._screws: dict[str, CouplingScrews] = {}
        self._rooted: dict[str, bool] = {}
        self._systems: dict[tuple[str, ...], ScrewSystem] = {}
        #: Each system's key (its coordinates and lift), by identity: systems are kept.
        self._keys: dict[int, tuple[ScrewSystem, tuple[tuple[int, ...], tuple[sympy.Expr, ...]]]] = {}
        self._formed: dict[tuple[tuple[int, ...], tuple[sympy.Expr, ...], str], Any] = {}

    def screws(self, name: str) -> CouplingScrews:
        """The full unit screws of coupling ``name`` (`coupling_screws`)."""
        known = self._screws.get(name)
        if known is None:
            known = self._screws[name] = coupling_screws(self.couplings[name], self.layout)
        return known

    def written_square_root(self, names: Iterable[str]) -> bool:
        """Whether a square root is written in the screws of any coupling of ``names``."""
        for name in names:
            rooted = self._rooted.get(name)
            if rooted is None:
                rooted = self._rooted[name] = written_square_root(self.screws(name))
            if rooted:
                return True
        return False

    def system(self, kept: tuple[str, ...]) -> ScrewSystem:
        """The screw system the couplings ``kept`` span (`minimal_screw_system`)."""
        known = self._systems.get(kept)
        if known is None:
            screws = [self.screws(n) for n in kept]
            essential = essential_twists(screws, self.layout.spatial)
            known = self._systems[kept] = minimal_screw_system(essential, self.layout.radicals)
        return known

    def reduced(self, system: ScrewSystem, name: str) -> ReducedCoupling:
        """Coupling ``name`` reduced to ``system`` (`reduce_coupling`); a coupling that
        does not fit raises `CouplingScrewError` every time it is asked for."""
        return self.formed(system, f"reduced {name}", lambda: reduce_coupling(system, self.screws(name), name))

    def formed(self, system: ScrewSystem, what: str, form: Callable[[], T]) -> T:
        """What ``form`` makes of ``system`` (``what`` names it), formed once for the
        states whose systems agree; where ``form`` raises, nothing is kept."""
        key = (*self._key(system), what)
        if key not in self._formed:
            self._formed[key] = form()
        return cast(T, self._formed[key])

    def _key(self, system: ScrewSystem) -> tuple[tuple[int, ...], tuple[sympy.Expr, ...]]:
        """The system by value (equal systems of different states share their work)."""
        known = self._keys.get(id(system))
        if known is None or known[0] is not system:
            known = self._keys[id(system)] = (system, (system.coordinates, tuple(system.lift)))
        return known[1]


#: The screw work of each whole train, shared by its states while the whole train lives.
_SHARED: IdentityCache[Train, SharedScrews] = IdentityCache()


def computed_shared_screws(whole: Train) -> SharedScrews | None:
    """The shared screw work of ``whole`` if its states have worked it out, else None."""
    return _SHARED.peek(whole)


def shared_screws(train: Train, whole_layout: Layout) -> SharedScrews | None:
    """The shared screw work of ``train``'s whole train (whose layout is
    ``whole_layout``), when ``train`` is a state whose couplings are its whole's with
    other ends (the only difference `coupling_screws` does not read); None for a train on
    its own."""
    whole = train.whole
    if whole is None:
        return None
    shared = _SHARED.get(whole, lambda: SharedScrews(whole, whole_layout))
    for c in train.couplings:
        own = shared.couplings.get(c.name)
        if own is None or replace(c, links=own.links) != own:
            return None
    return shared
