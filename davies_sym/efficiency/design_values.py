"""The values of one design, read the same way for every entry point.

``derive --eval NAME=VALUE``, `VariantSet.evaluate`, `VariantSet.design_point` and
`virtual_power_balance` all take their values through `design_values`: a name
(``"r1"``) or the symbol itself as key, a value exact as written (``0.99`` is 99/100, a
text by the expression grammar, never Python), each checked against its role (a size
positive, a mesh efficiency in (0, 1], decided by the exact sign of the value:
`davies_sym.topology.checks.role_problem`).  Every
problem is collected and reported once.
"""

from __future__ import annotations

import numbers
from collections.abc import Collection, Mapping
from decimal import Decimal

import sympy

from davies_sym.efficiency.operating_point import OPERATING_SYMBOLS
from davies_sym.errors import InputError, Problem, shortened
from davies_sym.losses.definitions import Definition
from davies_sym.topology.checks import friction_coefficient_symbols, mesh_efficiency_symbols, role_problem
from davies_sym.topology.coupling_kinds import toothed_meshes
from davies_sym.topology.expressions import ExpressionError, parse_expression
from davies_sym.topology.model import Train
from davies_sym.topology.symbols import exact_number

Values = Mapping[sympy.Symbol | str, object]


def _exact(value: object) -> sympy.Expr:
    """``value`` as an exact sympy number (``ValueError`` saying why it is not one)."""
    if isinstance(value, sympy.Basic):
        if not (isinstance(value, sympy.Expr) and value.is_number):
            raise ValueError("not a number")
        return value
    if isinstance(value, str):
        try:
            return parse_expression(value)  # the safe grammar, never Python
        except ExpressionError as exc:
            raise ValueError(str(exc)) from None
    if isinstance(value, bool):
        raise ValueError("a truth value is not a number")
    number = exact_number(value)  # int, float as written
    if number is not None:
        return number
    if isinstance(value, numbers.Rational):  # Fraction, numpy integers
        return sympy.Rational(int(value.numerator), int(value.denominator))
    if isinstance(value, numbers.Real):  # numpy floats of any width: the binary number itself
        number = exact_number(float(value))
        if number is None:
            raise ValueError("not a finite number")
        return number
    if isinstance(value, Decimal) and value.is_finite():
        return sympy.Rational(str(value))
    raise ValueError("not a number (a number or a text such as '1/3')")


def design_values(
    train: Train,
    values: Values,
    option: str = "values",
    operating: Collection[sympy.Symbol] = OPERATING_SYMBOLS,
) -> dict[sympy.Symbol, sympy.Expr]:
    """``values`` keyed by the train's symbols (and the ``operating`` ones the formulas
    take besides: input torque and speed), exact and checked; every problem named under
    ``option`` (``--eval``, ``values``) in one `InputError`."""
    names = {**train.symbols, **{str(s): s for s in operating}}
    symbols = set(names.values())
    efficiencies = mesh_efficiency_symbols(train.couplings)
    coefficients = friction_coefficient_symbols(train.couplings)
    defined = {d.symbol: d for d in train.definitions}
    solved = solved_coefficients(train)
    problems: list[Problem] = []
    out: dict[sympy.Symbol, sympy.Expr] = {}
    for key, value in values.items():
        # A symbol made elsewhere (sympy.Symbol("r1"), without the train's assumptions) is
        # the train's symbol of that name.
        symbol = names.get(key) if isinstance(key, str) else key if key in symbols else names.get(str(key))
        name = str(key)
        if symbol is None or symbol not in symbols:
            # What to write instead: the train's own parameters (not the coefficients its
            # efficiencies give, nor the operating torque and speed every train accepts).
            givable = sorted(n for n, s in train.symbols.items() if s not in solved)
            problems.append(Problem(option, f"unknown symbol {shortened(name)} (the train has: {', '.join(givable)})"))
            continue
        if symbol in solved:
            problems.append(Problem(option, solved[symbol]))
            continue
        if symbol in defined and not _exact_spelling(defined[symbol], values):
            # The cosine or sine of an angle may stand for it (cos_beta = 3/5, exact); a loss
            # model's output (a mesh efficiency from the tooth geometry) comes from its parameters.
            d = defined[symbol]
            given = ", ".join(sorted(map(str, d.expression.free_symbols)))
            problems.append(Problem(option, f"{name} is the {d.meaning} ({d.source}); give {given} instead"))
            continue
        if symbol in out:
            problems.append(Problem(option, f"{name} is given twice: give each value once"))
            continue
        try:
            number = _exact(value)
        except ValueError as exc:
            problems.append(Problem(option, f"{name} = {shortened(str(value))}: {exc}"))
            continue
        shown = value.strip() if isinstance(value, str) else sympy.sstr(number)
        shown = shown if len(shown) <= 40 else shortened(shown)
        why = role_problem(name, symbol, number, shown, efficiencies, coefficients)
        if why is not None:
            problems.append(Problem(option, why))
            continue
        out[symbol] = number
    if problems:
        raise InputError(problems, train.path)
    return out


def solved_coefficients(train: Train) -> dict[sympy.Symbol, str]:
    """The meshes' friction coefficients, each with why it takes no value: the formulas are
    in the ordinary efficiency, from which the coefficient is solved (Laus eqs. (32), (34))."""
    out = {}
    for c in toothed_meshes(train.couplings):
        law = c.friction.loaded[1] if c.friction.loaded is not None else None
        if isinstance(law, sympy.Symbol):
            names = ", ".join(dict.fromkeys(str(e) for e in c.efficiencies or ()))
            out[law] = (
                f"{law} is the friction coefficient of mesh {c.name}, solved from its "
                f"ordinary efficiency: give {names or 'the efficiency'} instead"
            )
    return out


def _exact_spelling(definition: Definition, values: Values) -> bool:
    """Whether ``definition``'s symbol may be given itself: the cosine or sine of an angle
    (an exact value where the angle has none), unless the angle is given too."""
    given = {str(k) for k in values}
    trigonometric = isinstance(definition.expression, (sympy.cos, sympy.sin))
    return trigonometric and not {str(s) for s in definition.expression.free_symbols} & given
