"""Ramps of a levelled scan: sloped walk surfaces that join two levels (issue 47).

The seed paper's walk-surface points have normals within 20° of up (§3 A2,
``mjwalk.scan.level.HORIZONTAL_DEG``); a ramp is such a surface that is no level: its points
lie on a plane inclined more than ``norms.HORIZONTAL_SLOPE`` and at most
``norms.MAX_RAMP_SLOPE`` (10°, ISO 14122). Found so:

1. The points above the floor that no level explains (farther than ``FLOOR_TOL`` from the floor
   and from each region's height within its cells) give local-PCA normals on 0.1 m voxels
   (:func:`mjwalk.scan.level.voxel_normals`); the upward-facing planar ones are grouped by 3-D
   adjacency (26 neighbours: a 10° ramp rises 18 mm over a voxel).
2. Each group's points get a trimmed plane fit (:func:`mjwalk.scan.planefit.plane_fit`); it
   is a ramp candidate when the plane's inclination lies in that range and its rms is that of a
   plane scanned (:data:`RAMP_RMS`). Its cells are those holding its points (closed over gaps
   up to a voxel: a far ramp's points are sparser than the grid) with nothing higher than
   ``EXPOSED_MIN`` above the plane (the obstacle band's foot), largest part.
3. **Ends.** The plane runs down to the level whose height it reaches below the cells' low end
   and up to the one above their high end (within the band the first step left out plus a cell
   of climb), each of which must lie there along a body's width
   (``mjwalk.world.contacts.MIN_CROSSING``). The ramp is then the plane's strip between the
   lines where it meets those two heights, as wide as its cells, along the axis of the raised
   level nearest the plane's climb (so the level's edge and the ramp's end meet along their
   width); its slope is the rise over that run, at most ``norms.MAX_RAMP_SLOPE`` within the
   scan's noise, and a ramp measured a hair over is written at the limit (:func:`within_limit`).

:func:`ramp_box` writes one as a tilted box whose top face is the ramp, so that
``mjwalk.world.find_walk_surfaces`` reads it as a ramp and ``level_graph`` links its two levels.
Metres, scene frame (floor at z = 0), radians.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import HORIZONTAL_DEG, MAX_SURFACE_HEIGHT, VOXEL, voxel_normals
from mjwalk.scan.obstacles import FLOOR_TOL, MIN_BAND_POINTS, FloorPlan
from mjwalk.scan.planefit import TRIM_SIGMAS, plane_fit
from mjwalk.scan.scanlevels import PLANAR_SHARE, ScanLevel, min_rectangle
from mjwalk.scan.stairfit import WRITE_MARGIN
from mjwalk.world.contacts import MIN_CROSSING
from mjwalk.world.floor import OBSTACLE_Z_RANGE
from mjwalk.world.norms import (
    CONTACT_GAP,
    EXPOSED_MIN,
    HORIZONTAL_SLOPE,
    LEVEL_TOLERANCE,
    MAX_RAMP_SLOPE,
    MIN_TREAD,
    STAND_WIDTH,
)

#: Largest rms of a ramp's plane fit, metres: twice the scan's range noise (5 mm, the sigma
#: ``FLOOR_TOL`` is six of); a curved top (a capsule, an ellipsoid) fits worse.
RAMP_RMS = FLOOR_TOL / 3
#: Material of the ramp boxes.
RAMP_MATERIAL = "scan_ramp"


@dataclass(frozen=True)
class ScanRamp:
    """A ramp of a scan between two levels.

    Attributes:
        lower, upper: indices of the levels its low and high ends meet (in the list given to
            :func:`find_ramps`; :func:`renumber` maps them).
        run: (2,) unit vector, the horizontal direction it climbs.
        s_lo, s_hi: where its low and high ends lie along ``run``, metres.
        w_lo, w_hi: its sides along ``run`` turned 90° CCW, metres.
        h_lo, h_hi: the heights of its ends (the two levels'), metres.
        rms: rms of its points from the fitted plane, metres.
        fit_slope: the fitted plane's inclination, radians.
    """

    lower: int
    upper: int
    run: np.ndarray
    s_lo: float
    s_hi: float
    w_lo: float
    w_hi: float
    h_lo: float
    h_hi: float
    rms: float
    fit_slope: float

    @property
    def slope(self) -> float:
        """Inclination from end to end, radians."""
        return math.atan2(self.h_hi - self.h_lo, self.s_hi - self.s_lo)

    @property
    def length(self) -> float:
        """Horizontal run from end to end, metres."""
        return self.s_hi - self.s_lo

    @property
    def width(self) -> float:
        """Width across, metres."""
        return self.w_hi - self.w_lo

    @property
    def rect(self) -> np.ndarray:
        """Its outline (4, 2) counter-clockwise, the low end first, metres."""
        side = np.array([-self.run[1], self.run[0]])
        uv = [(self.s_lo, self.w_lo), (self.s_hi, self.w_lo), (self.s_hi, self.w_hi),
              (self.s_lo, self.w_hi)]  # fmt: skip
        return np.array([u * self.run + v * side for u, v in uv])


def renumber(ramp: ScanRamp, new: dict[int, int]) -> ScanRamp:
    """The ramp with its levels' indices mapped.

    Args:
        ramp: the ramp.
        new: old level index -> new.

    Returns:
        A copy with ``lower`` and ``upper`` renumbered.
    """
    return dataclasses.replace(ramp, lower=new[ramp.lower], upper=new[ramp.upper])


def _cell_index(pts: np.ndarray, plan: FloorPlan) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(iy, ix, inside) of points on the plan's grid."""
    ix = np.floor((pts[:, 0] - plan.x0) / plan.resolution).astype(np.int64)
    iy = np.floor((pts[:, 1] - plan.y0) / plan.resolution).astype(np.int64)
    ny, nx = plan.floor.shape
    inside = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    return np.clip(iy, 0, ny - 1), np.clip(ix, 0, nx - 1), inside


def unexplained(
    levelled: np.ndarray, plan: FloorPlan, regions: Sequence[ScanLevel], below: bool = False
) -> np.ndarray:
    """The points above the floor that lie on no region (see the module docstring, step 1).

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: the floor plan (its grid).
        regions: the horizontal regions, the floor first.
        below: look below the floor instead (a ramp down into a pit, :mod:`.scanpits`).

    Returns:
        (M, 3) points between ``FLOOR_TOL`` and ``MAX_SURFACE_HEIGHT`` (below: between
        ``-MAX_SURFACE_HEIGHT`` and ``-FLOOR_TOL``) farther than ``FLOOR_TOL`` from every
        region's height within its cells.
    """
    z = -levelled[:, 2] if below else levelled[:, 2]
    pts = levelled[(z > FLOOR_TOL) & (z <= MAX_SURFACE_HEIGHT)]
    iy, ix, inside = _cell_index(pts, plan)
    keep = inside.copy()
    for r in regions[1:]:
        keep &= ~(r.cells[iy, ix] & (np.abs(pts[:, 2] - r.height) <= FLOOR_TOL))
    return pts[keep]


def _groups(pts: np.ndarray) -> list[np.ndarray]:
    """Point masks of the 3-D connected groups of upward-facing planar voxels."""
    if len(pts) < 10:
        return []
    vn = voxel_normals(pts, VOXEL)
    up = (vn.normal[:, 2] >= math.cos(math.radians(HORIZONTAL_DEG))) & (
        vn.eigval[:, 1] >= PLANAR_SHARE * vn.eigval[:, 2]
    )
    if not up.any():
        return []
    ijk = vn.ijk[up]
    grid = np.zeros(tuple(ijk.max(axis=0) + 1), bool)
    grid[tuple(ijk.T)] = True
    lab, n = ndimage.label(grid, np.ones((3, 3, 3), bool))
    origin = pts.min(axis=0)
    pijk = np.floor((pts - origin) / VOXEL).astype(np.int64)
    ok = (pijk < np.array(grid.shape)).all(axis=1)
    plab = np.zeros(len(pts), np.int64)
    plab[ok] = lab[tuple(pijk[ok].T)]
    least = 0.5 * MIN_TREAD * STAND_WIDTH
    out = []
    for k in range(1, n + 1):
        vox = ijk[lab[tuple(ijk.T)] == k]
        if len({(int(a), int(b)) for a, b, _ in vox}) * VOXEL**2 >= least:
            out.append(plab == k)
    return out


def _ramp_cells(
    levelled: np.ndarray, pts: np.ndarray, fit: tuple, plan: FloorPlan, seed: np.ndarray
) -> np.ndarray:
    """The cells of a ramp plane (step 2 of the module docstring): holding unexplained points
    within ``TRIM_SIGMAS`` rms of it (closed over gaps up to a voxel: far from the scanners a
    ramp's points are sparser than the grid, and the group joined them at the voxel's scale),
    fewer than ``MIN_BAND_POINTS`` in the band above it; the largest part that meets the
    group's points ``seed``."""
    c, h, grad, rms, _ = fit

    def above(p: np.ndarray) -> np.ndarray:
        return p[:, 2] - (h + (p[:, :2] - c) @ grad)

    ny, nx = plan.floor.shape
    near = np.zeros((ny, nx), np.int64)
    iy, ix, inside = _cell_index(pts, plan)
    sel = inside & (np.abs(above(pts)) <= max(TRIM_SIGMAS * rms, 1e-3))
    np.add.at(near, (iy[sel], ix[sel]), 1)
    band = np.zeros((ny, nx), np.int64)
    d = above(levelled)
    iy, ix, inside = _cell_index(levelled, plan)
    sel = inside & (d > EXPOSED_MIN) & (d <= OBSTACLE_Z_RANGE[1])
    np.add.at(band, (iy[sel], ix[sel]), 1)
    k = max(1, round(VOXEL / plan.resolution))  # the scale the group's voxels joined at
    hit = (near > 0) | ndimage.binary_closing(near > 0, np.ones((k, k), bool))
    cells = hit & (band < MIN_BAND_POINTS)
    lab, n = ndimage.label(cells, np.ones((3, 3), bool))
    if n == 0:
        return cells
    iy, ix, inside = _cell_index(seed, plan)
    hits = np.bincount(lab[iy[inside], ix[inside]], minlength=n + 1)
    hits[0] = 0
    if hits.max() == 0:
        return np.zeros_like(cells)
    return ndimage.binary_fill_holes(lab == int(np.argmax(hits)))


def _end(
    regions: Sequence[ScanLevel], frame: tuple, z_end: float, s_end: float, up: bool, plan
) -> tuple[int, float, float] | None:
    """The region a ramp's plane meets beyond one end of its cells (step 3): (index, height,
    place along the run where the plane reaches it), or None. The region's cells must lie past
    that place, where a walker steps off the ramp: a ramp's toe within ``FLOOR_TOL`` of the
    floor is floor to the scan, and over no floor beyond it linked a ramp that ends in the air
    (the written scene's floor stopped at the toe: no link there)."""
    grad, run, side, w0, w1 = frame
    g = float(grad @ run)
    res = plan.resolution
    reach = FLOOR_TOL + TRIM_SIGMAS * RAMP_RMS + 2 * res * g  # the band left out, a cell's climb
    best: tuple[int, float, float] | None = None
    for k, r in enumerate(regions):
        dz = (r.height - z_end) if up else (z_end - r.height)
        if not -FLOOR_TOL <= dz <= reach:
            continue
        s_at = s_end + (dz if up else -dz) / g
        iy, ix = np.nonzero(r.cells)
        q = np.column_stack([plan.x0 + (ix + 0.5) * res, plan.y0 + (iy + 0.5) * res])
        s, w = q @ run, q @ side
        d = CONTACT_GAP + 2 * res + TRIM_SIGMAS * RAMP_RMS / g
        beyond = (s - s_at) if up else (s_at - s)  # past the end, off the ramp
        there = (beyond >= 0.5 * res) & (beyond <= d) & (w >= w0) & (w <= w1)
        if len(np.unique(np.round(w[there] / res))) * res < MIN_CROSSING:
            continue
        if best is None or (r.height < best[1] if up else r.height > best[1]):
            best = (k, r.height, s_at)
    return best


def _axis_near(cells: np.ndarray, plan: FloorPlan, run: np.ndarray) -> np.ndarray:
    """The axis of a region's minimum-area rectangle nearest ``run``, signed like it."""
    rect = min_rectangle(cells, plan.x0, plan.y0, plan.resolution)
    axes = [rect[1] - rect[0], rect[3] - rect[0]]
    axes = [a / np.hypot(*a) for a in axes]
    a = max(axes, key=lambda v: abs(float(v @ run)))
    return a if a @ run > 0 else -a


def _ends(
    cells: np.ndarray, fit: tuple, run: np.ndarray, regions: Sequence[ScanLevel], plan: FloorPlan
) -> tuple[tuple[int, float, float], tuple[int, float, float], float, float] | None:
    """The regions a plane's cells meet at both ends along ``run`` (step 3), and the cells'
    sides (w_lo, w_hi) across it; None when an end meets none or the cells are too narrow."""
    c, h, grad, _, _ = fit
    res = plan.resolution
    side = np.array([-run[1], run[0]])
    iy, ix = np.nonzero(cells)
    q = np.column_stack([plan.x0 + (ix + 0.5) * res, plan.y0 + (iy + 0.5) * res])
    s, w = q @ run, q @ side
    w0, w1 = float(w.min()), float(w.max())
    if float(grad @ run) <= 0 or w1 - w0 < STAND_WIDTH - 2 * res:
        return None
    frame = (grad, run, side, w0, w1)
    z = [float(h + (sv * run + 0.5 * (w0 + w1) * side - c) @ grad) for sv in (s.min(), s.max())]
    lo = _end(regions, frame, z[0], float(s.min()), False, plan)
    hi = _end(regions, frame, z[1], float(s.max()), True, plan)
    if lo is None or hi is None or lo[0] == hi[0] or hi[1] - lo[1] <= LEVEL_TOLERANCE:
        return None
    return lo, hi, w0, w1


def _ramp_from(
    cells: np.ndarray, fit: tuple, regions: Sequence[ScanLevel], plan: FloorPlan
) -> ScanRamp | None:
    """A ramp from a plane's cells and fit, when both its ends meet regions (step 3): along
    the plane's climb, then along the raised level's axis nearest it."""
    grad, rms = fit[2], fit[3]
    run = grad / float(np.hypot(*grad))
    ends = _ends(cells, fit, run, regions, plan)
    if ends is None:
        return None
    raised = ends[1][0] if ends[1][0] != 0 else ends[0][0]
    if raised:
        axis = _axis_near(regions[raised].cells, plan, run)
        if float(axis @ run) < 1 - 1e-9:
            run, ends = axis, _ends(cells, fit, axis, regions, plan)
            if ends is None:
                return None
    (lo, h_lo, s_lo), (hi, h_hi, s_hi), w0, w1 = ends
    slope = math.atan(float(np.hypot(*grad)))
    ramp = ScanRamp(lo, hi, run, s_lo, s_hi, w0, w1, h_lo, h_hi, rms, slope)
    if ramp.length < MIN_TREAD or not within_noise(math.tan(ramp.slope), fit[4]):
        return None
    return within_limit(ramp)


def within_noise(slope: float, err: float) -> bool:
    """Whether a measured slope is no steeper than ``norms.MAX_RAMP_SLOPE`` as far as the scan
    can tell: at most ``TRIM_SIGMAS`` of its fit's standard error over it, as a ramp must lie
    that far over ``norms.HORIZONTAL_SLOPE`` (:func:`find_ramps`) and a riser within
    ``planefit.RISER_TOL`` of DIN 18065's range; the limit itself is not widened
    (:func:`within_limit` writes such a ramp at it).

    Args:
        slope: the measured rise over run (tan of the inclination).
        err: its standard error (``planefit.plane_fit``), rise over run.

    Returns:
        True when the slope is a ramp's within the scan's noise.
    """
    return slope <= math.tan(MAX_RAMP_SLOPE) + TRIM_SIGMAS * err


def within_limit(ramp: ScanRamp) -> ScanRamp:
    """A ramp measured over ``norms.MAX_RAMP_SLOPE`` (within the scan's noise,
    :func:`within_noise`), or within ``stairfit.WRITE_MARGIN`` of rise under it, written at the
    limit: its low end moved down the run until its rise is ``WRITE_MARGIN`` under the
    limit's over its run, its levels' heights kept (other links may depend on them). The
    written scene is read with the limit itself (``mjwalk.world.surfaces``: a 10 deg ramp
    the scan fitted at 10.001 deg and wrote so was no walk surface); a flight at DIN 18065's
    riser limit is written so too (:mod:`mjwalk.scan.writtennorm`).

    Args:
        ramp: the ramp as fitted.

    Returns:
        The ramp, or a copy with ``s_lo`` moved (by a few millimetres).
    """
    run = (ramp.h_hi - ramp.h_lo + WRITE_MARGIN) / math.tan(MAX_RAMP_SLOPE)
    return ramp if ramp.length >= run else dataclasses.replace(ramp, s_lo=ramp.s_hi - run)


def find_ramps(
    levelled: np.ndarray, plan: FloorPlan, regions: Sequence[ScanLevel], below: bool = False
) -> list[ScanRamp]:
    """The ramps of a levelled scan between its horizontal regions.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (its grid).
        regions: the horizontal walk-surface regions, the floor first
            (:func:`mjwalk.scan.scanlevels.find_regions`).
        below: look for ramps below the floor (down into pits, :mod:`.scanpits`) instead.

    Returns:
        The ramps (``lower``/``upper`` index ``regions``), none for a scan without any.
    """
    pts = unexplained(levelled, plan, regions, below)
    out: list[ScanRamp] = []
    for mask in _groups(pts):
        p = pts[mask]
        if len(p) < 10:
            continue
        fit = plane_fit(p)
        _, _, grad, rms, err = fit
        slope = float(np.hypot(*grad))
        if rms > RAMP_RMS or slope <= HORIZONTAL_SLOPE + TRIM_SIGMAS * err:
            continue
        if not within_noise(slope, err):
            continue
        cells = _ramp_cells(levelled, pts, fit, plan, p)
        if not cells.any():
            continue
        ramp = _ramp_from(cells, fit, regions, plan)
        if ramp is not None:
            out.append(ramp)
    return out


def ramp_box(ramp: ScanRamp, name: str) -> tuple[str, np.ndarray, np.ndarray, str, np.ndarray]:
    """A ramp as a tilted box: its top face is the ramp, from the lower level's height at the
    low end to the upper's at the high end; it is as thick as the rise over the slope's cosine,
    so under the high end it reaches down to the lower level.

    Args:
        ramp: the ramp.
        name: the geom's name.

    Returns:
        (name, centre (3,), half sizes (3,), material, xyaxes (6,): the box's x axis up the
        slope, its y axis across), metres.
    """
    th = ramp.slope
    rise = ramp.h_hi - ramp.h_lo
    u = ramp.run
    side = np.array([-u[1], u[0]])
    ex = np.array([math.cos(th) * u[0], math.cos(th) * u[1], math.sin(th)])
    ey = np.array([side[0], side[1], 0.0])
    ez = np.cross(ex, ey)
    thick = rise / math.cos(th)
    mid = 0.5 * (ramp.s_lo + ramp.s_hi) * u + 0.5 * (ramp.w_lo + ramp.w_hi) * side
    top = np.array([mid[0], mid[1], 0.5 * (ramp.h_lo + ramp.h_hi)])
    half = np.array([0.5 * ramp.length / math.cos(th), 0.5 * ramp.width, 0.5 * thick])
    return name, top - 0.5 * thick * ez, half, RAMP_MATERIAL, np.concatenate([ex, ey])
