"""Angles of a mesh entry (helix, lead, normal pressure angle) with their cos and sin.

The trigonometric functions of an angle become symbols of their own (``cos_gamma``)
defined as ``cos(gamma)``, so the derivation stays polynomial and the outputs state the
definitions.  An angle written as a number is in degrees, strictly between 0 and 90; a
symbol stands for radians.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from davies_sym.errors import shortened
from davies_sym.losses.definitions import Definition
from davies_sym.topology.entries import describe
from davies_sym.topology.symbols import train_symbol

if TYPE_CHECKING:
    from davies_sym.topology.entries import EntryReader


@dataclass(frozen=True)
class AngleFunctions:
    """cos and sin of one angle of a mesh, as symbols defined by the angle."""

    angle: sympy.Expr
    cos: sympy.Symbol
    sin: sympy.Symbol
    #: What the angle is, for the definitions ("the lead angle of worm w (mesh W)").
    meaning: str = ""

    @property
    def definitions(self) -> tuple[Definition, Definition]:
        units = tuple((str(s), "rad") for s in sorted(self.angle.free_symbols, key=str))
        source = "gear geometry"
        return (
            Definition(self.cos, sympy.cos(self.angle), f"cosine of {self.meaning}", source, units),
            Definition(self.sin, sympy.sin(self.angle), f"sine of {self.meaning}", source, units),
        )


def read_angle(
    value: Any, path: str, reader: EntryReader, coupling: str, what: str, meaning: str
) -> AngleFunctions | None:
    """An angle of the entry with its cos and sin symbols: a number in degrees (strictly
    between 0 and 90), or a symbol or expression in radians."""
    limit = 90
    if isinstance(value, bool):
        reader.problem(path, f"expected an angle, got {describe(value)}")
        return None
    read = reader.quantity(value, path, "angle")
    if read is None:
        return None
    if read.is_number:
        if not 0 < read < limit:
            reader.problem(
                path, f"expected a number of degrees strictly between 0 and {limit}, got {shortened(str(value), 40)}"
            )
            return None
        angle = read * sympy.pi / 180
        # No symbol names this angle: c_ and s_, so that no output shows cos of a symbol.
        names = f"c_{what}_{coupling}", f"s_{what}_{coupling}"
    else:
        if read.could_extract_minus_sign():
            # A symbol stands for the size of its angle: its negative is no angle of the range.
            reader.problem(path, f"{shortened(str(value), 40)} is negative: write the angle itself, in (0, pi/2)")
            return None
        angle = read
        stem = str(read) if isinstance(read, sympy.Symbol) else f"{what}_{coupling}"
        names = f"cos_{stem}", f"sin_{stem}"
    cos, sin = (train_symbol(re.sub(r"\W", "_", n, flags=re.ASCII), "angle function", reader.symbols) for n in names)
    return AngleFunctions(angle, cos, sin, meaning)
