"""Exact and numeric solution of a network's linear equations with some magnitudes
known (the primary variables of Laus eqs. (101) and (109))."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy

from davies_sym.errors import NotCoveredError


def solve_exact(
    matrix: sympy.Matrix, names: Sequence[str], known: Mapping[str, sympy.Expr], what: str
) -> dict[str, sympy.Expr]:
    """Every magnitude of ``matrix * x = 0`` from the ``known`` ones, as cancelled
    rational expressions; a system the known ones do not fix is refused (it has more
    freedoms than primaries, or none)."""
    unknown = [i for i, n in enumerate(names) if n not in known]
    rhs = sympy.zeros(matrix.rows, 1)
    for i, n in enumerate(names):
        if n in known:
            rhs -= matrix[:, i] * known[n]
    system = matrix.extract(list(range(matrix.rows)), unknown)
    try:
        solution, free = system.gauss_jordan_solve(rhs)
    except ValueError:
        raise NotCoveredError(f"the {what} have no solution with {', '.join(known)} given") from None
    if free.rows:
        raise NotCoveredError(
            f"the {what} are not fixed by {', '.join(known)}: the machine has more freedoms than primaries"
        )
    out = {n: sympy.sympify(v) for n, v in known.items()}
    for i, value in zip(unknown, solution, strict=True):
        out[names[i]] = sympy.cancel(value)
    return out


def solve_numeric(matrix: np.ndarray, names: Sequence[str], known: Mapping[str, float], what: str) -> dict[str, float]:
    """The same, in floating point; a singular system (a singular position of the
    linkage, or a friction system that locks) is refused with a reason."""
    index = {n: i for i, n in enumerate(names)}
    unknown = [i for i, n in enumerate(names) if n not in known]
    rhs = -sum((matrix[:, index[n]] * v for n, v in known.items()), np.zeros(matrix.shape[0]))
    system = matrix[:, unknown]
    if system.shape[0] == system.shape[1]:
        try:
            x = np.linalg.solve(system, rhs)
        except np.linalg.LinAlgError:
            raise NotCoveredError(f"the {what} are singular here (a singular position of the linkage)") from None
        if not np.all(np.isfinite(x)) or np.linalg.cond(system) > 1e12:
            raise NotCoveredError(f"the {what} are singular here (a singular position of the linkage)")
    else:
        x, *_ = np.linalg.lstsq(system, rhs, rcond=None)
        scale = max(1.0, float(np.max(np.abs(rhs))) if rhs.size else 1.0)
        if np.linalg.matrix_rank(system) < len(unknown) or np.max(np.abs(system @ x - rhs), initial=0.0) > 1e-9 * scale:
            raise NotCoveredError(f"the {what} are not fixed by {', '.join(known)} here (singular or overconstrained)")
    out = dict(known)
    for i, value in zip(unknown, x, strict=True):
        out[names[i]] = float(value)
    return out


def orientation(matrix: np.ndarray, names: Sequence[str], known: Mapping[str, float]) -> float:
    """The sign of the determinant of the square system ``solve_numeric`` solves (0 when
    it is not square).  Along a path it changes only where the system is singular: two
    neighbouring positions of opposite sign have a singular position between them."""
    unknown = [i for i, n in enumerate(names) if n not in known]
    system = np.asarray(matrix, dtype=float)[:, unknown]
    if system.shape[0] != system.shape[1]:
        return 0.0
    sign, _ = np.linalg.slogdet(system)
    return float(sign)
