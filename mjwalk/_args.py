"""Checks of user input, done before any work: points, counts, sizes and output paths.

The command line (``mjwalk.cli``) uses the ``arg_*`` functions as argparse ``type=``
converters (:class:`OneLineParser` prints their message as one line and exits with status 2); the
library uses :func:`parse_point` and :func:`finite_points` directly, which raise
:class:`~mjwalk.errors.InputError`. Output paths are checked with :func:`check_output_file` /
:func:`check_output_dir` before a command starts its work, so a bad ``--out`` or ``--png``
fails in a second instead of after the whole simulation; the writers themselves stay atomic
(:func:`mjwalk._io.atomic_path`). At import nothing here needs more than the standard library
and NumPy, so parsing a command line stays fast.
"""

from __future__ import annotations

import argparse
import math
import os
import re
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

import numpy as np

from mjwalk.errors import InputError

#: Text that is meant as coordinates rather than a site name: digits, signs, dots, commas,
#: exponents, spaces and the words nan/inf (site names are MJCF identifiers, which have letters).
_NUMERIC = re.compile(r"[\s0-9.,eE+\-]*|.*\b(nan|inf|infinity)\b.*", re.IGNORECASE)
#: Highest video frame rate, frames per second: the fastest common displays refresh at 240 Hz,
#: so more frames are never seen, while each costs its own render and memory
#: (``--fps 1e9`` asked for 16.6 GiB of frame times).
MAX_FPS = 240.0
#: Largest video frame side, pixels (H.264 level 6.2 allows 8192 x 4320).
MAX_VIDEO_SIDE = 8192


# ------------------------------------------------------------------ points


def looks_numeric(text: str) -> bool:
    """Whether ``text`` is meant as coordinates ("1.5,-2", "1.2.3,0", "nan,0"), not a site."""
    return "," in text and bool(_NUMERIC.fullmatch(text.strip()))


def parse_point(text: str, what: str = "point", n: int = 2) -> np.ndarray | None:
    """``"x,y"`` (or ``n`` comma-separated values) as a finite float array, metres.

    Returns None when ``text`` is not meant as coordinates (a site name). Raises InputError
    naming ``what`` and the bad part when it is meant as coordinates but malformed or not
    finite ("1.2.3,0", "nan,0", "1,2,3" where two values are wanted).
    """
    if not looks_numeric(text):
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != n:
        raise InputError(
            f"{what} {text!r}: expected {n} comma-separated numbers (X,Y in metres), "
            f"got {len(parts)}"
        )
    values = []
    for p in parts:
        try:
            values.append(float(p))
        except ValueError:
            raise InputError(
                f"{what} {text!r}: {p!r} is not a number (write X,Y in metres, e.g. -2,0.5)"
            ) from None
    arr = np.array(values)
    bad = [p for p, v in zip(parts, values, strict=True) if not math.isfinite(v)]
    if bad:
        raise InputError(f"{what} {text!r}: coordinates must be finite numbers, got {bad[0]!r}")
    return arr


def finite_points(xy, what: str = "points") -> np.ndarray:
    """``xy`` as a float array, raising InputError when any coordinate is NaN or infinite."""
    arr = np.asarray(xy, dtype=float)
    if not np.all(np.isfinite(arr)):
        flat = arr.reshape(-1, arr.shape[-1]) if arr.ndim else arr.reshape(1, 1)
        row = flat[~np.all(np.isfinite(flat), axis=-1)][0]
        raise InputError(
            f"{what}: coordinates must be finite numbers (metres), got {row.tolist()!r}"
        )
    return arr


def join_negative_values(argv: Sequence[str], options: Sequence[str]) -> list[str]:
    """``["--from", "-2,0"]`` as ``["--from=-2,0"]``: argparse takes a value that starts with
    "-" and is not a plain number for an option, so negative coordinates (as the README
    writes them) would be refused."""
    out: list[str] = []
    argv = list(argv)
    i = 0
    while i < len(argv):
        tok = argv[i]
        if tok in options and i + 1 < len(argv) and re.match(r"-[\d.]", argv[i + 1]):
            out.append(f"{tok}={argv[i + 1]}")
            i += 2
            continue
        out.append(tok)
        i += 1
    return out


