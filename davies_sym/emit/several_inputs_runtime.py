"""The hand-written part of every generated formula module of a train driven on several
shafts (numpy only).

`davies_sym.emit.several_inputs_module` copies this file's imports, types and
functions into each module it writes and puts the train's tables and formulas where the
placeholders below stand, so this code is linted, type-checked and imported like the
rest of the package.

The speed conditions are linear forms in the input speeds; their signs pick the
power-flow regions with those signs; of these, the one whose loaded forces (tooth
forces, bearing reactions) all have the signs it assumes holds (at light load, drag can
reverse a tooth force and swap a mesh's driving gear).  A point gets NaN (with a
warning, or an error) where it lies on a condition line, where no region's forces agree,
outside the parameters' ranges, or where the efficiency is outside (0, 1].
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any, Final, TypedDict

import numpy as np
from numpy.typing import ArrayLike, NDArray

from davies_sym.emit.array_api_runtime import (
    _agree_any,
    _count,
    _default_type,
    _device,
    _dtype,
    _in_ranges_any,
    _select_any,
    _shape_of,
)
from davies_sym.emit.shared_runtime import _at, _blockwise

Array = NDArray[np.float64]
_Table = dict[str, tuple[Callable[..., Any], tuple[str, ...]]]


class Parameter(TypedDict):
    """A parameter of the formulas and its range (low excluded unless closed_low)."""

    name: str
    meaning: str
    unit: str
    low: float
    high: float
    closed_low: bool


class Region(TypedDict):
    """One power-flow region: where it holds, which gears drive, where power goes in and
    out, and its efficiency (Mantriota and Pennestri 2003, eq. (6))."""

    name: str
    number: int
    code: int
    conditions: tuple[str, ...]
    meshes: tuple[str, ...]
    power_in: tuple[str, ...]
    power_out: tuple[str, ...]
    reversed: tuple[str, ...]
    forces: tuple[str, ...]
    formula: str
    latex: str


class DesignWarning(RuntimeWarning):
    """Some points are in no region, outside the ranges, or where losses exceed the load (NaN there)."""


class DesignError(ValueError):
    """Raised instead of DesignWarning with errors='raise'."""


# Placeholders: each generated module has its own tables and formulas here.
INPUTS: Final[tuple[str, ...]] = ()
OUTPUT: Final[str] = ""
PORTS: Final[tuple[str, ...]] = ()
PARAMETERS: Final[tuple[Parameter, ...]] = ()
SPEEDS: Final[dict[str, str]] = {}
CONDITIONS: Final[dict[str, tuple[str, str]]] = {}
REGIONS: Final[tuple[Region, ...]] = ()
_CONDITIONS: Final[_Table] = {}
_SPEEDS: Final[_Table] = {}
_EFFICIENCY: Final[_Table] = {}
_TORQUES: Final[_Table] = {}
_FORCES: Final[_Table] = {}


def _numpy(value: ArrayLike) -> Array:
    return np.asarray(value, dtype=np.float64)


def _choice_any(values: dict[str, Any], xp: Any) -> tuple[Any, Any]:
    """`_choice` on the arrays of another library than numpy, with where() on whole arrays."""
    shape = _shape_of(xp, values)
    device = _device(values)
    integer = _default_type(xp, "integral", xp.int64)
    code = xp.zeros(shape, dtype=integer, device=device)
    boundary = xp.zeros(shape, dtype=xp.bool, device=device)
    for bit, (function, names) in enumerate(_CONDITIONS.values()):
        level = function(**{n: values[n] for n in names})
        code = code + xp.astype(level < 0, integer) * (2**bit)
        boundary = boundary | ~(level != 0)
    numbers = xp.zeros(shape, dtype=integer, device=device)
    count = xp.zeros(shape, dtype=integer, device=device)
    for region in REGIONS:
        mask = (code == region["code"]) & ~boundary & _agree_any(xp, _FORCES, region["name"], values)
        numbers = xp.where(mask, region["number"], numbers)
        count = count + xp.astype(mask, integer)
    return xp.where(count > 1, -1, numbers), boundary


def _screened_any(values: dict[str, Any], table: _Table, width: int, errors: str, xp: Any) -> list[Any]:
    """`_screened` on the arrays of another library than numpy (a list of its arrays)."""
    _check_errors(errors)
    dtype = _dtype(xp, values)
    with np.errstate(all="ignore"):
        numbers, boundary = _choice_any(values, xp)
        result = _select_any(xp, REGIONS, numbers, table, width, values, dtype)
        eta = result[0] if table is _EFFICIENCY else _select_any(xp, REGIONS, numbers, _EFFICIENCY, 1, values, dtype)[0]
        outside = ~_in_ranges_any(xp, PARAMETERS, values, tuple(numbers.shape))
        bad, why = _not_covered(numbers, boundary, eta, outside, xp)
    if _count(bad, xp):
        if errors == "raise":
            raise DesignError(why)
        if errors == "warn":
            warnings.warn(why, DesignWarning, stacklevel=4)
    nan = xp.asarray(float("nan"), dtype=dtype, device=numbers.device)
    return [xp.where(bad, nan, r) for r in result]


def _check_errors(errors: str) -> None:
    if errors not in ("warn", "raise", "ignore"):
        raise ValueError(f"errors must be 'warn', 'raise' or 'ignore', got {errors!r}")


def _shape(values: dict[str, Array]) -> tuple[int, ...]:
    return np.broadcast_shapes(*(v.shape for v in values.values()))


def _codes(values: dict[str, Array]) -> tuple[NDArray[np.int64], NDArray[np.bool_]]:
    """Bit k set where speed condition k is negative; and where some condition is zero
    (the speeds on a boundary between regions)."""
    shape = _shape(values)
    code = np.zeros(shape, dtype=np.int64)
    boundary = np.zeros(shape, dtype=bool)
    with np.errstate(all="ignore"):
        for bit, (function, names) in enumerate(_CONDITIONS.values()):
            level = np.broadcast_to(function(**{n: values[n] for n in names}), shape)
            code |= np.asarray(level < 0, dtype=np.int64) << bit
            boundary |= ~(level != 0)
    return code, boundary


def _region_numbers(values: dict[str, Array], xp: Any = np) -> NDArray[np.int64]:
    """The number of the region that holds at each point: its speed conditions hold and
    every loaded force has the sign it assumes; 0 where none holds (on a condition line,
    or the losses reverse forces as no region covers), -1 where several do."""
    if xp is not np:
        numbers: NDArray[np.int64] = _choice_any(values, xp)[0]
        return numbers
    return _choice(values)[0]


def _choice(values: dict[str, Array]) -> tuple[NDArray[np.int64], NDArray[np.bool_]]:
    """`_region_numbers`, and where the speeds lie on a condition line."""
    code, boundary = _codes(values)
    numbers = np.zeros(code.shape, dtype=np.int64)
    count = np.zeros(code.shape, dtype=np.int64)
    # Regions that differ only in the loaded forces the losses reverse share their code.
    inside: dict[int, NDArray[np.bool_]] = {}
    with np.errstate(all="ignore"):
        for region in REGIONS:
            if region["code"] not in inside:
                inside[region["code"]] = np.asarray((code == region["code"]) & ~boundary, dtype=bool)
            mask = inside[region["code"]].copy()
            if mask.any() and region["name"] in _FORCES:
                function, names = _FORCES[region["name"]]
                index = np.flatnonzero(mask)
                forces = function(**_at(values, names, index, mask.shape))
                # A force that depends on none of the arrays comes back as a scalar.
                size = (len(index),)
                agree = np.all(
                    [
                        np.broadcast_to(np.asarray(f) >= 0, size)
                        for f in (forces if isinstance(forces, tuple) else (forces,))
                    ],
                    axis=0,
                )
                mask.reshape(-1)[index] = agree
            numbers[mask] = region["number"]
            count += mask
    numbers[count > 1] = -1
    return numbers, boundary


def _select(numbers: NDArray[np.int64], values: dict[str, Array], table: _Table, width: int) -> Array:
    """The function of the region that holds (``numbers``), evaluated on that region's
    points only; shape (width, *broadcast shape), NaN where no region holds."""
    result = np.full((width, *numbers.shape), np.nan)
    with np.errstate(all="ignore"):
        for region in REGIONS:
            mask = numbers == region["number"]
            if not mask.any() or region["name"] not in table:
                continue
            function, names = table[region["name"]]
            index = np.flatnonzero(mask)
            parts = function(**_at(values, names, index, mask.shape))
            flat = result.reshape(width, -1)
            for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
                flat[k, index] = part
    return result


def _outside_ranges(values: dict[str, Array]) -> NDArray[np.bool_]:
    """Where some parameter is outside its range (PARAMETERS)."""
    bad = np.zeros(_shape(values), dtype=bool)
    with np.errstate(all="ignore"):
        for p in PARAMETERS:
            v = values[p["name"]]
            bad |= ~(((v >= p["low"]) if p["closed_low"] else (v > p["low"])) & (v <= p["high"]))
    return bad


def _not_covered(
    numbers: NDArray[np.int64], boundary: NDArray[np.bool_], eta: Array, outside: NDArray[np.bool_], xp: Any = np
) -> tuple[NDArray[np.bool_], str]:
    """Where the formulas do not hold, and why (counts of each reason), given the regions
    chosen, the condition lines, the efficiency and the points outside the ranges."""
    on_line = boundary & ~outside
    nowhere = (numbers <= 0) & ~boundary & ~outside
    with np.errstate(invalid="ignore"):
        locked = ~((eta > 0) & (eta <= 1 + 1e-12)) & (numbers > 0) & ~outside
    why = (
        f"{_count(outside, xp)} point(s) outside the parameters' ranges (PARAMETERS), "
        f"{_count(on_line, xp)} on a speed-condition line, {_count(nowhere, xp)} where "
        "no region's loaded forces agree with their assumed signs (losses reversing forces as no region "
        f"covers) and {_count(locked, xp)} with an efficiency outside (0, 1]: NaN there"
    )
    return outside | on_line | nowhere | locked, why


def _screened(values: dict[str, Array], table: _Table, width: int, errors: str) -> Array:
    """The functions of ``table`` in the region that holds (shape (width, *shape)), NaN
    where the formulas do not hold; the regions are chosen once, block by block."""
    _check_errors(errors)

    def compute(part: dict[str, Array]) -> tuple[NDArray[Any], ...]:
        numbers, boundary = _choice(part)
        result = _select(numbers, part, table, width)
        eta = result[0] if table is _EFFICIENCY else _select(numbers, part, _EFFICIENCY, 1)[0]
        return result, numbers, boundary, eta, _outside_ranges(part)

    result, numbers, boundary, eta, outside = _blockwise(values, compute)
    bad, why = _not_covered(numbers, boundary, eta, outside)
    if not bad.any():
        return result
    if errors == "raise":
        raise DesignError(why)
    if errors == "warn":
        warnings.warn(why, DesignWarning, stacklevel=4)
    return np.where(bad, np.nan, result)


def _efficiency(errors: str, values: dict[str, Array], xp: Any = np) -> Array:
    """What ``efficiency`` returns, once its arguments are arrays."""
    if xp is not np:
        efficiency: Array = _screened_any(values, _EFFICIENCY, 1, errors, xp)[0]
        return efficiency
    return _numpy(_screened(values, _EFFICIENCY, 1, errors)[0])


def _torques(errors: str, values: dict[str, Array], xp: Any = np) -> dict[str, Array]:
    """What ``torques`` returns: the torque the outside applies at each port."""
    parts = (
        _screened_any(values, _TORQUES, len(PORTS), errors, xp)
        if xp is not np
        else _screened(values, _TORQUES, len(PORTS), errors)
    )
    return {port: part for port, part in zip(PORTS, parts, strict=True)}


def _speeds(values: dict[str, Array], xp: Any = np) -> dict[str, Array]:
    """What ``speeds`` returns: the speed of every port."""
    if xp is not np:
        dtype = _dtype(xp, values)
        shape = _shape_of(xp, values)
        return {
            port: xp.broadcast_to(xp.asarray(function(**{n: values[n] for n in names}), dtype=dtype), shape)
            for port, (function, names) in _SPEEDS.items()
        }
    shape = _shape(values)
    out = {}
    with np.errstate(all="ignore"):
        for port, (function, names) in _SPEEDS.items():
            out[port] = np.broadcast_to(_numpy(function(**{n: values[n] for n in names})), shape)
    return out
