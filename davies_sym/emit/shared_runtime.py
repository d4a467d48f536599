"""What the hand-written runtimes of the formula modules share: evaluation in blocks and
the gathering of a variant's (or region's) arguments at its points.

`davies_sym.emit.formula_code.runtime_of` copies this file's statements into every
generated module whose runtime imports from it (the import itself is left out), so a
module stays self-contained (numpy only).  Its imports must be among the runtimes' own.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

#: Design points evaluated at a time: the temporaries of a block stay in the cache and in
#: memory the allocator keeps, instead of being mapped and faulted in afresh by every
#: operation on the whole array (on a million points that took half the time).
_BLOCK = 65536


def _blockwise(
    values: dict[str, NDArray[np.float64]],
    compute: Callable[[dict[str, NDArray[np.float64]]], tuple[NDArray[Any], ...]],
) -> tuple[NDArray[Any], ...]:
    """``compute`` on ``values`` block by block of `_BLOCK` points (broadcast and
    flattened first); each result's blocks joined along its last axis, in the broadcast
    shape (leading axes, such as a function's outputs, kept)."""
    shape = np.broadcast_shapes(*(v.shape for v in values.values()))
    size = int(np.prod(shape))
    if size <= _BLOCK:
        return compute(values)
    flat = {n: v if v.ndim == 0 else np.broadcast_to(v, shape).reshape(-1) for n, v in values.items()}
    blocks = []
    for start in range(0, size, _BLOCK):
        results = compute({n: v if v.ndim == 0 else v[start : start + _BLOCK] for n, v in flat.items()})
        # A result that depends on none of the arrays (a constant speed ratio) is 0-d: one per point.
        length = min(_BLOCK, size - start)
        blocks.append(tuple(r if r.ndim else np.broadcast_to(r, (length,)) for r in results))
    return tuple(
        np.concatenate(pieces, axis=-1).reshape(*pieces[0].shape[:-1], *shape) for pieces in zip(*blocks, strict=True)
    )


def _at(
    values: dict[str, NDArray[np.float64]],
    names: tuple[str, ...],
    index: NDArray[np.intp],
    shape: tuple[int, ...],
    kept: dict[str, NDArray[np.float64]] | None = None,
) -> dict[str, NDArray[np.float64]]:
    """The arguments ``names`` at the flat ``index`` of the broadcast ``shape`` (gathered
    by index: a boolean mask would be counted again for every argument), taken from
    ``kept`` where gathered before at the same points, and kept there."""
    kept = {} if kept is None else kept
    for n in names:
        if n not in kept:
            v = values[n]
            kept[n] = v if v.ndim == 0 else np.broadcast_to(v, shape).reshape(-1)[index]
    return {n: kept[n] for n in names}
