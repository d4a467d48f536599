"""Permanent connections searched with the shift elements (level 2 of ``derive
shifts``): members of different planetary sets (or a shaft and a member) joined for
good, N joins at a time, and the shift schemes of each connected train.

A connection is a clutch always engaged: one more equation on the member speeds, so the
connected train's speeds are the old ones on the null space of the joins' equations.
Joins that make the same groups of members are one design, and so are designs that map
onto each other when identical sets (same sizes, member by member) swap their labels:
only one of each is searched or listed.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from itertools import permutations, product
from typing import Any

from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.progress import Progress, silent
from davies_sym.synthesis.shift_elements import ShiftElement
from davies_sym.synthesis.shift_kinematics import MemberSpeeds, null_basis, speed
from davies_sym.synthesis.shift_schedules import ShiftQuestion, ShiftScheme, scheme_search
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.model import Train

#: A group of members joined for good.
Block = frozenset[str]


@dataclass(frozen=True)
class PlanetarySet:
    """The main-axis members of one set (its carrier and the central gears its planets
    mesh) and each one's role with its size: ("carrier", planet radii) or ("sun" /
    "ring", pitch radius); sets with the same roles and sizes are identical."""

    members: tuple[str, ...]
    roles: Mapping[str, tuple[object, ...]]

    def signature(self) -> tuple[tuple[object, ...], ...]:
        return tuple(sorted(self.roles.values(), key=str))


def planetary_sets(train: Train, main_axis: Sequence[str]) -> tuple[PlanetarySet, ...]:
    """The sets of ``train``: the planets on one carrier with the central members they
    mesh; a main-axis member in no set (a shaft) is a set of its own."""
    axis = set(main_axis)
    radius = {g.link: g for g in train.gears}
    carriers: dict[str, set[str]] = {}
    planets: dict[str, list[str]] = {}
    for link in train.link_names:
        if link in axis or link == train.reference:
            continue
        held = [c for c in bearings(train.couplings) if link in c.links]
        meshed = [c for c in train.couplings if getattr(c, "meshing", False) and link in c.links]
        for c in held:
            carrier = c.links[0] if c.links[1] == link else c.links[1]
            if carrier in axis:
                carriers.setdefault(carrier, set()).update(
                    m for d in meshed for m in d.links if m in axis and m != carrier
                )
                planets.setdefault(carrier, []).append(link)
    sets: list[PlanetarySet] = []
    for carrier, central in carriers.items():
        roles: dict[str, tuple[object, ...]] = {
            carrier: ("carrier", tuple(sorted(str(radius[p].radius) for p in planets[carrier] if p in radius)))
        }
        for m in sorted(central):
            g = radius.get(m)
            roles[m] = ("ring" if g is not None and g.internal else "sun", str(g.radius) if g is not None else "")
        sets.append(PlanetarySet((carrier, *sorted(central)), roles))
    placed = {m for s in sets for m in s.members}
    sets += [PlanetarySet((m,), {m: ("shaft", m)}) for m in main_axis if m not in placed]
    return tuple(sets)


def relabellings(sets: Sequence[PlanetarySet]) -> list[dict[str, str]]:
    """Every renaming of members that swaps identical sets member for member (the
    identity first)."""
    groups: dict[tuple[tuple[object, ...], ...], list[PlanetarySet]] = {}
    for s in sets:
        groups.setdefault(s.signature(), []).append(s)
    per_group = []
    for same in groups.values():
        maps = []
        for order in permutations(same):
            mapping = {}
            for source, target in zip(same, order, strict=True):
                by_role = {role: m for m, role in target.roles.items()}
                mapping.update({m: by_role[role] for m, role in source.roles.items()})
            maps.append(mapping)
        per_group.append(maps)
    return [{k: v for part in combo for k, v in part.items()} for combo in product(*per_group)]


def join_groups(joins: Sequence[tuple[str, str]]) -> frozenset[Block]:
    """The groups of members ``joins`` make (groups of two or more)."""
    group: dict[str, set[str]] = {}
    for a, b in joins:
        merged = group.get(a, {a}) | group.get(b, {b})
        for m in merged:
            group[m] = merged
    return frozenset(frozenset(g) for g in {id(g): g for g in group.values()}.values())


def _renamed(blocks: frozenset[Block], mapping: Mapping[str, str]) -> tuple[tuple[str, ...], ...]:
    return tuple(sorted(tuple(sorted(mapping.get(m, m) for m in b)) for b in blocks))


def _member_order(sets: Sequence[PlanetarySet]) -> tuple[list[str], dict[str, int]]:
    """The members in the order the joins are assigned, and each one's set."""
    home = {m: k for k, s in enumerate(sets) for m in s.members}
    return list(home), home


