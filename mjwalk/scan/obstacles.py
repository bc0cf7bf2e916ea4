"""A levelled scan (floor at z = 0) as a floor plan: walkable floor, obstacles and voids.

On a grid of ``resolution`` metres over the floor:

- floor cells hold points within :data:`FLOOR_TOL` of z = 0, or, where the scan says where
  its scanner stood, are cells a ray of the scan reached on the floor (:mod:`.sight`: floor
  seen sparsely far from the scanner is floor);
- obstacle cells hold at least :data:`MIN_BAND_POINTS` points in the obstacle band (0.05-2.0 m
  above the floor, as for MJCF scenes, :data:`mjwalk.world.floor.OBSTACLE_Z_RANGE`); gaps
  of one cell are closed, and regions the obstacles enclose with no floor seen inside (the
  inside of a cabinet taller than the scanner) become obstacle too. Structure above the band
  (pipework, lamps, the ceiling) is not an obstacle;
- floor points closer than 2 :data:`FLOOR_GAP` are joined (closing);
- unscanned holes in the floor (under the scanner, behind small objects, between the sparse
  rings of far floor) count as floor, within the convex outline of the seen floor, when no
  point of them is farther than :data:`HOLE_RADIUS` from their edge; larger unseen regions are
  voids;
- **gaps**: an unscanned region of the floor (neither floor nor obstacle) that holds or borders
  :data:`MIN_BAND_POINTS` points lower than the band's foot below the floor (a pit's walls or
  bottom, a lowered trench, an open shaft whose bottom no ray reached) is a place where the
  floor is missing, not a hole in the scan: when it can hold a foot (:data:`GAP_WIDTH`) it is
  never filled as floor (neither as a small hole nor by the void policy) and is kept in
  :attr:`FloorPlan.gaps`; the blind disc under a scanner and the shadow behind an obstacle have
  no such points and are filled as before;
- the walkable floor is the largest connected floor region (pockets of floor walled in by
  obstacles, such as the floor seen under a car body on its wheels, are not reachable on foot);
  its bounding rectangle becomes the MJCF floor plane, and what of the rectangle is neither
  floor nor obstacle is void (an obstacle to the planner too: nobody walks where no floor
  was scanned).

Obstacles and voids become boxes (:func:`rectangles`): each connected obstacle is cut into the
fewest row-run rectangles, standing on the floor up to the obstacle's highest band point.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk._jit import njit
from mjwalk.anthropometry import SEG
from mjwalk.scan.sight import View, ray_seen
from mjwalk.world.floor import OBSTACLE_Z_RANGE

#: A floor point is within this height of z = 0 after levelling, metres: below the band's
#: 0.05 m, and 6 sigma of a 5 mm range noise.
FLOOR_TOL = 0.03
#: Band points a grid cell needs to be an obstacle (a lone point is a mixed pixel or noise).
MIN_BAND_POINTS = 2
#: An unscanned hole counts as floor when its inscribed radius is at most this, metres: the
#: blind cone below a terrestrial scanner (vertical field of view 300°, e.g. FARO Focus, i.e. 30°
#: half-angle) on a tripod up to 1.7 m high leaves a disc of radius 1.7 tan 30° = 0.98 m.
HOLE_RADIUS = 1.0
#: Floor points closer than twice this are joined into one floor, metres: the rings of floor
#: points a scanner leaves grow apart with range (d² Δθ / h: 0.15 m at 4 m for a 1.5 m high
#: scanner stepping 0.2°), and a gap narrower than a body diameter (2 x 0.25 m) holds no obstacle
#: the band points did not show.
FLOOR_GAP = 0.25
#: Heights of the obstacle band split into bins this tall to find each obstacle's top, metres.
TOP_STEP = 0.05
#: An unscanned region over points below the floor is a gap a foot can step into when its
#: inscribed diameter is at least this, metres: the foot width of a 1.50 m person (0.055 of
#: stature, Winter 2009, Fig. 4.1, ``mjwalk.anthropometry.SEG``; 1.50 m about the 5th
#: percentile of women's stature, DIN 33402-2), 0.083 m. Narrower slots (a drain, a cable
#: channel) stay floor.
GAP_WIDTH = SEG["foot_width"] * 1.50


@dataclass
class FloorPlan:
    """Grids over the scanned floor (world x, y in metres; ``[iy, ix]`` is the cell whose lower
    corner is ``(x0 + ix * resolution, y0 + iy * resolution)``).

    Attributes:
        floor: walkable floor cells (scanned or small holes), bool.
        obstacles: obstacle label per cell (0: none; 1..n connected obstacles).
        tops: (n + 1,) height of each obstacle's highest band point, metres (tops[0] unused).
        void: cells of the floor rectangle that are neither floor nor obstacle, bool.
        bounds: (xmin, ymin, xmax, ymax) of the floor rectangle, metres.
        holes_filled: number of unscanned holes counted as floor.
        seen: floor cells holding floor points or closed between them (:data:`FLOOR_GAP`);
            the rest of ``floor`` is unscanned holes counted as floor, bool.
        gaps: cells where the floor is missing (an unscanned region over points below the
            floor, module docstring), bool; neither floor, obstacle nor void (None: not looked
            for).
        drop: per cell the lowest point below the floor's band foot, metres (0: none; None:
            not looked for).
    """

    x0: float
    y0: float
    resolution: float
    floor: np.ndarray
    obstacles: np.ndarray
    tops: np.ndarray
    void: np.ndarray
    bounds: tuple[float, float, float, float]
    holes_filled: int
    seen: np.ndarray | None = None
    gaps: np.ndarray | None = None
    drop: np.ndarray | None = None


@njit
def _floor_box(points, tol):
    """(xmin, ymin, xmax, ymax) of the points within ``tol`` of z = 0 (inf/-inf: none), in
    one pass over the cloud (no masked copies of millions of points)."""
    out = np.array([np.inf, np.inf, -np.inf, -np.inf])
    for k in range(points.shape[0]):
        if abs(points[k, 2]) <= tol:
            x, y = points[k, 0], points[k, 1]
            out[0] = min(out[0], x)
            out[1] = min(out[1], y)
            out[2] = max(out[2], x)
            out[3] = max(out[3], y)
    return out


@njit
def _rasterize(points, x0, y0, res, nx, ny, tol, z0, z1, step, nbins):
    """Per floor-plan cell (ny, nx), in one pass over the cloud: the number of floor points
    (within ``tol`` of z = 0), of obstacle-band points (``z0 <= z <= z1``), the highest band
    bin (``step`` metres from ``z0``, -1: none) of the band points, the number of points below
    ``-z0`` and the lowest of those (0: none)."""
    floor_n = np.zeros((ny, nx), dtype=np.int64)
    band_n = np.zeros((ny, nx), dtype=np.int64)
    top = np.full((ny, nx), -1, dtype=np.int64)
    drop_n = np.zeros((ny, nx), dtype=np.int64)
    low = np.zeros((ny, nx), dtype=np.float64)
    for k in range(points.shape[0]):
        z = points[k, 2]
        near = abs(z) <= tol
        band = z0 <= z <= z1
        below = z < -z0
        if not (near or band or below):
            continue
        i = int(np.floor((points[k, 0] - x0) / res))
        j = int(np.floor((points[k, 1] - y0) / res))
        if i < 0 or i >= nx or j < 0 or j >= ny:
            continue
        if below:
            drop_n[j, i] += 1
            low[j, i] = min(low[j, i], z)
        if near:
            floor_n[j, i] += 1
        if band:
            band_n[j, i] += 1
            b = min(int((z - z0) / step), nbins - 1)
            if b > top[j, i]:
                top[j, i] = b
    return floor_n, band_n, top, drop_n, low


def floor_plan(
    points: np.ndarray,
    *,
    resolution: float = 0.02,
    z_range: tuple[float, float] = OBSTACLE_Z_RANGE,
    views: Sequence[View] = (),
    gaps: bool = True,
) -> FloorPlan | None:
    """The floor plan of a levelled cloud.

    Args:
        points: (N, 3) levelled points, metres, floor at z = 0.
        resolution: the grid edge, metres.
        z_range: the obstacle band above the floor, metres (low, high).
        views: the stations whose rays decide which floor was seen besides the cells holding
            floor points (:mod:`.sight`); none: the floor points alone.
        gaps: look for gaps, where points below the floor show it missing (module docstring);
            False: points below the floor are ignored and unscanned holes filled as floor
            regardless (the plan before gaps were looked for).

    Returns:
        The plan (floor, obstacle labels and tops, voids), or None without floor points.
    """
    pts = np.ascontiguousarray(points, dtype=np.float64)
    box = _floor_box(pts, FLOOR_TOL)
    if not np.isfinite(box).all():
        return None  # no floor points
    # A margin wider than a small hole: the unseen region around the floor is never "small".
    margin = HOLE_RADIUS + 3 * resolution
    lo = box[:2] - margin
    hi = box[2:] + margin
    nx, ny = (np.ceil((hi - lo) / resolution).astype(int) + 1).tolist()
    nbins = int(np.ceil((z_range[1] - z_range[0]) / TOP_STEP))
    floor_n, counts, top_bin, drop_n, low = _rasterize(
        pts, lo[0], lo[1], resolution, nx, ny, FLOOR_TOL, z_range[0], z_range[1], TOP_STEP, nbins
    )
    seen_floor = floor_n > 0
    drop = (drop_n >= MIN_BAND_POINTS) & gaps
    outline = _hull_mask(seen_floor)  # of the floor points: rays through a doorway leave it
    if views:
        seen_floor |= ray_seen(pts, views, lo[0], lo[1], resolution, (ny, nx), FLOOR_TOL)
    occupied = counts >= MIN_BAND_POINTS
    obst = _obstacle_cells(occupied, seen_floor)
    floor, closed, filled, gap = _floor_cells(seen_floor, obst, outline, resolution, drop)
    if floor is None:
        return None
    # obstacles are kept where they touch the walkable floor
    olab, _ = ndimage.label(obst, _SQUARE)
    touching = np.unique(olab[ndimage.binary_dilation(floor, _SQUARE) & obst])
    obst = np.isin(olab, touching[touching > 0])
    iy, ix = np.nonzero(floor)
    y0i, y1i, x0i, x1i = iy.min(), iy.max() + 1, ix.min(), ix.max() + 1
    floor = floor[y0i:y1i, x0i:x1i]
    seen = (closed | seen_floor)[y0i:y1i, x0i:x1i] & floor  # floor points, gaps closed
    obst = obst[y0i:y1i, x0i:x1i]
    olab, tops = _obstacle_tops(obst, top_bin[y0i:y1i, x0i:x1i], z_range)
    x0 = float(lo[0] + x0i * resolution)
    y0 = float(lo[1] + y0i * resolution)
    gap = gap[y0i:y1i, x0i:x1i] & ~obst
    void = ~floor & ~obst & ~gap
    # The floor's edge lies inside its outermost cells, on average at their centres.
    half = 0.5 * resolution
    bounds = (
        x0 + half,
        y0 + half,
        x0 + floor.shape[1] * resolution - half,
        y0 + floor.shape[0] * resolution - half,
    )
    low = low[y0i:y1i, x0i:x1i] if gaps else None
    return FloorPlan(
        x0, y0, resolution, floor, olab, tops, void, bounds, filled, seen, gap if gaps else None,
        low,
    )  # fmt: skip


#: 8-connectivity of the floor plan's cells.
_SQUARE = np.ones((3, 3), bool)


def _obstacle_cells(occupied: np.ndarray, seen_floor: np.ndarray) -> np.ndarray:
    """Obstacle cells: the occupied ones closed over one-cell gaps, and the enclosed regions
    without a floor point inside (the inside of an obstacle)."""
    obst = ndimage.binary_closing(occupied, _SQUARE) | occupied
    enclosed = ndimage.binary_fill_holes(obst) & ~obst
    lab, n = ndimage.label(enclosed, _SQUARE)
    if n:
        has_floor = ndimage.sum(seen_floor, lab, np.arange(1, n + 1)) > 0
        obst |= np.isin(lab, np.flatnonzero(~has_floor) + 1)
    return obst


def _floor_cells(
    seen_floor: np.ndarray,
    obst: np.ndarray,
    outline: np.ndarray,
    resolution: float,
    drop: np.ndarray,
) -> tuple[np.ndarray | None, np.ndarray, int, np.ndarray]:
    """The walkable floor (None: no floor), the floor evidence with its gaps closed, how many
    small unscanned holes were counted as floor, and the gaps (cells ``drop`` shows the floor
    missing at, module docstring)."""
    # Sparse floor evidence (the rings of far floor points) closed over gaps up to 2 FLOOR_GAP;
    # not over cells with points below the floor (the closing bridges a trench that narrow).
    drop = _drop_evidence(drop, resolution)
    spread = ndimage.distance_transform_edt(~seen_floor) * resolution <= FLOOR_GAP
    closed = ndimage.distance_transform_edt(spread) * resolution > FLOOR_GAP
    closed &= ~drop
    floor = (closed | seen_floor) & ~obst
    gap = _gap_cells(~floor & ~obst, drop, resolution)
    if gap.any():  # the closing rounds a gap's corners by up to FLOOR_GAP: no floor point there
        grow = ndimage.distance_transform_edt(~gap) * resolution <= FLOOR_GAP
        grow &= ~seen_floor & ~obst
        lab, _ = ndimage.label(grow | gap, _SQUARE)
        gap = ndimage.binary_opening(np.isin(lab, np.unique(lab[gap])), _SQUARE)  # no specks
        floor &= ~gap
    # Small unscanned holes are floor.
    # Only inside the seen floor's convex outline: a hole at the floor's edge (the blind disc
    # of a scanner near the edge, a shadow behind a rack) fills up to the floor's edge.
    # The outline is the floor points' own: floor the rays saw through a doorway adds floor
    # there, never a wider outline that would take the wall's far side in as a hole.
    unknown = ~floor & ~obst & outline & ~gap
    lab, n = ndimage.label(unknown, _SQUARE)
    filled = 0
    if n:
        radius = ndimage.distance_transform_edt(unknown) * resolution
        inscribed = ndimage.maximum(radius, lab, np.arange(1, n + 1))
        small = np.asarray(inscribed) <= HOLE_RADIUS
        floor |= np.isin(lab, np.flatnonzero(small) + 1)
        filled = int(small.sum())
    # The walkable floor: the largest connected floor region. Floor seen in pockets walled in
    # by obstacles (under a car body raised on its wheels, inside a fenced cell) is not
    # reachable on foot and becomes void.
    lab, n = ndimage.label(floor, _SQUARE)
    if n == 0:
        return None, closed, filled, gap
    sizes = ndimage.sum(floor, lab, np.arange(1, n + 1))
    return lab == int(np.argmax(sizes)) + 1, closed, filled, gap


def _gap_cells(unknown: np.ndarray, drop: np.ndarray, resolution: float) -> np.ndarray:
    """The unscanned regions (``unknown``: neither floor nor obstacle) that hold or border a
    cell of points below the floor (``drop``) and can hold a foot (:data:`GAP_WIDTH`)."""
    out = np.zeros_like(unknown)
    if not drop.any():
        return out
    lab, _ = ndimage.label(unknown, _SQUARE)
    hit = np.unique(lab[ndimage.binary_dilation(drop, _SQUARE) & unknown])
    hit = hit[hit > 0]
    if not len(hit):
        return out
    radius = ndimage.distance_transform_edt(unknown) * resolution
    inscribed = np.asarray(ndimage.maximum(radius, lab, hit))
    # a run of k cells has k // 2 + 1 cells to its edge's centre: width about 2 r - 1 cell
    return np.isin(lab, hit[2 * inscribed - resolution >= GAP_WIDTH])


def _drop_evidence(drop: np.ndarray, resolution: float) -> np.ndarray:
    """The cells of points below the floor that show the floor missing: clusters (cells at most
    one cell apart) spanning a foot's width (:data:`GAP_WIDTH`)."""
    if not drop.any():
        return drop
    # Evidence is a wall or a bottom seen along a foot's width, not stray points: a real scan's
    # range noise leaves single cells of two points 5-10 cm below the floor (the shared PCL
    # room scan: 70 such cells, none touching another).
    dlab, _ = ndimage.label(ndimage.binary_dilation(drop, _SQUARE), _SQUARE)  # a cell apart
    spans = [
        max(s[0].stop - s[0].start, s[1].stop - s[1].start) for s in ndimage.find_objects(dlab)
    ]
    wide = np.flatnonzero((np.array(spans) - 2) * resolution >= GAP_WIDTH) + 1
    return drop & np.isin(dlab, wide)


