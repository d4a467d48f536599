"""The sensitivities of the program of a train driven at one port: each variant's exact
partial derivative of its efficiency in each parameter, and ``sensitivity_<name>(...,
input_port)``, the derivative of the variant the choice takes, as the Python module's
``sensitivity`` gives it."""

from __future__ import annotations

from collections.abc import Callable, Mapping

import sympy

from davies_sym.efficiency.parameters import given_parameters
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.languages.program import NOT_COVERED, Argument, Kind, Routine, Step
from davies_sym.emit.languages.routines import call, formula_routine
from davies_sym.emit.languages.text import identifier_part
from davies_sym.emit.languages.variant_choice_program import Choice, PortSignature, by_port, working


def sensitivity_routines(
    variants: VariantSet,
    public: Callable[[sympy.Expr], sympy.Expr],
    choices: list[Choice],
    signature: PortSignature,
) -> list[Routine]:
    """For each parameter: each variant's exact partial derivative of its efficiency, and
    ``sensitivity_<name>(..., input_port)``, the derivative of the variant the choice takes
    (where the efficiency is, else ``not_covered``), as the Python module's ``sensitivity``."""
    symbols = given_parameters(variants)
    names = signature.names
    out: list[Routine] = []
    for name in names:
        part = identifier_part(name)
        slopes = {
            v.name: formula_routine(
                f"{v.name}_d_{part}",
                f"partial derivative in {name} of the efficiency of variant ({v.number})",
                sympy.diff(public(v.efficiency), symbols[name]),
                names,
            )
            for v in variants.variants
        }
        out += slopes.values()
        per_port = [
            _port_sensitivity(name, port, choice, slopes, names)
            for port, choice in zip(signature.ports, choices, strict=True)
        ]
        out += per_port
        out.append(
            by_port(f"sensitivity_{part}", f"the partial derivative of the efficiency in {name}", per_port, signature)
        )
    return out


def _port_sensitivity(
    name: str, port: str, choice: Choice, slopes: Mapping[str, Routine], names: tuple[str, ...]
) -> Routine:
    """``sensitivity_<name>_from_<port>(...)``: the derivative in ``name`` of the variant
    the choice of ``port`` takes (``slopes``: each variant's), where it has an efficiency."""
    part = identifier_part(name)
    slope, value = choice.local(f"d_{part}"), choice.local(f"value_d_{part}")
    branches = [(call(slopes[v]), held) for v, held in zip(choice.order, choice.held, strict=True)]
    taken = sympy.Piecewise(*branches, (NOT_COVERED, True), evaluate=False)
    screened = sympy.Piecewise(
        (sympy.Symbol(slope), sympy.And(choice.ok, choice.turns, working(choice.chosen))),
        (NOT_COVERED, True),
        evaluate=False,
    )
    return Routine(
        f"sensitivity_{part}_from_{identifier_part(port)}",
        f"partial derivative in {name} of efficiency_from_{identifier_part(port)}",
        tuple(Argument(n, Kind.REAL) for n in names),
        Kind.REAL,
        (*choice.steps, Step(slope, Kind.REAL, taken), Step(value, Kind.REAL, screened)),
        sympy.Symbol(value),
    )
