"""The uses of a graph that can load every gear pair, read from Willis' relations at
generic ratios modulo a prime (`davies_sym.atlas.idle_meshes`), against the drawn
train's exact lossless actions (`davies_sym.atlas.choices`, Laus eq. (2)), which share
no code with them; and on two trains small enough to work out by hand."""

from __future__ import annotations

from itertools import combinations

import pytest

from davies_sym.atlas import choices as atlas_choices
from davies_sym.atlas.atlas_entries import entry, places
from davies_sym.atlas.graphs import TrainGraph
from davies_sym.atlas.idle_meshes import loadable_uses


def test_a_simple_planetary_set_loads_both_meshes_between_its_coaxial_members() -> None:
    """Sun 0, annulus 1, carrier 2, planet 3: with any coaxial member held the two others
    load both meshes; with the carrier held, a port on the planet leaves the sun's or the
    annulus's mesh idle (that member turns freely)."""
    graph = TrainGraph(4, ((0, 1, 2), (2, 3)), ((0, 3), (1, 3)))
    assert set(loadable_uses(graph)) == {(0, 1, 2), (1, 0, 2), (2, 0, 1)}


def test_an_idler_planet_meshing_one_planet_idles_in_every_use() -> None:
    """The set above with a second planet 4 on the carrier meshing only planet 3: any use
    with planet 4 a port leaves the sun's or the annulus's mesh idle, any other leaves
    the mesh of planets 3 and 4 idle."""
    graph = TrainGraph(5, ((0, 1, 2), (2, 3), (2, 4)), ((0, 3), (1, 3), (3, 4)))
    assert loadable_uses(graph) == ()


def _every_use(graph: TrainGraph) -> tuple[tuple[int, int, int], ...]:
    """Every use, so that the atlas reads the lossless actions of every choice."""
    return tuple((h, a, b) for h in range(graph.links) for a, b in combinations(range(graph.links), 2))


def _agreement(monkeypatch: pytest.MonkeyPatch, links: int, step: int = 1, entries: bool = True) -> None:
    """Every graph: the drawn train's choices with every mesh loaded, read from the
    lossless actions of every choice, are exactly its choices among the generically
    loadable uses (a drawing's radii never unloaded a generic force in these atlases);
    and (``entries``) the atlas entry, which reads the actions of those alone, is the same."""
    for place in places(links)[::step]:
        uses = set(loadable_uses(place.graph))
        with monkeypatch.context() as patched:
            patched.setattr(atlas_choices, "loadable_uses", _every_use)
            e = entry(place)
        choices = {c.use for c in e.choices}
        loaded = {c.use for c in e.loaded}
        assert loaded == choices & uses, place.name
        if entries:
            kept = entry(place)
            assert (kept.choices, kept.loaded) == (e.choices, e.loaded), place.name


def test_the_loadable_uses_of_six_links_are_the_drawn_trains_loaded_choices(monkeypatch: pytest.MonkeyPatch) -> None:
    _agreement(monkeypatch, 6)


@pytest.mark.slow
def test_the_loadable_uses_of_seven_and_eight_links_are_the_drawn_trains_loaded_choices(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """All 647 graphs of 7 links; every 80th of the 6360 of 8, whose entries are also
    compared with those formed reading every choice's actions (as on 6 links)."""
    _agreement(monkeypatch, 7, entries=False)
    _agreement(monkeypatch, 8, step=80)
