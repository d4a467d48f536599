"""A read-only mapping whose values are computed when first read, then kept: the
solutions of the network hold one rational function per action, and most derivations
read a few of them (the ports, the meshes), so the rest are never formed."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Generic, TypeVar

K = TypeVar("K")
V = TypeVar("V")


class LazyMapping(Mapping[K, V], Generic[K, V]):
    """``keys`` mapped by ``value``, each value computed on first access."""

    def __init__(self, keys: Sequence[K], value: Callable[[K], V]):
        self._keys = tuple(keys)
        self._known = frozenset(self._keys)
        self._value = value
        self._cache: dict[K, V] = {}

    def __getitem__(self, key: K) -> V:
        if key not in self._cache:
            if key not in self._known:
                raise KeyError(key)
            self._cache[key] = self._value(key)
        return self._cache[key]

    def __iter__(self) -> Iterator[K]:
        return iter(self._keys)

    def __len__(self) -> int:
        return len(self._keys)
