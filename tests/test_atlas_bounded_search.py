"""The atlas search's best-first route (`davies_sym.synthesis.bounded_search`) against
the whole enumeration of `derive search` (`ratio_feasible`: the joins of the windows'
tables, no box and no bound shared): the same best design wherever the best-first
search says it finished, also with gears neither the ratio nor the efficiency depends
on; a search stopped by its budget says so; and the best design of 8-link trains,
written as a file, evaluates with ``derive --eval`` to the efficiency it was ranked by."""

from __future__ import annotations

import math
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import pytest
from harness.helpers import run_main_in

from davies_sym.atlas import search
from davies_sym.atlas.atlas_entries import entry, places
from davies_sym.synthesis import best_first
from davies_sym.synthesis.formulas import state_ratio
from davies_sym.synthesis.problem import search_problem
from davies_sym.synthesis.tooth_search import ratio_feasible, run_search

QUESTION = search.AtlasQuestion(Fraction("12.5"), Fraction("0.2"), (17, 40), None, 17)


def _direction(name: str, state: str, question: search.AtlasQuestion):  # type: ignore[no-untyped-def]
    """The search problem of one direction of an atlas train, as the atlas search asks it."""
    return _searched(name, state, question)[0]


def _searched(name: str, state: str, question: search.AtlasQuestion):  # type: ignore[no-untyped-def]
    """The search problem of one direction, the atlas entry and the train file searched."""
    e = entry(next(p for p in places(int(name[5])) if p.name == name))
    directions = search.oriented(e.loaded)
    written = search.search_file(e, directions, question.meshes)
    train = written.train()
    chosen = next(s for s in train.states if s.name == state)
    problem = search_problem(
        replace(train, states=(chosen,)),
        [(state, question.target)],
        question.tolerance,
        dict.fromkeys(written.independent or (), question.teeth),
        question.planets,
        question.min_teeth,
    )
    return problem, e, written, next(c for c in directions if c.name == state)


def _whole_enumeration_best(problem, state: str):  # type: ignore[no-untyped-def]
    feasible = ratio_feasible(problem, [state_ratio(problem, state)])
    found = run_search(problem, best=1, feasible=feasible).candidates
    return (dict(found[0].teeth), found[0].score) if found else None


