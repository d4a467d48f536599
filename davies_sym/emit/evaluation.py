"""The answer of ``derive --eval``: the variant that holds, the speed ratio and the
efficiency at given values, or the reason there is none.

The decision is the variant set's (`VariantSet.design_point`), the same for the Python
API: a design the formulas do not cover (a port that does not turn, a self-locking
train) is `NotCoveredError` (exit status 3); values that break a geometric constraint
are `DesignError` (exit status 2).  Nothing outside (0, 1] is returned as an efficiency.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import sympy

from davies_sym.efficiency.variant_result import Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.variant_report import condition_text


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
    """The variant, speed ratio and efficiency at ``values`` with ``port`` as input: the
    variant set's own decision (`VariantSet.design_point`), with its conditions in words."""
    point = variants.design_point(values, port)
    conditions = tuple(condition_text(variants, point.variant))
    return Evaluation(point.input, point.output, point.variant, conditions, point.speed_ratio, point.efficiency)
