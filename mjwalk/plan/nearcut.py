"""Which obstacles can matter to a walk guide's questions, ruled out by bounds before any exact
distance is asked (issue 50: the guide's per-obstacle NumPy calls were most of its time).

:func:`mjwalk.plan.sides.intruding` and :func:`mjwalk.plan.sides.side_gap` ask each obstacle
near a path for its exact distances (:meth:`~mjwalk.world.footprint.Footprint.signed_distance`)
and its extent along the walk (a NumPy matrix product, whose rounding depends on the array's
length: BLAS fuses some products). Most obstacles they ask cannot change the answer, which
bounds show without those calls:

- **Bounding-box distance** (a lower bound of an obstacle's distance from a point outside its
  box, where its footprint lies: :meth:`~mjwalk.world.footprint.Footprint.bounds`; none in it).
- **Nearest vertex distance** (an upper bound: a polygon's vertices lie in it; a rounded
  segment's ends are ``radius`` deep in it).
- **Extent along the walk in plain arithmetic** (within a few ulps of NumPy's product).

A bound decides only where it clears the threshold by :data:`MARGIN`, far more than rounding
(a few 1e-15 m at the scene's metres); everything else is left to the exact calls, so the
callers' answers are bit for bit those of asking every obstacle. Metres, world frame.
"""

from __future__ import annotations

import math
from operator import is_

import numpy as np

from mjwalk._jit import njit
from mjwalk.world.footprint import polygon_distances
from mjwalk.world.openings import passing_footprints

__all__ = [
    "MARGIN",
    "ObstaclePack",
    "gap_candidates",
    "gap_room",
    "intruding_candidates",
    "pack",
]

#: How far (m) a bound must clear a threshold to decide without the exact call: a million
#: times the rounding of a distance or product at tens of metres (about 1e-14 m).
MARGIN = 1e-9


class ObstaclePack:
    """A workplace's obstacle footprints as flat arrays for the compiled bounds.

    Attributes:
        bounds: (n, 4) each footprint's (xmin, ymin, xmax, ymax), metres.
        vertices: (V, 2) every footprint's vertices, one after another, metres.
        first: (n,) the index of each footprint's first vertex in ``vertices``.
        count: (n,) its number of vertices.
        radius: (n,) its radius, metres (0: a polygon).
    """

    def __init__(self, footprints) -> None:
        """Pack ``footprints``.

        Args:
            footprints: the workplace's :class:`~mjwalk.world.footprint.Footprint` s, in order.
        """
        boxes = np.array([fp.bounds() for fp in footprints], dtype=float)
        self.bounds = np.ascontiguousarray(boxes.reshape(-1, 4))
        verts = [np.asarray(fp.vertices, dtype=float).reshape(-1, 2) for fp in footprints]
        self.count = np.array([len(v) for v in verts], dtype=np.int64)
        self.first = np.concatenate([[0], np.cumsum(self.count)[:-1]]).astype(np.int64)
        self.vertices = np.ascontiguousarray(np.vstack(verts) if verts else np.zeros((0, 2)))
        self.radius = np.array([float(fp.radius) for fp in footprints], dtype=float)
        # each footprint object's rows (the side gap leaves out the one passed, found by
        # identity: a dict lookup instead of a test per footprint per route)
        self.rows: dict[int, list[int]] = {}
        for k, fp in enumerate(footprints):
            self.rows.setdefault(id(fp), []).append(k)


def pack(workplace) -> ObstaclePack:
    """The workplace's :class:`ObstaclePack` of its obstacles and its level's openings
    (:func:`~mjwalk.world.openings.passing_footprints`), kept on it for the same footprints (the
    same objects, in the same order).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).

    Returns:
        The pack.
    """
    obstacles = passing_footprints(workplace)  # its level's openings too (issue 47)
    kept = workplace.__dict__.get("_obstacle_pack")
    # the same footprint objects in the same order (kept alive by the pack's tuple), tested
    # object by object in C (building a tuple of their ids took 20 us a call on a 144-box
    # hall, a tenth of a side choice)
    if kept is None or len(kept[1]) != len(obstacles) or not all(map(is_, kept[1], obstacles)):
        kept = (ObstaclePack(obstacles), tuple(obstacles))
        workplace.__dict__["_obstacle_pack"] = kept
    return kept[0]


@njit
def _box_distance(b, x, y):
    """The distance (m) from (x, y) to the box b = (xmin, ymin, xmax, ymax) where it lies
    outside, -inf in it (the footprint's signed distance may be negative there): a lower
    bound of the footprint's signed distance."""
    dx = max(b[0] - x, 0.0, x - b[2])
    dy = max(b[1] - y, 0.0, y - b[3])
    if dx == 0.0 and dy == 0.0:
        return -np.inf
    return math.hypot(dx, dy)


