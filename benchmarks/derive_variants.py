"""Wall time of the variant derivation on chained two-annulus stages.

Each stage adds one turning condition, so k stages give 2^k x 2 variants (both input
sides).  Prints, per k, the conditions, the variants, the longest formula (characters)
and the wall time of ``derive_variants`` (friction solve, virtual power flow, every
substitution and factorisation, sampling and the partial-derivative checks).

    python benchmarks/derive_variants.py 1 2 3 4
"""

from __future__ import annotations

import sys
import time

from derive_chain import chain_yaml

import davies_sym
from davies_sym.efficiency.variants import derive_variants


def main(sizes: list[int]) -> None:
    print(f"{'k':>3} {'conditions':>10} {'variants':>8} {'longest':>8} {'time':>8}")
    for k in sizes:
        start = time.perf_counter()
        vs = derive_variants(davies_sym.loads(chain_yaml(k), f"chain{k}"))
        elapsed = time.perf_counter() - start
        longest = max(len(str(v.efficiency)) for v in vs.variants)
        print(f"{k:>3} {len(vs.conditions):>10} {len(vs.variants):>8} {longest:>8} {elapsed:>7.2f}s")


if __name__ == "__main__":
    main([int(x) for x in sys.argv[1:]] or [1, 2, 3, 4])
