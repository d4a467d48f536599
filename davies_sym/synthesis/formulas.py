"""The closed forms a search evaluates, one set per state: the speed ratio as a rational
function of the free tooth numbers, and the generated formula module whose vectorised
``efficiency`` ranks the designs (the variant that holds picked element by element).

Deriving the states is the search's longest step (seconds each for a multi-speed set):
they are fanned out (`davies_sym.fan_out`); each worker hands back text (the module's
source, the ratio), which this process compiles.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import ModuleType

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.errors import InputError
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.network.analysis import analyse
from davies_sym.network.motion_singularities import vanishing_denominators
from davies_sym.progress import Progress, silent
from davies_sym.synthesis.problem import SearchProblem, Target
from davies_sym.topology.loader import load
from davies_sym.topology.model import State, Train
from davies_sym.topology.states import train_in_state


@dataclass(frozen=True)
class DerivedState:
    """What a worker hands back for one state: text only (cheap to send)."""

    state: str | None
    port: str
    ratio: str
    #: The formula module for scoring (`python_module` with ``scoring``: its efficiency
    #: and variant choice, no gradient or losses).
    source: str
    #: Parameters of the formulas that are not tooth numbers (the file must fix them).
    others: tuple[str, ...]
    #: The efficiency of every variant of the input port (srepr), whichever holds.
    variants: tuple[str, ...] = ()
    #: The denominators of the motions that can vanish (srepr, `vanishing_denominators`).
    singular: tuple[str, ...] = ()


@dataclass(frozen=True)
class StateTask:
    """One state to derive: the train, or the path of its file for a worker in another
    process (a train object does not travel between processes), the state's name (None:
    the train as written) and the tooth-number symbols (the others must be numbers)."""

    train: Train | str
    state: str | None
    teeth: frozenset[str]


def derive_state(task: StateTask) -> DerivedState:
    """Derive the task's train in its state (Laus Tables 5 and 6) and write its formula
    module."""
    train = load(task.train) if isinstance(task.train, str) else task.train
    chosen = next((s for s in train.states if s.name == task.state), None)
    return derived_in_state(train, chosen, task.teeth)


def derived_in_state(train: Train, chosen: State | None, teeth: frozenset[str]) -> DerivedState:
    """The formulas of ``train`` in the operating state ``chosen`` (None: as written),
    which need not be one of the file's states (a gear the shift search proposes)."""
    if chosen is not None and chosen not in train.states:
        train = replace(train, states=(chosen,))
    in_state = train_in_state(train, chosen) if chosen is not None else train
    variants = derive_variants(in_state)
    others = tuple(sorted(str(s) for s in variants.parameters if str(s) not in teeth))
    ratio = sympy.srepr(variants.analysis.speed_ratio().to_expr())
    name = chosen.name if chosen is not None else None
    port = in_state.ports.input
    singular = tuple(sympy.srepr(d) for d in vanishing_denominators(variants.analysis))
    if others:
        return DerivedState(name, port, ratio, "", others, singular=singular)
    forms = tuple(sympy.srepr(v.efficiency_rf.to_expr()) for v in variants.variants if v.input == port)
    return DerivedState(name, port, ratio, python_module(variants, scoring=True), others, forms, singular)


@dataclass(frozen=True, eq=False)
class StateFormulas:
    """The formulas of one target's state."""

    target: Target
    port: str
    #: Input speed over output speed, in the free tooth numbers.
    ratio: sympy.Expr
    module: ModuleType
    #: The efficiency of each variant of the port in the free tooth numbers: where a
    #: design runs, its efficiency is one of them (what a best-first search bounds).
    variants: tuple[sympy.Expr, ...] = ()
    #: Polynomials in the free tooth numbers that vanish where the motions do not hold.
    singular: tuple[sympy.Expr, ...] = ()

    def efficiency(self, teeth: Mapping[str, NDArray[np.int64] | NDArray[np.float64]]) -> NDArray[np.float64]:
        """The efficiency at every design of ``teeth`` (arrays by name); NaN where the
        train self-locks or no variant holds (the module's reasons)."""
        accepted = inspect.signature(self.module.efficiency).parameters
        given = {name: values.astype(float) for name, values in teeth.items() if name in accepted}
        return np.asarray(self.module.efficiency(input=self.port, errors="ignore", **given), dtype=float)


