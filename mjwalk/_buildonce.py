"""A cached model file built by one process at a time.

The default models are trained on first use and cached (:func:`mjwalk._io.cache_root`). When
several processes meet an empty cache at once (two test workers, a batch's workers, two
terminals), each used to train the same model side by side, every one of them slower for the
others. :func:`built_once` lets the first process build while the others wait on a lock file
beside the model and then load what it wrote: the build's result is the same whichever process
made it (it is seeded), so the wait loses nothing.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TypeVar

from mjwalk.errors import ModelFileError

try:  # POSIX; elsewhere the processes build side by side, as before
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]

T = TypeVar("T")


@contextlib.contextmanager
def _locked(path: Path) -> Iterator[None]:
    """Hold an exclusive lock on ``path``'s lock file; no lock where one cannot be made (no
    ``fcntl``, a folder that cannot be written: the build's own write names that)."""
    if fcntl is None:
        yield
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(path.with_name(path.name + ".lock"), os.O_RDWR | os.O_CREAT, 0o644)
    except OSError:
        yield
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock


def built_once(
    path: Path,
    load: Callable[[Path], T],
    build: Callable[[], T],
    *,
    on_stale: Callable[[ModelFileError], None] | None = None,
) -> T:
    """The model at ``path``: loaded when a readable file is there, else built by ``build``
    (which saves it at ``path``) under an inter-process lock.

    Args:
        path: the cached model file.
        load: reads the file; raises :class:`~mjwalk.errors.ModelFileError` for a file of
            another version or a damaged one, which is then rebuilt.
        build: makes the model and saves it at ``path``.
        on_stale: told why a file that was there is rebuilt.

    Returns:
        The loaded or built model.
    """

    def try_load(report: bool) -> T | None:
        if not path.is_file():
            return None
        try:
            return load(path)
        except ModelFileError as exc:
            if report and on_stale is not None:
                on_stale(exc)
            return None

    model = try_load(report=False)
    if model is not None:
        return model
    with _locked(path):
        # another process may have built it while this one waited for the lock
        model = try_load(report=True)
        return model if model is not None else build()
