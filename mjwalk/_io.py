"""Small I/O helpers shared by every module that writes files: atomic writes, versioned
``.npz`` files, and the cache root."""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import tempfile
import tomllib
import zipfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from mjwalk.errors import ModelFileError, WriteError

#: The environment variable naming the root of every cache mjwalk keeps (trained default models,
#: workplace arrays under ``workplaces/``); unset: ``~/.cache/mjwalk``.
CACHE_ENV = "MJWALK_CACHE"


def cache_root() -> Path:
    """The root of mjwalk's caches: ``$MJWALK_CACHE`` (``~`` expanded) or ``~/.cache/mjwalk``.
    Deleting it is always safe: its files are rebuilt on first use."""
    env = os.environ.get(CACHE_ENV)
    return Path(env).expanduser() if env else Path.home() / ".cache" / "mjwalk"


def check_cache_writable(what: str) -> Path:
    """The cache root (:func:`cache_root`), checked to be a folder mjwalk can write, or one it
    can make, before ``what`` (e.g. "the default step model") is built for it: building takes
    up to a minute, and a cache that is a file or read-only would refuse it only afterwards.

    The check writes (and at once deletes) a temporary file in the cache root, or in its
    nearest existing parent when it does not exist yet: permissions alone do not tell (root
    may write anywhere except on a read-only file system). Creates nothing.

    Raises:
        WriteError: naming the cache, ``$MJWALK_CACHE`` and the cause.
    """
    root = cache_root()
    named = f"${CACHE_ENV}={root}" if os.environ.get(CACHE_ENV) else f"the cache {root}"
    fix = f"set ${CACHE_ENV} to a folder you may write (it is built there once, then reused)"
    existing = root
    while not existing.exists() and existing.parent != existing:
        existing = existing.parent
    if not existing.is_dir():
        where = "it" if existing == root else str(existing)
        raise WriteError(f"{named}: cannot hold {what}: {where} is a file, not a folder; {fix}")
    try:
        with tempfile.TemporaryFile(dir=existing):
            pass
    except OSError as exc:
        why = exc.strerror or type(exc).__name__
        raise WriteError(
            f"{named}: cannot hold {what}: {existing} is not writable ({why}); {fix}"
        ) from None
    return root


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` only on success.

    A crash or an exception leaves no half-written file behind: the temporary file is removed,
    and so are the folders made for ``path`` when they stay empty.
    An ``OSError`` while writing (a full disk, a file size limit, a folder that cannot be
    written) becomes a :class:`~mjwalk.errors.WriteError` naming ``path``.
    ``suffix`` defaults to the target's own suffix so writers that infer the format from the
    extension (imageio, matplotlib) keep working.
    """
    path = Path(path)
    made = []  # the folders made here, deepest first: removed again when the write fails
    folder = path.parent
    while not folder.exists() and folder.parent != folder:
        made.append(folder)
        folder = folder.parent
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(
            prefix=f".{path.name}.",
            suffix=suffix if suffix is not None else path.suffix,
            dir=path.parent,
        )
    except OSError as exc:
        raise write_error(path, exc) from exc
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600 files; give the usual permissions
    tmp_path = Path(tmp)
    done = False
    try:
        yield tmp_path
        os.replace(tmp_path, path)
        done = True
    except OSError as exc:
        if isinstance(exc, WriteError):
            raise
        raise write_error(path, exc) from exc
    finally:
        with contextlib.suppress(OSError):
            tmp_path.unlink(missing_ok=True)
        if not done:
            for folder in made:  # only while empty: another writer's file keeps it
                with contextlib.suppress(OSError):
                    folder.rmdir()


def write_error(path: str | os.PathLike, exc: OSError):
    """A :class:`~mjwalk.errors.WriteError` naming ``path`` for the ``OSError`` ``exc`` (one line,
    with a hint for a full disk or a file size limit)."""
    why = exc.strerror or str(exc).strip().split("\n")[0] or type(exc).__name__
    if exc.errno in (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EPIPE):
        why += " (is the disk or quota full, or a file size limit set: ulimit -f?)"
    err = WriteError(f"cannot write {path}: {why}")
    err.errno = exc.errno
    return err


def save_npz(path: str | os.PathLike, header: dict, arrays: dict) -> None:
    """Write ``arrays`` and a JSON ``header`` (format name, version, metadata) to one compressed
    ``.npz`` file, atomically. ``default`` turns numpy scalars/arrays in the header into JSON."""

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
    path = Path(path)
    if path.is_dir():
        raise ModelFileError(f"{path} is a folder, not a {what} file")
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
    if header.get("format") != fmt:
        raise ModelFileError(
            f"{source}: format {header.get('format')!r} is not {fmt!r} (a {what} file)"
        )
    if header.get("version") != version:
        raise ModelFileError(
            f"{source}: {what} version {header.get('version')!r} unsupported "
            f"(this mjwalk reads version {version})"
        )


#: Deepest nesting of arrays and inline tables a TOML file mjwalk reads may have. mjwalk's own
#: formats go two levels deep (``task = [{...}]``, ``mix = {adult = 0.7}``); Python's tomllib
#: parses nested values by recursion and fails with a RecursionError near 1000 levels
#: (``x = [[[[...]]]]``), so far deeper values are refused first, naming their key.
MAX_TOML_DEPTH = 8
#: Largest TOML file mjwalk reads, bytes: a cycle of an hour of one-second tasks written out in
#: full is about 300 kB (mjwalk's cycle limit is an hour); beyond, the file is not a cycle.
MAX_TOML_BYTES = 1 << 20

_TOML_TOKENS = re.compile(
    r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:\\.|[^"\\\n])*"|\'[^\'\n]*\'|#[^\n]*|[\[\]{}\n]'
)
_TOML_KEY = re.compile(r"\s*((?:\"[^\"\n]*\"|'[^'\n]*'|[A-Za-z0-9_.\-\s])+?)\s*=")


def read_toml(path: str | os.PathLike, what: str, error: type[Exception]) -> tuple[dict, str]:
    """Read a TOML file: (its data, its text). Raises ``error`` (an MjwalkError class) naming
    ``path`` and ``what`` it should be for a folder, a missing, unreadable, oversized
    (:data:`MAX_TOML_BYTES`) or non-UTF-8 file, and for values nested deeper than
    :data:`MAX_TOML_DEPTH` (naming the key and line). A UTF-8 byte-order mark (Windows
    editors write one) is accepted. TOML syntax errors raise ``tomllib.TOMLDecodeError``
    (the caller cites their line)."""
    path = Path(path)
    if path.is_dir():
        raise error(f"{path} is a folder, not a {what} file")
    if not path.is_file():
        raise error(f"{path}: {what} file not found")
    size = path.stat().st_size
    if size > MAX_TOML_BYTES:
        raise error(
            f"{path}: {size} bytes, more than a {what} file can be "
            f"({MAX_TOML_BYTES >> 20} MiB at most)"
        )
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise error(
            f"{path}: not a UTF-8 text file (byte {exc.start}): {what} files are TOML"
        ) from None
    except OSError as exc:
        raise error(f"{path}: cannot read the {what} file ({exc.strerror or exc})") from exc
    depth, line, key = 0, 1, None
    line_start = 0
    for m in _TOML_TOKENS.finditer(text):
        tok = m.group()
        if tok == "\n":
            line += 1
            line_start = m.end()
            continue
        if tok[0] in "\"'":
            line += tok.count("\n")
            continue
        if tok in "[{":
            if depth == 0:
                k = _TOML_KEY.match(text, line_start, m.start())
                key = k.group(1).strip()[:60] if k else None
            depth += 1
            if depth > MAX_TOML_DEPTH:
                name = f"key {key!r}" if key else "a value"
                raise error(
                    f"{path}:{line}: {name} is nested more than {MAX_TOML_DEPTH} levels deep "
                    f"(arrays or inline tables inside each other); a {what} file needs two"
                )
        elif tok in "]}":
            depth = max(depth - 1, 0)
    try:
        return tomllib.loads(text), text
    except RecursionError:  # a shape the scan above does not count
        raise error(f"{path}: values nested too deeply to read") from None
