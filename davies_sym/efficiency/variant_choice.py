"""Which variant holds at given values: Laus's turning conditions (Tables 5 and 6), then
the losses' own say.

The turning conditions are the signs of the lossless mesh powers (eqs. (86)-(88)).  With
losses a variant holds where its assumptions agree with its own solution: each driving
gear gives power in its carrier's frame, each bearing's reaction has the assumed sign
(`davies_sym.efficiency.light_load`).  Near a turning condition the friction in the
other meshes can reverse a small mesh power, so the variant that holds may be one of
the region's reversed-mesh variants (`davies_sym.efficiency.mesh_reversals`: the
neighbouring region's formula with the region's turning conditions and the reversed
mesh's condition); at light load a drag can reverse a force anywhere.  The region's own
variants come first; another region's is taken only where none of them agrees (a
reversal the sampling did not reach).  Every variant whose assumptions agree is found;
one efficiency among them is the answer, none or several different ones are refused,
never guessed.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy

from davies_sym.algebra.exact_sign import UndecidedSign, is_real_number, number_sign
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.errors import DerivationError, DesignError, MissingValuesError, NotCoveredError, Problem

Values = Mapping[sympy.Symbol, sympy.Expr]


def value_at(rf: RationalFunction, values: Values) -> sympy.Expr:
    """``rf`` at ``values``: exact in the polynomial ring where every value is rational,
    by sympy substitution otherwise (irrational values, missing symbols); ``nan`` on a pole."""
    try:
        q = rf.evaluate(values)
    except (KeyError, TypeError, ValueError):
        return sympy.sympify(rf.to_expr().subs(values))
    except ZeroDivisionError:
        return sympy.nan
    return sympy.Rational(int(q.p), int(q.q))


def _number(expr: sympy.Expr, what: str, path: str | None) -> sympy.Expr:
    if not expr.is_number:
        missing = sorted(map(str, expr.free_symbols))
        raise MissingValuesError([Problem("values", f"{what} needs values for {', '.join(missing)}")], path)
    return expr


def condition_signs_at(conditions: Sequence[TurningCondition], values: Values, path: str | None) -> dict[str, int]:
    """The sign of every turning condition at ``values`` (0 counts as positive)."""
    out = {}
    for c in conditions:
        value = _number(sympy.sympify(c.expression.subs(values)), f"condition {c.name}", path)
        out[c.name] = 1 if _decided_sign(value, f"condition {c.name}") >= 0 else -1
    return out


def assumption_values(variant: Variant, values: Values, path: str | None) -> dict[str, sympy.Expr]:
    """Each loaded force of ``variant`` at ``values`` times the sign it needs: every one
    non-negative where the variant's assumptions agree with its solution."""
    out = {}
    for coupling, (force, sign) in variant.loaded_forces.items():
        what = f"the force in {coupling} (which variant holds)"
        out[coupling] = _number(value_at(force, values), what, path) * sign
    return out


def _decided_sign(value: sympy.Expr, what: str) -> int:
    """The exact sign of ``value`` (`number_sign`): a value exactly on a limit is decided,
    and one whose sign cannot be proved is refused, never rounded."""
    try:
        return number_sign(value)
    except UndecidedSign as exc:
        raise NotCoveredError(f"{what}: {exc}; no variant is chosen where it cannot be decided exactly") from None


def _holds(value: sympy.Expr) -> bool:
    """Whether an assumption's value (force times its needed sign) is non-negative; a
    pole's ``nan`` is not."""
    return is_real_number(value) and _decided_sign(value, "a force of the power flow") >= 0


def _positive(value: sympy.Expr) -> bool:
    """Whether an efficiency is a real number greater than zero (exactly decided)."""
    return is_real_number(value) and _decided_sign(value, "an efficiency") > 0


def agrees(variant: Variant, values: Values, path: str | None) -> bool:
    """Whether every assumption of ``variant`` holds at ``values`` (a pole does not)."""
    return all(_holds(v) for v in assumption_values(variant, values, path).values())


