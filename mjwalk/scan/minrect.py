"""The minimum-area rectangle round a region of floor-plan cells, and its two side lengths
(a scan level's depth and width, :mod:`mjwalk.scan.scanlevels`). Metres, scene frame."""

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
    from scipy.spatial import ConvexHull, QhullError  # deferred: scipy.spatial's slow import

    iy, ix = np.nonzero(cells)
    pts = np.column_stack([x0 + (ix + 0.5) * res, y0 + (iy + 0.5) * res])
    try:
        hull = pts[ConvexHull(pts).vertices]
    except QhullError:  # a line of cells: a rectangle half a cell wide round it
        hull = pts
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
