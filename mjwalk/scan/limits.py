"""The ranges a scan must fall within to become a scene, each with its reason.

Checked on the points in metres, z up, before any floor is searched for:

- :data:`MAX_EXTENT`: the cloud's span along each axis. A cloud spanning more than the largest
  factory halls holds stray points (a return from the sky, a mis-registered station, a 1e9 in a
  text file); they would make every grid over the cloud as large as their distance.
- :data:`MAX_COORDINATE`: the distance of any point from the file's origin. The scene writes
  coordinates with 10 significant digits (millimetres below 1e7 m), and georeferenced scans in
  UTM (eastings below 1e6 m, northings below 1e7 m) stay within it; farther out the cloud is
  refused with the offset to subtract (``--offset``).
- :data:`RESOLUTION_RANGE` and :data:`MAX_PLAN_CELLS`: the floor-plan grid.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.errors import ScanError
from mjwalk.scan.obstacles import HOLE_RADIUS

#: Largest span of a cloud along any axis, metres: the longest assembly halls are about
#: 1.6 km (Boeing's Everett plant, 1.0 km; Tesla's Austin plant, 1.1 km); 2 km leaves room.
MAX_EXTENT = 2000.0
#: Largest distance of a point from the file's origin along an axis, metres: 10 significant
#: digits (the scene's number format) keep millimetres below 1e7 m, and UTM northings are
#: below 1e7 m by construction (the southern hemisphere's false northing).
MAX_COORDINATE = 1e7
#: Floor-plan grid edge, metres. Below 5 mm a cell is finer than the range noise of
#: terrestrial phase scanners (1-2 mm at 10 m, 5 mm assumed throughout, see
#: :data:`mjwalk.scan.level.PLANE_TOL`) and the grid grows as 1/r^2 for nothing; above
#: 0.1 m an obstacle's outline, known to half a cell, moves by more than 5 cm, a fifth of the
#: body radius (0.25 m) the planner keeps.
RESOLUTION_RANGE = (0.005, 0.10)
#: Largest floor-plan grid, cells. The grid's arrays peak at about 85 bytes a cell (counts,
#: labels, Euclidean distance transforms): measured with tracemalloc on a 62 x 42 m floor at
#: 1 cm (2.6e7 cells: 2.2 GB, 220 s on the 2-core build machine). 3e7 cells is about 2.6 GB,
#: e.g. 120 m x 60 m at 2 cm.
MAX_PLAN_CELLS = 30_000_000
#: Bytes a floor-plan cell takes at the peak (see :data:`MAX_PLAN_CELLS`).
PLAN_CELL_BYTES = 85


def check_resolution(resolution: float | str, what: str = "resolution") -> float:
    """A floor-plan resolution, checked.

    Args:
        resolution: metres, a number or its text.
        what: the name in the message ("" for a command-line value).

    Returns:
        The resolution as a float within :data:`RESOLUTION_RANGE`, metres.

    Raises:
        ScanError: not a number, or out of range.
    """
    lo, hi = RESOLUTION_RANGE
    try:
        r = float(resolution)
    except (TypeError, ValueError):
        raise ScanError(f"{what} {resolution!r} is not a number of metres".strip()) from None
    if not (math.isfinite(r) and lo <= r <= hi):
        raise ScanError(
            f"{what + ' ' if what else ''}{r:g} m is outside {lo}-{hi} m: finer than {lo} m is "
            f"below the scanner's range noise, coarser than {hi} m moves obstacle "
            f"outlines by more than {hi / 2} m (half a cell)"
        )
    return r


def _offset_hint(points: np.ndarray, scale: float, axes: np.ndarray) -> str:
    """The offset to subtract, in the file's units and axes: the cloud's median rounded to
    about a kilometre."""
    centre = np.median(points[:: max(1, len(points) // 100_000)], axis=0)
    raw = axes.T @ centre / scale  # back to the file's axes and units
    step = 10.0 ** round(math.log10(1000.0 / scale))
    off = np.round(raw / step) * step
    return ",".join(f"{v:.15g}" for v in off)


@njit
def _bounds(points):
    """Per-axis minimum and maximum of ``points`` (N, 3) in one pass (numpy's axis-0
    reductions over an (N, 3) array take 0.5 s on 7 million points; this 0.02 s)."""
    lo = points[0].copy()
    hi = points[0].copy()
    for k in range(points.shape[0]):
        for a in range(3):
            v = points[k, a]
            if v < lo[a]:
                lo[a] = v
            if v > hi[a]:
                hi[a] = v
    return lo, hi


def check_extent(
    points: np.ndarray,
    source: object,
    *,
    scale: float = 1.0,
    axes: np.ndarray | None = None,
) -> None:
    """Refuse a cloud with stray points or coordinates beyond range.

    Args:
        points: (N, 3) points, metres.
        source: the cloud's name in errors.
        scale: metres per file unit (for the offset suggested).
        axes: (3, 3) the up-axis rotation of the file (None: the identity).

    Raises:
        ScanError: a span over :data:`MAX_EXTENT` along an axis (stray points, named with their
            count) or coordinates beyond :data:`MAX_COORDINATE` (with the offset to subtract, in
            the file's units and axes).
    """
    lo, hi = _bounds(np.ascontiguousarray(points, dtype=np.float64))
    span = hi - lo
    if (span > MAX_EXTENT).any():
        a = int(np.argmax(span))
        mid = float(np.median(points[:: max(1, len(points) // 100_000), a]))
        stray = int(np.count_nonzero(np.abs(points[:, a] - mid) > 0.5 * MAX_EXTENT))
        raise ScanError(
            f"{source}: the cloud spans {span[a]:.4g} m along {'xyz'[a]} ({lo[a]:.4g} to "
            f"{hi[a]:.4g} m), more than any hall ({MAX_EXTENT:g} m at most): {stray} stray "
            f"point(s) lie over {0.5 * MAX_EXTENT:g} m from the cloud's median "
            f"{'xyz'[a]} = {mid:.4g} m; crop them from the scan"
        )
    far = np.maximum(np.abs(lo), np.abs(hi))
    if (far > MAX_COORDINATE).any():
        a = int(np.argmax(far))
        hint = _offset_hint(points, scale, np.eye(3) if axes is None else axes)
        raise ScanError(
            f"{source}: coordinates reach {far[a]:.4g} m along {'xyz'[a]}, beyond "
            f"{MAX_COORDINATE:g} m (the scene keeps millimetres only below it): subtract an "
            f"offset from the file's coordinates, e.g. --offset={hint} (file units; "
            f"offset=({hint}) in Python)"
        )


def check_plan_size(points: np.ndarray, resolution: float, source: object) -> None:
    """Refuse a cloud whose floor plan would be too large.

    Args:
        points: (N, 3) points, metres, z up.
        resolution: the floor-plan grid edge, metres.
        source: the cloud's name in errors.

    Raises:
        ScanError: the horizontal extent makes more than :data:`MAX_PLAN_CELLS` cells; the
            message names the coarsest resolution that fits (or says to crop).
    """
    lo, hi = _bounds(np.ascontiguousarray(points, dtype=np.float64))
    span = (hi - lo)[:2] + 2 * HOLE_RADIUS
    cells = float(np.prod(np.ceil(span / resolution) + 1))
    if cells > MAX_PLAN_CELLS:
        need = math.sqrt(float(np.prod(span)) / MAX_PLAN_CELLS)
        gb = cells * PLAN_CELL_BYTES / 1e9
        fits = (
            f"use --resolution {math.ceil(need * 1000) / 1000:g} or coarser"
            if need <= RESOLUTION_RANGE[1]
            else "crop the scan to the workplace"
        )
        raise ScanError(
            f"{source}: a floor plan of {span[0]:.1f} x {span[1]:.1f} m at {resolution:g} m "
            f"has {cells:.3g} cells (about {gb:.1f} GB), more than {MAX_PLAN_CELLS:.3g}: {fits}"
        )
