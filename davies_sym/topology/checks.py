"""Published checks (``expected:``) read against the schema like every other entry.

A check names a design (symbol -> number), the published value and its tolerance.  Every
key is checked (a misspelt ``tolerence`` is refused with its line), every number is read
by the expression grammar as an exact number, and the values must suit their symbols:
sizes positive, mesh efficiencies in (0, 1].
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping
from typing import Any

import sympy

from davies_sym.algebra.exact_sign import UndecidedSign, number_sign
from davies_sym.errors import shortened
from davies_sym.topology.coupling_kinds import gear_meshes
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.entries import EntryReader, describe
from davies_sym.topology.expressions import ExpressionError, check_name, parse_expression
from davies_sym.topology.model import Expected
from davies_sym.topology.schema import EXPECTED

#: Tolerance of a check that gives none.
DEFAULT_TOLERANCE = 5e-5


def read_expected(value: Any, reader: EntryReader, couplings: Mapping[str, Coupling]) -> tuple[Expected, ...]:
    """The ``expected`` list: one `Expected` per readable check."""
    if not isinstance(value, list):
        reader.problem("expected", f"expected a list of checks, got {describe(value)}")
        return ()
    checks = (_read_check(item, f"expected[{i}]", reader, couplings) for i, item in enumerate(value))
    return tuple(c for c in checks if c is not None)


def _read_check(item: Any, path: str, reader: EntryReader, couplings: Mapping[str, Coupling]) -> Expected | None:
    entry = reader.mapping(item, path)
    if entry is None:
        return None
    before = len(reader.problems)
    reader.check_keys(entry, path, EXPECTED)
    if entry.get("quantity", "efficiency") != "efficiency":
        reader.problem(f"{path}.quantity", f"unknown quantity {describe(entry['quantity'])}; write `efficiency`")
    values = _read_values(entry.get("values", {}), f"{path}.values", reader, couplings)
    value = _number(entry.get("value"), f"{path}.value", reader) if "value" in entry else None
    if value is not None and not 0 < value <= 1:
        reader.problem(f"{path}.value", f"a published efficiency lies in (0, 1], got {value:g}")
    tolerance = _number(entry.get("tolerance", DEFAULT_TOLERANCE), f"{path}.tolerance", reader)
    if tolerance is not None and not tolerance > 0:
        reader.problem(f"{path}.tolerance", f"the tolerance must be positive, got {tolerance:g}")
    texts = {key: _text(entry.get(key), f"{path}.{key}", reader) for key in ("source", "input", "state", "differs")}
    published = entry.get("published", True)
    if not isinstance(published, bool):
        reader.problem(f"{path}.published", f"expected true or false, got {describe(published)}")
    port = texts["input"]
    if port is not None and port not in couplings:
        reader.unknown(f"{path}.input", "coupling", port)
    elif port is not None and couplings[port].meshing:
        reader.problem(
            f"{path}.input", f"coupling {port!r} is a gear mesh; the input of a check is a port (a shaft's coupling)"
        )
    if len(reader.problems) > before or value is None or tolerance is None:
        return None
    return Expected(
        quantity="efficiency",
        values=values,
        value=value,
        tolerance=tolerance,
        source=texts["source"] or "",
        input=port,
        state=texts["state"],
        published=published is not False,
        differs=texts["differs"],
    )


def _read_values(value: Any, path: str, reader: EntryReader, couplings: Mapping[str, Coupling]) -> dict[str, str]:
    """Symbol -> the number as written, each read exactly and checked against its symbol's role."""
    entry = reader.mapping(value, path)
    if entry is None:
        return {}
    efficiencies = mesh_efficiency_symbols(couplings.values())
    coefficients = friction_coefficient_symbols(couplings.values())
    out = {}
    for name, item in entry.items():
        where = f"{path}.{name}"
        why = check_name(name)
        if why is not None:
            reader.problem(where, why)
            continue
        number = _exact(item, where, reader)
        if number is None:
            continue
        # A value for a name the train does not use (a radius written as a number) is kept:
        # the design stays whole, and evaluating it gives the value no role.
        why = role_problem(name, reader.symbols.get(name), number, shortened(str(item)), efficiencies, coefficients)
        if why is not None:
            reader.problem(where, why)
        else:
            out[name] = str(item)
    return out


def mesh_efficiency_symbols(couplings: Iterable[Coupling]) -> set[sympy.Symbol]:
    """The symbols written as a mesh's ordinary efficiency."""
    return {e for c in gear_meshes(couplings) if c.efficiencies for e in c.efficiencies if isinstance(e, sympy.Symbol)}


def friction_coefficient_symbols(couplings: Iterable[Coupling]) -> set[sympy.Symbol]:
    """The symbols of the couplings' friction laws: a coefficient may be 0 (the lossless
    limit), as the formula modules' ranges ``[0, inf)`` say."""
    out: set[sympy.Symbol] = set()
    for c in couplings:
        for law in (c.friction.coulomb, c.friction.linear, c.friction.viscous, c.friction.drag):
            if law is not None:
                out |= {s for s in law.free_symbols if isinstance(s, sympy.Symbol)}
    return out


def role_problem(
    name: str,
    symbol: sympy.Symbol | None,
    number: sympy.Expr,
    shown: str,
    efficiencies: set[sympy.Symbol],
    coefficients: Collection[sympy.Symbol] = (),
) -> str | None:
    """Why ``number`` (shown to the user as ``shown``) cannot be the value of ``symbol``:
    an efficiency lies in (0, 1], a size is positive, a friction coefficient (one of
    ``coefficients``) is not negative; None when it can (or the symbol is unknown).
    Decided by the exact sign, so a value exactly on a bound is decided too."""
    try:
        if symbol in efficiencies and (number_sign(number) <= 0 or number_sign(1 - number) < 0):
            return f"{name} = {shown} is not an efficiency: write a number in (0, 1]"
        if symbol in coefficients and number_sign(number) < 0:
            return f"{name} = {shown} is a friction coefficient: write a number >= 0"
        if symbol is not None and symbol not in coefficients and symbol.is_positive and number_sign(number) <= 0:
            return f"{name} = {shown} must be positive"
    except UndecidedSign:
        return f"{name} = {shown} is not a finite real number"
    if number.is_finite is False:
        return f"{name} = {shown} is not finite"
    return None


def _exact(value: Any, path: str, reader: EntryReader) -> sympy.Expr | None:
    """A number written as a YAML number or as text of the grammar (``"1/3"``), exactly."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        reader.problem(path, f"expected a number, got {describe(value)}")
        return None
    if isinstance(value, float) and not math.isfinite(value):
        reader.problem(path, f"expected a finite number, got {value!r}")
        return None
    try:
        return parse_expression(str(value))
    except ExpressionError as exc:
        reader.problem(path, str(exc))
        return None


def _number(value: Any, path: str, reader: EntryReader) -> float | None:
    exact = _exact(value, path, reader)
    if exact is None:
        return None
    number = float(exact)
    if not math.isfinite(number):
        reader.problem(path, f"{shortened(str(value))} is too large for a published number")
        return None
    return number


def _text(value: Any, path: str, reader: EntryReader) -> str | None:
    """Text (or a name written as a number, such as a port ``1``); None when absent."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (str, int)):
        reader.problem(path, f"expected text, got {describe(value)}")
        return None
    return str(value)
