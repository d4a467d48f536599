"""Results cached on the immutable values they were derived from.

A stage that derives something from a `Train` (its layout, its resolved form, the
reduced train of a state, the screw work its states share) keeps it here, keyed by the
train object itself and dropped with it: the train stays a plain frozen value (it has no
mutable slot for later stages to fill), and nothing outlives the objects it describes.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

K = TypeVar("K")
V = TypeVar("V")


class IdentityCache(Generic[K, V]):
    """Values computed from objects that cannot be hashed by value (frozen dataclasses
    holding mappings), kept while each object lives: keyed by identity (and a further
    hashable key), released by a weak reference's callback."""

    def __init__(self) -> None:
        self._entries: dict[tuple[int, Hashable], tuple[weakref.ref[object], V]] = {}

    def peek(self, owner: K, key: Hashable = None) -> V | None:
        """The value cached for ``owner`` (and ``key``), or None when none is."""
        found = self._entries.get((id(owner), key))
        return found[1] if found is not None and found[0]() is owner else None

    def get(self, owner: K, compute: Callable[[], V], key: Hashable = None) -> V:
        """The value for ``owner`` (and ``key``), computed by ``compute`` the first time."""
        slot = (id(owner), key)
        found = self._entries.get(slot)
        if found is not None and found[0]() is owner:
            return found[1]
        value = compute()
        entries = self._entries
        self._entries[slot] = (weakref.ref(owner, lambda _: entries.pop(slot, None)), value)
        return value
