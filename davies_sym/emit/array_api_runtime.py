"""The formula modules on arrays of any library that follows the array API standard
(CuPy, JAX, array-api-strict; PyTorch through ``array-api-compat``): which library the
arguments come from, and the variant choice on whole arrays with ``where`` (no writes
into an array, which JAX arrays do not allow; every variant evaluated everywhere and
the one that holds kept).  NumPy arrays keep the NumPy path of the runtimes, which
evaluates each variant on its own points only.

`davies_sym.emit.formula_code.runtime_of` copies these statements into every generated
module whose runtime imports from here, so a module stays self-contained: it needs
``array-api-compat`` only for a library whose arrays do not name their namespace.
The functions take the module's tables as arguments.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

_Functions = dict[str, tuple[Callable[..., Any], tuple[str, ...]]]


def _foreign(value: object) -> bool:
    """Whether ``value`` is an array of a library other than NumPy."""
    if value is None or isinstance(value, (np.ndarray, np.generic, int, float, list, tuple)):
        return False
    return hasattr(value, "__array_namespace__") or hasattr(value, "__dlpack__")


def _namespace(*values: object) -> Any:
    """``numpy``, or the array API namespace of the arrays of another library among
    ``values`` (through ``array-api-compat`` where it is installed)."""
    foreign = [v for v in values if _foreign(v)]
    if not foreign:
        return np
    try:
        compat = __import__("array_api_compat")
    except ImportError:
        compat = None
    if compat is not None:
        return compat.array_namespace(*foreign)
    spaces = []
    for v in foreign:
        if not hasattr(v, "__array_namespace__"):
            kind = f"{type(v).__module__}.{type(v).__name__}"
            raise TypeError(f"{kind} arrays need array-api-compat: pip install array-api-compat")
        spaces.append(v.__array_namespace__())
    if any(s is not spaces[0] for s in spaces):
        raise TypeError("the arguments are arrays of different libraries: give arrays of one")
    return spaces[0]


def _array(value: ArrayLike, xp: Any = np) -> NDArray[np.float64]:
    """``value`` as a float array of ``xp`` (numpy: float64; another library: its own
    floating type, a number as a 0-d array of its default one).  The annotation is
    numpy's: the formulas are the same on any library's arrays."""
    if xp is np:
        return np.asarray(value, dtype=np.float64)
    array: NDArray[np.float64] = xp.asarray(float(value) if isinstance(value, (int, float, np.generic)) else value)
    if xp.isdtype(array.dtype, "real floating"):
        return array
    converted: NDArray[np.float64] = xp.astype(array, _default_type(xp, "real floating", xp.float64))
    return converted


def _default_type(xp: Any, kind: str, otherwise: Any) -> Any:
    """The library's own type of ``kind`` (``"integral"``: int32 in JAX without x64, where
    asking for int64 warns and truncates), ``otherwise`` where it does not say."""
    info = getattr(xp, "__array_namespace_info__", None)
    return info().default_dtypes()[kind] if info is not None else otherwise


def _truth(value: object, xp: Any = np) -> NDArray[np.bool_]:
    """A comparison's result as a boolean array of ``xp``."""
    result: NDArray[np.bool_] = xp.asarray(value)
    return result


def _count(mask: Any, xp: Any = np) -> int:
    """How many elements of a boolean array are true."""
    return (
        int(np.count_nonzero(mask))
        if xp is np
        else int(xp.sum(xp.astype(mask, _default_type(xp, "integral", xp.int64))))
    )


def _dtype(xp: Any, values: dict[str, Any]) -> Any:
    """The floating type the arguments (arrays of ``xp``, `_array`'s) have together."""
    return xp.result_type(*(v.dtype for v in values.values())) if values else xp.float64


def _shape_of(xp: Any, values: dict[str, Any]) -> tuple[int, ...]:
    arrays = list(values.values())
    return tuple(xp.broadcast_arrays(*arrays)[0].shape) if arrays else ()


def _call(entry: tuple[Callable[..., Any], tuple[str, ...]], values: dict[str, Any]) -> Any:
    function, names = entry
    return function(**{n: values[n] for n in names})


def _region_any(xp: Any, conditions: _Functions, values: dict[str, Any], shape: tuple[int, ...]) -> Any:
    """Bit k set where turning condition k is negative."""
    integer = _default_type(xp, "integral", xp.int64)
    code = xp.zeros(shape, dtype=integer, device=_device(values))
    for bit, entry in enumerate(conditions.values()):
        code = code + xp.astype(_call(entry, values) < 0, integer) * (2**bit)
    return code


