"""Load a topology file (YAML, language version 1) into a validated `Train`.

Validation collects every problem with its line and entry path and raises once
(`TopologyError`).  Geometry and mobility are checked later, when the network
is built, because they need the screws.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import networkx as nx

from davies_sym.errors import TopologyError, shortened
from davies_sym.topology.calibration_entry import read_calibrate
from davies_sym.topology.checks import read_expected
from davies_sym.topology.coupling_kinds import KINDS
from davies_sym.topology.couplings import Coupling, coupling_fields
from davies_sym.topology.documents import document_from_bytes, read_document
from davies_sym.topology.entries import EntryReader, describe
from davies_sym.topology.gear_entries import read_gears
from davies_sym.topology.geometry_entries import read_independent, read_placement
from davies_sym.topology.helices import check_helices
from davies_sym.topology.model import Gear, Link, Ports, State, Train
from davies_sym.topology.schema import FORMAT_VERSION, LINK, PORT_KEYS, PORTS, STATE, TOP_LEVEL
from davies_sym.topology.yaml_source import SourceDocument, parse_yaml


def load(path: str | os.PathLike[str]) -> Train:
    """Read, parse and validate the train file at ``path``."""
    return build_train(read_document(path))


def load_bytes(data: bytes, name: str | None = None) -> Train:
    """Parse and validate the bytes of a train file (read elsewhere, e.g. by the process
    that hands the file to a cluster); ``name`` is used in messages."""
    return build_train(document_from_bytes(data, name))


def loads(text: str, name: str | None = None) -> Train:
    """Parse and validate a train given as YAML text (``name`` is used in messages)."""
    return build_train(parse_yaml(text, name))


def load_mapping(data: Mapping[str, Any], name: str | None = None) -> Train:
    """Validate a train given as a mapping of plain YAML values (mappings, lists, text,
    numbers, booleans), as a program that writes train files builds it: read as a
    parsed file is, its problems located by their entry paths (no file, no lines);
    ``name`` is used in messages."""
    return build_train(SourceDocument(data, name=name))


def build_train(document: SourceDocument) -> Train:
    reader = EntryReader(document)
    data = reader.mapping(document.data, "")
    if data is None:
        raise TopologyError(reader.problems, document.name)
    _check_top_level(data, reader)
    links = _read_links(data["links"], reader) if "links" in data else []
    gears = read_gears(data.get("gears", {}), reader, {link.name for link in links})
    couplings = (
        _read_couplings(data["couplings"], reader, {link.name for link in links}, gears) if "couplings" in data else {}
    )
    check_helices(couplings, reader)
    ports = _read_ports(data["ports"], reader, couplings) if "ports" in data else None
    if reader.problems:
        raise TopologyError(reader.problems, document.name)
    _check_connected(links, couplings, reader)
    reference = _read_reference(data.get("reference"), reader, links, couplings, ports)
    dof = _read_degrees_of_freedom(data.get("degrees_of_freedom"), reader)
    expected = read_expected(data.get("expected", []), reader, couplings)
    states = _read_states(data.get("states", {}), reader, {link.name for link in links}, couplings, reference)
    for i, check in enumerate(expected):
        if check.state is not None and check.state not in {st.name for st in states}:
            reader.problem(f"expected[{i}].state", f"unknown state {shortened(check.state)}")
    placement = read_placement(data["placement"], reader) if "placement" in data else None
    independent = read_independent(data["independent"], reader) if "independent" in data else None
    calibrate = read_calibrate(data["calibrate"], reader) if "calibrate" in data else None
    _check_texts(data, reader)
    if reader.problems or ports is None or reference is None:
        raise TopologyError(reader.problems, document.name)
    return Train(
        name=str(data["name"]),
        links=tuple(links),
        gears=tuple(gears.values()),
        couplings=tuple(couplings.values()),
        ports=ports,
        reference=reference,
        symbols=MappingProxyType(dict(sorted(reader.symbols.items()))),
        source=str(data.get("source", "")),
        degrees_of_freedom=dof,
        expected=expected,
        path=document.name,
        locations=MappingProxyType(dict(document.lines)),
        states=states,
        calibrate=calibrate,
        placement=placement,
        independent=independent,
        written=MappingProxyType(dict(reader.written)),
    )


def _check_top_level(data: Mapping[str, Any], reader: EntryReader) -> None:
    """The file's top-level keys and language version; a missing table of links or
    couplings is noted so that references to its names are not reported one by one."""
    reader.check_keys(data, "", TOP_LEVEL)
    version = data.get("format", FORMAT_VERSION)
    if version != FORMAT_VERSION or isinstance(version, bool):  # YAML's true is not the version 1
        reader.problem(
            "format", f"unsupported topology language version {describe(version)} (this is {FORMAT_VERSION})"
        )
    # A missing table is reported once (its key); references to its names are not.
    for key, kind in (("links", "link"), ("couplings", "coupling")):
        if key not in data:
            reader.unreadable.add(kind)
    if "gears" not in data:
        reader.absent.add("gear")


def _read_degrees_of_freedom(dof: Any, reader: EntryReader) -> int | None:
    """The file's ``degrees_of_freedom``: a positive integer, or None (absent or refused)."""
    if dof is not None and (not isinstance(dof, int) or isinstance(dof, bool) or dof < 1):
        reader.problem("degrees_of_freedom", f"expected a positive integer, got {describe(dof)}")
        return None
    return dof


