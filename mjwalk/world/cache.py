"""The prepared workplace's large arrays cached on disk, keyed by the scene's content.

A 100 x 100 m hall's clearance field is 25 million nodes (200 MB) and its occupancy grids a few
tens of MB; several processes (joblib workers, repeated command-line runs) planning in the same
hall should build them once. Each array is stored as a ``.npy`` file named by a SHA-256 of
everything it depends on (the footprints' geometry, the floor bounds, the resolution and the
format version below), written atomically, and opened memory-mapped (copy-on-write): the
operating system shares the pages between the processes that read it.

The directory is ``$MJWALK_CACHE_DIR`` when set, else ``~/.cache/mjwalk/workplaces``. Files
are never read when their key differs, so a changed scene simply builds (and stores) anew;
deleting the directory is always safe.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

#: Bump when the arrays' meaning or their algorithm changes: old files are then ignored.
FORMAT = "mjwalk-workplace-1"
#: Fields of at least this many nodes are cached by default (about 20 x 20 m at 0.02 m):
#: smaller ones build in well under a second.
AUTO_NODES = 1_000_000
ENV_DIR = "MJWALK_CACHE_DIR"


def cache_dir() -> Path:
    """Where cached arrays live: ``$MJWALK_CACHE_DIR`` or ``~/.cache/mjwalk/workplaces``."""
    env = os.environ.get(ENV_DIR)
    return Path(env) if env else Path.home() / ".cache" / "mjwalk" / "workplaces"


def content_key(*parts: object, arrays: Iterable[np.ndarray] = ()) -> str:
    """SHA-256 (hex) of the format version, ``parts`` (their repr) and the arrays' bytes,
    dtypes and shapes."""
    h = hashlib.sha256(FORMAT.encode())
    for p in parts:
        h.update(repr(p).encode())
        h.update(b"\0")
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def cached_array(key: str, what: str, build: Callable[[], np.ndarray]) -> np.ndarray:
    """The array stored under ``key``/``what``, memory-mapped; built by ``build()`` and stored
    (atomically) on a miss. A cache that cannot be written (read-only home, full disk) is
    skipped: the built array is returned as is."""
    path = cache_dir() / f"{key[:32]}-{what}.npy"
    if path.is_file():
        try:
            return np.asarray(np.load(path, mmap_mode="c"))
        except (OSError, ValueError):  # a damaged file: rebuild over it
            pass
    arr = build()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".npy.tmp")
        try:
            with os.fdopen(fd, "wb") as fh:
                np.save(fh, arr)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except OSError:
        return arr
    return np.asarray(np.load(path, mmap_mode="c"))
