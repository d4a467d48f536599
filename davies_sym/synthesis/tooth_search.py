"""The whole search: candidates by exact-bound pruning, the rules checked exactly, the
efficiency of every state through the generated formulas (vectorised), the ranking and
the Pareto fronts."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np
import sympy
from numpy.typing import NDArray

from davies_sym.fan_out import IN_THIS_PROCESS, Workers
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train
from davies_sym.progress import Progress, silent
from davies_sym.synthesis import rules
from davies_sym.synthesis.design_enumeration import Window, enumerate_designs
from davies_sym.synthesis.exact_values import ExactRational
from davies_sym.synthesis.feasible_designs import ExactRules
from davies_sym.synthesis.formulas import StateFormulas, state_formulas
from davies_sym.synthesis.planet_sets import PlanetSet, planet_sets
from davies_sym.synthesis.problem import SearchProblem


@dataclass(frozen=True)
class Candidate:
    """A feasible design: every tooth number, and per state (None: no states) the exact
    speed ratio and the efficiency of the variant that holds."""

    teeth: Mapping[str, int]
    ratios: Mapping[str | None, Fraction]
    efficiencies: Mapping[str | None, float]
    #: Weighted mean of the efficiencies (the weights of the targets).
    score: float
    #: Largest relative deviation of a ratio from its target.
    ratio_error: float
    #: Teeth of the largest gear (a ring where there is one): the set's size.
    size: int

    def document(self) -> dict[str, object]:
        def by_state(values: Mapping[str | None, object]) -> object:
            return values[None] if None in values else dict(values)

        return {
            "teeth": dict(self.teeth),
            "speed_ratio": by_state({s: float(r) for s, r in self.ratios.items()}),
            "speed_ratio_exact": by_state({s: str(r) for s, r in self.ratios.items()}),
            "efficiency": by_state(self.efficiencies),
            "score": self.score,
            "ratio_error": self.ratio_error,
            "size": self.size,
        }


@dataclass(frozen=True)
class SearchResult:
    """Every feasible design, best first, and how the search went."""

    problem: SearchProblem
    candidates: tuple[Candidate, ...]
    #: Designs the bounds hold, and designs bounded one by one (the rest were pruned in blocks).
    searched: int
    examined: int
    rules: tuple[rules.Rule, ...]
    seconds: float
    planet_sets: tuple[PlanetSet, ...] = field(default=(), repr=False)

    def pareto(self, cost: Callable[[Candidate], float]) -> list[int]:
        """Indices (best first) of the candidates no other beats on both the score and ``cost``."""
        front, best_cost = [], math.inf
        for k, c in sorted(enumerate(self.candidates), key=lambda kc: (-kc[1].score, cost(kc[1]))):
            if cost(c) < best_cost:
                front.append(k)
                best_cost = cost(c)
        return front

    def document(self, top: int) -> dict[str, object]:
        return {
            "candidates": [c.document() for c in self.candidates[:top]],
            "searched": self.searched,
            "examined": self.examined,
            "feasible": len(self.candidates),
            "rules": [r.name for r in self.rules if r.applied],
            "rule_details": [r.document() for r in self.rules],
            "planet_sets": [s.name for s in self.planet_sets],
            "pareto": {
                "ratio_error": self.pareto(lambda c: c.ratio_error),
                "size": self.pareto(lambda c: c.size),
            },
            "seconds": self.seconds,
        }


def windows(problem: SearchProblem, ratios: Sequence[sympy.Expr]) -> list[Window]:
    """What a design must meet, as floats (the exact rules decide after them): each ratio
    within its target's window, every tooth number at least the minimum."""
    out = []
    for target, ratio in zip(problem.targets, ratios, strict=True):
        low, high = problem.window(target)
        out.append(Window(ratio, float(low), float(high)))
    for _, expression in problem.dependent:
        out.append(Window(expression, problem.min_teeth, math.inf))
    for s in problem.free:
        out.append(Window(s, problem.min_teeth, math.inf))
    return out


def planet_rules(problem: SearchProblem, sets: Sequence[PlanetSet]) -> list[rules.Rule]:
    """The assembly and tip-clearance rules, each applied or not and why not (no
    ``--planets``, no planet set, one planet)."""
    if problem.planets is None:
        note = "no --planets given"
    elif not sets:
        note = "the train has no planet set"
    else:
        note = ""
    applied = not note
    clearance_note = note or ("one planet: no neighbour" if problem.planets == 1 else "")
    return [
        rules.Rule(rules.ASSEMBLY, rules.MEANINGS[rules.ASSEMBLY], applied, note),
        rules.Rule(rules.TIP_CLEARANCE, rules.MEANINGS[rules.TIP_CLEARANCE], not clearance_note, clearance_note),
    ]


