"""How a laser scan is turned into a scene: one frozen record, checked on construction.

:func:`~mjwalk.scan.scene.scan_to_scene` and :func:`~mjwalk.scan.scene.build_scene` take a
:class:`ScanOptions`; the ``mjwalk scan`` command builds it from its flags in one place. The input
files (scans, poses, sites) and the output are not options: they are the call's arguments.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mjwalk.errors import InputError, ScanError
from mjwalk.scan.limits import check_resolution
from mjwalk.scan.read import check_options
from mjwalk.scan.voids import check_policy

#: Default floor-plan grid edge, metres: the 2 cm the occupancy grids, the walk field and the
#: clearance field are built at (:data:`mjwalk.world.workplace.MAX_RESOLUTION`).
DEFAULT_RESOLUTION = 0.02
#: The choices of :attr:`ScanOptions.gaps`.
GAP_POLICIES = ("obstacle", "floor")


class ScanOptionsError(ScanError, InputError):
    """A bad :class:`ScanOptions` value: a scan error (as the pipeline's own checks raise) and an
    input error (a bad argument), with the pipeline's one-line message."""


@dataclass(frozen=True)
class ScanOptions:
    """How a scan is read, levelled and cut into boxes. Checked on construction
    (:class:`ScanOptionsError`, one line, the messages of the pipeline's own checks).

    Attributes:
        units: the file's length unit when it does not say (:data:`mjwalk.world.units.UNITS`).
            Default metres: E57 states metres by its standard, LAS its scale in metres.
        up: the file's up axis when it does not say (:data:`mjwalk.world.units.UP_AXES`,
            ``+z``/``-y``...; a bare ``z`` reads as ``+z``). Default ``+z``, the axis E57 and LAS
            files and scanner software exports use.
        drop_invalid: leave out points with NaN or infinite coordinates (organised clouds mark
            missing returns so). Default False: they are an error unless asked for.
        resolution: floor-plan grid edge, metres, within
            :data:`mjwalk.scan.limits.RESOLUTION_RANGE` (stored as a float). Default
            :data:`DEFAULT_RESOLUTION`.
        offset: a point (x, y, z) in the file's units and axes subtracted from every point first,
            for a georeferenced cloud far from its origin (stored as a tuple of floats); None:
            nothing subtracted.
        voids: the unseen-floor policy of :mod:`mjwalk.scan.voids` (blocked, fill, free).
            Default ``blocked``: nobody walks where no floor was seen.
        register: align the scans after the first that no pose places
            (:func:`mjwalk.scan.register.align`). Default False: registration is never
            automatic; scans already in one frame are merged as they are.
        gaps: what a gap in the floor is (:data:`GAP_POLICIES`; an unscanned region over
            points below the floor: a pit, a trench, :mod:`mjwalk.scan.obstacles`). Default
            ``obstacle``: a hazard the planner must see, written as a guard-rail box; ``floor``:
            filled as floor like any unscanned hole (the plan before gaps were looked for).
    """

    units: str = "m"
    up: str = "+z"
    drop_invalid: bool = False
    resolution: float = DEFAULT_RESOLUTION
    offset: tuple[float, float, float] | None = None
    voids: str = "blocked"
    register: bool = False
    gaps: str = "obstacle"

    def __post_init__(self) -> None:
        if self.gaps not in GAP_POLICIES:
            raise ScanOptionsError(f"unknown gaps {self.gaps!r} (one of {', '.join(GAP_POLICIES)})")
        try:
            object.__setattr__(self, "resolution", check_resolution(self.resolution))
            check_policy(self.voids)
            check_options(self.units, self.up, "scan options")
        except ScanError as exc:
            raise ScanOptionsError(str(exc)) from None
        if self.offset is not None:
            object.__setattr__(self, "offset", _offset(self.offset))


def _offset(offset: object) -> tuple[float, float, float]:
    """``offset`` as three finite floats (the same values), or ScanOptionsError."""
    try:
        values = tuple(float(v) for v in offset)  # type: ignore[attr-defined]
    except (TypeError, ValueError):
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ScanOptionsError(f"offset must be 3 finite numbers (file units), got {offset!r}")
    return values[0], values[1], values[2]
