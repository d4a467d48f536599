"""Power lost in each friction element, as a fraction of the input power, per variant.

The power through a coupling is its action screw paired with its motion screw (Laus
eqs. (5), (27)-(29)); a lossless coupling does none, so the port powers and the powers
of the friction elements balance: P_in + P_out + sum_k P_k = 0.  The loss of element k
is -P_k, and with the ordinary efficiencies of a variant substituted for the friction
coefficients (eqs. (74)-(75)) the fractions -P_k / P_in add up to 1 - eta.  The action
null space does not depend on which port is called the input, so a variant with the
other input uses the same solution divided by the other port's power (unless friction
laws besides the meshes' made the swapped derivation differ).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.variants import Variant, VariantSet, at_operating_point, substituted, zeta_forms
from davies_sym.efficiency.virtual_power import named_mesh_power_flow


def lossy_couplings(variants: VariantSet) -> tuple[str, ...]:
    """The couplings with a friction law, in the order of the file."""
    names = {law.coupling for law in variants.analysis.network.laws}
    return tuple(c.name for c in variants.train.couplings if c.name in names)


@dataclass(frozen=True, eq=False)
class _InputSide:
    """What every variant with one input port shares: -P_k / P_in in the friction
    coefficients, and the coefficients in ordinary efficiencies."""

    forms: Mapping[str, RationalFunction]
    zetas: Mapping[tuple[str, bool], RationalFunction]


def _input_side(variants: VariantSet, port: str) -> _InputSide:
    declared = port == variants.train.ports.input
    analysis = variants.analysis if declared or variants.swapped is None else variants.swapped
    if analysis is variants.analysis:
        flows = {r.coupling: r.flow for r in variants.roles}
    else:
        flows = {r.coupling: named_mesh_power_flow(analysis, r.coupling) for r in variants.roles}
    p_in = analysis.port_power_rf(port)
    forms = {name: at_operating_point(-(analysis.power_rf(name) / p_in), analysis)
             for name in lossy_couplings(variants)}
    return _InputSide(forms, zeta_forms(flows, variants.roles))


def _substituted(variants: VariantSet, side: _InputSide, variant: Variant) -> dict[str, RationalFunction]:
    return {name: substituted(form, variants.roles, side.zetas, variant.first_drives)
            for name, form in side.forms.items()}


def loss_fractions(variants: VariantSet, variant: Variant) -> dict[str, RationalFunction]:
    """-P_k / P_in of every lossy coupling k in ``variant``."""
    return _substituted(variants, _input_side(variants, variant.input), variant)


def all_loss_fractions(variants: VariantSet) -> dict[str, dict[str, RationalFunction]]:
    """:func:`loss_fractions` of every variant (by name), each input side solved once."""
    sides = {port: _input_side(variants, port) for port in (variants.train.ports.input, variants.train.ports.output)}
    return {v.name: _substituted(variants, sides[v.input], v) for v in variants.variants}
