"""The hand-written part of every generated formula module (it needs numpy alone; the
arrays of another array API library take the path of `davies_sym.emit.array_api_runtime`).

`davies_sym.emit.python_module` copies this file's imports, types and functions
into each module it writes, and puts the train's own tables and formulas where the
placeholders below stand.  Keeping this code in a real module means it is linted,
type-checked (``mypy --strict``) and imported like the rest of the package, so a
generated module can only differ from it in data and formulas.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any, Final, TypedDict, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from davies_sym.emit.array_api_runtime import (
    _admissible_any,
    _array,
    _count,
    _device,
    _dtype,
    _first_disagreement,
    _numbers_any,
    _own_any,
    _region_any,
    _select_any,
    _shape_of,
)
from davies_sym.emit.shared_runtime import _at, _blockwise

Array = NDArray[np.float64]
_Table = dict[str, tuple[Callable[..., Any], tuple[str, ...]]]
#: Each variant's flat point indices and its arguments gathered there, by variant number.
_Gathered = dict[int, tuple[NDArray[np.intp], dict[str, Array]]]


class Parameter(TypedDict):
    """A parameter of the formulas and its admissible range (low excluded unless closed_low)."""

    name: str
    meaning: str
    unit: str
    low: float
    high: float
    closed_low: bool


class Variant(TypedDict):
    """One formula of the efficiency and where it holds."""

    name: str
    number: int
    input: str
    output: str
    region: int
    conditions: tuple[str, ...]
    conditions_latex: tuple[str, ...]
    meshes: tuple[str, ...]
    formula: str
    latex: str
    feasible: bool
    reversed: tuple[str, ...]
    forces: tuple[str, ...]


class DesignWarning(RuntimeWarning):
    """Some design points are outside the admissible parameters, self-lock, or lie where
    no variant's power flow agrees with its own forces (NaN there)."""


class DesignError(ValueError):
    """Raised instead of DesignWarning with errors='raise'."""


# Placeholders: each generated module has its own tables and formulas here.
PORTS: Final[tuple[str, str]] = ("input", "output")
LOSSY: Final[tuple[str, ...]] = ()
SENSITIVE: Final[tuple[str, ...]] = ()
PARAMETERS: Final[tuple[Parameter, ...]] = ()
IGNORED: Final[tuple[str, ...]] = ()
RELATIONS: Final[tuple[str, ...]] = ()
DEPENDENT: Final[dict[str, str]] = {}
CONDITIONS: Final[dict[str, tuple[str, str]]] = {}
EXCLUDED: Final[tuple[int, ...]] = ()
VARIANTS: Final[tuple[Variant, ...]] = ()
_CONDITIONS: Final[_Table] = {}
_RELATIONS: Final[_Table] = {}
_DEPENDENT: Final[_Table] = {}
_EFFICIENCY: Final[_Table] = {}
_LOSSES: Final[_Table] = {}
_GRADIENT: Final[_Table] = {}
_RATIO: Final[_Table] = {}
_MOTION: Final[_Table] = {}
_FORCES: Final[_Table] = {}


def _check_input(input: str) -> None:
    if input not in PORTS:
        raise ValueError(f"input must be one of {PORTS}, got {input!r}")


def _region(values: dict[str, Array], shape: tuple[int, ...]) -> NDArray[np.int64]:
    """Bit k set where turning condition k is negative."""
    code = np.zeros(shape, dtype=np.int64)
    for bit, (function, names) in enumerate(_CONDITIONS.values()):
        code |= np.asarray(function(**{n: values[n] for n in names}) < 0, dtype=np.int64) << bit
    return code


