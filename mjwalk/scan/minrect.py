"""The minimum-area rectangle round a region of floor-plan cells, its two side lengths (a scan
level's depth and width, :mod:`mjwalk.scan.scanlevels`), and the one axis that fits several
regions' rectangles best (a flight's treads, :mod:`mjwalk.scan.stairfit`), and the long axis of
several regions' pooled second moments (a raised flight's treads). Metres, scene frame."""

from __future__ import annotations

import math

import numpy as np


def min_rectangle(cells: np.ndarray, x0: float, y0: float, res: float) -> np.ndarray:
    """The minimum-area rectangle round the centres of a region's cells.

    Args:
        cells: (ny, nx) bool.
        x0: the grid's lower x, metres.
        y0: the grid's lower y, metres.
        res: the cell edge, metres.

    Returns:
        (4, 2) corners, counter-clockwise, metres (the first edge is the rectangle's first axis).
    """
    hull = _hull(cells, x0, y0, res)
    best = (math.inf, np.eye(2), np.zeros(2), np.zeros(2))
    for i in range(len(hull)):
        e = hull[(i + 1) % len(hull)] - hull[i]
        n = float(np.hypot(*e))
        if n < 1e-12:
            continue
        rot = np.array([e / n, [-e[1] / n, e[0] / n]])  # rows: the rectangle's axes
        q = hull @ rot.T
        lo, hi = q.min(axis=0), q.max(axis=0)
        area = float(np.prod(np.maximum(hi - lo, 0.5 * res)))
        if area < best[0] - 1e-12:
            best = (area, rot, lo, hi)
    _, rot, lo, hi = best
    mid = 0.5 * (lo + hi)
    lo, hi = np.minimum(lo, mid - 0.25 * res), np.maximum(hi, mid + 0.25 * res)
    corners = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]])
    return corners @ rot


def _centres(cells: np.ndarray, x0: float, y0: float, res: float) -> np.ndarray:
    """A region's cell centres, (K, 2) metres, scene frame."""
    iy, ix = np.nonzero(cells)
    return np.column_stack([x0 + (ix + 0.5) * res, y0 + (iy + 0.5) * res])


def _hull(cells: np.ndarray, x0: float, y0: float, res: float) -> np.ndarray:
    """The convex hull of a region's cell centres, (K, 2) metres (the centres themselves when
    they lie on a line)."""
    from scipy.spatial import ConvexHull, QhullError  # deferred: scipy.spatial's slow import

    pts = _centres(cells, x0, y0, res)
    try:
        return pts[ConvexHull(pts).vertices]
    except QhullError:  # a line of cells
        return pts


def common_axis(regions: list[np.ndarray], x0: float, y0: float, res: float) -> np.ndarray:
    """The one axis along which the regions' bounding rectangles have the least summed area.

    A flight's treads share one axis; each tread's own minimum rectangle can turn by up to
    about ``atan(2 res / width)`` where a cell more or less at a corner tips its hull (a 1.52 m
    tread on a 2 cm grid: 1.5 deg, generated hall 1069's pit); the summed area weighs each
    region by its size, so one tipped tread does not turn the others. The axes tried are every
    region's hull edges' directions (a single region's minimum rectangle has a side on one of
    its hull's edges: Freeman and Shapira 1975, Comm. ACM 18(7)).

    Args:
        regions: (ny, nx) bool cells, each a non-empty region on one grid.
        x0: the grid's lower x, metres.
        y0: the grid's lower y, metres.
        res: the cell edge, metres.

    Returns:
        (2,) unit vector, the axis (the other is it turned by 90 deg), scene frame.
    """
    hulls = [_hull(c, x0, y0, res) for c in regions]
    best = (math.inf, np.array([1.0, 0.0]))
    for hull in hulls:
        for i in range(len(hull)):
            e = hull[(i + 1) % len(hull)] - hull[i]
            n = float(np.hypot(*e))
            if n < 1e-12:
                continue
            rot = np.array([e / n, [-e[1] / n, e[0] / n]])
            area = 0.0
            for h in hulls:
                q = h @ rot.T
                area += float(np.prod(np.maximum(np.ptp(q, axis=0), 0.5 * res)))
            if area < best[0] - 1e-12:
                best = (area, rot[0])
    return best[1]


def principal_axis(
    regions: list[np.ndarray], x0: float, y0: float, res: float
) -> tuple[np.ndarray, float, list[np.ndarray]]:
    """The long axis of regions' cell centres' second moments, pooled about each one's centroid.

    A rectangle ``w`` by ``d`` has second moments ``w**2 / 12`` and ``d**2 / 12`` along its
    sides, so a long region's axis is read from all its cells, not from the few hull corners
    its minimum rectangle rests on (one cell more or less at a corner turns that by up to about
    ``atan(2 res / width)``); a square's moments are equal in every direction and give no axis
    (the ratio 1). Regions pooled this way should share one axis (a flight's treads).

    Args:
        regions: (ny, nx) bool cells, each a non-empty region on one grid.
        x0: the grid's lower x, metres.
        y0: the grid's lower y, metres.
        res: the cell edge, metres.

    Returns:
        ``(axis, ratio, axes)``: the pooled long axis, a (2,) unit vector in the scene frame;
        the ratio of the pooled moments, long over short (at least 1; inf for cells on a line);
        and each region's own long axis, (2,) unit vectors.
    """
    pooled = np.zeros((2, 2))
    axes = []
    for cells in regions:
        pts = _centres(cells, x0, y0, res)
        q = pts - pts.mean(axis=0)
        m = q.T @ q
        axes.append(np.linalg.eigh(m)[1][:, 1])
        pooled += m
    w, v = np.linalg.eigh(pooled)
    ratio = float(w[1] / w[0]) if w[0] > 1e-12 else math.inf
    return v[:, 1], ratio, axes


def rectangle_size(corners: np.ndarray) -> tuple[float, float]:
    """(depth: the shorter side, width: the longer) of a rectangle (4, 2), metres.

    Args:
        corners: (4, 2) corners in order.

    Returns:
        Its two side lengths, shorter first, metres.
    """
    a = float(np.hypot(*(corners[1] - corners[0])))
    b = float(np.hypot(*(corners[2] - corners[1])))
    return min(a, b), max(a, b)
