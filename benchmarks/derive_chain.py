"""Wall time of the derivation on chained two-annulus stages (serial(k) of PERFORMANCE.md).

Stage i is a two-annulus epicyclic train whose input carrier is driven by the output
annulus of stage i - 1, all sharing the housing annulus.  Prints, per k, the size of
D_A and the time of each step (motions, actions with friction, efficiency).

    python benchmarks/derive_chain.py 1 2 3 4 6 8
"""

from __future__ import annotations

import sys
import time
from itertools import pairwise

import davies_sym


def chain_yaml(k: int) -> str:
    """Stage i: annulus a_i on the housing 0, planet p_i (gears p_i, q_i), output annulus b_i
    on link o_i; the carrier of stage i is link o_{i-1} (c1 for the first stage)."""
    links = ["0", "c1"] + [f"{n}{i}" for i in range(1, k + 1) for n in ("p", "o")]
    lines = [f"name: serial chain of {k} two-annulus stages", f"links: [{', '.join(links)}]", "reference: 0", "gears:"]
    for i in range(1, k + 1):
        lines += [
            f"  a{i}: {{link: 0, radius: ra{i}, internal: true}}",
            f"  b{i}: {{link: o{i}, radius: rb{i}, internal: true}}",
            f"  p{i}: {{link: p{i}, radius: rp{i}}}",
            f"  q{i}: {{link: p{i}, radius: rq{i}}}",
        ]
    lines += ["couplings:", "  A1: {type: revolute, links: [0, c1]}"]
    for i in range(1, k + 1):
        carrier = "c1" if i == 1 else f"o{i - 1}"
        lines += [
            f"  B{i}: {{type: revolute, links: [0, o{i}]}}",
            f"  C{i}: {{type: mesh, gears: [a{i}, p{i}]}}",
            f"  D{i}: {{type: mesh, gears: [b{i}, q{i}]}}",
            f"  E{i}: {{type: revolute, links: [p{i}, {carrier}], axis: p{i}}}",
        ]
    lines.append(f"ports: {{input: A1, output: B{k}}}")
    return "\n".join(lines) + "\n"


def main(sizes: list[int]) -> None:
    print(
        f"{'k':>3} {'D_A':>9} {'network':>8} {'motions':>8} {'signs':>8} {'actions':>8} {'efficiency':>10} {'total':>8}"
    )
    for k in sizes:
        times = [time.perf_counter()]
        a = davies_sym.analyse(davies_sym.loads(chain_yaml(k), f"chain{k}"))
        for step in ("motion_coefficients", "coulomb_sign_values", "action_solution", "efficiency_rf"):
            times.append(time.perf_counter())
            getattr(a, step)
        times.append(time.perf_counter())
        _ = a.efficiency  # conversion of the factored result to sympy
        times.append(time.perf_counter())
        D = a.augmented_action_matrix
        steps = [b - a_ for a_, b in pairwise(times)]
        print(
            f"{k:>3} {D.rows:>4}x{D.cols:<4} "
            + " ".join(f"{t:>7.3f}s" for t in steps[:4])
            + f" {steps[4] + steps[5]:>9.3f}s {times[-1] - times[0]:>7.2f}s"
        )


if __name__ == "__main__":
    main([int(x) for x in sys.argv[1:]] or [1, 2, 3, 4])