def _variant_numbers(input: str, values: dict[str, Array], gathered: _Gathered | None = None) -> NDArray[np.int64]:
    """The number of the variant that holds at each point with ``input`` as input port:
    its turning conditions hold and each of its loaded forces (the power each driving gear
    gives, a bearing's reaction) has the sign it needs; where the losses move a turning
    point past its lossless boundary, the variant of another region whose loaded forces
    all agree; 0 where none does.  Where a force is zero two variants agree and give the
    same value: the first is taken.  ``gathered`` keeps each variant's arguments at its
    points for `_select`."""
    _check_input(input)
    shape = np.broadcast_shapes(*(v.shape for v in values.values()))
    numbers = np.zeros(shape, dtype=np.int64)
    with np.errstate(all="ignore"):
        code = _region(values, shape)
        mine = [v for v in VARIANTS if v["input"] == input]
        for variant in mine:
            mask = np.array((code == variant["region"]) & (numbers == 0), dtype=bool)
            numbers[_agreeing(variant, values, mask, gathered)] = variant["number"]
        for variant in mine:
            if variant["name"] in _FORCES:
                numbers[_agreeing(variant, values, numbers == 0)] = variant["number"]
    return numbers


def _own_where_none(input: str, values: dict[str, Array], numbers: NDArray[np.int64]) -> NDArray[np.int64]:
    """``numbers`` with each 0 (no variant agrees with its own forces) replaced by the
    variant of the point's lossless region: its efficiency tells a train that self-locks
    there (not positive) from one whose losses reverse forces as no variant covers."""
    if (numbers != 0).all():
        return numbers
    with np.errstate(all="ignore"):
        code = _region(values, numbers.shape)
    own = numbers.copy()
    for variant in reversed([v for v in VARIANTS if v["input"] == input]):
        own[(numbers == 0) & (code == variant["region"])] = variant["number"]
    return own


def _agreeing(
    variant: Variant, values: dict[str, Array], mask: NDArray[np.bool_], gathered: _Gathered | None = None
) -> NDArray[np.bool_]:
    """``mask`` where each loaded force of ``variant`` has the sign it needs (its
    arguments kept in ``gathered`` where every point agrees)."""
    mask = np.array(mask, dtype=bool)
    if not mask.any() or variant["name"] not in _FORCES:
        return mask
    function, names = _FORCES[variant["name"]]
    index = np.flatnonzero(mask)
    kept: dict[str, Array] = {}
    forces = function(**_at(values, names, index, mask.shape, kept))
    # A force that depends on none of the arrays comes back as a scalar.
    size = (len(index),)
    agree = np.all(
        [np.broadcast_to(np.asarray(f) >= 0, size) for f in (forces if isinstance(forces, tuple) else (forces,))],
        axis=0,
    )
    if gathered is not None and agree.all():
        gathered[variant["number"]] = (index, kept)
    mask.reshape(-1)[index] = agree
    return mask


def _select(
    numbers: NDArray[np.int64], values: dict[str, Array], table: _Table, width: int, gathered: _Gathered | None = None
) -> Array:
    """The function of the variant that holds (``numbers``, from `_variant_numbers`),
    evaluated element by element (each variant only on its own points, their arguments
    from ``gathered`` where it holds them); shape (width, *broadcast shape), NaN where
    none holds."""
    result = np.full((width, *numbers.shape), np.nan)
    with np.errstate(all="ignore"):
        for variant in VARIANTS:
            mask = numbers == variant["number"]
            if not mask.any():
                continue
            function, names = table[variant["name"]]
            if mask.all():
                parts = function(**{n: values[n] for n in names})
                for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
                    result[k, ...] = part
            else:
                index = np.flatnonzero(mask)
                # Points are only ever added to a variant: as many points are the same points.
                known = (gathered or {}).get(variant["number"])
                kept = known[1] if known is not None and len(known[0]) == len(index) else None
                parts = function(**_at(values, names, index, mask.shape, kept))
                flat = result.reshape(width, -1)
                for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
                    flat[k, index] = part
    return result


