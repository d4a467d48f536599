"""Power lost in each friction element, as a fraction of the input power, per variant.

The power through a coupling is its action screw paired with its motion screw (Laus
eqs. (5), (27)-(29)); a lossless coupling does none, so the port powers and the powers
of the friction elements balance: P_in + P_out + sum_k P_k = 0.  The loss of element k
is -P_k, the power of its friction actions alone, and with the ordinary efficiencies of
a variant substituted for the friction coefficients (eqs. (74)-(75)) the fractions
-P_k / P_in add up to 1 - eta.  The action null space does not depend on which port is
called the input, so a variant with the other input uses the same solution divided by
the other port's power (unless friction laws besides the meshes' made the swapped
derivation differ).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.light_load import Derivation
from davies_sym.efficiency.operating_point import at_operating_point, substituted
from davies_sym.efficiency.variant_result import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.network.analysis import Analysis


def lossy_couplings(variants: VariantSet) -> tuple[str, ...]:
    """The couplings with a friction law, in the order of the file."""
    names = {law.coupling for law in variants.analysis.network.laws}
    return tuple(c.name for c in variants.train.couplings if c.name in names)


def _friction_actions(analysis: Analysis, coupling: str) -> list[str]:
    """The actions of ``coupling``'s friction elements: their power is its loss (the
    coupling's other actions are reactions, which do no work in its motion, and at a port
    the outside's torque)."""
    return [law.variable for law in analysis.network.laws if law.coupling == coupling]


@dataclass(frozen=True, eq=False)
class _InputSide:
    """What every variant with one input port shares: -P_k / P_in in the friction
    coefficients, and the coefficients in ordinary efficiencies."""

    forms: Mapping[str, RationalFunction]
    zetas: Mapping[tuple[str, bool], RationalFunction]


def _input_side(variants: VariantSet, port: str, derivation: Derivation) -> _InputSide:
    """-P_k / P_in with ``port`` as input, from ``derivation`` (the variant's own, or the
    declared input's when only the meshes' friction makes the two sides alike)."""
    analysis = derivation.analysis
    p_in = analysis.port_power_rf(port)
    forms = {
        name: at_operating_point(-(analysis.power_rf(name, _friction_actions(analysis, name)) / p_in), analysis)
        for name in lossy_couplings(variants)
    }
    return _InputSide(forms, derivation.zetas)


def _substituted(variants: VariantSet, side: _InputSide, variant: Variant) -> dict[str, RationalFunction]:
    return {
        name: substituted(form, variants.roles, side.zetas, variant.first_drives) for name, form in side.forms.items()
    }


def loss_fractions(variants: VariantSet, variant: Variant) -> dict[str, RationalFunction]:
    """-P_k / P_in of every lossy coupling k in ``variant``."""
    return _substituted(variants, _input_side(variants, variant.input, variants.derivation_of(variant)), variant)


def all_loss_fractions(variants: VariantSet) -> dict[str, dict[str, RationalFunction]]:
    """`loss_fractions` of every variant (by name), each derivation's side solved once."""
    sides: dict[tuple[str, int], _InputSide] = {}
    out = {}
    for v in variants.variants:
        derivation = variants.derivation_of(v)
        key = (v.input, id(derivation))
        if key not in sides:
            sides[key] = _input_side(variants, v.input, derivation)
        out[v.name] = _substituted(variants, sides[key], v)
    return out
