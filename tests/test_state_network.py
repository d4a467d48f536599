"""The states of a multi-speed file share their whole train's screw work (network/shared_screws.py).

Each state's network, built on the shared coupling screws, screw systems and reduced
couplings, must equal the network built from scratch (a fresh load, every screw worked
out for that state alone), and the shared work must be done once per whole train.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

import davies_sym
import davies_sym.network.shared_screws as shared_module
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.network.matrices import Network
from davies_sym.network.shared_screws import SharedScrews, computed_shared_screws, shared_screws
from davies_sym.topology.model import Train

ROOT = Path(__file__).resolve().parent.parent
FILES = ["catalog/ravigneaux.yaml", "catalog/simpson.yaml", "benchmarks/eight_speed.yaml"]


def _states(path: str) -> list[Train]:
    """Every state of ``path``, resolved as the analysis takes it, from a fresh load."""
    train = davies_sym.load(ROOT / path)
    return [resolved_train(davies_sym.train_in_state(train, s)) for s in train.states]


def _from_scratch(path: str, name: str) -> Network:
    """The network of state ``name`` of a freshly loaded ``path``, its screw work done for
    that state alone (a layout given: nothing taken from the whole train)."""
    train = davies_sym.load(ROOT / path)
    state = resolved_train(davies_sym.train_in_state(train, next(s for s in train.states if s.name == name)))
    return Network(state, layout=train_layout(state))


@pytest.mark.parametrize("path", FILES)
def test_shared_network_equals_network_from_scratch(path: str) -> None:
    train = davies_sym.load(ROOT / path)
    for state in train.states:
        resolved = resolved_train(davies_sym.train_in_state(train, state))
        assert resolved.whole is not None
        assert shared_screws(resolved, train_layout(resolved.whole)) is not None, state.name
        net, fresh = Network(resolved), _from_scratch(path, state.name)
        assert net.tree == fresh.tree and net.action_tree == fresh.action_tree
        assert net.system.coordinates == fresh.system.coordinates and net.system.lift == fresh.system.lift
        assert net.reduced == fresh.reduced
        assert net.motions == fresh.motions, state.name
        assert net.actions == fresh.actions, state.name
        assert net.laws == fresh.laws, state.name
        assert net.layout == fresh.layout
        assert net.network_motion_matrix() == fresh.network_motion_matrix()
        assert net.network_action_matrix() == fresh.network_action_matrix()
        assert net.network_action_matrix(lossless=True) == fresh.network_action_matrix(lossless=True)


@pytest.mark.parametrize("path", FILES)
def test_coupling_screws_computed_once_per_whole_train(path: str, monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[tuple[int, str]] = []
    real = shared_module.coupling_screws

    def counted(coupling, layout):  # type: ignore[no-untyped-def]
        calls.append((id(layout), coupling.name))
        return real(coupling, layout)

    monkeypatch.setattr(shared_module, "coupling_screws", counted)
    states = _states(path)
    for state in states:
        Network(state)
    wholes = {id(s.whole): s.whole for s in states}
    assert len(wholes) < len(states)  # some states share a whole train
    # Once per coupling and whole train: the couplings its states keep, each one time.
    kept = {(id(s.whole), c.name) for s in states for c in s.couplings}
    assert len(calls) == len(set(calls)) == len(kept)
    for whole in wholes.values():
        assert isinstance(whole, Train) and isinstance(computed_shared_screws(whole), SharedScrews)


@pytest.mark.parametrize("path", FILES)
def test_states_of_one_whole_share_reduced_couplings(path: str) -> None:
    states = _states(path)
    nets = [Network(s) for s in states]
    shared_pairs = 0
    for i, a in enumerate(nets):
        for b in nets[i + 1 :]:
            if a.train.whole is not b.train.whole:
                continue
            common = set(a.reduced) & set(b.reduced)
            assert common
            if a.system.coordinates == b.system.coordinates and a.system.lift == b.system.lift:
                # The same objects, not equal copies: the reduction ran once.
                assert all(a.reduced[n] is b.reduced[n] for n in common)
                shared_pairs += 1
    assert shared_pairs >= 1


def test_states_with_the_same_couplings_share_the_screw_system() -> None:
    # Ravigneaux 2nd and 3rd gear keep the same couplings (a brake on s2, a clutch s1-s2).
    _, _, second, third = _states("catalog/ravigneaux.yaml")  # reverse, first, second, third
    assert second.whole is third.whole
    assert [c.name for c in second.couplings] == [c.name for c in third.couplings]
    assert Network(second).system is Network(third).system


def test_a_given_layout_or_a_train_on_its_own_takes_nothing_shared() -> None:
    state = _states("catalog/simpson.yaml")[0]
    assert state.whole is not None
    Network(state, layout=train_layout(state))
    assert computed_shared_screws(state.whole) is None
    alone = resolved_train(davies_sym.load(ROOT / "catalog/tuplin.yaml"))
    assert shared_screws(alone, train_layout(alone)) is None


def test_a_coupling_other_than_its_whole_s_is_not_shared() -> None:
    state = _states("catalog/simpson.yaml")[0]
    first, *rest = state.couplings
    assert state.whole is not None
    whole = train_layout(state.whole)
    assert shared_screws(state, whole) is not None
    # Screws are shared only for the whole's own couplings (their ends aside).
    assert shared_screws(replace(state, couplings=(replace(first, name=f"{first.name}2"), *rest)), whole) is None


def test_states_that_free_the_same_members_share_one_whole_whatever_their_ports() -> None:
    """A whole train per set of free members, not per pair of ports: the Simpson states
    that free no member, and one driven at its output, share one whole (its layout
    solved once); the reverse state, which frees two members, has the whole without them."""
    train = davies_sym.load(ROOT / "catalog/simpson.yaml")
    first = train.states[0]
    fixed = [s for s in train.states if not s.free]
    fixed.append(replace(first, name="driven_at_the_output", input=first.output, output=first.input))
    states = [davies_sym.train_in_state(train, s) for s in fixed]
    assert len({(s.ports.input, s.ports.output) for s in states}) == 2
    assert len({id(s.whole) for s in states}) == 1
    (reverse,) = (s for s in train.states if s.free)
    alone = davies_sym.train_in_state(train, reverse)
    assert alone.whole is not states[0].whole
    assert alone.whole is not None and not set(reverse.free) & set(alone.whole.link_names)