def _device(values: dict[str, Any]) -> Any:
    return next(iter(values.values())).device if values else None


def _agree_any(xp: Any, forces: _Functions, name: str, values: dict[str, Any]) -> Any:
    """Where each loaded force of variant ``name`` has the sign it needs (True without any)."""
    if name not in forces:
        return True
    found = _call(forces[name], values)
    agree: Any = True
    for force in found if isinstance(found, tuple) else (found,):
        agree = agree & (xp.asarray(force) >= 0)
    return agree


def _numbers_any(
    xp: Any,
    mine: Any,
    conditions: _Functions,
    forces: _Functions,
    values: dict[str, Any],
    shape: tuple[int, ...],
) -> tuple[Any, Any]:
    """The number of the variant (of ``mine``, those of the input port) that holds at each
    point, 0 where none does, as the NumPy path chooses it; and the region codes."""
    code = _region_any(xp, conditions, values, shape)
    numbers = xp.zeros(shape, dtype=_default_type(xp, "integral", xp.int64), device=_device(values))
    agree = {v["name"]: _agree_any(xp, forces, v["name"], values) for v in mine}
    for v in mine:
        numbers = xp.where((code == v["region"]) & (numbers == 0) & agree[v["name"]], v["number"], numbers)
    for v in mine:
        if v["name"] in forces:
            numbers = xp.where((numbers == 0) & agree[v["name"]], v["number"], numbers)
    return numbers, code


def _own_any(xp: Any, mine: Any, numbers: Any, code: Any) -> Any:
    """``numbers`` with each 0 replaced by the variant of the point's lossless region."""
    own = numbers
    for v in reversed(mine):
        own = xp.where((numbers == 0) & (code == v["region"]), v["number"], own)
    return own


# Seven parameters, as the generated modules have them: this module is copied as it is
# into each (`davies_sym.emit.formula_code.runtime_of`), so a change here changes every
# module generated, which the catalog's outputs pin; a comment between definitions is
# not copied.
def _select_any(
    xp: Any,
    variants: Any,
    numbers: Any,
    table: _Functions,
    width: int,
    values: dict[str, Any],
    dtype: Any,
) -> list[Any]:
    """The function of the variant that holds (``numbers``) at each point, ``width``
    results, NaN where none holds."""
    device = _device(values)
    result = [xp.full(tuple(numbers.shape), float("nan"), dtype=dtype, device=device) for _ in range(width)]
    for v in variants:
        here = numbers == v["number"]
        if v["name"] not in table or not bool(xp.any(here)):
            continue
        parts = _call(table[v["name"]], values)
        for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
            result[k] = xp.where(here, xp.asarray(part, dtype=dtype, device=device), result[k])
    return result


def _admissible_any(
    xp: Any,
    parameters: Any,
    relations: _Functions,
    excluded: tuple[int, ...],
    code: Any,
    values: dict[str, Any],
) -> Any:
    """Where every parameter is in its range, every relation holds and the region is not
    one of ``excluded``."""
    ok = _in_ranges_any(xp, parameters, values, tuple(code.shape))
    for entry in relations.values():
        if all(n in values for n in entry[1]):
            ok = ok & xp.asarray(_call(entry, values))
    for region in excluded:
        ok = ok & (code != region)
    return ok


def _in_ranges_any(xp: Any, parameters: Any, values: dict[str, Any], shape: tuple[int, ...]) -> Any:
    """Where every parameter given is in its range (low excluded unless closed_low)."""
    ok = xp.ones(shape, dtype=xp.bool, device=_device(values))
    for p in parameters:
        if p["name"] in values:
            v = values[p["name"]]
            ok = ok & ((v >= p["low"]) if p["closed_low"] else (v > p["low"])) & (v <= p["high"])
    return ok


def _first_disagreement(xp: Any, given: Any, implied: Any) -> tuple[float, float] | None:
    """The first (given, implied) pair that differ by more than 1e-9 relative (as
    numpy.isclose with atol 0), or None."""
    given, implied = xp.broadcast_arrays(given, implied)
    wrong = xp.reshape(~(xp.abs(given - implied) <= 1e-9 * xp.abs(implied)), (-1,))
    if not _count(wrong, xp):
        return None
    k = int(xp.argmax(xp.astype(wrong, xp.int8)))
    return float(xp.reshape(given, (-1,))[k]), float(xp.reshape(implied, (-1,))[k])