def _check_texts(data: Mapping[str, Any], reader: EntryReader) -> None:
    """The free texts of the file (``name``, ``source``, ``notes``) are text, and the name
    is not blank."""
    for key in ("name", "source", "notes"):
        if key in data and not isinstance(data[key], str):
            reader.problem(key, f"expected text, got {describe(data[key])}")
    if isinstance(data.get("name"), str) and not data["name"].strip():
        reader.problem("name", "the train needs a name: write a few words that say what it is")


def _read_links(value: Any, reader: EntryReader) -> list[Link]:
    links: list[Link] = []
    if not isinstance(value, Mapping):
        # A list of names; one name alone is the list of that name (a machine needs two, below).
        value = reader.items(value, "links", "a list of link names or a mapping of links")
    if value is None:
        reader.unreadable.add("link")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            name = reader.defined_name(item, f"links[{i}]", "link")
            if name is None:
                continue
            if any(link.name == name for link in links):
                reader.problem(f"links[{i}]", f"duplicate link {name!r}")
                continue
            links.append(Link(name))
    elif isinstance(value, Mapping):
        for name, entry in value.items():
            entry = entry or {}
            if reader.defined_name(name, f"links.{name}", "link") is None:
                continue
            if reader.mapping(entry, f"links.{name}") is None:
                links.append(Link(name))  # defined all the same: only its description is unreadable
                continue
            reader.check_keys(entry, f"links.{name}", LINK)
            links.append(Link(name, _text(entry, "description", f"links.{name}", reader)))
    if value is not None and len(links) < 2:
        reader.problem("links", "a machine needs at least two links")
        reader.unreadable.add("link")  # references to the others say nothing more
    return links


def _read_couplings(value: Any, reader: EntryReader, links: set[str], gears: Mapping[str, Gear]) -> dict[str, Coupling]:
    couplings: dict[str, Coupling] = {}
    table = reader.mapping(value, "couplings")
    if table is None:
        reader.unreadable.add("coupling")
    for name, entry in (table or {}).items():
        path = f"couplings.{name}"
        if reader.defined_name(name, path, "coupling") is None:
            continue
        entry = reader.mapping(entry, path)
        kind = _coupling_kind(entry, path, reader) if entry is not None else None
        # A refused coupling is reported once: ports and states naming it say nothing more.
        coupling = kind.from_entry(name, entry, path, reader, gears) if kind is not None and entry is not None else None
        if coupling is None:
            reader.broken.add(name)
            continue
        for i, link in enumerate(coupling.links):
            # A mesh's links are its gears' links, whose entries report an unknown one.
            if link not in links and coupling.gears is None:
                reader.unknown(f"{path}.links[{i}]", "link", link)
        for key, link in coupling.named_links:
            if link not in links:
                reader.unknown(f"{path}.{key}", "link", link)
        couplings[name] = coupling
    if table and not couplings:
        reader.unreadable.add("coupling")  # not one coupling could be read: the table's problems say it all
    if table is not None and not couplings and not reader.problems:
        reader.problem("couplings", "no couplings given")
    return couplings


