"""Walk-independent pieces of a walk over levels, computed once and kept on their owner.

A scene's crossings, level views and walkers come back walk after walk (a cycle's operator walks
the same routes; a benchmark plans the same pair with other seeds), and several pieces of a walk
over levels depend on nothing else: a crossing's footfalls for a walker and direction
(:func:`mjwalk.plan.levelcross.flight_start`), the crossing walked on past its far stance
(:func:`mjwalk.plan.levelcross.departure`), whether the body fits along a segment of a level
(:func:`mjwalk.plan.levelcross.line_clear`). :func:`kept` keeps such a value in a bounded memo
(:class:`~mjwalk.boundedmemo.Memo`) on the object it belongs to (the crossing, the level's
view), keyed by everything else it depends on, so a cached value is the very value the
computation gives (no rounding of keys: the same floats give the same key). Arrays kept are
made read-only, so no caller can change them for the next. No behaviour of walkers: a cost
bound only.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Hashable
from dataclasses import replace
from typing import TypeVar

import numpy as np

from mjwalk.boundedmemo import Memo
from mjwalk.plan.options import PlannerOptions

T = TypeVar("T")

#: Entries kept per owner and name before the oldest is dropped: a memory bound (a cycle's
#: operators come and go, each a walker of its own), no behaviour.
MAX_KEPT = 256


def kept(owner: object, name: str, key: Hashable, make: Callable[[], T]) -> T:
    """``make()``, computed once per ``key`` and kept in a :class:`~mjwalk.boundedmemo.Memo` of
    :data:`MAX_KEPT` values in ``owner``'s ``__dict__`` under ``name``.

    Args:
        owner: the object the value belongs to (a crossing, a level's view; frozen
            dataclasses have an instance ``__dict__``).
        name: the cache's attribute name on ``owner``.
        key: everything else the value depends on (hashable; floats as given).
        make: computes the value.

    Returns:
        The value; numpy arrays in it (alone or in a tuple) read-only. An owner without an
        instance dictionary of its own (a class) keeps nothing: the value is made each time.
    """
    own = getattr(owner, "__dict__", None)
    if not isinstance(own, dict):
        return make()
    memo = own.get(name)
    if memo is None:
        memo = own[name] = Memo(limit=MAX_KEPT)
    return memo.get(key, lambda: _read_only(make()))


def _read_only(value: T) -> T:
    """``value`` with the numpy arrays in it (alone or in a tuple) made read-only."""
    for a in value if isinstance(value, tuple) else (value,):
        if isinstance(a, np.ndarray):
            a.flags.writeable = False
    return value


def _exact(value: object) -> object:
    """A key part that tells apart what ``==`` does not: a float's sign of zero."""
    return (value, math.copysign(1.0, value)) if isinstance(value, float) else value


def variant(options: T, **changes: object) -> T:
    """``dataclasses.replace(options, **changes)``, made once per options object and changes
    (planner options check every field on construction, about 0.07 ms; a level walk asks for
    the same variants leg after leg). Kept per ``id(options)`` with ``options`` held, so an
    entry is never another object's; floats keyed with their sign.

    Args:
        options: a frozen dataclass (:class:`~mjwalk.plan.options.PlannerOptions`).
        **changes: the fields to change.

    Returns:
        The variant (the same object for the same ``options`` and changes).
    """
    key = (id(options), *((k, _exact(v)) for k, v in sorted(changes.items())))
    hit = _VARIANTS.get(key)
    if hit is not None and hit[0] is options:
        return hit[1]
    made = replace(options, **changes)  # type: ignore[type-var]
    while len(_VARIANTS) >= MAX_KEPT:
        _VARIANTS.pop(next(iter(_VARIANTS)))
    _VARIANTS[key] = (options, made)
    return made


#: :func:`variant`'s entries: key -> (the options, the variant).
_VARIANTS: dict[tuple, tuple] = {}


@functools.cache
def default_options() -> PlannerOptions:
    """``PlannerOptions()``, made once (it has no arguments, so every call's is equal).

    Returns:
        The default planner options (one object).
    """
    return PlannerOptions()