@njit
def _vertex_distance(vertices, first, count, radius, x, y):
    """The distance (m) from (x, y) to the nearest vertex of a polygon, or the nearer end of
    a rounded segment less its radius: at least the footprint's distance."""
    best = np.inf
    for v in range(first, first + count):
        if radius == 0.0 or v == first or v == first + count - 1:
            best = min(best, math.hypot(x - vertices[v, 0], y - vertices[v, 1]))
    return best - radius


@njit
def _meets(b, x0, y0, x1, y1):
    """Whether box b meets (x0, y0, x1, y1), edges included (as ``boxes_meeting``)."""
    return b[2] >= x0 and b[0] <= x1 and b[3] >= y0 and b[1] <= y1


@njit
def _intruding_candidates(dense, bounds, vertices, first, count, radius, ends, u, length, berth):
    """:func:`intruding_candidates`, compiled: rows (k, along unknown, ends unknown)."""
    x0, y0 = dense[:, 0].min() - berth, dense[:, 1].min() - berth
    x1, y1 = dense[:, 0].max() + berth, dense[:, 1].max() + berth
    reach = berth + 1e-9  # as mjwalk.plan.sides' grown boxes
    sx, sy = ends[0, 0], ends[0, 1]
    out = np.empty((bounds.shape[0], 3), dtype=np.int64)
    m = 0
    for k in range(bounds.shape[0]):
        b = bounds[k]
        if not _meets(b, x0, y0, x1, y1):
            continue
        in_box = False  # some point in the box grown by the berth (the callers' own test)
        clear = True  # every point farther than the berth from the box, by the margin
        for i in range(dense.shape[0]):
            x, y = dense[i, 0], dense[i, 1]
            if b[0] - reach <= x <= b[2] + reach and b[1] - reach <= y <= b[3] + reach:
                in_box = True
            if _box_distance(b, x, y) < berth + MARGIN:
                clear = False
        if not in_box or clear:
            continue  # not a candidate, or none of the path within the berth of it
        lo, hi = np.inf, -np.inf
        for v in range(first[k], first[k] + count[k]):
            a = (vertices[v, 0] - sx) * u[0] + (vertices[v, 1] - sy) * u[1]
            lo, hi = min(lo, a), max(hi, a)
        lo, hi = lo - radius[k], hi + radius[k]
        if lo < -berth - MARGIN or hi > length + berth + MARGIN:
            continue  # not passed by, whatever the rounding
        along_unknown = lo < -berth + MARGIN or hi > length + berth - MARGIN
        ends_unknown = False
        for e in range(2):
            if _box_distance(b, ends[e, 0], ends[e, 1]) < berth + MARGIN:
                ends_unknown = True
        out[m, 0], out[m, 1], out[m, 2] = k, along_unknown, ends_unknown
        m += 1
    return out[:m]


def intruding_candidates(
    pk: ObstaclePack, dense: np.ndarray, ends: np.ndarray, length: float, u, berth: float
) -> np.ndarray:
    """The obstacles :func:`mjwalk.plan.sides.intruding` must ask, in its order: those whose
    bounding box meets the densified path's own grown by ``berth``, holds a point of it within
    the berth (plus 1 nm), lies within the berth of some point (by its box distance) and is
    not ruled out as passed by (a wall the walk runs along, one behind an end) by its
    extent along ``u``; each flagged where its extent or its distance from an end is too near
    the threshold for the bounds to decide.

    Args:
        pk: the workplace's obstacles (:func:`pack`).
        dense: (k, 2) the path at its checked points, metres, world frame.
        ends: (2, 2) the walk's start and goal, metres.
        length: the distance start -> goal, metres.
        u: (2,) the unit direction start -> goal.
        berth: the distance kept, metres.

    Returns:
        (m, 3) int rows: the obstacle's index, whether its extent along the walk must be
        measured exactly, whether its distance from the ends must be.
    """
    return _intruding_candidates(
        np.ascontiguousarray(dense, dtype=float), pk.bounds, pk.vertices, pk.first, pk.count,
        pk.radius, np.ascontiguousarray(ends, dtype=float), np.ascontiguousarray(u, dtype=float),
        float(length), float(berth),
    )  # fmt: skip