def _coupling_kind(entry: Mapping[str, Any], path: str, reader: EntryReader) -> type[Coupling] | None:
    """The kind ``type`` names, its keys checked, or None with the problem recorded."""
    kind_name = entry.get("type")
    kind = KINDS.get(kind_name) if isinstance(kind_name, str) else None
    if kind is None and "type" not in entry:
        reader.problem(path, f"missing required key 'type': add `type:` ({', '.join(KINDS)})")
    elif kind is None:
        reader.problem(f"{path}.type", f"unknown coupling type {shortened(str(kind_name))} (known: {', '.join(KINDS)})")
    else:
        reader.check_keys(entry, path, coupling_fields(kind))
    return kind


def _read_ports(value: Any, reader: EntryReader, couplings: Mapping[str, Coupling]) -> Ports | None:
    entry = reader.mapping(value, "ports")
    if entry is None:
        return None
    reader.check_keys(entry, "ports", PORTS)
    names: dict[str, list[str]] = {}
    for role in PORT_KEYS:
        if role not in entry:
            continue
        # Several inputs (a differential driven on two shafts) are written as a list.
        values = entry[role] if role == "input" and isinstance(entry[role], list) else [entry[role]]
        paths = [f"ports.{role}[{i}]" if len(values) > 1 else f"ports.{role}" for i in range(len(values))]
        found = [_port(v, path, reader, couplings) for v, path in zip(values, paths, strict=True)]
        if not values or None in found:
            if not values:
                reader.problem(f"ports.{role}", "expected a coupling name or a list of them")
            continue
        names[role] = [n for n in found if n is not None]
    if len(names) != 2:
        return None
    every = [*names["input"], *names["output"]]
    if len(set(every)) != len(every):
        reader.problem(
            "ports", "every port must be a different coupling (an input is also the output, or listed twice)"
        )
        return None
    first, *others = names["input"]
    return Ports(first, names["output"][0], tuple(others))


def _port(value: Any, path: str, reader: EntryReader, couplings: Mapping[str, Coupling]) -> str | None:
    name = reader.name(value, path)
    if name is None:
        return None
    if name not in couplings:
        reader.unknown(path, "coupling", name, f"port on a missing coupling {shortened(name)}")
        return None
    if couplings[name].meshing:
        reader.problem(
            path, f"coupling {name!r} is a gear mesh; a port sits on a revolute or prismatic coupling (a shaft)"
        )
        return None
    return name


def _check_connected(links: list[Link], couplings: Mapping[str, Coupling], reader: EntryReader) -> None:
    graph = nx.MultiGraph()
    graph.add_nodes_from(link.name for link in links)
    graph.add_edges_from(c.links for c in couplings.values())
    if not nx.is_connected(graph):
        parts = sorted((sorted(map(str, part)) for part in nx.connected_components(graph)), key=len)
        said = "the coupling graph is not connected: " + " | ".join(", ".join(p) for p in parts) + " are separate"
        lonely = [p[0] for p in parts if len(p) == 1 and graph.degree(p[0]) == 0]
        if lonely:  # a link no coupling joins: said at the link itself
            reader.problem(f"links.{lonely[0]}", f"no coupling joins link {lonely[0]!r} ({said}); join it or remove it")
        else:
            reader.problem("couplings", said)


def _read_reference(
    value: Any, reader: EntryReader, links: list[Link], couplings: Mapping[str, Coupling], ports: Ports | None
) -> str | None:
    names = [link.name for link in links]
    if value is not None:
        name = reader.name(value, "reference")
        if name is not None and name not in names:
            reader.unknown("reference", "link", name)
            return None
        return name
    if ports is None:
        return None
    common = set(couplings[ports.input].links) & set(couplings[ports.output].links)
    if len(common) != 1:
        reader.problem(
            "reference",
            f"give the reference link: the input and output couplings share {'no link' if not common else 'two links'}",
        )
        return None
    return common.pop()


def _as_written(value: Any) -> str:
    """A name as written, for a message (`describe` without its quotes)."""
    return describe(value).strip("'\"")


