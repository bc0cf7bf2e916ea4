"""A bounded memo: values made once per key and kept, the oldest dropped first
(:class:`Memo`). The cycle's caches are memos with a key of their own, each owned by the
module that makes its values (the planners and grid-A* routes, the prepared contexts and the
operators' humanoids by :mod:`mjwalk.cycle.context`, the stand zones by
:mod:`mjwalk.cycle.standing`)."""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class Memo(Generic[K, V]):
    """The values ``make(key)``, each made on its key's first :meth:`get` and kept, at most
    ``limit`` of them (None: no bound): the one kept longest goes first when a new key needs
    room. A value depends on its key alone, so what was asked before never changes what a
    :meth:`get` returns.

    Args:
        make: builds the value of a key.
        limit: how many values are kept (None: all).
    """

    def __init__(self, make: Callable[[K], V], limit: int | None = None):
        self._make = make
        self._limit = limit
        self._kept: dict[K, V] = {}

    def get(self, key: K) -> V:
        """The value of ``key`` (made now when it is not kept, dropping the oldest kept value when
        the memo is full).

        Args:
            key: the value's key.

        Returns:
            ``make(key)``, made once while it is kept.
        """
        if key not in self._kept:
            if self._limit is not None:
                while len(self._kept) >= self._limit:
                    self._kept.pop(next(iter(self._kept)))
            self._kept[key] = self._make(key)
        return self._kept[key]

    def __len__(self) -> int:
        return len(self._kept)

    def __contains__(self, key: object) -> bool:
        return key in self._kept
