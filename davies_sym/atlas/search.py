"""The tooth-number search over the whole atlas: every train of up to N links, every held
member and both directions between two others, ranked by the closed-form efficiency.

Each train is written with tooth numbers (module 1) and fixed ordinary mesh
efficiencies; a state's efficiency is derived only when its speed ratio, from the motions
alone, can reach the target within the bounds, and its best tooth numbers are found
best-first (`davies_sym.synthesis.bounded_search`) within a bounded work: exact where the
search finishes, and said otherwise.  A gear on which neither the ratio nor the efficiency
depends is held at its least teeth (`SearchProblem.idle_fixed`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

from davies_sym.atlas.atlas_entries import Entry, GraphPlace, entry, places
from davies_sym.atlas.idle_meshes import loadable_uses
from davies_sym.atlas.train_file import Choice, ToothedForm, TrainFile, train_text
from davies_sym.errors import NotCoveredError
from davies_sym.fan_out import IN_THIS_PROCESS, Counted, Workers, fan_out
from davies_sym.geometry.dependent import resolved_train
from davies_sym.progress import Progress, silent
from davies_sym.synthesis.best_first import BUDGET
from davies_sym.synthesis.bounded_search import best_designs, ratio_reachable
from davies_sym.synthesis.formulas import state_formulas, state_motion
from davies_sym.synthesis.problem import SearchProblem, search_problem, tooth_symbols
from davies_sym.synthesis.tooth_search import Candidate, run_search

#: Ordinary efficiencies of the meshes (an external spur mesh loses about 2 %, an
#: internal one about half as much), as in the search example of docs/search.md.
MESHES = ToothedForm(external="0.98", internal="0.99")


@dataclass(frozen=True)
class AtlasQuestion:
    """What the atlas search asks: one speed ratio within a tolerance, every tooth number
    within ``teeth`` (inclusive)."""

    target: Fraction
    tolerance: Fraction
    teeth: tuple[int, int]
    planets: int | None
    min_teeth: int
    meshes: ToothedForm = MESHES
    #: Designs kept per train and direction: the best, so that the ranking lists
    #: different trains and uses, not one train with its idle gears resized.
    per_state: int = 1
    #: Designs scored plus boxes bounded per train and direction before its search stops
    #: unfinished (`davies_sym.synthesis.best_first`).
    budget: int = BUDGET


@dataclass(frozen=True)
class AtlasDesign:
    """A feasible design: which train, which use of it, and its tooth numbers."""

    train: str
    links: int
    code: str
    choice: Choice
    candidate: Candidate
    #: The train file searched: tooth symbols, every direction of the train as a state.
    searched: TrainFile
    #: The highest efficiency a design not scored could reach when the search of this
    #: direction stopped at its budget; -inf: it finished, the design is the best.
    unexplored: float = -math.inf

    @property
    def proven(self) -> bool:
        """Whether no other design of this train and direction scores higher."""
        return self.unexplored == -math.inf

    def document(self) -> dict[str, Any]:
        return {
            "train": self.train,
            "links": self.links,
            "code": self.code,
            "held": self.choice.held,
            "input": self.choice.input,
            "output": self.choice.output,
            "state": self.choice.name,
            **self.candidate.document(),
            "proven_best": self.proven,
            "unexplored_bound": None if self.proven else self.unexplored,
        }


def oriented(choices: tuple[Choice, ...]) -> tuple[Choice, ...]:
    """Each choice in both directions (the input first)."""
    return tuple(c for x in choices for c in (x, Choice(x.held, x.output, x.input)))


def search_file(e: Entry, choices: tuple[Choice, ...], meshes: ToothedForm) -> TrainFile:
    """The train file of ``e`` with tooth numbers, ``choices`` as its states and the free
    tooth numbers (those the geometry does not fix) listed in ``independent:``."""
    title = f"{e.name} (tooth numbers to choose)"
    source = f"derive search --atlas: {e.name}"
    written = TrainFile(e.drawn, title, source, choices, e.planar, e.free_axes, meshes, order=e.order)
    train = written.train()
    fixed = {str(r.symbol) for r in resolved_train(train).dependent or ()}
    return replace(written, independent=tuple(sorted(str(s) for s in tooth_symbols(train) if str(s) not in fixed)))


@dataclass(frozen=True)
class TrainDesigns:
    """What the search of one train found: the best designs of each direction, and the
    directions (``train state``) whose search stopped at its budget before it found
    whether their ratio can reach the target."""

    designs: tuple[AtlasDesign, ...] = ()
    undecided: tuple[str, ...] = ()
    #: Directions whose efficiency is not derived (``train state: reason``): a closed
    #: form past the work bound, as `derive` refuses it with exit status 3.
    refused: tuple[str, ...] = ()


def _entry_designs(e: Entry, question: AtlasQuestion) -> TrainDesigns:
    """The best designs of every direction of every loaded choice of one train (no gear
    idle: an idle one makes it a train of fewer links, searched there): the train
    written and read once with every direction as a state."""
    directions = oriented(e.loaded)
    if not directions:
        return TrainDesigns()
    searched = search_file(e, directions, question.meshes)
    train = searched.train()
    free = searched.independent or ()
    every = search_problem(
        train,
        [(choice.name, question.target) for choice in directions],
        question.tolerance,
        dict.fromkeys(free, question.teeth),
        question.planets,
        question.min_teeth,
    )
    designs: list[AtlasDesign] = []
    undecided: list[str] = []
    refused: list[str] = []
    for choice, target in zip(directions, every.targets, strict=True):
        # Each direction searched alone, its state one of the whole train's: the states
        # share what the train gives (its layout, resolved radii, sampled points).
        problem = replace(every, targets=(target,))
        try:
            found = _direction_designs(problem, choice.name, question)
        except NotCoveredError as exc:
            refused.append(f"{e.name} {choice.name}: {exc}")
            continue
        if found is None:
            undecided.append(f"{e.name} {choice.name}")
            continue
        candidates, unexplored = found
        designs += [AtlasDesign(e.name, e.links, e.code, choice, c, searched, unexplored) for c in candidates]
    return TrainDesigns(tuple(designs), tuple(undecided), tuple(refused))


def _direction_designs(
    problem: SearchProblem, state: str, question: AtlasQuestion
) -> tuple[tuple[Candidate, ...], float] | None:
    """The best designs of one direction and the highest efficiency a design not scored
    could reach (-inf: none), its efficiency derived only where the ratio can be reached;
    None where the budget ran out before that was found, or before a design that runs."""
    ratio, singular = state_motion(problem, state)
    reads = set(ratio.free_symbols).union(*(x.free_symbols for x in singular))
    reachable = ratio_reachable(problem.idle_fixed(reads), [ratio], singular, question.budget)
    if not reachable:
        return None if reachable is None else ((), -math.inf)
    formulas = state_formulas(problem)
    used = reads.union(*(v.free_symbols for f in formulas for v in f.variants))
    narrowed = problem.idle_fixed(used)
    best = best_designs(narrowed, formulas, question.per_state, question.budget)
    result = run_search(narrowed, best=question.per_state, feasible=best.feasible, formulas=formulas)
    if not result.candidates and best.unexplored > -math.inf:
        return None  # stopped before any design that runs was scored: nothing is known
    return result.candidates[: question.per_state], best.unexplored


@dataclass(frozen=True)
class SearchTask:
    """One train of the atlas and the question asked of it: a worker's task."""

    place: GraphPlace
    question: AtlasQuestion


