"""Exception hierarchy: every failure mjwalk reports on purpose is an ``MjwalkError``."""


class MjwalkError(Exception):
    """Base class of all mjwalk errors; messages name the file, element and value."""


class SceneError(MjwalkError):
    """An MJCF scene cannot be used (missing file, malformed XML, no floor, unknown site...)."""


class CaptureError(MjwalkError):
    """A motion-capture file is truncated, inconsistent or lacks a required joint."""


class PlanningError(MjwalkError):
    """A walk cannot be planned (start/goal blocked or off the floor, unreachable, budget spent)."""


class ModelFileError(MjwalkError):
    """A saved model file is corrupt, of another kind, or of an unsupported version."""


class CycleSpecError(MjwalkError):
    """A cycle specification (TOML) has an unknown key, a missing site or an impossible task.

    Attributes (set by the spec loader): ``path`` the spec file, ``line`` the 1-based line,
    ``key`` the offending key (None when the error is not about one key)."""

    path: object = None
    line: int | None = None
    key: str | None = None


class InputError(MjwalkError, ValueError):
    """A bad argument value (a non-finite coordinate, a negative count, an unwritable output
    path...). Also a ``ValueError``, so code that catches those keeps working."""


class ScanError(SceneError):
    """A point cloud cannot become a scene (unreadable, empty, NaN points, units, no floor)."""


class WriteError(MjwalkError, OSError):
    """An output file cannot be written (disk full, file too large, permission...); the message
    names the file. Also an ``OSError``, so code that catches those keeps working."""
