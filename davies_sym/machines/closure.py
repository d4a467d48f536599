"""Loop closure: joint positions the file leaves unknown, fixed by its closure
equations (``norm(C - B) = a2``) at each position of the input.

An equation with one unknown left is solved exactly (Laus eq. (97): a quadratic gives
the slider's position under a square root), the root taken that lies nearest the
file's guess at a sample position; the solved unknowns are substituted into the
geometry, so the closed forms see plain expressions.  What no such step solves (two
circles meeting, a spatial loop) is solved numerically at every position by Newton's
method, started from the previous position's solution (or the guess), so a task stays
on one assembly branch.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
import sympy

from davies_sym.errors import MissingValuesError, NotCoveredError, Problem
from davies_sym.machines.machine_model import Machine

#: Newton iterations before a position is refused, and the residual accepted.
ITERATIONS = 60
TOLERANCE = 1e-12


def _sample(machine: Machine) -> dict[sympy.Symbol, sympy.Expr]:
    """Parameter values and a generic position for choosing a root."""
    sample = machine.sample()
    if machine.cycle is not None:
        start, stop = machine.cycle.start, machine.cycle.stop
        sample.setdefault(machine.cycle.variable, start + (stop - start) * sympy.Rational(3, 10))
    for task in machine.tasks.values():
        for s, e in task.path.items():
            sample.setdefault(s, e.subs(sympy.Symbol("t", real=True), task.start))
    for s in machine.position:
        sample.setdefault(s, sympy.Rational(7, 10))
    return sample


def _nearest(roots: list[sympy.Expr], guess: sympy.Expr, sample: Mapping[sympy.Symbol, sympy.Expr]) -> sympy.Expr:
    left = sorted({s.name for r in [guess, *roots] for s in r.subs(sample).free_symbols})
    if left:
        raise MissingValuesError(
            [Problem("values", f"give {', '.join(left)} in values: (the assembly branch is chosen there)")], None
        )
    target = complex(sympy.N(guess.subs(sample)))
    real = []
    for root in roots:
        value = complex(sympy.N(root.subs(sample)))
        if abs(value.imag) <= 1e-9 * (1 + abs(value.real)):
            real.append((abs(value.real - target.real), root))
    if not real:
        raise NotCoveredError("the loop closure has no real solution at the sample position")
    return min(real, key=lambda pair: pair[0])[1]


def _polynomial(eq: sympy.Expr, unknown: sympy.Symbol) -> sympy.Expr | None:
    """``eq`` as a polynomial in ``unknown``: itself, or with its one square root of the
    unknown squared away (``A + B sqrt(X) = 0`` gives ``A**2 - B**2 X = 0``; the roots
    this adds are dropped by `_holds`)."""
    eq = sympy.expand(eq)
    if eq.is_polynomial(unknown):
        return eq
    roots = [p for p in eq.atoms(sympy.Pow) if p.exp == sympy.Rational(1, 2) and p.has(unknown)]
    if len(roots) != 1:
        return None
    root = roots[0]
    b = eq.coeff(root)
    a = sympy.expand(eq - b * root)
    if a.has(root) or b.has(root):
        return None
    squared = sympy.expand(a**2 - b**2 * root.base)
    return squared if squared.is_polynomial(unknown) else None


def _holds(residual: sympy.Expr, sample: Mapping[sympy.Symbol, sympy.Expr]) -> bool:
    value = sympy.N(residual.subs(sample))
    return value.is_number and abs(complex(value)) < 1e-9


def solve_closure(machine: Machine) -> Machine:
    """``machine`` with the unknowns that one-unknown steps solve substituted exactly;
    the rest stay unknowns for `NumericClosure`."""
    if not machine.unknowns:
        return machine
    sample = _sample(machine)
    equations = list(machine.closure)
    solved: dict[sympy.Symbol, sympy.Expr] = {}
    progress = True
    while progress and equations:
        progress = False
        for eq in equations:
            left = [u for u in machine.unknowns if u not in solved and eq.has(u)]
            if len(left) != 1:
                continue
            unknown = left[0]
            polynomial = _polynomial(eq, unknown)
            if polynomial is None or sympy.degree(polynomial, unknown) > 2:
                continue
            roots = [r for r in sympy.solve(polynomial, unknown) if _holds(eq.subs(unknown, r), sample)]
            solved[unknown] = _nearest(roots, machine.unknowns[unknown].subs(solved), {**sample, **solved})
            equations = [e.subs(unknown, solved[unknown]) for e in equations if e is not eq]
            progress = True
            break
    if not solved:
        return machine
    return substitute(machine, solved, tuple(e for e in equations if e != 0))


def substitute(
    machine: Machine, solved: Mapping[sympy.Symbol, sympy.Expr], equations: tuple[sympy.Expr, ...]
) -> Machine:
    def vec(v: tuple[sympy.Expr, ...] | None) -> Any:
        return None if v is None else tuple(c.subs(solved) for c in v)

    couplings = tuple(replace(c, at=vec(c.at), axis=vec(c.axis), normal=vec(c.normal)) for c in machine.couplings)
    ports = tuple(replace(p, direction=vec(p.direction)) for p in machine.ports)
    vectors = {name: vec(v) for name, v in machine.vectors.items()}
    unknowns = {u: g for u, g in machine.unknowns.items() if u not in solved}
    return replace(machine, couplings=couplings, ports=ports, vectors=vectors, unknowns=unknowns, closure=equations)


class NumericClosure:
    """Newton's method on the closure equations the exact steps left, compiled once."""

    def __init__(self, machine: Machine, symbols: tuple[sympy.Symbol, ...]):
        self.unknowns = tuple(machine.unknowns)
        self.parameters = tuple(s for s in symbols if s not in machine.unknowns)
        residual = sympy.Matrix(machine.closure)
        jacobian = residual.jacobian(self.unknowns)
        args = (*self.unknowns, *self.parameters)
        self._residual = sympy.lambdify(args, list(residual), "math", cse=True)
        self._jacobian = sympy.lambdify(args, jacobian.tolist(), "math", cse=True)
        self._guess = sympy.lambdify(self.parameters, [machine.unknowns[u] for u in self.unknowns], "math")
        self.last: tuple[float, ...] | None = None

    def solve(self, values: Mapping[sympy.Symbol, float], restart: bool = False) -> dict[sympy.Symbol, float]:
        params = [float(values[s]) for s in self.parameters]
        x = np.array(self.last if self.last is not None and not restart else self._guess(*params), dtype=float)
        for _ in range(ITERATIONS):
            try:
                f = np.array(self._residual(*x, *params), dtype=float)
                if np.max(np.abs(f)) <= TOLERANCE * (1 + np.max(np.abs(x))):
                    self.last = tuple(x)
                    return dict(zip(self.unknowns, (float(v) for v in x), strict=True))
                x = x - np.linalg.solve(np.array(self._jacobian(*x, *params), dtype=float), f)
            except (ValueError, ZeroDivisionError, np.linalg.LinAlgError):
                break
        raise NotCoveredError("the loop closure has no solution here: the linkage cannot be assembled")