def _gear_columns(
    problem: SearchProblem, teeth: Mapping[str, NDArray[np.int64]], size: int
) -> dict[str, NDArray[np.int64]]:
    """Tooth numbers of every gear (by gear name) at every row: a number, a tooth symbol or
    an expression of them; a gear without teeth is left out."""
    out = {}
    for g in problem.train.gears:
        if g.teeth is None:
            continue
        value = sympy.sympify(g.teeth)
        symbols = sorted(value.free_symbols, key=str)
        if not {str(s) for s in symbols} <= set(teeth):
            continue
        evaluate = sympy.lambdify(symbols, value, "numpy")
        column = np.broadcast_to(np.asarray(evaluate(*(teeth[str(s)] for s in symbols))), (size,))
        out[g.name] = column.astype(np.int64)
    return out


def run_search(
    problem: SearchProblem,
    progress: Progress = silent,
    workers: Workers = IN_THIS_PROCESS,
    best: int | None = None,
    feasible: tuple[NDArray[np.int64], dict[str, NDArray[np.int64]], int] | None = None,
    formulas: Sequence[StateFormulas] | None = None,
) -> SearchResult:
    """Every feasible design of ``problem``, ranked (see the module's docstring); the states
    derived by ``workers``.  With ``best``,
    only the designs whose score reaches the ``best``-th highest (ties kept) are ranked,
    for a search over many trains that keeps a few designs of each; ``feasible``: what
    `ratio_feasible` gave for these ratios already; ``formulas``: the states derived
    already."""
    start = time.perf_counter()
    formulas = formulas or state_formulas(problem, progress, workers)
    whole_train = resolved_train(problem.train)
    sets = planet_sets(whole_train, train_layout(whole_train))
    free = problem.free
    planet_applied = planet_rules(problem, sets)
    singular = [x for f in formulas for x in f.singular]
    rows, teeth, examined = feasible or ratio_feasible(problem, [f.ratio for f in formulas], progress, singular)
    ratio_parts = [ExactRational.of(f.ratio, free) for f in formulas]
    rows, teeth = planet_filtered(problem, sets, rows, teeth)
    if best is not None and len(rows) > best:
        keep = _among_the_best(formulas, _in_gear_order(problem, teeth), best)
        rows, teeth = rows[keep], {k: t[keep] for k, t in teeth.items()}
    ratios = []
    for exact in ratio_parts:
        num, den = exact.rows(list(rows.T))
        ratios.append([Fraction(int(a), int(b)) for a, b in zip(num, den, strict=True)])
    ordered = _in_gear_order(problem, teeth)
    kept = [
        (
            {name: int(t[k]) for name, t in ordered.items()},
            {f.target.state: ratios[j][k] for j, f in enumerate(formulas)},
        )
        for k in range(len(rows))
    ]
    candidates = _ranked(problem, formulas, kept)
    applied = [
        rules.Rule(rules.WHOLE, rules.MEANINGS[rules.WHOLE]),
        rules.Rule(rules.MIN_TEETH, rules.MEANINGS[rules.MIN_TEETH]),
        rules.Rule(rules.RATIO, rules.MEANINGS[rules.RATIO]),
        *planet_applied,
        rules.Rule(rules.RUNS, rules.MEANINGS[rules.RUNS]),
    ]
    return SearchResult(problem, candidates, problem.size, examined, tuple(applied), time.perf_counter() - start, sets)


def planet_filtered(
    problem: SearchProblem, sets: Sequence[PlanetSet], rows: NDArray[np.int64], teeth: dict[str, NDArray[np.int64]]
) -> tuple[NDArray[np.int64], dict[str, NDArray[np.int64]]]:
    """The designs (``rows`` of free tooth numbers, ``teeth`` every tooth number by name)
    whose ``problem.planets`` planets assemble equally spaced and clear each other's
    tips, where the rules apply (`_planet_rules`)."""
    applied = [r.applied for r in planet_rules(problem, sets)]
    n = problem.planets
    gears = _gear_columns(problem, teeth, len(rows))
    if applied[0] and n is not None and len(rows):
        keep = rules.equally_spaced(sets, gears, n)
        rows, teeth, gears = rows[keep], {k: t[keep] for k, t in teeth.items()}, {k: g[keep] for k, g in gears.items()}
    if applied[1] and n is not None and len(rows):
        keep = np.ones(len(rows), dtype=bool)
        for pset in sets:
            for planet in pset.planets:
                radius = sympy.lambdify(problem.free, pset.orbit[planet], "numpy")
                orbit = np.broadcast_to(np.asarray(radius(*rows.T.astype(float)), dtype=float), (len(rows),))
                for g in problem.train.gears:
                    if g.link == planet and g.module is not None and g.name in gears:
                        keep &= rules.tips_clear(orbit, (float(g.module) * (gears[g.name] + 2.0)).astype(np.float64), n)
        rows, teeth = rows[keep], {k: t[keep] for k, t in teeth.items()}
    return rows, teeth


