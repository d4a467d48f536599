"""The atlas reads a choice between two later members of a held member's axis by
superposition of two analyses (`davies_sym.atlas.choices`): its speed ratio from the
members' speeds of the one motion, its loaded meshes from the difference of two lossless
equilibria.  Checked here against the choice's own analysis: its state built and solved
alone, its ratio and its meshes' tooth forces read directly (Laus eq. (2))."""

from __future__ import annotations

import pytest

from davies_sym.atlas.atlas_entries import GraphPlace, places
from davies_sym.atlas.choices import _way_to_draw, admissible_choices, every_choice
from davies_sym.atlas.realisation import Realisation, realisations
from davies_sym.errors import DaviesError
from davies_sym.network.analysis import analyse
from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state


def _alone(train: Train, state: str) -> tuple[bool, bool] | None:
    """Kept (the ratio depends on the radii) and loaded, from the state's own analysis;
    None where it fails."""
    try:
        analysis = analyse(train_in_state(train, state))
        ratio = analysis.speed_ratio()
        if ratio.num.total_degree() == 0 and ratio.den.total_degree() == 0:
            return False, False
        forces = analysis.lossless_action_coefficients
        net = analysis.network
        meshes = gear_meshes(analysis.train.couplings)
        return True, all(
            any(not forces[a.name].is_zero() for a in net.coupling_actions(m.name, lossless=True)) for m in meshes
        )
    except (DaviesError, ZeroDivisionError):
        return None


def _superposed_places(links: int, count: int) -> list[tuple[GraphPlace, Realisation]]:
    """The first ``count`` graphs of ``links`` links whose first drawing holds a member of
    an axis of four or more, so that some choices are read by superposition."""
    out = []
    for place in places(links):
        drawn = next(iter(realisations(place.graph)))
        if drawn.frame is None and len(place.graph.axes[drawn.main_axis]) >= 4:
            out.append((place, drawn))
        if len(out) == count:
            break
    return out


def _check(drawn: Realisation) -> int:
    """The admissible and loaded choices equal those of each choice analysed alone;
    the number of choices read by superposition."""
    candidates = every_choice(drawn)
    found = _way_to_draw(drawn, candidates)
    assert not isinstance(found, str), found
    _, train = found
    read = admissible_choices(drawn)
    alone = {c: _alone(train, s.name) for c, s in zip(candidates, train.states, strict=True)}
    assert list(read.choices) == [c for c in candidates if (alone[c] or (False,))[0]]
    assert list(read.loaded) == [c for c in candidates if alone[c] == (True, True)]
    firsts: dict[int, int] = {}
    for c in candidates:
        firsts.setdefault(c.held, c.input)
    return sum(c.input != firsts[c.held] for c in candidates)


def test_superposed_choices_of_six_links_equal_their_own_analyses() -> None:
    """Six graphs of 6 links with four coaxial members: every choice's admissibility and
    loaded meshes as its own state's analysis says."""
    read = sum(_check(drawn) for _, drawn in _superposed_places(6, 6))
    assert read >= 6 * 4  # four held members, each with one choice read by superposition


@pytest.mark.slow
def test_superposed_choices_of_seven_links_equal_their_own_analyses() -> None:
    """Every 7-link graph with four or more coaxial members among the first 40."""
    assert sum(_check(drawn) for _, drawn in _superposed_places(7, 40)) >= 40 * 4