# ------------------------------------------------------------------ seeds


def check_patterns(**patterns: str | None) -> None:
    """Check that each given name-filter pattern is a regular expression (``re.search`` syntax).

    Args:
        **patterns: the patterns by option name (e.g. ``include=..., exclude=...``); None
            means no filter and passes.

    Raises:
        InputError: naming the option and the pattern, with ``re``'s reason.
    """
    for name, pattern in patterns.items():
        if pattern is not None:
            try:
                re.compile(pattern)
            except re.error as exc:
                raise InputError(f"{name}={pattern!r} is not a regular expression: {exc}") from exc


def check_seed(seed, what: str = "seed") -> int:
    """``seed`` as an int, raising InputError naming ``what`` unless it is a whole number >= 0
    (numpy's SeedSequence takes non-negative integers only; mjwalk refuses a negative seed
    everywhere, on the command line and in the API, rather than mapping it to another)."""
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise InputError(f"{what} must be a whole number >= 0, got {seed!r}")
    return int(seed)


def as_generator(rng, what: str = "rng") -> np.random.Generator:
    """``numpy.random.default_rng(rng)`` for a Generator, a BitGenerator, a SeedSequence, None
    or a seed (a whole number >= 0, or a list of them); anything else raises InputError
    naming ``what`` (numpy's own message never names the argument)."""
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, int | np.integer) and not isinstance(rng, bool):
        check_seed(rng, what)
    try:
        return np.random.default_rng(rng)
    except (TypeError, ValueError) as exc:
        raise InputError(
            f"{what} must be a numpy Generator or a seed (a whole number >= 0), got {rng!r}"
        ) from exc


# ------------------------------------------------------------------ argparse converters


class OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line, like every other mjwalk error:
    ``mjwalk: error: <argparse's message> (see <command> --help)`` on stderr, exit status 2
    (argparse's own prints its usage block of 2-6 lines first). Sub-commands' parsers are of
    this class too (``add_subparsers`` makes them of their parent's class)."""

    def error(self, message: str) -> NoReturn:
        root = self.prog.split()[0]
        self.exit(2, f"{root}: error: {' '.join(message.split())} (see {self.prog} --help)\n")


def _argtype(fn):
    """Turn an InputError of ``fn`` into argparse's ArgumentTypeError (its message is shown)."""

    def convert(text: str):
        try:
            return fn(text)
        except InputError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

    convert.__name__ = fn.__name__
    return convert


def _number(text: str, kind, name: str):
    try:
        value = kind(text)
    except ValueError:
        raise InputError(f"{text!r} is not {name}") from None
    if kind is float and not math.isfinite(value):
        raise InputError(f"{text!r} is not a finite number")
    return value


@_argtype
def arg_point(text: str) -> str:
    """A site name or "X,Y" coordinates (checked here; resolved against the scene later)."""
    parse_point(text, "point")
    return text.strip()


@_argtype
def arg_positive_int(text: str) -> int:
    value = _number(text, int, "a whole number")
    if value < 1:
        raise InputError(f"must be at least 1, got {value}")
    return value


@_argtype
def arg_count(text: str) -> int:
    """A whole number >= 0."""
    value = _number(text, int, "a whole number")
    if value < 0:
        raise InputError(f"must be 0 or more, got {value}")
    return value


@_argtype
def arg_jobs(text: str) -> int:
    """joblib's n_jobs: >= 1 processes, or -1 for all cores (-2 all but one, ...)."""
    value = _number(text, int, "a whole number")
    if value == 0:
        raise InputError("must be a number of processes >= 1, or -1 for all cores; got 0")
    return value


@_argtype
def arg_seed(text: str) -> int:
    """A random seed: a whole number >= 0 (:func:`check_seed`)."""
    return check_seed(_number(text, int, "a whole number"), "the seed")


@_argtype
def arg_positive_float(text: str) -> float:
    value = _number(text, float, "a number")
    if value <= 0:
        raise InputError(f"must be a positive number, got {value:g}")
    return value


@_argtype
def arg_fraction(text: str) -> float:
    """A number in (0, 1] (a share of variance)."""
    value = _number(text, float, "a number")
    if not 0.0 < value <= 1.0:
        raise InputError(f"must be a share in (0, 1], e.g. 0.95; got {value:g}")
    return value


@_argtype
def arg_fps(text: str) -> float:
    """A video frame rate: a number in (0, :data:`MAX_FPS`]."""
    value = _number(text, float, "a number")
    return check_fps(value, "must be")


def check_fps(fps, what: str = "fps") -> float:
    """``fps`` as a float, raising InputError naming ``what`` unless 0 < fps <= MAX_FPS."""
    if isinstance(fps, bool) or not isinstance(fps, int | float | np.number):
        raise InputError(f"{what} a frame rate in frames per second, got {fps!r}")
    value = float(fps)
    if not (math.isfinite(value) and 0.0 < value <= MAX_FPS):
        raise InputError(
            f"{what} a frame rate above 0 and at most {MAX_FPS:g} frames per second (the "
            f"fastest displays show 240), got {value:g}"
        )
    return value


@_argtype
def arg_video_side(text: str) -> int:
    """A video width or height: an even number of pixels, 16 to :data:`MAX_VIDEO_SIDE` (H.264's
    4:2:0 colour planes need even sides)."""
    value = _number(text, int, "a whole number of pixels")
    if not 16 <= value <= MAX_VIDEO_SIDE or value % 2:
        raise InputError(
            f"must be an even number of pixels from 16 to {MAX_VIDEO_SIDE}, got {value}"
        )
    return value


# ------------------------------------------------------------------ output paths


def image_suffixes() -> tuple[str, ...]:
    """The file suffixes matplotlib can save figures as (".png", ".svg", ...), from its
    backend registry (imports matplotlib: call it only when an image is to be written)."""
    from matplotlib.backend_bases import FigureCanvasBase  # deferred: matplotlib is heavy

    return tuple(sorted(f".{ext}" for ext in FigureCanvasBase.get_supported_filetypes()))


def _nearest_existing(path: Path) -> Path:
    p = path
    while not p.exists():
        if p.parent == p:
            break
        p = p.parent
    return p


def _check_folder_writable(folder: Path, path: Path, what: str) -> None:
    """``folder`` (or its nearest existing ancestor) must be a writable folder."""
    existing = _nearest_existing(folder)
    if not existing.is_dir():
        raise InputError(
            f"{what} {str(path)!r}: {str(existing)!r} is a file, not a folder, so nothing can be "
            "written under it"
        )
    if not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"{what} {str(path)!r}: the folder {str(existing)!r} is not writable")


def check_output_file(path: str | os.PathLike, what: str, suffixes: Sequence[str] = ()) -> Path:
    """Raise InputError unless ``path`` can be written (atomically, as mjwalk writes): not a
    folder, under a writable folder (created when missing), and with one of ``suffixes``
    when given. Creates nothing."""
    path = Path(path)
    if suffixes and path.suffix.lower() not in suffixes:
        got = f"{path.suffix!r}" if path.suffix else "no extension"
        raise InputError(
            f"{what} {str(path)!r}: unsupported file type ({got}); use one of {', '.join(suffixes)}"
        )
    if path.is_dir():
        raise InputError(f"{what} {str(path)!r} is a folder; give a file name")
    if path.exists() and not os.access(path, os.W_OK):
        raise InputError(f"{what} {str(path)!r}: the file exists and is not writable")
    _check_folder_writable(path.parent, path, what)
    return path


def check_output_dir(path: str | os.PathLike, what: str) -> Path:
    """Raise InputError unless ``path`` is, or can be created as, a writable folder.
    Creates nothing."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise InputError(f"{what} {str(path)!r} is a file, not a folder")
    _check_folder_writable(path, path, what)
    return path
