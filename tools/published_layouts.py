"""Geometries as printed in the sources, where they differ from the consistent one the
engine derives (to reproduce the published tables; see the README on Humpage)."""

from __future__ import annotations

import dataclasses

from davies_sym.algebra.screws import vector
from davies_sym.geometry import train_layout
from davies_sym.geometry.layout import Layout
from davies_sym.topology.model import Train


def laus_humpage_layout(train: Train) -> Layout:
    """The Humpage train (catalog ``humpage``) with Laus's printed planet axis p_G of
    eq. (80), pitch points of App. C: the geometry of Table 6 and Fig. 11."""
    layout = train_layout(train)
    r1, r2, r5 = (train.symbols[n] for n in ("r1", "r2", "r5"))
    s = layout.radicals[0].symbol
    printed = vector([0, -(r5 - r1) / (2 * r2), s / (2 * r2)])
    return dataclasses.replace(
        layout,
        coupling_axes={**layout.coupling_axes, "G": printed},
        gear_axes={**layout.gear_axes, "2": printed, "3": printed},
    )
