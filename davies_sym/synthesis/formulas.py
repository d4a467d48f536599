"""The closed forms a search evaluates, one set per state: the speed ratio as a rational
function of the free tooth numbers, and the generated formula module whose vectorised
``efficiency`` ranks the designs (the variant that holds picked element by element)."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass
from types import ModuleType

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.errors import InputError, Problem
from davies_sym.synthesis.problem import SearchProblem, Target
from davies_sym.topology.states import train_in_state

Progress = Callable[[str], None]


@dataclass(frozen=True, eq=False)
class StateFormulas:
    """The formulas of one target's state."""

    target: Target
    variants: VariantSet
    #: Input speed over output speed, in the free tooth numbers.
    ratio: sympy.Expr
    module: ModuleType

    @property
    def port(self) -> str:
        return self.variants.train.ports.input

    def efficiency(self, teeth: dict[str, NDArray[np.int64]]) -> NDArray[np.float64]:
        """The efficiency at every design of ``teeth`` (arrays by name); NaN where the
        train self-locks or no variant holds (the module's reasons)."""
        accepted = inspect.signature(self.module.efficiency).parameters
        given = {name: values.astype(float) for name, values in teeth.items() if name in accepted}
        return np.asarray(self.module.efficiency(input=self.port, errors="ignore", **given), dtype=float)


def state_formulas(problem: SearchProblem, progress: Progress | None = None) -> tuple[StateFormulas, ...]:
    """Derive every target's state once (Laus Tables 5 and 6 for each) and compile its module."""
    say = progress or (lambda message: None)
    whole = problem.train
    teeth = {*problem.free, *(s for s, _ in problem.dependent)}
    substitution = dict(problem.dependent)
    out = []
    for target in problem.targets:
        state = next((s for s in whole.states if s.name == target.state), None)
        train = train_in_state(whole, state) if state is not None else whole
        say(f"deriving {('state ' + target.state) if target.state else 'the train'}")
        variants = derive_variants(train)
        others = sorted(str(s) for s in variants.parameters if s not in teeth)
        if others:
            raise InputError(
                [
                    Problem(
                        "TRAIN",
                        f"the efficiency needs {', '.join(others)} besides the tooth numbers: "
                        "write them as numbers in the file",
                    )
                ],
                whole.path,
            )
        ratio = sympy.cancel(variants.analysis.speed_ratio().to_expr().subs(substitution))
        module = compiled_module(python_module(variants), train.name)
        out.append(StateFormulas(target, variants, ratio, module))
    return tuple(out)
