"""The engine against plain sympy on the null space of D_A of the chained stages.

For each k, builds the chain of k two-annulus stages of benchmarks/derive_chain.py
(Coulomb friction on every mesh), times the engine (load, analyse and the efficiency, as
derive_chain.py does: motions, lossless actions, signs, the null space of D_A and the
factored efficiency), then times sympy's ``D_A.nullspace()`` alone on the same augmented
action matrix, in a child process killed after ``--limit`` seconds (default 300), which
is then reported as "> limit".  The engine's time covers the whole derivation, sympy's
only the null space, so the ratio sympy / engine is a lower bound.

    python benchmarks/versus_sympy.py 1 2 3 4 --limit 60
"""

from __future__ import annotations

import argparse
import importlib.util
import multiprocessing
import os
import time
from multiprocessing.connection import Connection

import sympy

import davies_sym

HERE = os.path.dirname(os.path.abspath(__file__))


def _chain_yaml():
    """`chain_yaml` of benchmarks/derive_chain.py (benchmarks/ is a plain folder)."""
    spec = importlib.util.spec_from_file_location("derive_chain", os.path.join(HERE, "derive_chain.py"))
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.chain_yaml


chain_yaml = _chain_yaml()


def _nullspace(matrix: sympy.Matrix, pipe: Connection) -> None:
    """Child process: time ``matrix.nullspace()`` and send (seconds, dimension) back."""
    start = time.perf_counter()
    basis = matrix.nullspace()
    pipe.send((time.perf_counter() - start, len(basis)))
    pipe.close()


def sympy_nullspace(matrix: sympy.Matrix, limit: float) -> tuple[float, int] | None:
    """(seconds, dimension of the null space), or None when sympy is not done in ``limit``."""
    context = multiprocessing.get_context("fork")  # the child inherits the matrix: no pickling
    receive, send = context.Pipe(duplex=False)
    child = context.Process(target=_nullspace, args=(matrix, send), daemon=True)
    child.start()
    send.close()
    try:
        if receive.poll(limit):
            return receive.recv()
        return None
    except EOFError:  # the child died without an answer (e.g. out of memory)
        raise RuntimeError(f"the sympy child process ended with exit status {child.exitcode}") from None
    finally:
        if child.is_alive():
            child.kill()
        child.join()
        receive.close()


def main(sizes: list[int], limit: float) -> None:
    print(f"{'k':>3} {'D_A':>9} {'engine':>9} {'sympy nullspace':>16} {'sympy/engine':>13}", flush=True)
    for k in sizes:
        start = time.perf_counter()
        analysis = davies_sym.analyse(davies_sym.loads(chain_yaml(k), f"chain{k}"))
        _ = analysis.efficiency
        engine = time.perf_counter() - start
        D = analysis.augmented_action_matrix
        result = sympy_nullspace(D, limit)
        if result is None:
            shown, ratio = f"> {limit:g}s", f"> {limit / engine:.0f}"
        else:
            seconds, dimension = result
            shown, ratio = f"{seconds:.2f}s ({dimension})", f"{seconds / engine:.1f}"
        print(f"{k:>3} {D.rows:>4}x{D.cols:<4} {engine:>8.2f}s {shown:>16} {ratio:>13}", flush=True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=list(range(1, 9)), help="numbers of stages k (1..8)")
    parser.add_argument("--limit", type=float, default=300.0, help="seconds sympy may take per k (default 300)")
    arguments = parser.parse_args()
    main(arguments.sizes, arguments.limit)
