"""Routines of a generated code file made from formulas: a formula as a function with its
common subexpressions computed once (sympy ``cse``), a list of checks as a function
returning whether all hold, and calls of routines as expressions of another routine."""

from __future__ import annotations

import re
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence

import sympy
from sympy.core.function import AppliedUndef

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.emit.languages.program import Argument, Kind, Routine, Step
from davies_sym.errors import DerivationError

#: A check ``expression op bound``: op one of ``>``, ``>=``, ``<=``, ``==``.
Check = tuple[sympy.Expr, str, sympy.Expr]


def plain(expr: sympy.Basic) -> sympy.Basic:
    """``expr`` in symbols without assumptions (same names): a relation built on it stays a
    relation to print instead of being decided by the assumptions (``r1 > 0`` is not
    ``True`` here: the generated code checks it)."""
    return expr.xreplace({s: sympy.Symbol(s.name) for s in expr.free_symbols if isinstance(s, sympy.Symbol)})


def fresh(base: str, taken: Collection[str]) -> str:
    """``base``, or ``base`` with underscores appended until no name in ``taken`` is it."""
    name = base
    while name in taken:
        name += "_"
    return name


def temporary_prefix(taken: Iterable[str]) -> str:
    """A prefix ``p`` such that no name in ``taken`` is ``p`` followed by digits."""
    names = list(taken)
    prefix = "t"
    while any(re.fullmatch(re.escape(prefix) + r"\d+", n) for n in names):
        prefix += "t"
    return prefix


def arguments_of(exprs: Iterable[sympy.Basic], order: Sequence[str]) -> tuple[Argument, ...]:
    """The real arguments a routine of ``exprs`` needs, in the order of ``order`` (the
    parameters of the whole file), so every routine lists its arguments alike."""
    used = {s.name for e in exprs for s in e.free_symbols if isinstance(s, sympy.Symbol)}
    missing = sorted(used - set(order))
    if missing:
        raise DerivationError(
            f"a formula uses {', '.join(missing)}, which the efficiency does not take as "
            "parameters; the code cannot be written"
        )
    return tuple(Argument(n, Kind.REAL) for n in order if n in used)


def _reduced(exprs: Sequence[sympy.Expr], prefix: str) -> tuple[tuple[Step, ...], list[sympy.Expr]]:
    """Common subexpressions of ``exprs`` as steps (``prefix``0, 1, ...) and the
    expressions in them; ``cse``'s canonical order makes the same formulas give the same
    steps on every run."""
    replacements, reduced = sympy.cse(list(exprs), symbols=sympy.numbered_symbols(prefix), order="canonical")
    steps = tuple(Step(str(s), Kind.REAL, v) for s, v in replacements)
    return steps, list(reduced)


def formula_routine(name: str, summary: str, expr: sympy.Expr, order: Sequence[str]) -> Routine:
    """``name(arguments)``: the value of ``expr`` (in plain symbols)."""
    expr = plain(expr)
    arguments = arguments_of([expr], order)
    steps, (result,) = _reduced([expr], temporary_prefix(order))
    return Routine(name, summary, arguments, Kind.REAL, steps, result)


def relation(lhs: sympy.Basic, op: str, rhs: sympy.Basic) -> sympy.Basic:
    """``lhs op rhs`` kept as written (never decided by sympy, so a NaN fails it in the
    generated code as in numpy)."""
    return sympy.Rel(lhs, rhs, op, evaluate=False)


def checks_routine(
    name: str, summary: str, checks: Sequence[Check], order: Sequence[str], exported: bool = False
) -> Routine:
    """``name(arguments)``: whether every check holds (false where a side is NaN, as
    numpy's comparisons are)."""
    sides = [plain(e) for e, _, _ in checks]
    arguments = arguments_of(sides, order)
    steps, reduced = _reduced(sides, temporary_prefix(order))
    relations = [relation(r, op, bound) for r, (_, op, bound) in zip(reduced, checks, strict=True)]
    result = sympy.And(*relations) if relations else sympy.true
    return Routine(name, summary, arguments, Kind.BOOL, steps, result, exported)


def forces_agree_routine(
    name: str,
    needs: str,
    loaded_forces: Mapping[str, tuple[RationalFunction, int]],
    public: Callable[[sympy.Expr], sympy.Expr],
    order: Sequence[str],
) -> Routine:
    """``<name>_forces_agree(...)``: whether each loaded force (a tooth force, a bearing
    reaction) has the sign a variant or region ``needs`` (``public``: the formula in the
    parameters the user gives)."""
    checks: list[Check] = [(public(f.to_expr() * sign), ">=", sympy.Integer(0)) for f, sign in loaded_forces.values()]
    summary = f"whether the loaded forces of {', '.join(loaded_forces)} have the signs {needs}"
    return checks_routine(f"{name}_forces_agree", summary, checks, order)


def call(routine: Routine) -> AppliedUndef:
    """``routine(arguments)`` as an expression of the routine that calls it (whose
    arguments have the same names)."""
    return sympy.Function(routine.name)(*(sympy.Symbol(a) for a in routine.argument_names))
