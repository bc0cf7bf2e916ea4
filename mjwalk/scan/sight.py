"""Which floor a scanner saw: the floor cells a ray of the scan reached, at the scan's own
angular step, however sparse its points lie there.

A terrestrial scanner casts rays on a regular grid of directions (azimuth x elevation, a fixed
angular step). On the floor, neighbouring rays land (d² + h²) Δθ / h apart along the range and
d Δφ apart across it (d the horizontal distance, h the scanner's height): a floor seen at 4 m
from a 1.27 m high scanner stepping 1° lies in rings 0.23 m apart, and the floor plan's fixed
closing (:data:`~mjwalk.scan.obstacles.FLOOR_GAP`) leaves most of it void. Counting points
cannot tell that floor from floor behind an obstacle; the rays can:

- the scan's angular step is measured on its own returns, as seen from its scanner (the median
  angle to a return's 4th nearest neighbour, the larger of the two grid steps when they differ
  by less than a factor 2);
- a floor cell is *seen* by a station when, of that station's returns, the one whose direction
  is nearest the direction from the scanner to the cell's centre on the floor, within one
  angular step, is a floor return: the ray the scanner cast there reached the floor there. A ray
  stopped short of the cell (an obstacle's shadow), or no ray within a step (outside the field
  of view, the blind cone below the scanner, no return), leaves the cell unseen; a void is
  floor no ray of any station could have seen;
- the rays add floor that was seen, sparsely, and take none away: the floor plan still counts
  an unseen hole narrower than :data:`~mjwalk.scan.obstacles.HOLE_RADIUS` (an obstacle's
  shadow among them) as floor, as it does without rays.

The scanner's position comes from the file (:class:`~mjwalk.scan.read.Station`: a PCD's
VIEWPOINT, an E57 scan's pose). PCL writes ``VIEWPOINT 0 0 0 1 0 0 0`` into every cloud by
default, whether a scanner stood there or not, so a position is used only when the cloud agrees
that a scanner stood there (:func:`check_station`): it stands above the floor, and its returns
are first returns (a scanner records one point per ray: at most :data:`MAX_HIDDEN` of its points
may lie behind another point of the same station in the same direction). Otherwise the floor
plan keeps counting floor points, and its report says so.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

#: The angular step is measured on at most this many returns (a regular stride through them).
STEP_SAMPLE = 200_000
#: A scanner stands at least this high above the floor, metres: below it the floor is seen at
#: grazing angles only (a tripod's lowest setting is about 0.5 m; a scan from the floor itself
#: is no station).
MIN_STATION_HEIGHT = 0.2
#: A point lies behind another of the same station when that one is nearer the scanner by
#: more than this, metres: 10 sigma of a 5 mm range noise (as the floor tolerance).
BEHIND = 0.05
#: At most this share of a station's points may lie behind another of its points within half
#: an angular step (mixed pixels at edges, multiple returns); a position that hides more is not
#: where the scanner stood. Measured on the shared PCL room scan (step 0.97°): 0.1 % from its
#: scanner; from positions 0.1, 0.2, 0.3 m beside it 2.9, 4.5, 5.6 %, 0.5 m below it 15 %
#: (tests/scan/test_sight.py). A position within about 0.1 m of the scanner's moves
#: a floor cell's ray by a fraction of a step at the ranges of a room.
MAX_HIDDEN = 0.02
#: Returns checked for :data:`MAX_HIDDEN` (a regular stride through them).
HIDDEN_SAMPLE = 20_000
#: Floor cells tested per k-d tree query batch.
BATCH = 1_000_000


@dataclass(frozen=True)
class View:
    """One station as the floor plan uses it: ``viewpoint`` (3,) metres in the levelled frame
    (floor at z = 0), its points ``start:stop`` of the levelled cloud, its angular ``step``
    (radians) and ``origin`` (where the position came from)."""

    viewpoint: np.ndarray
    start: int
    stop: int
    step: float
    origin: str


def _directions(points: np.ndarray, viewpoint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    rel = points - viewpoint
    rng = np.linalg.norm(rel, axis=1)
    ok = rng > 1e-6
    return rel[ok] / rng[ok, None], rng[ok]


def angular_step(directions: np.ndarray) -> float:
    """The scan's angular step.

    Args:
        directions: (K, 3) unit vectors from the scanner to its returns.

    Returns:
        Radians: the median angle from a return's direction to its 4th nearest distinct
        neighbour; NaN with fewer than 5 directions.
    """
    u = np.unique(np.round(directions, 7), axis=0)
    if len(u) < 5:
        return float("nan")
    u = u[:: max(1, len(u) // STEP_SAMPLE)]
    d, _ = cKDTree(u).query(u, k=5)
    chord = float(np.median(d[:, 4]))
    return 2.0 * float(np.arcsin(min(chord / 2.0, 1.0)))


def hidden_share(points: np.ndarray, viewpoint: np.ndarray, step: float) -> float:
    """The share of returns hidden behind others.

    Args:
        points: (K, 3) returns, metres.
        viewpoint: (3,) the scanner's position, metres.
        step: the angular step, radians.

    Returns:
        The share (in [0, 1], of a sample) of ``points`` lying more than :data:`BEHIND` farther
        from ``viewpoint`` than another within half a ``step`` of its direction; 1 without points.
    """
    u, rng = _directions(points, viewpoint)
    if len(u) == 0:
        return 1.0
    tree = cKDTree(u)
    pick = np.arange(0, len(u), max(1, len(u) // HIDDEN_SAMPLE))
    near = tree.query_ball_point(u[pick], 2 * np.sin(step / 4))
    hidden = [
        bool(len(n) > 1 and rng[n].min() < rng[i] - BEHIND) for i, n in zip(pick, near, strict=True)
    ]
    return float(np.mean(hidden))


def check_station(points: np.ndarray, viewpoint: np.ndarray, floor_tol: float) -> tuple[float, str]:
    """Whether the cloud agrees a scanner stood at a position.

    Args:
        points: (K, 3) the station's returns, levelled, metres.
        viewpoint: (3,) the scanner's position, levelled, metres.
        floor_tol: a floor point's largest distance from z = 0, metres.

    Returns:
        (angular step radians, "") when it agrees; else (NaN, why not in one clause).
    """
    h = float(viewpoint[2])
    if h < MIN_STATION_HEIGHT:
        return float("nan"), f"{h:+.2f} m above the floor, not a scanner's height"
    if not (np.abs(points[:, 2]) <= floor_tol).any():
        return float("nan"), "no floor among its points"
    return ray_agreement(points, viewpoint)


def ray_agreement(points: np.ndarray, viewpoint: np.ndarray) -> tuple[float, str]:
    """Whether a scanner's returns agree it stood at a position, whatever the floor: they fan
    out at one angular step and at most :data:`MAX_HIDDEN` of them lie behind others (a
    rigid motion, a cloud turned upside down included, keeps both).

    Args:
        points: (K, 3) the station's returns, metres.
        viewpoint: (3,) the scanner's position in their frame, metres.

    Returns:
        (angular step radians, "") when they agree; else (NaN, why not in one clause).
    """
    u, _ = _directions(points, viewpoint)
    step = angular_step(u)
    if not np.isfinite(step) or step <= 0:
        return float("nan"), "too few points to measure an angular step"
    share = hidden_share(points, viewpoint, step)
    if share > MAX_HIDDEN:
        return float("nan"), (
            f"{100 * share:.0f} % of its points lie behind others from there (a scanner's "
            f"returns are first returns: at most {100 * MAX_HIDDEN:.0f} %)"
        )
    return step, ""


def ray_seen(
    points: np.ndarray,
    views: Sequence[View],
    x0: float,
    y0: float,
    resolution: float,
    shape: tuple[int, int],
    floor_tol: float,
) -> np.ndarray:
    """The floor-plan cells some station's rays reached (module docstring).

    Args:
        points: (N, 3) levelled points, metres.
        views: the stations, each with its rows of ``points``.
        x0: the grid's lower corner x, metres.
        y0: the grid's lower corner y, metres.
        resolution: the cell edge, metres.
        shape: (ny, nx) of the grid.
        floor_tol: a floor point's largest distance from z = 0, metres.

    Returns:
        (ny, nx) bool: True where, from some station, the return nearest in direction to the
        cell's centre (within its angular step) is a floor return.
    """
    ny, nx = shape
    seen = np.zeros(shape, bool)
    for v in views:
        pts = points[v.start : v.stop]
        u, _ = _directions(pts, v.viewpoint)
        floor = np.abs(pts[np.linalg.norm(pts - v.viewpoint, axis=1) > 1e-6, 2]) <= floor_tol
        if not floor.any():
            continue
        # Only cells within the reach of this station's floor returns can be seen by it.
        fl = pts[np.abs(pts[:, 2]) <= floor_tol]
        i0, j0 = np.floor((fl[:, :2].min(axis=0) - (x0, y0)) / resolution).astype(int) - 1
        i1, j1 = np.ceil((fl[:, :2].max(axis=0) - (x0, y0)) / resolution).astype(int) + 1
        i0, j0, i1, j1 = max(i0, 0), max(j0, 0), min(i1, nx), min(j1, ny)
        if i0 >= i1 or j0 >= j1:
            continue
        tree = cKDTree(u)
        gx, gy = np.meshgrid(
            x0 + (np.arange(i0, i1) + 0.5) * resolution, y0 + (np.arange(j0, j1) + 0.5) * resolution
        )
        cells = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
        hit = np.zeros(len(cells), bool)
        bound = 2 * np.sin(v.step / 2)
        for k in range(0, len(cells), BATCH):
            cu, _ = _directions(cells[k : k + BATCH], v.viewpoint)
            d, idx = tree.query(cu, k=1, distance_upper_bound=bound)
            found = np.flatnonzero(np.isfinite(d))
            hit[k + found] = floor[idx[found]]
        seen[j0:j1, i0:i1] |= hit.reshape(gx.shape)
    return seen