def _consistent(given: dict[str, ArrayLike | None], values: dict[str, Array], xp: Any = np) -> None:
    """Refuse a dependent parameter (DEPENDENT) whose value breaks its relation."""
    for name, value in given.items():
        if value is None:
            continue
        function, names = _DEPENDENT[name]
        if xp is not np:  # compared where the arrays are, the first disagreement brought back
            wrong = _first_disagreement(xp, _array(value, xp), function(**{n: values[n] for n in names}))
            if wrong is not None:
                raise DesignError(
                    f"{name} = {wrong[0]} breaks the relation {DEPENDENT[name]}, which gives {wrong[1]}; "
                    f"the difference is {wrong[0] - wrong[1]}"
                )
            continue
        implied = np.broadcast_to(function(**{n: values[n] for n in names}), np.shape(value))
        bad = ~np.isclose(_array(value), implied, rtol=1e-9, atol=0.0)
        if bad.any():
            k = np.flatnonzero(bad)[0]
            actual = np.ravel(_array(value))[k]
            expected = np.ravel(implied)[k]
            raise DesignError(
                f"{name} = {actual} breaks the relation {DEPENDENT[name]}, which gives {expected}; "
                f"the difference is {actual - expected}"
            )


def _given(optional: dict[str, ArrayLike | None], xp: Any = np) -> dict[str, Array]:
    """The optional parameters given (not None), as arrays."""
    return {name: _array(value, xp) for name, value in optional.items() if value is not None}


def _admissible(values: dict[str, Array]) -> NDArray[np.bool_]:
    """Where every parameter is in its range, every relation positive and the turning
    conditions' signs are not those of a region no admissible design reaches (EXCLUDED)."""
    shape = np.broadcast_shapes(*(v.shape for v in values.values()))
    ok = np.ones(shape, dtype=bool)
    with np.errstate(all="ignore"):
        for p in PARAMETERS:
            if p["name"] not in values:
                continue
            v = values[p["name"]]
            ok &= ((v >= p["low"]) if p["closed_low"] else (v > p["low"])) & (v <= p["high"])
        for function, names in _RELATIONS.values():
            if all(n in values for n in names):
                ok &= function(**{n: values[n] for n in names})
        if EXCLUDED:
            ok &= ~np.isin(_region(values, shape), EXCLUDED)
    return ok


def _check_errors(errors: str) -> None:
    if errors not in ("warn", "raise", "ignore"):
        raise ValueError(f"errors must be 'warn', 'raise' or 'ignore', got {errors!r}")


def _refuse(bad: NDArray[np.bool_], message: str, errors: str, stacklevel: int, xp: Any = np) -> None:
    """A DesignWarning (or a DesignError) saying why, where some point is ``bad``;
    ``stacklevel`` points the warning at the caller of the entry point."""
    if not _count(bad, xp):
        return
    if errors == "raise":
        raise DesignError(message)
    if errors == "warn":
        warnings.warn(message, DesignWarning, stacklevel=stacklevel + 1)


def _nan_where(
    bad: NDArray[np.bool_], result: Array, message: str, errors: str, stacklevel: int, xp: Any = np
) -> Array:
    """``result`` with NaN where ``bad``, after `_refuse`."""
    _refuse(bad, message, errors, stacklevel + 1, xp)
    if xp is not np:
        return cast(Array, xp.where(bad, xp.asarray(float("nan"), dtype=result.dtype, device=result.device), result))
    return np.where(bad, np.nan, result) if bad.any() else result


def _still(values: dict[str, Array], xp: Any = np) -> NDArray[np.bool_]:
    """Where a port does not turn (speed ratio 0 or infinite, or the train locks:
    `_locked`), as far as the given values tell (False where they do not)."""
    still = _locked(values, xp)
    function, names = _RATIO[PORTS[0]]
    if all(n in values for n in names):
        with np.errstate(all="ignore"):
            ratio = xp.asarray(function(**{n: values[n] for n in names}))
        return cast(NDArray[np.bool_], still | ~xp.isfinite(ratio) | (ratio == 0))
    return still


def _locked(values: dict[str, Array], xp: Any = np) -> NDArray[np.bool_]:
    """Where a denominator of the motions (a member's speed over the input's) is 0: the
    train does not move from its input, however finite the reduced speed ratio."""
    if xp is not np:
        locked = xp.zeros(_shape_of(xp, values), dtype=xp.bool, device=_device(values))
    else:
        locked = np.zeros(np.broadcast_shapes(*(v.shape for v in values.values())), dtype=bool)
    for function, names in _MOTION.values():
        if all(n in values for n in names):
            with np.errstate(all="ignore"):
                locked = locked | (xp.asarray(function(**{n: values[n] for n in names})) == 0)
    return cast(NDArray[np.bool_], locked)


