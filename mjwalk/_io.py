"""Small I/O helpers shared by every module that writes files: atomic writes, versioned
``.npz`` files, and the cache root."""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path

#: The environment variable naming the root of every cache mjwalk keeps (trained default models,
#: workplace arrays under ``workplaces/``); unset: ``~/.cache/mjwalk``.
CACHE_ENV = "MJWALK_CACHE"


def cache_root() -> Path:
    """The root of mjwalk's caches: ``$MJWALK_CACHE`` (``~`` expanded) or ``~/.cache/mjwalk``.
    Deleting it is always safe: its files are rebuilt on first use."""
    env = os.environ.get(CACHE_ENV)
    return Path(env).expanduser() if env else Path.home() / ".cache" / "mjwalk"


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` only on success.

    A crash or an exception leaves no half-written file behind: the temporary file is removed.
    ``suffix`` defaults to the target's own suffix so writers that infer the format from the
    extension (imageio, matplotlib) keep working.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{path.name}.",
        suffix=suffix if suffix is not None else path.suffix,
        dir=path.parent,
    )
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600 files; give the usual permissions
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        os.replace(tmp_path, path)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


def save_npz(path: str | os.PathLike, header: dict, arrays: dict) -> None:
    """Write ``arrays`` and a JSON ``header`` (format name, version, metadata) to one compressed
    ``.npz`` file, atomically. ``default`` turns numpy scalars/arrays in the header into JSON."""
    import json

    import numpy as np

    def default(obj):
        if isinstance(obj, np.generic):
            return obj.item()
        if isinstance(obj, np.ndarray):
            return obj.tolist()
        raise TypeError(f"not JSON serializable: {type(obj).__name__}")

    data = dict(arrays, header=np.array(json.dumps(header, default=default)))
    with atomic_path(path, suffix=".npz") as tmp, open(tmp, "wb") as fh:
        np.savez_compressed(fh, **data)


def load_npz(path: str | os.PathLike, what: str) -> tuple[dict, dict]:
    """Read a file written by :func:`save_npz`: (header dict, arrays without the header).

    A missing, unreadable or header-less file raises ``ModelFileError`` naming the file and
    ``what`` it should have been (e.g. "step-model"); :func:`check_header` checks the format
    and version.
    """
    import json
    import zipfile

    import numpy as np

    from mjwalk.errors import ModelFileError

    path = Path(path)
    if not path.is_file():
        raise ModelFileError(f"{path}: no such {what} file")
    if not zipfile.is_zipfile(path):
        raise ModelFileError(
            f"{path}: not an mjwalk {what} file: mjwalk writes .npz (zip) archives, and this "
            "file is not one (corrupt, truncated, or another kind of file)"
        )
    try:
        with np.load(path, allow_pickle=False) as z:
            if "header" not in z.files:
                raise ModelFileError(f"{path}: not an mjwalk {what} file (no header)")
            header = json.loads(str(z["header"]))
            data = {k: z[k] for k in z.files if k != "header"}
    except ModelFileError:
        raise
    except (OSError, ValueError, KeyError, zipfile.BadZipFile, EOFError, TypeError) as exc:
        if "pickle" in str(exc):  # numpy's advice to load pickles is not ours to give
            why = "it holds Python objects (pickled arrays), which mjwalk never writes"
        else:
            why = f"{type(exc).__name__}: {exc}"
        raise ModelFileError(f"{path}: not a readable mjwalk {what} file ({why})") from exc
    if not isinstance(header, dict):
        raise ModelFileError(f"{path}: the {what} file's header is not a JSON object")
    return header, data


def check_header(header: dict, source, what: str, fmt: str, version: int) -> None:
    """Raise ``ModelFileError`` naming ``source`` unless ``header`` is of format ``fmt`` and
    version ``version`` (the header :func:`save_npz` wrote, or one nested inside it)."""
    from mjwalk.errors import ModelFileError

    if header.get("format") != fmt:
        raise ModelFileError(
            f"{source}: format {header.get('format')!r} is not {fmt!r} (a {what} file)"
        )
    if header.get("version") != version:
        raise ModelFileError(
            f"{source}: {what} version {header.get('version')!r} unsupported "
            f"(this mjwalk reads version {version})"
        )