def _read_states(
    value: Any, reader: EntryReader, links: set[str], couplings: Mapping[str, Coupling], reference: str | None
) -> tuple[State, ...]:
    """The ``states`` mapping: ports, brakes, clutches and free members per state, each
    problem at the state's own entry."""
    states = reader.mapping(value, "states")
    if states is None:
        return ()
    out = []
    for name, entry in states.items():
        path = f"states.{name}"
        if reader.defined_name(name, path, "state") is None:
            continue
        entry = reader.mapping(entry, path)
        if entry is None:
            continue
        reader.check_keys(entry, path, STATE)
        ports = _state_ports(entry, path, reader, couplings)
        brake = _members(entry.get("brake", []), f"{path}.brake", reader, links)
        for i, link in enumerate(brake):
            if link == reference:
                reader.problem(
                    f"{path}.brake[{i}]",
                    f"{link!r} is the reference link (the housing): a brake holds another member to it; "
                    "name the member to hold",
                )
        free = _members(entry.get("free", []), f"{path}.free", reader, links)
        clutch = _clutches(entry.get("clutch", []), path, reader, links)
        if ports[0] is not None and ports[1] is not None:
            out.append(
                State(
                    str(name),
                    ports[0],
                    ports[1],
                    tuple(brake),
                    tuple(clutch),
                    tuple(free),
                    _text(entry, "description", f"states.{name}", reader),
                )
            )
    return tuple(out)


def _state_ports(
    entry: Mapping[str, Any], path: str, reader: EntryReader, couplings: Mapping[str, Coupling]
) -> list[str | None]:
    """A state's input and output ports, read as the top-level ones are (a coupling, not a
    mesh); an output that is also the input is refused (None)."""
    ports = [_port(entry[key], f"{path}.{key}", reader, couplings) if key in entry else None for key in PORT_KEYS]
    if ports[0] is not None and ports[0] == ports[1]:
        reader.problem(f"{path}.output", f"{ports[1]!r} is also the input: every port must be a different coupling")
        ports[1] = None
    return ports


def _members(items: Any, path: str, reader: EntryReader, links: set[str]) -> list[str]:
    """The links a state's list at ``path`` names (a brake's, a clutch's, the free ones);
    an unknown link is reported and left out."""
    found: list[str] = []
    for i, item in enumerate(reader.items(items, path, "a list of links") or []):
        link = reader.name(item, f"{path}[{i}]")
        if link is not None and link not in links:
            reader.unknown(f"{path}[{i}]", "link", link)
        elif link is not None:
            found.append(link)
    return found


def _clutches(value: Any, path: str, reader: EntryReader, links: set[str]) -> list[tuple[str, str]]:
    """The pairs of links the clutches of the state at ``path`` join."""
    clutch: list[tuple[str, str]] = []
    pairs = reader.items(value, f"{path}.clutch", "a list of pairs [link, link]") or []
    if pairs and not any(isinstance(pair, list) for pair in pairs):
        # Names where pairs are expected (`clutch: c2`, `clutch: [r1, s]`): one problem, not one per name.
        shown = f"[[{', '.join(_as_written(n) for n in pairs)}]]" if len(pairs) == 2 else ""
        shown = shown if 0 < len(shown) <= 80 else "[[LINK, LINK]]"
        reader.problem(f"{path}.clutch", f"a clutch is a pair of links inside the list: write clutch: {shown}")
        pairs = []
    for i, pair in enumerate(pairs):
        found = _members(pair, f"{path}.clutch[{i}]", reader, links)
        if len(found) != 2 or found[0] == found[1]:
            reader.problem(f"{path}.clutch[{i}]", "a clutch joins two different links: [link, link]")
        else:
            clutch.append((found[0], found[1]))
    return clutch


def _text(entry: Mapping[str, Any], key: str, path: str, reader: EntryReader) -> str:
    """A free text of an entry (a description): a string; anything else is refused."""
    value = entry.get(key, "")
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return str(value)  # a number reads as its text
    if not isinstance(value, str):
        reader.problem(f"{path}.{key}", f"expected text, got {describe(value)}")
        return ""
    return value
