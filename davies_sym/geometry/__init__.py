"""Geometry stage: where every axis and pitch point of a train lies -> :class:`Layout`.

It owns the positions and directions the coupling screws need, the geometric
constraints the loops of meshes imply (Laus section 3.4.1.6: r1 - r3 = r2 - r4) and
the square roots a tilted axis brings (Laus App. C).  Three layouts: trains drawn on
one line (Laus Figs. 5 and 7), planar trains in 2-D (:mod:`.plane`) and trains whose
axes meet at one apex (:mod:`.cone`, Laus Fig. 9, Chen Fig. 4.10).
"""

from __future__ import annotations

from davies_sym.geometry.cone import conical_layout
from davies_sym.geometry.layout import GeometricConstraint, Layout
from davies_sym.geometry.line import planar_line_layout
from davies_sym.geometry.plane import plane_layout
from davies_sym.topology.model import Train

__all__ = ["GeometricConstraint", "Layout", "train_layout"]


def train_layout(train: Train) -> Layout:
    """The layout of ``train``: conical when its gears give axis directions, else planar."""
    if any(g.axis is not None or g.tilted for g in train.gears):
        return conical_layout(train)
    if train.placement is not None:
        return plane_layout(train, train.placement)
    return planar_line_layout(train)
