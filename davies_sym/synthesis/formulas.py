"""The closed forms a search evaluates, one set per state: the speed ratio as a rational
function of the free tooth numbers, and the generated formula module whose vectorised
``efficiency`` ranks the designs (the variant that holds picked element by element).

Deriving the states is the search's longest step (seconds each for a multi-speed set):
they are derived in this process, on ``jobs`` processes or on a Dask cluster; each worker
hands back text (the module's source, the ratio), which this process compiles.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from types import ModuleType

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.errors import InputError, MissingDependencyError, Problem
from davies_sym.network.analysis import analyse
from davies_sym.synthesis.problem import SearchProblem, Target
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state

Progress = Callable[[str], None]
#: The first word of the message each derived state sends (a progress bar counts them).
DERIVED = "derived"


@dataclass(frozen=True)
class DerivedState:
    """What a worker hands back for one state: text only (cheap to send)."""

    state: str | None
    port: str
    ratio: str
    source: str
    #: Parameters of the formulas that are not tooth numbers (the file must fix them).
    others: tuple[str, ...]


def derive_state(train: Train | str, state: str | None, teeth: frozenset[str]) -> DerivedState:
    """Derive ``train`` (or the train file at that path, for a worker) in ``state`` (Laus
    Tables 5 and 6) and write its formula module."""
    train = load(train) if isinstance(train, str) else train
    chosen = next((s for s in train.states if s.name == state), None)
    in_state = train_in_state(train, chosen) if chosen is not None else train
    variants = derive_variants(in_state)
    others = tuple(sorted(str(s) for s in variants.parameters if str(s) not in teeth))
    ratio = sympy.srepr(variants.analysis.speed_ratio().to_expr())
    return DerivedState(state, in_state.ports.input, ratio, python_module(variants) if not others else "", others)


@dataclass(frozen=True, eq=False)
class StateFormulas:
    """The formulas of one target's state."""

    target: Target
    port: str
    #: Input speed over output speed, in the free tooth numbers.
    ratio: sympy.Expr
    module: ModuleType

    def efficiency(self, teeth: dict[str, NDArray[np.int64]]) -> NDArray[np.float64]:
        """The efficiency at every design of ``teeth`` (arrays by name); NaN where the
        train self-locks or no variant holds (the module's reasons)."""
        accepted = inspect.signature(self.module.efficiency).parameters
        given = {name: values.astype(float) for name, values in teeth.items() if name in accepted}
        return np.asarray(self.module.efficiency(input=self.port, errors="ignore", **given), dtype=float)


def _derived(problem: SearchProblem, jobs: int, scheduler: str | None, say: Progress) -> list[DerivedState]:
    teeth = frozenset(str(s) for s in (*problem.free, *(s for s, _ in problem.dependent)))
    states = [t.state for t in problem.targets]
    train = problem.train
    # A worker reads the file itself (a train object does not travel between processes).
    path = train.path if train.path and os.path.isfile(train.path) else None
    if scheduler is not None and path is not None:
        try:
            from dask.distributed import Client
        except ImportError:
            raise MissingDependencyError(
                "--scheduler needs dask.distributed (pip install 'davies_sym[dask]')"
            ) from None
        try:
            client = Client(scheduler, timeout="10s")  # type: ignore[no-untyped-call]
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(
                [Problem("--scheduler", f"cannot reach a Dask scheduler at {scheduler!r}: {exc}")]
            ) from None
        with client:
            say(f"deriving {len(states)} state(s) on the cluster at {scheduler}")
            submitted = [client.submit(derive_state, path, s, teeth, pure=False) for s in states]
            return list(client.gather(submitted))  # type: ignore[no-untyped-call]
    if jobs > 1 and len(states) > 1 and path is not None:
        say(f"deriving {len(states)} states on {min(jobs, len(states))} processes")
        with ProcessPoolExecutor(max_workers=min(jobs, len(states))) as pool:
            futures = {pool.submit(derive_state, path, s, teeth): k for k, s in enumerate(states)}
            done: dict[int, DerivedState] = {}
            for future in as_completed(futures):
                done[futures[future]] = future.result()
                say(f"{DERIVED} state {done[futures[future]].state} ({len(done)} of {len(states)})")
            return [done[k] for k in range(len(states))]
    out = []
    for k, s in enumerate(states):
        out.append(derive_state(train, s, teeth))
        say(f"{DERIVED} {'state ' + s if s else 'the train'} ({k + 1} of {len(states)})")
    return out


def state_formulas(
    problem: SearchProblem, progress: Progress | None = None, jobs: int = 1, scheduler: str | None = None
) -> tuple[StateFormulas, ...]:
    """Derive every target's state once and compile its module."""
    say = progress or (lambda message: None)
    derived = _derived(problem, jobs, scheduler, say)
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
        out.append(StateFormulas(target, d.port, ratio, compiled_module(d.source, problem.train.name)))
    return tuple(out)


def state_ratio(problem: SearchProblem, state: str | None) -> sympy.Expr:
    """The speed ratio of ``state`` in the free tooth numbers, from the motions alone (the
    null space of M_N): what a search over many trains asks before deriving any efficiency."""
    train = problem.train
    chosen = next((s for s in train.states if s.name == state), None)
    in_state = train_in_state(train, chosen) if chosen is not None else train
    ratio = analyse(in_state).speed_ratio().to_expr()
    return sympy.cancel(_symbols_of(train, ratio).subs(dict(problem.dependent)))


def _symbols_of(train: Train, expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with the train's own symbols (assumptions included) for those of its names."""
    return expr.xreplace({s: train.symbols[str(s)] for s in expr.free_symbols if str(s) in train.symbols})
