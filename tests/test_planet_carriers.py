"""Which link carries which planet, and which link holds the two gear axes of each mesh, in
the catalog's planetary trains: the one answer the layouts, the virtual power of the meshes
(`davies_sym.efficiency.virtual_power.find_carrier`) and the planet sets of the search
(`davies_sym.synthesis.planet_sets`) share.  Every expected value is read by hand from the
train files' couplings (the revolute that pins each planet, the links each mesh joins)."""

from __future__ import annotations

import pytest

import davies_sym
from davies_sym.efficiency.virtual_power import find_carrier
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.synthesis.planet_sets import planet_sets
from davies_sym.topology.coupling_kinds import as_toothed_mesh
from davies_sym.topology.states import train_in_state

from conftest import catalog_path

#: Planet -> (its carrier, the revolute that pins it there), as each file writes them.
PLANETS = {
    # E: {links: [c, ps], axis: ps}, F: {links: [c, pl], axis: pl}
    "ravigneaux": {"ps": ("c", "E"), "pl": ("c", "F")},
    # H: {links: [p1, o], axis: p1} (o: front carrier and rear ring), J: {links: [p2, c2]}
    "simpson": {"p1": ("o", "H"), "p2": ("c2", "J")},
    # F: {links: [p, c]}
    "wolfrom": {"p": ("c", "F")},
    # P: {links: [3, 2]} (link 3: the arm)
    "planetary_simple": {"2": ("3", "P")},
}

#: Mesh -> the link holding both of its gear axes: the carrier of the planet it meshes.
MESH_CARRIERS = {
    "ravigneaux": {"G1": "c", "G2": "c", "G3": "c", "G4": "c"},
    "simpson": {"C": "o", "D": "o", "E": "c2", "F": "c2"},
    "wolfrom": {"C": "c", "D": "c", "E": "c"},
    "planetary_simple": {"G": "3"},
}

#: A state of each train with states in which every planet still turns in its carrier.
TURNING_STATE = {"ravigneaux": "second", "simpson": "second"}


def _train(name: str) -> davies_sym.Train:
    return resolved_train(davies_sym.load(catalog_path(name)))


@pytest.mark.parametrize("name", sorted(PLANETS))
def test_planet_sets_name_each_planets_carrier_and_pin(name: str) -> None:
    """The planet sets hold every planet of the file with its carrier and its pin."""
    train = _train(name)
    found = {p: (s.carrier, s.pivots[p]) for s in planet_sets(train, train_layout(train)) for p in s.planets}
    assert found == PLANETS[name]


@pytest.mark.parametrize("name", sorted(MESH_CARRIERS))
def test_virtual_power_measures_each_mesh_from_its_carrier(name: str) -> None:
    """The virtual power of each mesh is measured from the link holding both gear axes."""
    train = davies_sym.load(catalog_path(name))
    if name in TURNING_STATE:
        train = train_in_state(train, TURNING_STATE[name])
    analysis = davies_sym.analyse(train)
    meshes = [m for c in analysis.train.couplings if (m := as_toothed_mesh(c)) is not None]
    assert {m.name: find_carrier(analysis, m)[0] for m in meshes} == MESH_CARRIERS[name]


def test_locked_set_turns_in_no_carrier() -> None:
    """Ravigneaux third gear (both suns clutched): the set turns as one block, every link
    but the housing, so no gear turns in the link the mesh is measured from, a member of
    the block other than the mesh's own two links."""
    analysis = davies_sym.analyse(train_in_state(davies_sym.load(catalog_path("ravigneaux")), "third"))
    block = {"s1+s2", "c", "ps", "pl", "r"}
    meshes = [m for c in analysis.train.couplings if (m := as_toothed_mesh(c)) is not None]
    assert [m.name for m in meshes] == ["G1", "G2", "G3", "G4"]
    for mesh in meshes:
        carrier, sides = find_carrier(analysis, mesh)
        assert carrier in block - set(mesh.links), mesh.name
        assert all(x.is_zero() for twist in sides for x in twist), mesh.name