def ratio_feasible(
    problem: SearchProblem,
    ratios: Sequence[sympy.Expr],
    progress: Progress | None = None,
    singular: Sequence[sympy.Expr] = (),
) -> tuple[NDArray[np.int64], dict[str, NDArray[np.int64]], int]:
    """The designs whose tooth numbers are whole and large enough and whose speed ratios
    (one per target, in the free tooth numbers) lie within the tolerance, decided exactly:
    the rows of free tooth numbers, every tooth number by name, and the designs examined.
    Needs only the ratios, so a search over many trains derives the efficiency of those
    that can reach the targets alone."""
    enumeration = enumerate_designs(problem.free, dict(problem.bounds), windows(problem, ratios), progress)
    rows, teeth = ExactRules.of(problem, ratios, singular).feasible(enumeration.candidates)
    return rows, teeth, enumeration.examined


def design_scores(
    formulas: Sequence[StateFormulas], teeth: Mapping[str, NDArray[np.int64] | NDArray[np.float64]]
) -> NDArray[np.float64]:
    """The score of every design (the weighted mean of the states' efficiencies), -inf
    where a state does not run (`rules.runs`), in one vectorised call per state."""
    weights = np.array([f.target.weight for f in formulas])
    size = len(next(iter(teeth.values()))) if teeth else 1
    etas = {f.target.state: np.broadcast_to(f.efficiency(dict(teeth)), (size,)) for f in formulas}
    stacked = np.stack([etas[f.target.state] for f in formulas])
    score = weights @ np.where(np.isfinite(stacked), stacked, 0.0) / weights.sum()
    return np.where(rules.runs(etas), score, -np.inf)


def _among_the_best(
    formulas: Sequence[StateFormulas], teeth: Mapping[str, NDArray[np.int64]], best: int
) -> NDArray[np.bool_]:
    """The rows whose score (mean efficiency over the states, a state that does not run
    counted as -inf) is at least the ``best``-th highest."""
    score = design_scores(formulas, teeth)
    threshold = np.sort(score)[-best]
    return np.asarray(score >= threshold, dtype=bool)


def _in_gear_order(problem: SearchProblem, teeth: Mapping[str, NDArray[np.int64]]) -> dict[str, NDArray[np.int64]]:
    """The tooth numbers in the order their gears are written."""
    order = []
    for g in problem.train.gears:
        if isinstance(g.teeth, sympy.Symbol) and str(g.teeth) not in order:
            order.append(str(g.teeth))
    return {name: teeth[name] for name in order if name in teeth}


def _ranked(
    problem: SearchProblem,
    formulas: Sequence[StateFormulas],
    kept: Sequence[tuple[dict[str, int], dict[str | None, Fraction]]],
) -> tuple[Candidate, ...]:
    """Efficiencies in bulk (one vectorised call per state), the designs that run, best first."""
    if not kept:
        return ()
    names = list(kept[0][0])
    arrays = {n: np.array([t[n] for t, _ in kept], dtype=np.int64) for n in names}
    etas = {f.target.state: f.efficiency(arrays) for f in formulas}
    weights = {f.target.state: f.target.weight for f in formulas}
    total = sum(weights.values())
    internal = {g.name for g in problem.train.gears if g.internal}
    gears = _gear_columns(problem, arrays, len(kept))
    # The set's size: its largest ring where it has one, else its largest gear.
    sizes = np.max(np.stack([c for g, c in gears.items() if g in internal] or list(gears.values())), axis=0)
    etas = {s: np.broadcast_to(e, (len(kept),)) for s, e in etas.items()}
    running = rules.runs(etas)
    out = []
    for k, (teeth, ratios) in enumerate(kept):
        if not running[k]:
            continue
        efficiencies = {s: float(e[k]) for s, e in etas.items()}
        score = sum(weights[s] * e for s, e in efficiencies.items()) / total
        error = max(float(abs(ratios[f.target.state] - f.target.ratio) / abs(f.target.ratio)) for f in formulas)
        out.append(Candidate(teeth, ratios, efficiencies, score, error, int(sizes[k])))
    out.sort(key=lambda c: (-c.score, c.ratio_error, c.size, tuple(c.teeth.values())))
    return tuple(out)
