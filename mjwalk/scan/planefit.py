"""Plane fits of a scan's walk-surface regions (issue 47): a trimmed least-squares plane, and
the flat part of a region that a ramp's strip joins at its edge.

A candidate height's region (:func:`mjwalk.scan.scanlevels.regions_at`) holds every cell with a
point within ``FLOOR_TOL`` (3 cm) of that height. A ramp that runs up to a level crosses that
band over ``2 FLOOR_TOL / tan(slope)`` of its run (0.4 m at 8.5 deg), and its strip joins the
level's region at its edge: enough to tilt the level's plane past ``norms.HORIZONTAL_SLOPE``.
:func:`flat_part` keeps the cells whose points lie at the height most of the region's points
lie at (as :mod:`mjwalk.scan.scanpits` does for a pit's bottom a ramp runs down to). Metres,
scene frame (floor at z = 0).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from mjwalk.scan.obstacles import FLOOR_TOL, FloorPlan

#: Trim of the plane fits: residuals beyond this many rms are dropped (twice).
TRIM_SIGMAS = 3.0
#: The scan's range noise, metres (5 mm: ``FLOOR_TOL`` is six of it); a flat surface's points
#: lie within three of it from its height (:func:`flat_cells`).
RANGE_NOISE = FLOOR_TOL / 6
#: How far a riser measured between two fitted regions may lie from the true one, metres: one
#: :data:`RANGE_NOISE`. A region's height is a trimmed least-squares plane through tens to
#: thousands of points, its standard error a fraction of one point's noise; a riser, the
#: difference of two such heights, carries both and the levelling's residual tilt between them,
#: within one point's noise (a generated pit's 0.19 m riser measured 0.1901 m). A measured riser
#: is tested against a norm's limits (``norms.MIN_RISER``-``MAX_RISER``, DIN 18065) widened by
#: this much, and by nothing more: the norm is not widened (a 0.25 m riser is refused).
RISER_TOL = RANGE_NOISE
#: Least share of a cell's points at a surface's height for the cell to be the surface's, not a
#: ramp's strip at that height (:func:`flat_cells`).
FLAT_SHARE = 0.8


def fit_plane(xyz: np.ndarray) -> tuple[float, float, float, float]:
    """A least-squares plane z = h + a (x - cx) + b (y - cy) through points, trimmed at
    :data:`TRIM_SIGMAS` robust sigmas (1.4826 median absolute residuals: a riser's points near
    the nosing are a minority and do not widen the cut).

    Args:
        xyz: (M, 3) points, metres, M >= 3.

    Returns:
        (h: the height at the points' centroid, rms: of the kept points' residuals, slope: the
        plane's tan inclination, slope_err: its standard error); metres and rise over run.
    """
    _, h, grad, rms, err = plane_fit(xyz)
    return h, rms, float(math.hypot(*grad)), err


def plane_fit(xyz: np.ndarray) -> tuple[np.ndarray, float, np.ndarray, float, float]:
    """The trimmed plane fit of :func:`fit_plane` with its gradient.

    Args:
        xyz: (M, 3) points, metres, M >= 3.

    Returns:
        (centre: (2,) the kept points' xy centroid, h: the height there, grad: (2,) dz/dx and
        dz/dy, rms: of the kept residuals, slope_err: the gradient's standard error); metres.
    """
    keep = np.ones(len(xyz), bool)
    for _ in range(4):
        p = xyz[keep]
        c = p[:, :2].mean(axis=0)
        a = np.column_stack([np.ones(len(p)), p[:, 0] - c[0], p[:, 1] - c[1]])
        coef, *_ = np.linalg.lstsq(a, p[:, 2], rcond=None)
        res = p[:, 2] - a @ coef
        rms = float(np.sqrt(np.mean(res**2)))
        full = xyz[:, 2] - (coef[0] + coef[1] * (xyz[:, 0] - c[0]) + coef[2] * (xyz[:, 1] - c[1]))
        sigma = 1.4826 * float(np.median(np.abs(full - np.median(full))))
        new = np.abs(full) <= max(TRIM_SIGMAS * sigma, 1e-4)
        if new.sum() < 3 or (new == keep).all():
            break
        keep = new
    cov = rms**2 * np.linalg.pinv(a.T @ a)
    err = float(np.sqrt(max(cov[1, 1] + cov[2, 2], 0.0)))
    return c, float(coef[0]), np.array([coef[1], coef[2]]), rms, err


def flat_cells(p: np.ndarray, plan: FloorPlan, ref: float | None = None) -> np.ndarray:
    """The cells where a surface's points lie flat: at least :data:`FLAT_SHARE` of each cell's
    points within 3 :data:`RANGE_NOISE` of the height most of them lie at (5 mm bins).

    Args:
        p: (M, 3) points near one height, metres, M >= 1.
        plan: the floor plan (its grid).
        ref: the height the bins are counted from, metres (None: the points' median).

    Returns:
        (ny, nx) bool on the plan's grid.
    """
    h0 = float(np.median(p[:, 2])) if ref is None else ref
    bins = np.round((p[:, 2] - h0) / RANGE_NOISE).astype(np.int64)
    vals, counts = np.unique(bins, return_counts=True)
    mode = h0 + float(vals[np.argmax(counts)]) * RANGE_NOISE
    ny, nx = plan.floor.shape
    ix = np.floor((p[:, 0] - plan.x0) / plan.resolution).astype(np.int64)
    iy = np.floor((p[:, 1] - plan.y0) / plan.resolution).astype(np.int64)
    ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    total, at = np.zeros((ny, nx)), np.zeros((ny, nx))
    np.add.at(total, (iy[ok], ix[ok]), 1.0)
    np.add.at(at, (iy[ok], ix[ok]), (np.abs(p[ok, 2] - mode) <= 3 * RANGE_NOISE).astype(float))
    return (total > 0) & (at >= FLAT_SHARE * total)


def flat_part(
    p: np.ndarray, cells: np.ndarray, plan: FloorPlan
) -> tuple[np.ndarray, tuple[float, float, float, float], np.ndarray] | None:
    """A region's flat part: its cells of :func:`flat_cells`, closed over the gaps between a
    sparse scan's points (a cell either side) and kept in their largest connected part, holes
    filled; refitted (:func:`fit_plane`).

    Args:
        p: (M, 3) the region's points, metres.
        cells: (ny, nx) bool, the region's cells.
        plan: the floor plan (its grid).

    Returns:
        (cells, fit, points) of the flat part, or None when fewer than three points are left.
    """
    if len(p) < 3:
        return None
    flat = flat_cells(p, plan)
    flat = (flat | ndimage.binary_closing(flat, np.ones((3, 3), bool))) & cells
    lab, n = ndimage.label(flat, np.ones((3, 3), bool))
    if n == 0:
        return None
    part = ndimage.binary_fill_holes(lab == int(np.argmax(np.bincount(lab.ravel())[1:])) + 1)
    res = plan.resolution
    ix = np.floor((p[:, 0] - plan.x0) / res).astype(np.int64)
    iy = np.floor((p[:, 1] - plan.y0) / res).astype(np.int64)
    q = p[part[iy, ix]]
    if len(q) < 3:
        return None
    return part, fit_plane(q), q