# Seven parameters, as the generated modules have them: this module is copied as it is
# into each (`davies_sym.emit.formula_code.runtime_of`), so a change here changes every
# module generated, which the catalog's outputs pin; a comment between definitions is
# not copied.
def _screened(
    result: Array,
    numbers: NDArray[np.int64],
    outside: NDArray[np.bool_],
    still: NDArray[np.bool_],
    errors: str,
    xp: Any = np,
    depth: int = 4,
) -> Array:
    """NaN (with a warning, or an error) where the design is not admissible (``outside``),
    a port does not turn (``still``), no variant holds (``numbers`` 0: the losses reverse
    loaded forces as none covers; ``result`` is then the region's own variant) or the train
    self-locks (the reasons and their words are those of `VariantSet.design_point`)."""
    _check_errors(errors)
    still = still & ~outside
    with np.errstate(invalid="ignore"):
        # Where no variant agrees, ``result`` is the region's own variant (`_own_where_none`):
        # not positive, the train self-locks; otherwise the losses reverse forces uncovered.
        uncovered = (numbers == 0) & ~(result <= 0) & ~outside & ~still
        locked = ~((result > 0) & (result <= 1 + 1e-12)) & ~outside & ~uncovered & ~still
    message = (
        f"{_count(outside, xp)} design point(s) outside the admissible parameters "
        f"(PARAMETERS, RELATIONS), {_count(still, xp)} where a port does not turn (speed ratio 0 "
        f"or infinite, or the train locks: a denominator of the motions vanishes), {_count(uncovered, xp)} "
        "where no variant's power flow agrees with its own forces (the losses reverse forces as no "
        f"variant covers) and {_count(locked, xp)} "
        "where the train self-locks (efficiency outside (0, 1]): NaN there"
    )
    return _nan_where(outside | still | uncovered | locked, result, message, errors, depth, xp)


def _chosen_any(input: str, values: dict[str, Array], xp: Any) -> tuple[Any, Any, Any, Any, Any]:
    """With arrays of another library than numpy: the variant numbers, the region's own
    ones where none holds, the arguments' floating type, and where the design is outside
    the admissible parameters or a port does not turn."""
    _check_input(input)
    dtype = _dtype(xp, values)
    mine = [v for v in VARIANTS if v["input"] == input]
    numbers, code = _numbers_any(xp, mine, _CONDITIONS, _FORCES, values, _shape_of(xp, values))
    outside = ~_admissible_any(xp, PARAMETERS, _RELATIONS, EXCLUDED, code, values)
    return numbers, _own_any(xp, mine, numbers, code), dtype, outside, _still(values, xp)


def _efficiency(input: str, errors: str, values: dict[str, Array], xp: Any = np) -> Array:
    """What ``efficiency`` returns, once its arguments are arrays."""
    if xp is not np:
        with np.errstate(all="ignore"):
            numbers, own, dtype, outside, still = _chosen_any(input, values, xp)
            selected = _select_any(xp, VARIANTS, own, _EFFICIENCY, 1, values, dtype)[0]
        return _screened(selected, numbers, outside, still, errors, xp, depth=4)

    def compute(part: dict[str, Array]) -> tuple[NDArray[Any], ...]:
        gathered: _Gathered = {}
        numbers = _variant_numbers(input, part, gathered)
        own = _own_where_none(input, part, numbers)
        return numbers, _select(own, part, _EFFICIENCY, 1, gathered), ~_admissible(part), _still(part)

    numbers, selected, outside, still = _blockwise(values, compute)
    return _screened(selected[0], numbers, outside, still, errors)


def _losses(input: str, errors: str, values: dict[str, Array], xp: Any = np) -> dict[str, Array]:
    """What ``losses`` returns: NaN wherever ``efficiency`` is."""
    return dict(zip(LOSSY, _per_variant(input, errors, values, xp, _LOSSES, len(LOSSY)), strict=True))


