"""A multi-speed set in one operating state: brakes, clutches and free members applied.

A braked member is joined rigidly to the housing (the reference link) and a clutch joins
two members: the joined links become one link, and the couplings between them vanish
(a bearing that no longer turns, a mesh inside one rigid block carries no relative
motion and so no loss).  A free (unloaded) member is removed with its couplings: it
carries no power and no loss.  The result is an ordinary train, analysed as any other.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from types import MappingProxyType

from davies_sym.caches import IdentityCache
from davies_sym.errors import InputError, Problem, TopologyError
from davies_sym.topology.coupling_kinds import as_bearing, bearings
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.link_groups import link_roots
from davies_sym.topology.model import Link, Ports, State, Train
from davies_sym.topology.schema import PORT_KEYS


def train_in_state(train: Train, state: State | str) -> Train:
    """``train`` with ``state``'s ports, brakes, clutches and free members applied
    (``state``: one of ``train.states`` or its name)."""
    if isinstance(state, str):
        state = train.state(state, "state")
    problems: list[Problem] = []
    pairs = [*((link, train.reference) for link in state.brake), *((b, a) for a, b in state.clutch)]
    joined = link_roots(train.link_names, pairs)
    groups: dict[str, list[str]] = {}
    for link in train.link_names:
        groups.setdefault(joined[link], []).append(link)
    names = {root: root if root == train.reference else "+".join(members) for root, members in groups.items()}

    def rename(link: str) -> str:
        return names[joined[link]]

    free = set(state.free)
    for link in free:
        if joined[link] != link or len(groups[link]) > 1:
            problems.append(
                train.problem(f"states.{state.name}.free", f"{link!r} cannot be free and braked or clutched")
            )
    couplings = _joined_couplings(train, state, rename, free, problems)
    order = {c.name: i for i, c in enumerate(train.couplings)}
    couplings.sort(key=lambda c: order[c.name])
    kept = {c.name for c in couplings}
    for key, port in (("input", state.input), ("output", state.output)):
        if port not in kept:
            problems.append(
                train.problem(
                    f"states.{state.name}.{key}",
                    f"port {port!r} does not exist in this state (its members are joined or free)",
                )
            )
    if problems:
        raise TopologyError(problems, train.path)
    links = tuple(
        Link(name, "") for name in dict.fromkeys(rename(link) for link in train.link_names if link not in free)
    )
    gears = tuple(replace(g, link=rename(g.link)) for g in train.gears if g.link not in free)
    return replace(
        train,
        name=f"{train.name}, {state.description or state.name}",
        links=links,
        gears=gears,
        couplings=tuple(couplings),
        ports=Ports(state.input, state.output),
        reference=rename(train.reference),
        degrees_of_freedom=None,
        states=(),
        whole=_without(train.whole or train, free),
        # The state's ports are written in its own entry: a problem with them points there.
        renamed=MappingProxyType(
            {"ports": f"states.{state.name}", **{f"ports.{key}": f"states.{state.name}.{key}" for key in PORT_KEYS}}
        ),
    )


def _joined_couplings(
    train: Train, state: State, rename: Callable[[str], str], free: set[str], problems: list[Problem]
) -> list[Coupling]:
    """The couplings of ``train`` between the members ``state`` leaves (``rename``: a
    link's member), those inside one member or at a free link left out, and of two
    bearings between the same two members the first (a lossy twin is a problem)."""
    couplings: list[Coupling] = []
    ports = {state.input, state.output}
    # Ports first, so that of two bearings a clutch makes parallel the port is kept.
    for c in sorted(train.couplings, key=lambda c: c.name not in ports):
        if set(c.links) & free:
            continue
        ends = (rename(c.links[0]), rename(c.links[1]))
        if ends[0] == ends[1]:
            continue
        twin = next(
            (d for d in bearings(couplings) if as_bearing(c) is not None and set(d.links) == set(ends)),
            None,
        )
        if twin is not None:
            # Two bearings between the same two members (a clutch joined two shafts that
            # both run in the housing): one carries the load; a lossy twin would split it.
            if not c.friction.lossless:
                problems.append(
                    train.problem(
                        f"couplings.{c.name}",
                        f"in state {state.name!r} this bearing "
                        f"runs beside {twin.name!r} between the same members; their "
                        "friction would need a load split",
                    )
                )
            continue
        couplings.append(replace(c, links=ends))
    return couplings


def _without(train: Train, free: set[str]) -> Train:
    """``train`` without the ``free`` members and their gears and couplings: the geometry a
    state keeps (brakes and clutches join members without moving axes; free members take
    no part, so no axis of the state depends on theirs).  Cached with the train, so the
    states that free the same members share one whole train, whatever their ports: its
    layout is solved once, its coupling screws and screw systems worked out once
    (`davies_sym.network.shared_screws`).  Its ports stay the file's, which may name a
    coupling of a free member: neither the layout nor the screws read them."""
    return _WITHOUT.get(train, lambda: _reduced(train, free), frozenset(free))


#: The reduced train of each set of free members, while the whole train lives.
_WITHOUT: IdentityCache[Train, Train] = IdentityCache()


def _reduced(train: Train, free: set[str]) -> Train:
    if not free:
        return replace(train, states=())
    return replace(
        train,
        links=tuple(link for link in train.links if link.name not in free),
        gears=tuple(g for g in train.gears if g.link not in free),
        couplings=tuple(c for c in train.couplings if not set(c.links) & free),
        states=(),
    )


def train_to_derive(train: Train, state: State | str | None) -> Train:
    """The train the API derives: ``train`` in ``state`` (an operating state or its name), or
    ``train`` itself when it has no states; a train with states and none named is refused
    with their names, as one derivation holds for one state."""
    if state is not None:
        if not train.states:
            raise InputError(
                [Problem("state", f"the train has no states; leave state out (got {state!r})")], train.path
            )
        return train_in_state(train, state)
    if train.states:
        names = ", ".join(st.name for st in train.states)
        first = train.states[0].name
        raise InputError(
            [
                Problem(
                    "states",
                    f"the train has operating states ({names}) and one derivation holds for one of them: "
                    f"name it (davies_sym.derive(train, state={first!r}); derive FILE --state {first})",
                )
            ],
            train.file_lines,
        )
    return train