def _groupings(
    members: Sequence[str], home: Mapping[str, int], joins: int, groups: list[list[str]], start: int, stop: int
) -> Iterator[list[list[str]]]:
    """Every way to place ``members[start:stop]`` into ``groups`` (which hold the members
    before ``start``; no group with two members of one set) on the way to ``joins``
    joins, the groups themselves yielded at ``stop`` (changed after each yield)."""
    made = start - len(groups)
    if made > joins or len(members) - start < joins - made:
        return
    if start == stop:
        yield groups
        return
    member = members[start]
    for k in _open_to(member, groups, home):
        _place(groups, k, member)
        yield from _groupings(members, home, joins, groups, start + 1, stop)
        if len(groups[k]) > 1:
            groups[k].pop()
        else:
            groups.pop()


def _place(groups: list[list[str]], k: int, member: str) -> None:
    """``member`` into group ``k``, or a group of its own where ``k`` is the next number."""
    if k < len(groups):
        groups[k].append(member)
    else:
        groups.append([member])


def _open_to(member: str, groups: list[list[str]], home: Mapping[str, int]) -> list[int]:
    """The groups ``member`` may join (none holding a member of its set; a group of its
    own numbered last)."""
    return [k for k, g in enumerate(groups) if all(home[m] != home[member] for m in g)] + [len(groups)]


def join_prefixes(sets: Sequence[PlanetarySet], joins: int, depth: int) -> list[tuple[int, ...]]:
    """The ways the first ``depth`` members can be grouped on the way to ``joins`` joins
    (each member's group by number, groups numbered as they open): each prefix is one
    task of the search, which `connection_choices` completes."""
    members, home = _member_order(sets)
    depth = min(depth, len(members))
    out = []
    for groups in _groupings(members, home, joins, [], 0, depth):
        number = {m: k for k, g in enumerate(groups) for m in g}
        out.append(tuple(number[m] for m in members[:depth]))
    return out


def connection_choices(
    sets: Sequence[PlanetarySet], joins: int, prefix: tuple[int, ...] = ()
) -> Iterator[frozenset[Block]]:
    """Every way to make ``joins`` independent joins between members of different sets
    (beginning as ``prefix`` groups the first members), as the groups they make: the
    groupings of the members in which no group holds two members of one set, each
    taken in the one labelling of identical sets that writes it least."""
    members, home = _member_order(sets)
    maps = relabellings(sets)
    groups: list[list[str]] = []
    for k, member in zip(prefix, members, strict=False):
        _place(groups, k, member)
    for grouped in _groupings(members, home, joins, groups, len(prefix), len(members)):
        blocks = frozenset(frozenset(g) for g in grouped if len(g) > 1)
        if _renamed(blocks, maps[0]) == min(_renamed(blocks, m) for m in maps):
            yield blocks


def joined_speeds(speeds: MemberSpeeds, blocks: frozenset[Block]) -> MemberSpeeds | None:
    """The member speeds once the ``blocks`` turn as one: the old forms on a basis of
    the joins' null space (None when the joins lock the train)."""
    rows = [
        tuple(a - b for a, b in zip(speeds.forms[first], speeds.forms[m], strict=True))
        for block in sorted(blocks, key=sorted)
        for first in [min(block)]
        for m in sorted(block - {first})
    ]
    basis = null_basis(rows, speeds.degrees_of_freedom)
    if len(basis) < 2:
        return None
    free = tuple(f"q{k}" for k in range(len(basis)))
    forms = {m: tuple(speed(f, v) for v in basis) for m, f in speeds.forms.items()}
    return MemberSpeeds(free, forms, speeds.shaft)


