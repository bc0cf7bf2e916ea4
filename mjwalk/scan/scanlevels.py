"""The walk-surface levels of a levelled scan: platforms, steps and stairs (issue 47).

The seed paper (mocap-based DHM walking in as-built environments, §3 A2) extracts walk-surface
points (normal within 20° of up) and groups them by region growing; its Fig. 9 shows floors and
stair treads as separate walk surfaces. Region growing over 0.1 m voxels in 3-D (as
:func:`mjwalk.scan.level.walk_surfaces` does for the floor) joins a 0.17 m step to the floor
through diagonal voxels, so here levels are found in two passes:

1. **Heights**: the upward-facing voxels (the local-PCA normals of :func:`~mjwalk.scan.level.
   voxel_normals`, within the paper's 20° of up) between the obstacle band's foot and the top of
   the band vote with their centroid height into a 1 cm histogram; its peaks, strongest first and
   at least :data:`PEAK_SEPARATION` apart, are the candidate heights. A histogram, not Open3D's
   RANSAC plane segmentation: RANSAC finds one plane at a time over the whole cloud (each
   treads' 0.28 m² is lost next to the floor's 100 m² unless the floor is removed and the search
   repeated per plane) and is random; the histogram is one deterministic pass.
2. **Regions**: per candidate height ``h``, on the floor plan's grid, a cell is surface when it
   holds a point within :data:`~mjwalk.scan.obstacles.FLOOR_TOL` of ``h`` and fewer than
   :data:`~mjwalk.scan.obstacles.MIN_BAND_POINTS` points in its own obstacle band (0.05-2.0 m
   above ``h``, :data:`mjwalk.world.floor.OBSTACLE_Z_RANGE`), joined over the gaps up to a voxel
   where no point was seen from below ``h`` to the band's top (:mod:`mjwalk.scan.sparsecells`:
   a deck's middle in its own scanner's blind cone, seen by the others only in rows several
   cells apart); connected cells (8-neighbourhood) are one region, its height a least-squares
   plane through the points of its cells inside its rim (trimmed at 3 rms; the rim cells hold
   the risers' points within ``FLOOR_TOL``, the lower riser's below the tread at its front, the
   upper one's above at its back, which tilt a full tread's fit past 1 % where a scanner sees
   the risers head-on and the tread at a grazing angle), kept when that plane is horizontal
   (``norms.HORIZONTAL_SLOPE`` plus three standard errors of the fit; else its flat part,
   :func:`mjwalk.scan.planefit.flat_part`, when a ramp's strip at that height joined a level's
   edge and tilted it) and the region is a tread deep and a person wide (``norms.MIN_TREAD`` by
   ``norms.STAND_WIDTH``, less a cell each side for the cells its edges cut). A region whose
   height lies more than :data:`OWN_HEIGHT_TOL` from its candidate's (a peak two surfaces a few
   centimetres apart made between them) is found again at its own height.

Regions whose edges touch (within ``norms.CONTACT_GAP`` and a cell) along at least a body's
width (``mjwalk.world.contacts.MIN_CROSSING``) with a riser of at most ``norms.MAX_RISER`` are
joined (a riser measured within ``planefit.RISER_TOL`` of the limit: a region's height is a fit);
a region less than :data:`PEAK_SEPARATION` from a larger one it touches (that one's unseen strip
counted, as for the steps) is part of it, no level (the obstacle band begins there); the levels
are the regions reachable from the floor so (a table top stays an obstacle).
Stairs: a chain of at least ``norms.MIN_STAIR_RISERS`` risers over single treads (regions no
deeper than ``norms.MAX_TREAD``) with risers and treads regular within the scan's measuring
tolerance is fitted as one regular flight (:mod:`mjwalk.scan.levelboxes`). Metres, scene frame
(floor at z = 0).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk._jit import njit
from mjwalk.scan.level import HORIZONTAL_DEG, MAX_SURFACE_HEIGHT, VOXEL, voxel_normals
from mjwalk.scan.minrect import min_rectangle, rectangle_size
from mjwalk.scan.obstacles import FLOOR_TOL, MIN_BAND_POINTS, FloorPlan
from mjwalk.scan.planefit import RANGE_NOISE, TRIM_SIGMAS, fit_plane, flat_part
from mjwalk.scan.regionsteps import region_steps, touching, with_shadow
from mjwalk.scan.sparsecells import (
    enclosed_unseen,
    join_sparse,
    other_surfaces,
    unseen_cells,
    unseen_regions,
)
from mjwalk.world.floor import OBSTACLE_Z_RANGE
from mjwalk.world.norms import HORIZONTAL_SLOPE, MAX_TREAD, MIN_TREAD, STAND_WIDTH

#: Bin of the height histogram, metres.
HIST_BIN = 0.01
#: Two candidate heights closer than this are one (metres): the foot of the obstacle band
#: (``OBSTACLE_Z_RANGE[0]``): anything lower on a surface is part of it, not an obstacle.
PEAK_SEPARATION = OBSTACLE_Z_RANGE[0]
#: Least area of upward voxels a candidate height needs, square metres: half the least surface
#: (``MIN_TREAD`` x ``STAND_WIDTH``), for the voxels its edges cut.
PEAK_AREA = 0.5 * MIN_TREAD * STAND_WIDTH
#: A voxel is planar when its middle covariance eigenvalue is at least this share of the
#: largest (a scan line crossing a voxel spans one direction only; as ``level.walk_surfaces``).
PLANAR_SHARE = 0.1

#: Least depth of a stair tread seen in part, metres: half the least tread (``norms.MIN_TREAD``;
#: a choice, no norm). The next level's edge may shadow a tread's back from the scanners; such a
#: region is a level only as a tread of a regular flight (:func:`mjwalk.scan.stairfit.fit_stair`).
SHADOWED_DEPTH = 0.5 * MIN_TREAD
#: Rounds of looking again for surfaces no region explains (:func:`find_regions`).
MORE_ROUNDS = 2
#: A region whose fitted height lies further than this from the candidate height it was found
#: at lost points (metres): its points lie within three ``planefit.RANGE_NOISE`` of its height,
#: the candidate's cells within ``FLOOR_TOL`` of the candidate. Two surfaces a few centimetres
#: apart (a tread and a crate's lid) make one histogram peak between them; such a region is
#: found again at its own height (:func:`_at_own_height`).
OWN_HEIGHT_TOL = FLOOR_TOL - 3 * RANGE_NOISE
#: Kinds of scan level.
LEVEL_KINDS = ("floor", "tread", "platform")


@dataclass(frozen=True)
class ScanLevel:
    """One walk-surface region of a scan.

    Attributes:
        index: its place in :attr:`ScanLevels.levels` (0: the floor).
        kind: "floor", "tread" (no deeper than ``norms.MAX_TREAD``) or "platform".
        height: the fitted plane's height at the region's centroid, metres above the floor.
        rms: rms distance of its points from the plane, metres.
        slope: the fitted plane's inclination, radians.
        cells: (ny, nx) bool, its cells on the floor plan's grid, holes filled.
        area: the cells' area, square metres.
        depth, width: its least extent and the extent across it (minimum-area rectangle of the
            cells' centres), metres.
        peak: index of the candidate height it was found at (-1: the floor).
    """

    index: int
    kind: str
    height: float
    rms: float
    slope: float
    cells: np.ndarray
    area: float
    depth: float
    width: float
    peak: int


@dataclass(frozen=True)
class ScanLink:
    """Where a walker gets from one scan level to another.

    Attributes:
        kind: "step" (one riser), "stair" (a regular flight) or "ramp".
        lower, upper: the levels' indices.
        risers: each riser's height, bottom up, metres (a stair's: its regular riser; a ramp:
            none).
        tread: a stair's tread depth, metres (None otherwise).
        via: a stair's tread levels, bottom up (empty otherwise).
        slope: a ramp's inclination, radians (None otherwise).
        run: a ramp's horizontal length, metres (None otherwise).
    """

    kind: str
    lower: int
    upper: int
    risers: tuple[float, ...]
    tread: float | None = None
    via: tuple[int, ...] = ()
    slope: float | None = None
    run: float | None = None

    @property
    def rise(self) -> float:
        """Height from the lower level to the upper, metres."""
        if self.slope is not None and self.run is not None:
            return self.run * math.tan(self.slope)
        return float(sum(self.risers))


@dataclass
class Layers:
    """The cloud rasterised per candidate height ``heights`` (K,) on the floor plan's grid:
    ``near`` (K, ny, nx) points within ``FLOOR_TOL``, ``band`` points in the obstacle band above,
    ``top`` the highest band point (metres; -inf: none); ``lowest`` (ny, nx) the lowest point
    per cell at any height (metres; +inf: none; None: not rasterised)."""

    heights: np.ndarray
    near: np.ndarray
    band: np.ndarray
    top: np.ndarray
    lowest: np.ndarray | None = None


def candidate_heights(
    levelled: np.ndarray, span: tuple[float, float] = (PEAK_SEPARATION, MAX_SURFACE_HEIGHT)
) -> np.ndarray:
    """The heights where upward-facing surfaces of a levelled cloud lie, strongest first.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        span: (lowest, highest) height looked at, metres; the default: the raised surfaces
            (below the floor, :mod:`mjwalk.scan.scanpits` looks at pits).

    Returns:
        (K,) heights, metres, each the mean of its upward voxels' centroids within
        ``FLOOR_TOL`` of its histogram peak; within ``span``.
    """
    return peak_heights(upward_centroids(levelled, span)[:, 2], span)


def upward_centroids(levelled: np.ndarray, span: tuple[float, float]) -> np.ndarray:
    """The planar upward-facing voxels of a levelled cloud (the paper's 20 deg of up).

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        span: (lowest, highest) voxel height kept, metres.

    Returns:
        (M, 3) the voxels' centroids, metres.
    """
    lo, hi = span
    sel = levelled[(levelled[:, 2] > lo - VOXEL) & (levelled[:, 2] <= hi + VOXEL)]
    if len(sel) < 10:
        return np.zeros((0, 3))
    vn = voxel_normals(sel, VOXEL)
    ev = vn.eigval
    up = (vn.normal[:, 2] >= math.cos(math.radians(HORIZONTAL_DEG))) & (
        ev[:, 1] >= PLANAR_SHARE * ev[:, 2]
    )
    c = vn.centroid[up]
    return c[(c[:, 2] > lo) & (c[:, 2] <= hi)]


def peak_heights(z: np.ndarray, span: tuple[float, float]) -> np.ndarray:
    """The peaks of a 1 cm histogram of upward voxels' heights.

    Args:
        z: (M,) the voxels' centroid heights, metres.
        span: (lowest, highest) height looked at, metres.

    Returns:
        (K,) heights, metres, strongest first, each at least :data:`PEAK_SEPARATION` from a
        stronger one and holding at least :data:`PEAK_AREA` of voxels within ``FLOOR_TOL``;
        each the mean of its voxels there.
    """
    lo, hi = span
    if len(z) == 0:
        return np.zeros(0)
    nb = math.ceil((hi - lo) / HIST_BIN)
    hist = np.bincount(((z - lo) / HIST_BIN).astype(np.int64), minlength=nb)[:nb].astype(float)
    half = round(FLOOR_TOL / HIST_BIN)
    window = np.convolve(hist, np.ones(2 * half + 1), mode="same") * VOXEL**2  # m² per window
    out: list[float] = []
    while window.size and window.max() >= PEAK_AREA:
        b = int(np.argmax(window))
        h0 = lo + (b + 0.5) * HIST_BIN
        near = z[np.abs(z - h0) <= FLOOR_TOL]
        h = float(near.mean()) if len(near) else h0
        out.append(h)
        gone = np.abs(lo + (np.arange(nb) + 0.5) * HIST_BIN - h) < PEAK_SEPARATION
        window[gone] = 0.0
    return np.array(out)


@njit
def _rasterize_layers(points, heights, x0, y0, res, nx, ny, tol, band_lo, band_hi):
    """Per height k and cell: points within ``tol`` of ``heights[k]``, points in the band
    (``heights[k] + band_lo``, ``heights[k] + band_hi``], and the highest of those; per cell the
    lowest point."""
    k_n = heights.shape[0]
    near = np.zeros((k_n, ny, nx), dtype=np.int32)
    band = np.zeros((k_n, ny, nx), dtype=np.int32)
    top = np.full((k_n, ny, nx), -np.inf, dtype=np.float32)
    lowest = np.full((ny, nx), np.inf, dtype=np.float32)
    for p in range(points.shape[0]):
        i = int(np.floor((points[p, 0] - x0) / res))
        j = int(np.floor((points[p, 1] - y0) / res))
        if i < 0 or i >= nx or j < 0 or j >= ny:
            continue
        z = points[p, 2]
        if z < lowest[j, i]:
            lowest[j, i] = z
        for k in range(k_n):
            d = z - heights[k]
            if abs(d) <= tol:
                near[k, j, i] += 1
            elif band_lo < d <= band_hi:
                band[k, j, i] += 1
                if z > top[k, j, i]:
                    top[k, j, i] = z
    return near, band, top, lowest


def rasterize_layers(levelled: np.ndarray, heights: np.ndarray, plan: FloorPlan) -> Layers:
    """The cloud per candidate height on the floor plan's grid (:class:`Layers`).

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        heights: (K,) candidate heights, metres; the floor's 0 is prepended.
        plan: the floor plan whose grid is used.

    Returns:
        The layers, the floor's first.
    """
    hs = np.concatenate([[0.0], np.asarray(heights, dtype=np.float64)])
    ny, nx = plan.floor.shape
    near, band, top, lowest = _rasterize_layers(
        np.ascontiguousarray(levelled, dtype=np.float64), hs, plan.x0, plan.y0,
        plan.resolution, nx, ny, FLOOR_TOL, OBSTACLE_Z_RANGE[0], OBSTACLE_Z_RANGE[1],
    )  # fmt: skip
    return Layers(hs, near, band, top, lowest)


def regions_at(
    levelled: np.ndarray, layers: Layers, k: int, plan: FloorPlan, least: float = MIN_TREAD
) -> list[tuple[np.ndarray, tuple[float, float, float, float]]]:
    """The horizontal walk-surface regions at candidate height ``k`` (``layers.heights[k]``).

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        layers: the rasterised cloud.
        k: the candidate's index in ``layers`` (>= 1; 0 is the floor).
        plan: the floor plan (its grid).
        least: the least depth of a region, metres (less two cells for the edges' cells).

    Returns:
        Per region kept: its cells (holes filled) and its plane fit (:func:`fit_plane`).
    """
    res = plan.resolution
    h0 = layers.heights[k]
    unseen = (
        unseen_cells(layers.lowest, h0) if layers.lowest is not None else np.zeros_like(plan.floor)
    )
    surface = (layers.near[k] > 0) & (layers.band[k] < MIN_BAND_POINTS)
    surface = join_sparse(surface, res, unseen)  # a sparse scan's gaps nothing was seen in
    elsewhere = other_surfaces(layers.near, layers.band, k)  # no bay's ring: other levels
    bays = None if (low := layers.lowest) is None else unseen_regions(low, h0)  # once
    if low is not None:  # wider holes no ray reached, ringed by it and what stands on it
        surface |= enclosed_unseen(surface, low, h0, res, elsewhere, bays)
    lab, n = ndimage.label(surface, np.ones((3, 3), bool))
    if n == 0:
        return []
    pts = levelled[np.abs(levelled[:, 2] - h0) <= FLOOR_TOL]
    ix = np.floor((pts[:, 0] - plan.x0) / res).astype(np.int64)
    iy = np.floor((pts[:, 1] - plan.y0) / res).astype(np.int64)
    ny, nx = surface.shape
    inside = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    pts, ix, iy = pts[inside], ix[inside], iy[inside]
    plab = lab[iy, ix]
    order = np.argsort(plab, kind="stable")
    bounds = np.searchsorted(plab[order], np.arange(n + 2))
    sizes = np.bincount(lab.ravel(), minlength=n + 1)
    least = MIN_TREAD * STAND_WIDTH
    out = []
    for r in range(1, n + 1):
        if sizes[r] * res * res < 0.5 * least:
            continue
        cells = ndimage.binary_fill_holes(lab == r)
        depth, width = rectangle_size(min_rectangle(cells, plan.x0, plan.y0, res))
        if depth < least - 2 * res or width < STAND_WIDTH - 2 * res:
            continue
        p = pts[order[bounds[r] : bounds[r + 1]]]
        if len(p) < 3:
            continue
        fit = _inner_fit(p, cells, plan, fit_plane(p))  # the risers' points at the rim tilt it
        if fit[2] > HORIZONTAL_SLOPE + TRIM_SIGMAS * fit[3]:
            flat = flat_part(p, cells, plan)  # a level with a ramp's strip joined at its edge
            if flat is None or flat[1][2] > HORIZONTAL_SLOPE + TRIM_SIGMAS * flat[1][3]:
                continue  # a sloped region: a ramp's strip at this height
            cells, fit, p = flat
        cells = _inlier_cells(p, fit, plan, cells, unseen)
        if low is not None:  # the inliers' join is a voxel's: the wider holes again
            cells = cells | enclosed_unseen(cells, low, h0, res, elsewhere, bays)
        depth, width = rectangle_size(min_rectangle(cells, plan.x0, plan.y0, res))
        if depth < least - 2 * res or width < STAND_WIDTH - 2 * res:
            continue
        out.append((cells, fit))
    return out


def _inner_fit(p: np.ndarray, cells: np.ndarray, plan: FloorPlan, fit: tuple) -> tuple:
    """The plane fit of a region's points less those in its rim cells (where the risers'
    points within ``FLOOR_TOL`` of its height lie), or ``fit`` when fewer than three are left."""
    res = plan.resolution
    inner = ndimage.binary_erosion(cells, np.ones((3, 3), bool))
    ix = np.floor((p[:, 0] - plan.x0) / res).astype(np.int64)
    iy = np.floor((p[:, 1] - plan.y0) / res).astype(np.int64)
    q = p[inner[iy, ix]]
    return fit_plane(q) if len(q) >= 3 else fit


def _inlier_cells(
    p: np.ndarray,
    fit: tuple[float, float, float, float],
    plan: FloorPlan,
    cells: np.ndarray,
    unseen: np.ndarray,
) -> np.ndarray:
    """The region's cells holding a point within :data:`TRIM_SIGMAS` rms of its horizontal
    plane, joined over the ``unseen`` cells between them (:func:`~mjwalk.scan.sparsecells.
    join_sparse`): their largest connected part, holes filled (a ramp's strip joined at the
    region's edge within ``FLOOR_TOL`` falls away)."""
    h, rms = fit[0], fit[1]
    q = p[np.abs(p[:, 2] - h) <= max(TRIM_SIGMAS * rms, 1e-3)]
    res = plan.resolution
    ix = np.floor((q[:, 0] - plan.x0) / res).astype(np.int64)
    iy = np.floor((q[:, 1] - plan.y0) / res).astype(np.int64)
    hit = np.zeros_like(cells)
    hit[iy, ix] = True
    hit &= cells
    box = ndimage.find_objects(cells.astype(np.int8))
    if not box or box[0] is None:
        return hit
    pad = math.ceil(VOXEL / res)  # the region's bounding box and a voxel: all the join needs
    sub = tuple(slice(max(0, b.start - pad), b.stop + pad) for b in box[0])
    part = join_sparse(hit[sub], res, unseen[sub] & cells[sub])
    lab, n = ndimage.label(part, np.ones((3, 3), bool))
    out = np.zeros_like(cells)
    if n == 0:
        return out
    big = int(np.argmax(np.bincount(lab.ravel())[1:])) + 1
    out[sub] = ndimage.binary_fill_holes(lab == big)
    return out


def _add_regions(found: list[ScanLevel], levelled, layers: Layers, plan: FloorPlan, ks, avoid=0):
    """Append the regions at heights ``ks`` to ``found``; with ``avoid``, none sharing a cell
    with one of ``found[1:avoid]`` less than :data:`PEAK_SEPARATION` from its height (that
    surface again) or more than its rim cells with any (surfaces at other heights share at
    most the cells a riser's line crosses)."""
    for k in ks:
        for cells, (h, rms, slope, _) in regions_at(levelled, layers, k, plan, SHADOWED_DEPTH):
            inner = ndimage.binary_erosion(cells, np.ones((3, 3), bool))
            if any(
                (r.cells & (cells if abs(r.height - h) < PEAK_SEPARATION else inner)).any()
                for r in found[1:avoid]
            ):
                continue
            found.append(_region(cells, (h, rms, slope), k, plan))


def _region(cells: np.ndarray, fit: tuple, k: int, plan: FloorPlan) -> ScanLevel:
    """The region of ``cells`` with its plane ``fit`` (height, rms, slope) at candidate ``k``."""
    res = plan.resolution
    depth, width = rectangle_size(min_rectangle(cells, plan.x0, plan.y0, res))
    kind = "tread" if depth <= MAX_TREAD + res else "platform"
    area = float(cells.sum()) * res * res
    h, rms, slope = fit[:3]
    return ScanLevel(0, kind, h, rms, math.atan(slope), cells, area, depth, width, k)


def _at_own_height(
    found: list[ScanLevel], levelled: np.ndarray, layers: Layers, plan: FloorPlan
) -> Layers:
    """Find again, at its own height, each region of ``found`` (in place) more than
    :data:`OWN_HEIGHT_TOL` from its candidate's; the region there sharing most cells with it
    replaces it when at least as large. Returns the layers with those heights added."""
    off = [
        i for i in range(1, len(found))
        if abs(found[i].height - layers.heights[found[i].peak]) > OWN_HEIGHT_TOL
    ]  # fmt: skip
    if not off:
        return layers
    own = np.array([found[i].height for i in off])
    layers = rasterize_layers(levelled, np.concatenate([layers.heights[1:], own]), plan)
    k0 = len(layers.heights) - len(off)
    for n, i in enumerate(off):
        best, shared = None, 0
        for cells, fit in regions_at(levelled, layers, k0 + n, plan, SHADOWED_DEPTH):
            if (c := int((cells & found[i].cells).sum())) > shared:
                best, shared = (cells, fit), c
        if best is not None and best[0].sum() >= found[i].cells.sum():
            found[i] = _region(best[0], best[1], k0 + n, plan)
    return layers


def _unexplained(
    up: np.ndarray, found: list[ScanLevel], plan: FloorPlan, looked: np.ndarray
) -> np.ndarray:
    """Heights of the upward voxels no region explains (a tread 2 cm over a platform elsewhere
    has no peak of its own); none within :data:`HIST_BIN` of one looked at already."""
    if len(up) == 0:
        return np.zeros(0)
    res = plan.resolution
    ny, nx = plan.floor.shape
    ix = np.clip(np.floor((up[:, 0] - plan.x0) / res).astype(np.int64), 0, nx - 1)
    iy = np.clip(np.floor((up[:, 1] - plan.y0) / res).astype(np.int64), 0, ny - 1)
    left = np.ones(len(up), bool)
    for r in found[1:]:
        left &= ~(r.cells[iy, ix] & (np.abs(up[:, 2] - r.height) <= FLOOR_TOL))
    peaks = peak_heights(up[left, 2], (PEAK_SEPARATION, MAX_SURFACE_HEIGHT))
    new = [h for h in peaks if np.min(np.abs(np.asarray(looked) - h)) > HIST_BIN]
    return np.array(new)


def _distinct(found: list[ScanLevel], layers: Layers, res: float) -> list[ScanLevel]:
    """The regions less any less than :data:`PEAK_SEPARATION` from a larger one's height that
    shares half its cells (one surface found at two candidate heights) or touches it along a
    body's width, its unseen strip counted as the steps count it (:func:`~mjwalk.scan.
    regionsteps.with_shadow`): the obstacle band begins ``PEAK_SEPARATION`` above a surface, so
    what the steps would reach from it by a lower riser is part of it, no level of its own and
    no step up (a box beside a mezzanine, its top 3.6 cm above the deck)."""
    keep = [found[0]]
    order = sorted(range(1, len(found)), key=lambda i: -found[i].area)
    kept: list[int] = []
    for i in order:
        a = found[i]
        if not any(
            (a.cells & found[j].cells).sum() >= 0.5 * a.cells.sum()
            or touching(with_shadow(found[j], layers, res), a.cells, res)
            for j in kept
            if abs(a.height - found[j].height) < PEAK_SEPARATION
        ):
            kept.append(i)
    keep += [found[i] for i in sorted(kept)]
    return keep


def find_regions(levelled: np.ndarray, plan: FloorPlan) -> tuple[list[ScanLevel], list, Layers]:
    """Every horizontal walk-surface region of a levelled scan, reachable from the floor or not.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (:func:`mjwalk.scan.obstacles.floor_plan`).

    Returns:
        The regions (the floor first, ``index`` not yet set), the steps between them as
        (lower, upper) index pairs (a riser of at most ``norms.MAX_RISER`` along touching
        edges), and the rasterised layers (the floor's and each candidate height).
    """
    span = (PEAK_SEPARATION, MAX_SURFACE_HEIGHT)
    up = upward_centroids(levelled, span)
    heights = peak_heights(up[:, 2], span)
    layers = rasterize_layers(levelled, heights, plan)
    res = plan.resolution
    a_floor = float(plan.floor.sum()) * res * res
    floor = ScanLevel(0, "floor", 0.0, 0.0, 0.0, plan.floor, a_floor, 0.0, 0.0, -1)
    found = [floor]
    _add_regions(found, levelled, layers, plan, range(1, len(layers.heights)))
    for _ in range(MORE_ROUNDS):  # surfaces a stronger peak near their height hid
        extra = _unexplained(up, found, plan, layers.heights)
        if not extra.size:
            break
        heights = np.concatenate([heights, extra])
        layers = rasterize_layers(levelled, heights, plan)
        k0 = len(layers.heights) - len(extra)
        _add_regions(found, levelled, layers, plan, range(k0, len(layers.heights)), len(found))
    layers = _at_own_height(found, levelled, layers, plan)
    found = _distinct(found, layers, res)
    return found, region_steps(found, layers, res), layers


def seen_in_part(level: ScanLevel, res: float) -> bool:
    """Whether a region is shallower than a tread: a tread seen in part (at least
    :data:`SHADOWED_DEPTH`), a level only in a regular flight.

    Args:
        level: the region.
        res: the grid's cell edge, metres.

    Returns:
        True for a tread less than ``norms.MIN_TREAD`` deep, less two cells.
    """
    return level.kind == "tread" and level.depth < MIN_TREAD - 2 * res


def keep_reachable(
    found: list[ScanLevel],
    steps: list[tuple[int, int]],
    ramps: Sequence[tuple[int, int]] = (),
) -> tuple[list[ScanLevel], list[tuple[int, int]], dict[int, int]]:
    """The regions reachable from the floor (``found[0]``) by steps or ramps, as levels.

    Args:
        found: the regions (:func:`find_regions`), the floor first.
        steps: (lower, upper) pairs of regions a step apart.
        ramps: (lower, upper) pairs of regions a ramp joins (:mod:`mjwalk.scan.scanramps`).

    Returns:
        The levels (the floor first, then by height, ``index`` set), the steps between them as
        (lower, upper) level indices, and the map from region index to level index.
    """
    seen, todo = {0}, [0]
    joins = [*steps, *ramps]
    while todo:
        cur = todo.pop()
        for i, j in joins:
            for x, y in ((i, j), (j, i)):
                if x == cur and y not in seen:
                    seen.add(y)
                    todo.append(y)
    keep = [0, *sorted((i for i in seen if i), key=lambda i: (found[i].height, i))]
    new = {old: n for n, old in enumerate(keep)}
    levels = [_reindex(found[old], n) for n, old in enumerate(keep)]
    pairs = [(new[i], new[j]) for i, j in steps if i in new and j in new]
    return levels, sorted(pairs), new


def find_levels(levelled: np.ndarray, plan: FloorPlan) -> tuple[list[ScanLevel], list, Layers]:
    """The walk-surface levels of a levelled scan reachable from its floor by steps.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (:func:`mjwalk.scan.obstacles.floor_plan`).

    Returns:
        The levels (the floor first, then by height; only the floor when the scan is flat), the
        steps between them as (lower, upper) index pairs, and the rasterised layers (the
        floor's and each level's candidate height).
    """
    found, steps, layers = find_regions(levelled, plan)
    levels, pairs, _ = keep_reachable(found, steps)
    return levels, pairs, layers


def _reindex(level: ScanLevel, index: int) -> ScanLevel:
    return ScanLevel(
        index, level.kind, level.height, level.rms, level.slope, level.cells, level.area,
        level.depth, level.width, level.peak,
    )  # fmt: skip
