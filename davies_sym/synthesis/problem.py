"""The search asked for: free tooth numbers and their bounds, the dependent ones, the
target speed ratio of every state, the tolerance and the planet count, checked against
the train before any search (every refusal names the option, exit status 2)."""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction

import sympy

from davies_sym.errors import InputError, Problem
from davies_sym.geometry.dependent import resolved_train
from davies_sym.topology.model import Train

#: The fewest teeth on any gear unless ``--min-teeth`` says otherwise (spur gears with a
#: 20 degree pressure angle cut by a rack undercut below 17).
MIN_TEETH = 17


@dataclass(frozen=True)
class Target:
    """The speed ratio (input speed over output speed) wanted in one state (None: the
    file has no states), with its weight in the score."""

    state: str | None
    ratio: Fraction
    weight: float = 1.0


@dataclass(frozen=True)
class SearchProblem:
    """A checked search: ``free`` tooth numbers between their bounds (inclusive), the
    ``dependent`` ones as expressions of the free, the targets and the rules' settings."""

    train: Train
    free: tuple[sympy.Symbol, ...]
    bounds: Mapping[sympy.Symbol, tuple[int, int]]
    #: Tooth numbers the geometry fixes (a planet's: coaxial sun, planet and ring).
    dependent: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    targets: tuple[Target, ...]
    tolerance: Fraction
    planets: int | None = None
    min_teeth: int = MIN_TEETH

    @property
    def size(self) -> int:
        """How many designs the bounds hold (the product of the ranges)."""
        out = 1
        for low, high in self.bounds.values():
            out *= high - low + 1
        return out

    def window(self, target: Target) -> tuple[Fraction, Fraction]:
        """The ratios within the tolerance of ``target``."""
        spread = abs(target.ratio) * self.tolerance
        return target.ratio - spread, target.ratio + spread

    def idle_fixed(self, used: Collection[sympy.Symbol]) -> SearchProblem:
        """The problem with every free tooth number outside ``used`` (what the ratios and
        efficiencies depend on) held at its least admissible value.  Such a gear changes
        neither a ratio nor an efficiency, nor any dependent tooth number; of its designs the
        ranking prefers the smallest set, then the smallest teeth in order, both reached at
        its least value.  With ``planets`` nothing is held: the planet rules read every
        tooth number."""
        reads = set(used) | {x for _, e in self.dependent for x in e.free_symbols}
        if self.planets is not None:
            return self
        bounds = dict(self.bounds)
        for s in self.free:
            low, high = bounds[s]
            least = max(low, self.min_teeth)
            if s not in reads and least <= high:
                bounds[s] = (least, least)
        return replace(self, bounds=bounds)


def tooth_symbols(train: Train) -> dict[sympy.Symbol, list[str]]:
    """Each symbol that is a tooth number, with the gears it counts."""
    out: dict[sympy.Symbol, list[str]] = {}
    for g in train.gears:
        if isinstance(g.teeth, sympy.Symbol):
            out.setdefault(g.teeth, []).append(g.name)
    return out


def _refused(option: str, message: str, train: Train) -> InputError:
    return InputError([Problem(option, message)], train.path)


def _bounds(
    train: Train, teeth: Mapping[str, tuple[int, int]], free: Sequence[sympy.Symbol]
) -> dict[sympy.Symbol, tuple[int, int]]:
    names = {str(s): s for s in free}
    problems = []
    out = {}
    for name, (low, high) in teeth.items():
        if name not in names:
            known = ", ".join(sorted(names)) or "none"
            problems.append(Problem("--teeth", f"{name} is not a free tooth number of the train (free ones: {known})"))
        elif low > high:
            problems.append(Problem("--teeth", f"{name}={low}:{high} is an empty range: write LO:HI with LO <= HI"))
        elif low < 1:
            problems.append(Problem("--teeth", f"{name}={low}:{high}: a gear has at least one tooth"))
        else:
            out[names[name]] = (low, high)
    missing = [str(s) for s in free if str(s) not in teeth]
    if missing:
        problems.append(Problem("--teeth", f"give the bounds of {', '.join(missing)} (NAME=LO:HI)"))
    if problems:
        raise InputError(problems, train.path)
    return out