def holding_variant(
    variants: Sequence[Variant],
    conditions: Sequence[TurningCondition],
    port: str,
    values: Values,
    path: str | None = None,
    excluded: Sequence[ExcludedVariant] = (),
) -> Variant:
    """The variant with input ``port`` that holds at ``values``.

    Every variant of the port whose assumptions agree is a state the friction allows;
    those with a positive efficiency are the working ones.  One efficiency among them
    is the answer (the region's variant first).  Where none agrees and the region's
    variant does not give a positive efficiency, that variant is returned: the train
    self-locks there, and its value says so.  Otherwise `NotCoveredError`.  Without
    values for the losses, the region's variant when it is the only one (the lossless
    rule of Laus's tables)."""
    signs = condition_signs_at(conditions, values, path)
    port_variants = [v for v in variants if v.input == port]
    own = _region_variants(port_variants, excluded, port, signs, path)
    others = [v for v in port_variants if dict(v.signs) != signs and v.loaded_forces]
    try:
        agreeing = [v for v in (*own, *others) if agrees(v, values, path)]
    except MissingValuesError:
        if len(own) == 1:
            return own[0]  # without the losses' values, the lossless rule alone (Laus's tables)
        raise
    efficiency = {v.number: _number(value_at(v.efficiency_rf, values), "the efficiency", path) for v in agreeing}
    working = [v for v in agreeing if _positive(efficiency[v.number])]
    chosen = working or agreeing
    if chosen and _one_value([efficiency[v.number] for v in chosen]):
        return chosen[0]
    base = own[0]
    if not chosen:
        own_value = _number(value_at(base.efficiency_rf, values), "the efficiency", path)
        if not _positive(own_value):
            return base
        raise NotCoveredError(
            f"no variant's power flow agrees with its own forces at these values (input {port}): "
            f"in variant ({base.number}) {_disagreeing(base, values, path)}; the friction admits no "
            "motion driven from this input (the train jams), or reverses forces as no derived variant covers"
        )
    numbers = ", ".join(f"({v.number})" for v in chosen)
    raise NotCoveredError(
        f"the power flows of variants {numbers} all agree with their own forces at these values, "
        "with different efficiencies: the friction does not decide the power flow here"
    )


def _region_variants(
    port_variants: Sequence[Variant],
    excluded: Sequence[ExcludedVariant],
    port: str,
    signs: Mapping[str, int],
    path: str | None,
) -> list[Variant]:
    """The variants of input ``port`` (``port_variants``) in the region of the turning
    conditions' ``signs``; refused where that region's variant is ``excluded`` (no
    admissible design reaches it)."""
    own = [v for v in port_variants if dict(v.signs) == signs]
    never = [v for v in excluded if v.input == port and dict(v.signs) == signs]
    if not own and never:
        raise DesignError(
            [
                Problem(
                    "values",
                    f"these values lie in the region of variant ({never[0].number}), which no admissible "
                    f"design reaches: {never[0].reason}; check the values",
                )
            ],
            path,
        )
    if not own:
        raise DerivationError(f"no variant for input {port} and signs {signs}")  # pragma: no cover
    return own


def _one_value(values: Sequence[sympy.Expr]) -> bool:
    """Whether ``values`` are one number, however each is written (exactly compared)."""
    first = values[0]
    if not all(is_real_number(v) for v in values):
        return len(set(values)) == 1
    return all(_decided_sign(v - first, "a difference of efficiencies") == 0 for v in values[1:])


def _disagreeing(variant: Variant, values: Values, path: str | None) -> str:
    """Which assumptions of ``variant`` fail at ``values``, in words."""
    failed = [c for c, v in assumption_values(variant, values, path).items() if not _holds(v)]
    return ", ".join(f"the power flow or force in {c} is reversed by the losses" for c in failed) or "none fails"