def _designs_of(task: SearchTask) -> TrainDesigns:
    # A graph whose every use idles a gear at generic ratios idles one in any drawing:
    # nothing to search, and nothing to draw (most trains of 8 links).
    if not loadable_uses(task.place.graph):
        return TrainDesigns()
    e = entry(task.place)
    return TrainDesigns() if e.not_drawable else _entry_designs(e, task.question)


@dataclass(frozen=True)
class SearchFailure:
    """A train whose search raised past every refusal (a fault of the engine): reported
    with its cause, and the other trains are still searched."""

    train: str
    error: Exception


@dataclass(frozen=True)
class AtlasSearch:
    """The feasible designs, best first (score, then ratio error, then size), how many
    trains were searched, those whose search failed and the directions left undecided
    or refused (`TrainDesigns`)."""

    designs: tuple[AtlasDesign, ...]
    trains: int
    failures: tuple[SearchFailure, ...] = ()
    undecided: tuple[str, ...] = ()
    refused: tuple[str, ...] = ()


def _failure(task: SearchTask, exc: Exception) -> TrainDesigns | SearchFailure:
    return SearchFailure(task.place.name, exc)


def atlas_search(
    most_links: int, question: AtlasQuestion, workers: Workers = IN_THIS_PROCESS, say: Progress = silent
) -> AtlasSearch:
    """Every feasible design of every atlas train of up to ``most_links`` links."""
    tasks = [SearchTask(p, question) for links in range(4, most_links + 1) for p in places(links)]
    say(f"searching {len(tasks)} trains of 4 to {most_links} links")
    designs: list[AtlasDesign] = []
    failures: list[SearchFailure] = []
    undecided: list[str] = []
    refused: list[str] = []
    for found in fan_out(_designs_of, tasks, workers, Counted(say, "train"), _failure):
        if isinstance(found, SearchFailure):
            failures.append(found)
        else:
            designs += found.designs
            undecided += found.undecided
            refused += found.refused
    # Among equals the train of fewer links comes first (an extra link that carries no
    # power leaves the efficiency as it is).
    designs.sort(
        key=lambda d: (-d.candidate.score, d.candidate.ratio_error, d.links, d.candidate.size, d.train, d.choice.name)
    )
    return AtlasSearch(tuple(designs), len(tasks), tuple(failures), tuple(undecided), tuple(refused))


def design_file(design: AtlasDesign, rank: int) -> str:
    """The design as a train file with numbers (its direction the only state and the
    ports), which ``derive`` evaluates to the efficiency it was ranked by."""
    title = f"{design.train} {design.choice.name} (design {rank})"
    written = replace(design.searched, title=title, choices=(design.choice,), independent=None)
    data = written.document()
    for gear in data["gears"].values():
        gear["teeth"] = design.candidate.teeth[gear["teeth"]] if isinstance(gear["teeth"], str) else gear["teeth"]
    state = data["states"][design.choice.name]
    note = (
        f"Design {rank} of derive search --atlas: {design.train}, {state['description']}; "
        f"efficiency {design.candidate.score:.6f}, speed ratio {float(design.candidate.ratios[design.choice.name]):.6f}"
    )
    return train_text(data, note)