@njit
def _gap_candidates(beside, other, bounds, vertices, first, count, radius, passed, gap_open):
    """:func:`gap_candidates`, compiled."""
    x0, y0 = beside[:, 0].min() - gap_open, beside[:, 1].min() - gap_open
    x1, y1 = beside[:, 0].max() + gap_open, beside[:, 1].max() + gap_open
    n, m = bounds.shape[0], beside.shape[0]
    ks = np.empty(n, dtype=np.int64)
    c = 0
    for k in range(n):
        if not passed[k] and _meets(bounds[k], x0, y0, x1, y1):
            ks[c] = k
            c += 1
    ub = np.empty((c, m))
    best1 = other.copy()  # per point the least upper bound of all (the edges' room included)
    best2 = other.copy()  # ... and of all but the one giving best1
    arg1 = np.full(m, -1)
    for j in range(c):
        k = ks[j]
        for i in range(m):
            d = _vertex_distance(
                vertices, first[k], count[k], radius[k], beside[i, 0], beside[i, 1]
            )
            ub[j, i] = d
            if d < best1[i]:
                best2[i], best1[i], arg1[i] = best1[i], d, j
            elif d < best2[i]:
                best2[i] = d
    keep = np.empty(c, dtype=np.int64)
    kept = 0
    for j in range(c):
        k = ks[j]
        for i in range(m):
            others = best2[i] if arg1[i] == j else best1[i]
            if _box_distance(bounds[k], beside[i, 0], beside[i, 1]) < others + MARGIN:
                keep[kept] = k
                kept += 1
                break
    return keep[:kept]


def gap_candidates(
    pk: ObstaclePack, beside: np.ndarray, other: np.ndarray, passed, gap_open: float
) -> np.ndarray:
    """The obstacles :func:`mjwalk.plan.sides.side_gap` must ask for their distances, in its
    order: of those whose bounding box meets the box of the points ``beside`` grown by
    ``gap_open``, less the ``passed`` one, each that may come nearer some point than
    every other (its box distance below the least of the others' nearest-vertex distances
    and the room ``other`` already known, by the margin). The others cannot lower any point's
    least distance, so the gap is the same without them.

    Args:
        pk: the workplace's obstacles (:func:`pack`).
        beside: (m >= 1, 2) the points, metres, world frame.
        other: (m,) the room already known at each point, metres (floor edges, the cap).
        passed: (n,) bool, which of the workplace's obstacles is the one passed.
        gap_open: metres.

    Returns:
        The obstacles' indices, ascending.
    """
    return _gap_candidates(
        np.ascontiguousarray(beside, dtype=float), np.ascontiguousarray(other, dtype=float),
        pk.bounds, pk.vertices, pk.first, pk.count, pk.radius,
        np.ascontiguousarray(passed, dtype=np.bool_), float(gap_open),
    )  # fmt: skip


@njit
def _minimum(a, b):
    """np.minimum of two floats: ``a`` where a <= b or a is NaN, else ``b`` (NaN propagates)."""
    return a if (a <= b or a != a) else b


@njit
def gap_room(beside, floor, bounds, vertices, first, count, radius, passed, gap_open):
    """The room beside each point of a side's route (:func:`mjwalk.plan.sides.side_gap`), in
    one compiled pass: its distance from the floor's edges, at most ``gap_open``, lowered to
    every polygon obstacle's exact signed distance (:func:`~mjwalk.world.footprint.
    polygon_distances`) among :func:`gap_candidates`; the rounded segments among them are
    left to the caller (their NumPy distance). Each step is the NumPy code's ``np.minimum``
    (NaN propagating; a minimum's order does not change it), so the room is that code's to
    the bit.

    Args:
        beside: (m >= 1, 2) the points, metres, world frame (C-contiguous).
        floor: (4,) the floor's (xmin, ymin, xmax, ymax), metres.
        bounds: :attr:`ObstaclePack.bounds`.
        vertices: :attr:`ObstaclePack.vertices`.
        first: :attr:`ObstaclePack.first`.
        count: :attr:`ObstaclePack.count`.
        radius: :attr:`ObstaclePack.radius`.
        passed: (n,) bool, which obstacle is the one passed.
        gap_open: the cap, metres.

    Returns:
        (room (m,) metres, the rounded-segment candidates' indices, ascending).
    """
    m = beside.shape[0]
    other = np.empty(m)
    xmin, ymin, xmax, ymax = floor[0], floor[1], floor[2], floor[3]
    for i in range(m):
        x, y = beside[i, 0], beside[i, 1]
        edge = _minimum(_minimum(_minimum(x - xmin, xmax - x), y - ymin), ymax - y)
        other[i] = _minimum(edge, gap_open)
    ks = _gap_candidates(beside, other, bounds, vertices, first, count, radius, passed, gap_open)
    rounded = np.empty(ks.shape[0], dtype=np.int64)
    nr = 0
    for k in ks:
        if radius[k] != 0.0:
            rounded[nr] = k
            nr += 1
            continue
        d = polygon_distances(beside, vertices[first[k] : first[k] + count[k]])
        for i in range(m):
            other[i] = _minimum(other[i], d[i])
    return other, rounded[:nr]