@pytest.mark.parametrize(
    ("name", "state", "teeth"),
    [
        ("atlas6_r02_d1", "h0_i2_o1", (17, 40)),  # the Simpson graph, the docs' best
        ("atlas6_r02_d1", "h5_i2_o0", (17, 40)),
        ("atlas5_r05_d3", "h2_i1_o3", (17, 40)),  # the Wolfrom graph
        ("atlas6_r10_d9", "h1_i5_o2", (17, 40)),
        ("atlas6_r02_d1", "h0_i1_o2", (17, 40)),  # a ratio no design reaches
        # Three planets whose teeth neither the ratio nor the efficiency reads.
        ("atlas7_r92_d23", "h1_i2_o3", (17, 24)),
    ],
)
def test_the_best_first_route_finds_the_whole_enumerations_best(
    name: str, state: str, teeth: tuple[int, int], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(best_first, "LEAF", 64)  # many boxes split and bounded
    question = replace(QUESTION, teeth=teeth)
    problem = _direction(name, state, question)
    expected = _whole_enumeration_best(problem, state)
    found = search._direction_designs(problem, state, question)
    assert found is not None
    candidates, unexplored = found
    assert unexplored == -math.inf  # finished: the answer is the best
    if expected is None:
        assert candidates == ()
    else:
        assert (dict(candidates[0].teeth), candidates[0].score) == expected


def test_the_idle_planets_are_held_at_their_least_teeth() -> None:
    problem = _direction("atlas7_r92_d23", "h1_i2_o3", replace(QUESTION, teeth=(15, 24)))
    ratio = state_ratio(problem, "h1_i2_o3")
    held = problem.idle_fixed(ratio.free_symbols)
    idle = [s for s in problem.free if s not in ratio.free_symbols]
    assert [str(s) for s in idle] == ["z4b", "z5c", "z6d"]
    assert all(held.bounds[s] == (17, 17) for s in idle)  # the least admissible, not 15
    assert all(held.bounds[s] == (15, 24) for s in problem.free if s not in idle)
    assert problem.idle_fixed(set(problem.free)) == problem
    assert replace(problem, planets=3).idle_fixed(()) == replace(problem, planets=3)  # the planet rules read them


@pytest.mark.slow  # the 8-link atlas is enumerated (half a minute)
def test_a_search_stopped_by_its_budget_says_so_and_still_gives_a_feasible_design() -> None:
    """atlas8_r05_d1 held at link 7 (six free tooth numbers in one ratio): 200,000
    designs do not finish it; the design it gives meets the ratio exactly, and the bound
    it gives is at least its efficiency."""
    question = replace(QUESTION, budget=200_000)
    problem = _direction("atlas8_r05_d1", "h7_i2_o0", question)
    found = search._direction_designs(problem, "h7_i2_o0", question)
    assert found is not None
    (best,), unexplored = found
    assert unexplored >= best.score
    low, high = problem.window(problem.targets[0])
    assert low <= best.ratios["h7_i2_o0"] <= high
    assert all(t >= 17 for t in best.teeth.values())


def _evaluated(path: Path, cwd: Path) -> float:
    result = run_main_in(cwd, [str(path), "--eval", "--quiet"], timeout=600)
    assert result.returncode == 0, result.describe()
    return float(result.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_eight_link_designs_evaluate_to_the_efficiency_they_were_ranked_by(tmp_path: Path) -> None:
    """Four 8-link trains (two whose search stops at its budget): each train's best
    design written as a file (`design_file`) and evaluated
    by ``derive --eval`` gives the efficiency the search ranked it by."""
    question = replace(QUESTION, budget=500_000)
    # Among the best of the whole 8-link search (docs/atlas.md), r889_d1 and r07_d1 proven.
    chosen = {"atlas8_r05_d1", "atlas8_r07_d1", "atlas8_r889_d1", "atlas8_r34_d1"}
    designs = []
    for place in places(8):
        if place.name in chosen:
            found = search._designs_of(search.SearchTask(place, question)).designs
            if found:
                designs.append(max(found, key=lambda d: d.candidate.score))
    assert len(designs) == 4
    assert any(not d.proven for d in designs)
    for rank, design in enumerate(designs, 1):
        path = tmp_path / f"design{rank}.yaml"
        path.write_text(search.design_file(design, rank))
        assert _evaluated(path, tmp_path) == pytest.approx(design.candidate.score, rel=1e-9)


#: atlas8_r495_d38 held at link 2, link 3 in: the compound planet 7 copies the suns.
LOCKED = {"z1a": 29, "z2a": 30, "z3a": 21, "z4b": 18, "z5b": 17, "z6b": 26, "z7c": 29, "z7c2": 30, "z7c3": 21}


@pytest.mark.slow  # the 8-link atlas is enumerated (half a minute)
def test_tooth_numbers_at_which_the_train_locks_are_not_a_design(tmp_path: Path) -> None:
    """With z7c = z1a, z7c2 = z2a and z7c3 = z3a the reduced speed ratio stays finite
    (87/7) and the lossless formulas give an efficiency of exactly 1, but the train does
    not move from its input: ``derive`` refuses the file with these numbers (its own
    check, on the numbers).  The search's exact rules refuse the design too (a
    denominator of the motions vanishes), so does the state's formula module (NaN), and
    the design it keeps evaluates as ranked."""
    import numpy as np

    from davies_sym.synthesis.feasible_designs import ExactRules
    from davies_sym.synthesis.formulas import state_formulas, state_motion

    state = "h2_i3_o1"
    problem, e, written, choice = _searched("atlas8_r495_d38", state, QUESTION)
    ratio, singular = state_motion(problem, state)
    row = np.array([[LOCKED[str(s)] for s in problem.free]], dtype=np.int64)
    assert len(ExactRules.of(problem, [ratio]).feasible(row)[0]) == 1  # the ratio alone admits it
    assert len(ExactRules.of(problem, [ratio], singular).feasible(row)[0]) == 0
    # The state's formula module refuses it too (NaN: the train locks), as derive does.
    (formulas,) = state_formulas(problem)
    assert np.isnan(formulas.efficiency({k: np.array([float(v)]) for k, v in LOCKED.items()}))[0]

    found = search._direction_designs(problem, state, QUESTION)
    assert found is not None
    (candidate,), _ = found
    best = search.AtlasDesign(e.name, e.links, e.code, choice, candidate, written)
    assert best.candidate.teeth != LOCKED and best.candidate.score < 1
    locked = replace(best, candidate=replace(best.candidate, teeth=LOCKED))
    path = tmp_path / "locked.yaml"
    path.write_text(search.design_file(locked, 1))
    refused = run_main_in(tmp_path, [str(path), "--eval", "--quiet"], timeout=600)
    assert refused.returncode == 2 and "cannot move" in refused.stderr, refused.describe()
    path.write_text(search.design_file(best, 1))
    assert _evaluated(path, tmp_path) == pytest.approx(best.candidate.score, rel=1e-9)
