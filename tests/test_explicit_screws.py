"""The low-level screw form (Laus App. B): Tuplin's train written with explicit unit screws
(tests/data/tuplin_screws.yaml) derives what its high-level description derives, every
variant included, and an action that does work on its motion is refused."""

from __future__ import annotations

import os

import davies_sym

from conftest import ROOT, equal, read_text, variant


def test_explicit_screws_of_tables_12_13_give_eq71():
    """Tuplin's train written with the unit screws of Laus Tables 12-13 gives the same
    efficiency as the high-level description (eq. (71), signed linear law)."""
    low = davies_sym.analyse(davies_sym.load(os.path.join(ROOT, "tests", "data", "tuplin_screws.yaml")))
    high = davies_sym.analyse(
        variant("tuplin", {"coulomb: zeta_C": "linear: zeta_C", "coulomb: zeta_D": "linear: zeta_D"})
    )
    assert low.network.unit_motion_matrix() == high.network.unit_motion_matrix()
    assert equal(low.efficiency, high.efficiency)


def test_explicit_screws_derive_every_variant_without_a_pole_crash():
    """Sampling the region of a train written as bare screws (no gear radii to keep the
    samples apart) can land on a pole of the formula (r1 = r2); that sample is skipped,
    not a crash.  Both variants are eq. (71) with the signs of the declared input."""
    train = davies_sym.load(os.path.join(ROOT, "tests", "data", "tuplin_screws.yaml"))
    variants = davies_sym.derive(train)
    assert [v.input for v in variants.variants] == ["A", "B"]
    forward = davies_sym.analyse(train).efficiency
    assert equal(variants.variants[0].efficiency, forward)
    assert equal(variants.variants[1].efficiency, 1 / forward)


def test_non_reciprocal_explicit_action_is_rejected():
    text = read_text(os.path.join(ROOT, "tests", "data", "tuplin_screws.yaml"))
    bad = text.replace("actions: {U_C: {T: -r1, U: 1}}", "actions: {U_C: {T: 1, U: 1}}")
    try:
        _ = davies_sym.analyse(davies_sym.loads(bad, "bad.yaml")).efficiency
    except davies_sym.TopologyError as exc:
        assert "does work on motion" in str(exc) and "couplings.C.actions" in str(exc)
    else:  # pragma: no cover
        raise AssertionError("a non-reciprocal action must be rejected")