@dataclass(frozen=True)
class ConnectedScheme:
    """A scheme of a train with permanent ``connections`` (the groups of members joined)."""

    connections: frozenset[Block]
    scheme: ShiftScheme


@dataclass(frozen=True)
class JoinTask:
    """The connected trains of one join prefix (`join_prefixes`): the free train's
    speeds, its sets, the ports' members and the question."""

    speeds: MemberSpeeds
    sets: tuple[PlanetarySet, ...]
    ports: tuple[str, str]
    question: ShiftQuestion
    prefix: tuple[int, ...]


def join_schemes(task: JoinTask) -> tuple[list[ConnectedScheme], int]:
    """The schemes of every connected train of the task's prefix, and how many
    combinations of engaged elements were screened."""
    found: list[ConnectedScheme] = []
    searched = 0
    for blocks in connection_choices(task.sets, task.question.connections, task.prefix):
        joined = joined_speeds(task.speeds, blocks)
        if joined is None or any(task.ports[0] in b and task.ports[1] in b for b in blocks):
            continue
        schemes, screened = scheme_search(joined, task.ports, task.question)
        searched += screened
        found += [ConnectedScheme(blocks, scheme) for scheme in schemes]
    return found, searched


#: Members grouped in advance per task of the connection search.
PREFIX_DEPTH = 6


def designs(
    train: Train,
    speeds: MemberSpeeds,
    ports: tuple[str, str],
    question: ShiftQuestion,
    workers: Workers = IN_THIS_PROCESS,
    progress: Progress = silent,
) -> tuple[list[ConnectedScheme], int]:
    """The schemes of the train as written, or of every choice of
    ``question.connections`` joins (each design once under the relabellings of
    identical sets; the choices spread over ``workers`` by their first members'
    grouping), and how many combinations of engaged elements were screened."""
    if not question.connections:
        schemes, searched = scheme_search(speeds, ports, question)
        return [ConnectedScheme(frozenset(), s) for s in schemes], searched
    sets = planetary_sets(train, speeds.members())
    maps = relabellings(sets)
    tasks = [
        JoinTask(speeds, sets, ports, question, p) for p in join_prefixes(sets, question.connections, PREFIX_DEPTH)
    ]
    progress(f"{len(tasks)} groups of connection choices {workers.describe(len(tasks))}")
    seen: set[tuple[Any, ...]] = set()
    found: list[ConnectedScheme] = []
    searched = 0
    for part, screened in fan_out(join_schemes, tasks, workers, Counted(progress, "group")):
        searched += screened
        for design in part:
            key = min(_design_key(design.connections, design.scheme, m) for m in maps)
            if key not in seen:
                seen.add(key)
                found.append(design)
    return found, searched


def joins_of(blocks: frozenset[Block]) -> list[tuple[str, str]]:
    """The groups as joins: the first member of each (by name) to each other."""
    return [(min(b), m) for b in sorted(blocks, key=sorted) for m in sorted(b - {min(b)})]


def _design_key(blocks: frozenset[Block], scheme: ShiftScheme, mapping: Mapping[str, str]) -> tuple[Any, ...]:
    """The design renamed by ``mapping``, written so that equal designs compare equal:
    the groups, and per gear the engaged elements each as every way it may be written."""

    def written(e: ShiftElement) -> tuple[tuple[str, ...], ...]:
        return tuple(sorted(tuple(sorted(mapping.get(m, m) for m in w)) for w in (e.members, *e.alike)))

    gears = tuple(sorted((g, tuple(sorted(written(e) for e in scheme.engaged(g)))) for g in scheme.schedule))
    return (_renamed(blocks, mapping), gears)
