"""The answer of ``derive --eval``: the variant that holds, the speed ratio and the
efficiency at given values, or the reason there is none.

A design the formulas do not cover (a port that does not turn, a self-locking train) is
`NotCoveredError` (exit status 3); values that break a geometric constraint are
`DesignError` (exit status 2).  Nothing outside (0, 1] is returned as an efficiency.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import sympy

from davies_sym.efficiency.operating_point import INPUT_TORQUE
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.variant import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.variant_report import condition_text
from davies_sym.errors import DesignError, InputError, NotCoveredError, Problem
from davies_sym.losses.definitions import completed


@dataclass(frozen=True)
class Evaluation:
    """The efficiency of one variant at exact values, with ``input`` as the input port."""

    input: str
    output: str
    variant: Variant
    conditions: tuple[str, ...]
    speed_ratio: sympy.Expr
    efficiency: sympy.Expr

    def document(self) -> dict[str, object]:
        """The JSON answer (``--eval --json``): status, variant, both numbers and their exact values."""
        return {
            "status": "ok",
            "input": self.input,
            "output": self.output,
            "variant": {"number": self.variant.number, "name": self.variant.name, "conditions": list(self.conditions)},
            "speed_ratio": float(self.speed_ratio),
            "speed_ratio_exact": sympy.sstr(self.speed_ratio),
            "efficiency": float(self.efficiency),
            "efficiency_exact": sympy.sstr(self.efficiency),
        }

    def text(self) -> str:
        """Three lines: the variant, the speed ratio, and the efficiency alone (scripts read the last line)."""
        return (
            f"variant ({self.variant.number}): input {self.input}, output {self.output}\n"
            f"speed ratio ({self.input} over {self.output}): {float(self.speed_ratio)!r}\n"
            f"{float(self.efficiency)!r}\n"
        )


def evaluate(variants: VariantSet, values: Mapping[sympy.Symbol, sympy.Expr], port: str) -> Evaluation:
    """The variant, speed ratio and efficiency at ``values`` with ``port`` as input."""
    train = variants.train
    other = train.ports.output if port == train.ports.input else train.ports.input
    ratio_expr = variants.analysis.speed_ratio().to_expr()
    needed = formula_symbols(variants)
    missing = [str(s) for s in needed if s not in values]
    values = completed(values, train.definitions)
    if missing:
        raise InputError([Problem("--eval", f"missing values for {', '.join(missing)}")], train.path)
    for c in variants.analysis.network.layout.constraints:
        # A constraint no parameter could be solved for (a nonlinear one) is checked here.
        residual = sympy.expand(c.expression.subs(values))
        if residual.is_number and residual != 0:
            raise DesignError(
                [Problem("--eval", f"the values break the geometric constraint {c} (difference {residual})")],
                train.path,
            )
    ratio = ratio_expr.subs(values)
    ratio = ratio if port == train.ports.input else 1 / ratio
    if not (ratio.is_finite and ratio != 0):
        still = other if ratio != 0 else port
        raise NotCoveredError(
            f"port {still} does not turn at these values (speed ratio {port} over {other} "
            f"{'0' if ratio == 0 else 'infinite'}): no efficiency"
        )
    variant = variants.variant_for(values, port)
    value = variants.evaluate(values, port)
    if value <= 0 and INPUT_TORQUE in variant.efficiency.free_symbols:
        raise NotCoveredError(
            f"the input torque does not overcome the load-independent losses (drag, viscous or "
            f"bearing friction) at these values with {port} as input: variant ({variant.number}) "
            f"gives {sympy.N(value, 6)}; the output would have to put power in"
        )
    if not 0 < value <= 1:
        raise NotCoveredError(
            f"the train self-locks at these values with {port} as input: variant "
            f"({variant.number}) gives {sympy.N(value, 6)}, outside (0, 1]"
        )
    return Evaluation(port, other, variant, tuple(condition_text(variants, variant)), ratio, value)
