"""The answer of ``derive search`` as a text table and as the Pareto figure (efficiency
against ratio error and against size)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from davies_sym.emit.plots import new_figure
from davies_sym.synthesis.tooth_search import Candidate, SearchResult


def _cell(values: dict[str | None, Any], digits: int) -> str:
    return "  ".join(f"{v:.{digits}f}" if s is None else f"{s} {v:.{digits}f}" for s, v in values.items())


def search_text(result: SearchResult, top: int) -> str:
    """One line per design (best first): tooth numbers, ratios, efficiencies, score."""
    p = result.problem
    lines = [
        f"{p.train.name}: {len(result.candidates)} feasible design(s) of {result.searched} "
        f"({result.examined} rows evaluated) in {result.seconds:.2f} s",
        "rules: " + "; ".join(r.name + ("" if r.applied else f" (not applied: {r.note})") for r in result.rules),
    ]
    for s in result.planet_sets:
        lines.append(f"planet set: {s.name}")
    for k, c in enumerate(result.candidates[:top], start=1):
        teeth = " ".join(f"{n}={z}" for n, z in c.teeth.items())
        ratios = _cell({s: float(r) for s, r in c.ratios.items()}, 4)
        lines.append(
            f"{k:4d}. {teeth}  ratio {ratios}  efficiency {_cell(dict(c.efficiencies), 5)}  score {c.score:.6f}"
        )
    if len(result.candidates) > top:
        lines.append(f"      ... {len(result.candidates) - top} more (--top)")
    return "\n".join(lines) + "\n"


def pareto_figure(result: SearchResult) -> Any:
    """Score against ratio error and against size, the Pareto front of each marked."""
    figure = new_figure(10.0, 4.5)
    axes = figure.subplots(1, 2)
    costs: tuple[tuple[Callable[[Candidate], float], str], ...] = (
        (lambda c: c.ratio_error, "largest relative ratio error"),
        (lambda c: float(c.size), "teeth of the largest gear"),
    )
    for ax, (cost, label) in zip(axes, costs, strict=True):
        xs = [cost(c) for c in result.candidates]
        ys = [c.score for c in result.candidates]
        ax.scatter(xs, ys, s=10, color="0.6", label="feasible designs")
        front: list[Candidate] = [result.candidates[k] for k in result.pareto(cost)]
        ax.plot([cost(c) for c in front], [c.score for c in front], "o-", color="C0", label="Pareto front")
        ax.set_xlabel(label)
        ax.set_ylabel("efficiency (weighted over the states)")
        ax.legend(loc="lower right")
    figure.suptitle(f"{result.problem.train.name}: {len(result.candidates)} feasible designs")
    return figure
