"""The prepared workplace's large arrays cached on disk, keyed by the scene's content.

A 100 x 100 m hall's clearance field is 25 million nodes (200 MB) and its occupancy grids a few
tens of MB; several processes (joblib workers, repeated command-line runs) planning in the same
hall should build them once. Each array is stored as a ``.npy`` file named by a SHA-256 of
everything it depends on (the footprints' geometry, the floor bounds, the resolution and the
format version below), written atomically, and opened memory-mapped (copy-on-write): the
operating system shares the pages between the processes that read it.

The directory is ``workplaces/`` under the cache root (:func:`mjwalk._io.cache_root`:
``$MJWALK_CACHE`` or ``~/.cache/mjwalk``); ``$MJWALK_CACHE_DIR``, the directory itself, is still
read when set, with a deprecation message. Files are never read when their key differs, so a
changed scene simply builds (and stores) anew; deleting the directory is always safe.
"""

from __future__ import annotations

import functools
import hashlib
import logging
import os
import warnings
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from mjwalk._io import atomic_path, cache_root

#: Bump when the arrays' meaning or their algorithm changes: old files are then ignored.
FORMAT = "mjwalk-workplace-1"
#: Fields of at least this many nodes are cached by default (about 20 x 20 m at 0.02 m):
#: smaller ones build in well under a second.
AUTO_NODES = 1_000_000
#: Deprecated: the workplace cache directory itself (use ``$MJWALK_CACHE``, the cache root).
ENV_DIR = "MJWALK_CACHE_DIR"


def cache_dir() -> Path:
    """Where cached arrays live.

    Returns:
        ``workplaces/`` under :func:`mjwalk._io.cache_root`, or ``$MJWALK_CACHE_DIR`` when set
        (deprecated: a DeprecationWarning and a log message).
    """
    env = os.environ.get(ENV_DIR)
    if env:
        _deprecated_env()
        return Path(env).expanduser()
    return cache_root() / "workplaces"


@functools.cache
def _deprecated_env() -> None:
    """Say once per process that ``$MJWALK_CACHE_DIR`` is deprecated."""
    msg = (
        f"${ENV_DIR} is deprecated: set $MJWALK_CACHE (the root of all mjwalk caches; "
        "workplaces are cached in its workplaces/ folder)"
    )
    warnings.warn(msg, DeprecationWarning, stacklevel=3)
    logging.getLogger(__name__).warning(msg)


def use_disk(cache: bool | None, auto: bool) -> bool:
    """The workplace's cache policy (:attr:`mjwalk.world.workplace.WorkplaceOptions.cache`) for
    one array: whether it is read from and written to this cache.

    Args:
        cache: the policy: True always, False never, None where ``auto`` says.
        auto: whether the array is worth keeping by default (its rebuild costs more than a read:
            a field of at least :data:`AUTO_NODES` nodes, a hull of at least
            :data:`mjwalk.world.hullstore.DISK_HULL_POINTS` points).

    Returns:
        ``cache`` when given, else ``auto``.
    """
    return cache if cache is not None else auto


def content_key(*parts: object, arrays: Iterable[np.ndarray] = ()) -> str:
    """The cache key of everything an array depends on.

    Args:
        *parts: values hashed by their repr (bounds, resolution, counts...).
        arrays: arrays hashed by their bytes, dtype and shape.

    Returns:
        SHA-256 (64 hex digits) of the format version, ``parts`` and ``arrays``.
    """
    h = hashlib.sha256(FORMAT.encode())
    for p in parts:
        h.update(repr(p).encode())
        h.update(b"\0")
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def cached_array(
    key: str,
    what: str,
    build: Callable[[], np.ndarray],
    valid: Callable[[np.ndarray], bool] | None = None,
) -> np.ndarray:
    """The array stored under a key, memory-mapped; built and stored on a miss.

    A cache that cannot be written (read-only home, full disk) is skipped: the built array is
    returned as is. A damaged file (one NumPy cannot read, or one ``valid`` refuses) is rebuilt
    over.

    Args:
        key: the content key (:func:`content_key`).
        what: which array of the key ("clearance", "walk"...), part of the file name.
        build: makes the array on a miss.
        valid: checks a stored array before it is used (None: any array NumPy reads is taken).

    Returns:
        The array, copy-on-write memory-mapped from ``{key[:32]}-{what}.npy`` when stored.
    """
    path = cache_dir() / f"{key[:32]}-{what}.npy"
    if path.is_file():
        try:
            stored = np.asarray(np.load(path, mmap_mode="c"))
        except (OSError, ValueError):  # a damaged file: rebuild over it
            pass
        else:
            if valid is None or valid(stored):
                return stored
    arr = build()
    try:
        with atomic_path(path) as tmp:
            np.save(tmp, arr)
    except OSError:
        return arr
    return np.asarray(np.load(path, mmap_mode="c"))