def _derived(problem: SearchProblem, workers: Workers, say: Progress) -> list[DerivedState]:
    teeth = frozenset(str(s) for s in (*problem.free, *(s for s, _ in problem.dependent)))
    train = problem.train
    # A worker reads the file itself; a train not read from a file is derived here.
    path = train.path if train.path and os.path.isfile(train.path) else None
    if path is None or workers.here(len(problem.targets)):
        tasks = [StateTask(train, t.state, teeth) for t in problem.targets]
        workers = IN_THIS_PROCESS
    else:
        tasks = [StateTask(path, t.state, teeth) for t in problem.targets]
    say(f"deriving {len(tasks)} state(s) {workers.describe(len(tasks))}")
    counted = Counted(say, "state", lambda d: f"derived {'state ' + d.state if d.state else 'the train'}")
    return list(fan_out(derive_state, tasks, workers, counted))


def state_formulas(
    problem: SearchProblem, progress: Progress = silent, workers: Workers = IN_THIS_PROCESS
) -> tuple[StateFormulas, ...]:
    """Derive every target's state once (by ``workers``) and compile its module."""
    derived = _derived(problem, workers, progress)
    others = sorted({o for d in derived for o in d.others})
    if others:
        why = (
            f"the efficiency needs {', '.join(others)} besides the tooth numbers: write them as numbers in the file "
            "(a mesh's `efficiency: 0.98`)"
        )
        raise InputError([problem.train.symbol_problem(others[0], why)], problem.train.path)
    substitution = dict(problem.dependent)
    out = []
    for target, d in zip(problem.targets, derived, strict=True):
        ratio = sympy.cancel(_symbols_of(problem.train, sympy.sympify(d.ratio)).subs(substitution))
        forms = tuple(_symbols_of(problem.train, sympy.sympify(v)).subs(substitution) for v in d.variants)
        singular = tuple(_symbols_of(problem.train, sympy.sympify(x)).subs(substitution) for x in d.singular)
        module = compiled_module(d.source, problem.train.name)
        out.append(StateFormulas(target, d.port, ratio, module, forms, singular))
    return tuple(out)


def state_ratio(problem: SearchProblem, state: str | None) -> sympy.Expr:
    """The speed ratio of ``state`` in the free tooth numbers, from the motions alone (the
    null space of M_N): what a search over many trains asks before deriving any efficiency."""
    return state_motion(problem, state)[0]


def state_motion(problem: SearchProblem, state: str | None) -> tuple[sympy.Expr, tuple[sympy.Expr, ...]]:
    """The speed ratio of ``state`` and the denominators of every member's speed over the
    input's (Laus eq. (56)), in the free tooth numbers.  Where one of them vanishes the
    motions of the solution do not hold: the train does not move as one degree of freedom
    from its input there (it locks, or a member turns freely), whatever value the reduced
    ratio keeps."""
    train = problem.train
    chosen = next((s for s in train.states if s.name == state), None)
    in_state = train_in_state(train, chosen) if chosen is not None else train
    analysis = analyse(in_state)
    ratio = analysis.speed_ratio().to_expr()
    substitution = dict(problem.dependent)
    singular = tuple(_symbols_of(train, d).subs(substitution) for d in vanishing_denominators(analysis))
    return sympy.cancel(_symbols_of(train, ratio).subs(substitution)), singular


def _symbols_of(train: Train, expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with the train's own symbols (assumptions included) for those of its names."""
    return expr.xreplace({s: train.symbols[str(s)] for s in expr.free_symbols if str(s) in train.symbols})