def _sensitivity(wrt: str, input: str, errors: str, values: dict[str, Array], xp: Any = np) -> Array:
    """What ``sensitivity`` returns: the partial derivative in ``wrt`` of the variant that
    holds (`_GRADIENT`), NaN wherever ``efficiency`` is."""
    if wrt not in SENSITIVE:
        raise ValueError(f"wrt must be one of {SENSITIVE}, got {wrt!r}")
    return _per_variant(input, errors, values, xp, _GRADIENT, len(SENSITIVE))[SENSITIVE.index(wrt)]


def _per_variant(input: str, errors: str, values: dict[str, Array], xp: Any, table: _Table, width: int) -> list[Array]:
    """The ``width`` results of ``table`` in the variant that holds, NaN wherever
    ``efficiency`` is (its warning said once)."""
    if xp is not np:
        with np.errstate(all="ignore"):
            numbers, own, dtype, outside, still = _chosen_any(input, values, xp)
            efficiency = _select_any(xp, VARIANTS, own, _EFFICIENCY, 1, values, dtype)[0]
            found = _select_any(xp, VARIANTS, numbers, table, width, values, dtype)
        bad = xp.isnan(_screened(efficiency, numbers, outside, still, errors, xp, depth=5))
        nan = xp.asarray(float("nan"), dtype=dtype, device=bad.device)
        return [xp.where(bad, nan, part) for part in found]

    def compute(part: dict[str, Array]) -> tuple[NDArray[Any], ...]:
        gathered: _Gathered = {}
        numbers = _variant_numbers(input, part, gathered)
        efficiency = _select(_own_where_none(input, part, numbers), part, _EFFICIENCY, 1, gathered)
        return numbers, efficiency, _select(numbers, part, table, width, gathered), ~_admissible(part), _still(part)

    numbers, efficiency, parts, outside, still = _blockwise(values, compute)
    bad = np.isnan(_screened(efficiency[0], numbers, outside, still, errors, depth=5))
    return [np.where(bad, np.nan, part) for part in parts]


def _speed_ratio(input: str, errors: str, values: dict[str, Array], xp: Any = np) -> Array:
    """Input speed over output speed with ``input`` as the input port; NaN (with a
    warning, or an error) where the design is not admissible."""
    _check_input(input)
    _check_errors(errors)
    function, names = _RATIO[PORTS[0]]
    with np.errstate(all="ignore"):
        if xp is not np:
            dtype = _dtype(xp, values)
            code = _region_any(xp, _CONDITIONS, values, _shape_of(xp, values))
            admissible = _admissible_any(xp, PARAMETERS, _RELATIONS, EXCLUDED, code, values)
        else:
            admissible, dtype = _admissible(values), np.float64
        ratio = xp.asarray(function(**{n: values[n] for n in names}), dtype=dtype)
        ratio = ratio if input == PORTS[0] else xp.asarray(1 / ratio)
    outside = ~admissible | ~xp.isfinite(ratio) | _locked(values, xp)
    message = (
        f"{_count(outside, xp)} design point(s) outside the admissible parameters "
        "(PARAMETERS, RELATIONS) or where a port does not turn: NaN there"
    )
    return _nan_where(outside, ratio, message, errors, 3, xp)


def _variant(input: str, errors: str, values: dict[str, Array], xp: Any = np) -> NDArray[np.int64]:
    """What ``variant`` returns: the variant numbers, 0 where none holds or the design is
    not admissible (with a warning, or an error)."""
    _check_errors(errors)
    if xp is not np:
        with np.errstate(all="ignore"):
            numbers, _, _, outside, _ = _chosen_any(input, values, xp)
    else:
        numbers, outside = _variant_numbers(input, values), ~_admissible(values)
    bad = (numbers == 0) | outside
    _refuse(
        bad,
        f"{_count(bad, xp)} design point(s) outside the admissible parameters or in no variant",
        errors,
        3,
        xp,
    )
    return cast(NDArray[np.int64], xp.where(bad, 0, numbers))