#: Largest speed ratio a target may name: far beyond any worm drive (a few thousand), and
#: small enough that the windows' integer bounds stay exact and bounded.
LARGEST_RATIO = 1_000_000


def _targets(
    train: Train, targets: Sequence[tuple[str | None, Fraction]], weights: Mapping[str, float]
) -> tuple[Target, ...]:
    states = [s.name for s in train.states]
    problems = []
    for state, ratio in targets:
        if ratio == 0:
            problems.append(
                Problem("--target", "a speed ratio of 0 is not a transmission: give the input over output speed")
            )
        elif abs(ratio) > LARGEST_RATIO:
            problems.append(
                Problem("--target", f"a speed ratio beyond {LARGEST_RATIO:,} in magnitude is no gear train's")
            )
        if states and state is None:
            problems.append(Problem("--target", f"the train has states ({', '.join(states)}): write STATE=RATIO"))
        elif not states and state is not None:
            problems.append(Problem("--target", f"the train has no states: write the ratio alone, not {state}={ratio}"))
        elif state is not None and state not in states:
            problems.append(Problem("--target", f"the train has no state {state!r} (it has: {', '.join(states)})"))
    named = [s for s, _ in targets]
    twice = sorted({str(s) for s in named if named.count(s) > 1})
    if twice:
        problems.append(Problem("--target", f"one target per state: {', '.join(twice)} has several"))
    missing = [s for s in states if s not in named]
    if missing and not problems:
        problems.append(Problem("--target", f"give a target for every state: {', '.join(missing)} has none"))
    for state, weight in weights.items():
        if state not in states:
            problems.append(Problem("--weights", f"the train has no state {state!r} to weigh"))
        elif not weight > 0:
            problems.append(Problem("--weights", f"the weight of {state} must be positive, got {weight}"))
    if not targets:
        problems.append(Problem("--target", "give the target speed ratio (input over output speed)"))
    if problems:
        raise InputError(problems, train.path)
    return tuple(Target(s, r, weights.get(s, 1.0) if s is not None else 1.0) for s, r in targets)


def search_problem(
    train: Train,
    targets: Sequence[tuple[str | None, Fraction]],
    tolerance: Fraction,
    teeth: Mapping[str, tuple[int, int]],
    planets: int | None = None,
    min_teeth: int = MIN_TEETH,
    weights: Mapping[str, float] | None = None,
) -> SearchProblem:
    """The search of ``train`` for ``targets`` ((state, ratio) pairs), checked.  Its
    seven parameters are ``derive search``'s options one for one (and the atlas search
    passes them so); each is checked and named by its option."""
    if tolerance < 0:
        raise _refused("--tolerance", f"a tolerance is a relative deviation >= 0, got {tolerance}", train)
    if planets is not None and planets < 1:
        raise _refused("--planets", f"the number of planets is at least 1, got {planets}", train)
    if min_teeth < 1:
        raise _refused("--min-teeth", f"a gear has at least one tooth, got {min_teeth}", train)
    symbols = tooth_symbols(train)
    if not symbols:
        why = "no gear has a symbolic tooth number (write `teeth: zs` with a `module:`)"
        raise InputError([train.problem("gears", why)], train.path)
    relations = {r.symbol: r.expression for r in resolved_train(train).dependent or ()}
    # Without `independent:` the free tooth numbers are those the geometry leaves free.
    chosen = {str(s) for s in symbols if s not in relations} if train.independent is None else set(train.independent)
    free = tuple(s for s in sorted(symbols, key=str) if str(s) in chosen)
    if not free:
        names = ", ".join(sorted(map(str, symbols)))
        raise InputError(
            [train.problem("independent", f"names none of the tooth numbers ({names}): list the free ones")],
            train.path,
        )
    dependent = []
    for s in sorted(symbols, key=str):
        if s in free:
            continue
        expression = relations.get(s)
        if expression is None or not expression.free_symbols <= set(free):
            why = f"the tooth number {s} is neither free (independent:) nor fixed by the geometry from the free ones"
            raise InputError([train.symbol_problem(str(s), why)], train.path)
        dependent.append((s, sympy.sympify(expression)))
    return SearchProblem(
        train,
        free,
        _bounds(train, teeth, free),
        tuple(dependent),
        _targets(train, targets, weights or {}),
        tolerance,
        planets,
        min_teeth,
    )
