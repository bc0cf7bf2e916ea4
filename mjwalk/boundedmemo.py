"""A bounded memo: values made once per key and kept, the oldest dropped first (:class:`Memo`).

Shared by every stage (it sits below them all): the cycle's caches (:mod:`mjwalk.cycle.memo`
re-exports it; the planners and grid-A* routes, the prepared contexts and the operators'
humanoids by :mod:`mjwalk.cycle.context`, the stand zones by :mod:`mjwalk.cycle.standing`) and
the walk-independent pieces of a walk over levels kept on their owner
(:func:`mjwalk.plan.levelmemo.kept`). A memory bound, no behaviour: a value depends on its key
alone.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")

#: What :meth:`Memo.get` finds for a key not kept (no value is this object).
_ABSENT = object()


class Memo(Generic[K, V]):
    """The values ``make(key)``, each made on its key's first :meth:`get` and kept, at most
    ``limit`` of them (None: no bound): the one kept longest goes first when a new key needs
    room. A value depends on its key alone, so what was asked before never changes what a
    :meth:`get` returns.

    Args:
        make: builds the value of a key (None: each :meth:`get` gives its own maker).
        limit: how many values are kept (None: all).
    """

    def __init__(self, make: Callable[[K], V] | None = None, limit: int | None = None):
        self._make = make
        self._limit = limit
        self._kept: dict[K, V] = {}

    def get(self, key: K, make: Callable[[], V] | None = None) -> V:
        """The value of ``key`` (made now when it is not kept, dropping the oldest kept value when
        the memo is full).

        Args:
            key: the value's key.
            make: builds the value when it is not kept (None: the memo's ``make(key)``); the
                caller's key names everything it depends on.

        Returns:
            The value, made once while it is kept.

        Raises:
            TypeError: the memo has no maker and the call gives none.
        """
        kept = self._kept
        value = kept.get(key, _ABSENT)  # one hash of the key on a hit (a stand zone's is long)
        if value is not _ABSENT:
            return value  # type: ignore[return-value]
        if make is None and self._make is None:
            raise TypeError("Memo.get: no maker for a key not kept")
        if self._limit is not None:
            while len(kept) >= self._limit:
                kept.pop(next(iter(kept)))
        value = make() if make is not None else self._make(key)  # type: ignore[misc]
        kept[key] = value
        return value

    def __len__(self) -> int:
        return len(self._kept)

    def clear(self) -> None:
        """Forget every kept value (a benchmark's cold start)."""
        self._kept.clear()

    def __contains__(self, key: object) -> bool:
        return key in self._kept