def _obstacle_tops(
    obst: np.ndarray, top_bin: np.ndarray, z_range: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray]:
    """Obstacle labels (0: none) and each label's top height, metres (index 0 unused): the top
    of its highest band bin, at most the band's top."""
    olab, n = ndimage.label(obst, _SQUARE)
    tops = np.zeros(n + 1)
    if n:
        tb = ndimage.maximum(top_bin, olab, np.arange(1, n + 1))
        tb = np.maximum(np.asarray(tb), 0)
        tops[1:] = np.minimum(z_range[0] + (tb + 1) * TOP_STEP, z_range[1])
    return olab, tops


def _hull_mask(mask: np.ndarray) -> np.ndarray:
    """Cells inside the convex hull of the set cells of ``mask``."""
    from scipy.spatial import (
        ConvexHull,
        QhullError,
    )  # deferred: scipy.spatial adds ~0.2 s to start-up

    iy, ix = np.nonzero(mask)
    pts = np.column_stack([ix, iy]).astype(float)
    out = np.zeros_like(mask)
    try:
        hull = ConvexHull(pts)
    except QhullError:
        return mask.copy()
    gx, gy = np.meshgrid(np.arange(mask.shape[1]), np.arange(mask.shape[0]))
    eq = hull.equations  # a x + b y + c <= 0 inside
    inside = np.ones(mask.shape, bool)
    for a, b, c in eq:
        inside &= a * gx + b * gy + c <= 1e-9
    out |= inside
    return out


def rectangles(labels: np.ndarray) -> list[tuple[int, int, int, int, int]]:
    """Cover each labelled region with axis-aligned rectangles of cells.

    Runs of equal label along each row, stacked while the same run repeats on the next row.

    Args:
        labels: (ny, nx) integer labels, 0 = empty.

    Returns:
        (iy0, iy1, ix0, ix1, label) per rectangle, ends exclusive.
    """
    ny, nx = labels.shape
    out: list[tuple[int, int, int, int, int]] = []
    active: dict[tuple[int, int, int], int] = {}
    padded = np.zeros((ny + 1, nx + 2), dtype=labels.dtype)
    padded[:ny, 1:-1] = labels
    for iy in range(ny + 1):
        row = padded[iy]
        change = np.flatnonzero(row[1:] != row[:-1])  # run boundaries in cell coordinates
        runs = set()
        for a, b in itertools.pairwise(change):
            lab = int(row[a + 1])
            if lab:
                runs.add((int(a), int(b), lab))
        for key in list(active):
            if key not in runs:
                out.append((active.pop(key), iy, key[0], key[1], key[2]))
        for key in runs:
            active.setdefault(key, iy)
    return out
