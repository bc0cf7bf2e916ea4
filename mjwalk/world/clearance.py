"""The 2-D clearance field: metres from a floor point to the nearest obstacle footprint."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk._args import finite_points
from mjwalk.world.footprint import Footprint


@dataclass
class ClearanceField:
    """Distance field sampled on a regular grid over the floor (world x, y in metres).

    ``values[iy, ix]`` is the clearance at ``(x0 + ix * resolution, y0 + iy * resolution)``:
    the distance to the nearest obstacle footprint, negative inside one. Lookups between grid
    nodes are bilinear; points beyond the grid take the value of the nearest border node.
    """

    x0: float
    y0: float
    resolution: float
    values: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        return self.values.shape  # (ny, nx)

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) covered by the grid nodes, metres."""
        ny, nx = self.values.shape
        return (
            self.x0,
            self.y0,
            self.x0 + (nx - 1) * self.resolution,
            self.y0 + (ny - 1) * self.resolution,
        )

    def grid_xy(self) -> tuple[np.ndarray, np.ndarray]:
        """The node coordinates: x (nx,) and y (ny,), metres."""
        ny, nx = self.values.shape
        return (
            self.x0 + self.resolution * np.arange(nx),
            self.y0 + self.resolution * np.arange(ny),
        )

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        """Bilinear clearance at points ``xy`` (..., 2), metres. Vectorized over any shape.

        NaN or infinite coordinates raise :class:`~mjwalk.errors.InputError`."""
        xy = finite_points(xy, "clearance lookup")
        ny, nx = self.values.shape
        fx = np.clip((xy[..., 0] - self.x0) / self.resolution, 0.0, nx - 1.000001)
        fy = np.clip((xy[..., 1] - self.y0) / self.resolution, 0.0, ny - 1.000001)
        ix = fx.astype(np.intp)
        iy = fy.astype(np.intp)
        tx = fx - ix
        ty = fy - iy
        v = self.values
        v00 = v[iy, ix]
        v01 = v[iy, ix + 1]
        v10 = v[iy + 1, ix]
        v11 = v[iy + 1, ix + 1]
        return (v00 * (1 - tx) + v01 * tx) * (1 - ty) + (v10 * (1 - tx) + v11 * tx) * ty

    lookup = __call__

    def _coefficients(self) -> np.ndarray:
        """Per cell (row-major over the (ny-1, nx-1) cells) the bilinear form's coefficients
        (a, b, c, d): value = a + b·tx + c·ty + d·tx·ty at cell fractions tx, ty in [0, 1), for the
        planner's compiled lookup (:func:`mjwalk.plan.stepcheck._clearance`)."""
        coef = getattr(self, "_coef", None)
        if coef is None or self._coef_of is not self.values:
            v = self.values
            v00, v01, v10, v11 = v[:-1, :-1], v[:-1, 1:], v[1:, :-1], v[1:, 1:]
            coef = np.stack([v00, v01 - v00, v10 - v00, v11 - v10 - v01 + v00], axis=-1)
            coef = np.ascontiguousarray(coef.reshape(-1, 4))
            self._coef, self._coef_of = coef, self.values
        return coef


def build_clearance(
    footprints: Sequence[Footprint],
    bounds: tuple[float, float, float, float],
    resolution: float = 0.02,
    *,
    far: float = 100.0,
) -> ClearanceField:
    """Sample the clearance to ``footprints`` over ``bounds`` = (xmin, ymin, xmax, ymax).

    Exact signed distances (to within the footprints' tessellation) at every node; ``far`` is
    the value where there is no obstacle at all. Each footprint is evaluated only where it can
    still lower the running minimum (a cheap bounding-circle test), which keeps the build fast
    for scenes with many small geoms.
    """
    xmin, ymin, xmax, ymax = bounds
    nx = int(np.floor((xmax - xmin) / resolution + 1e-9)) + 1
    ny = int(np.floor((ymax - ymin) / resolution + 1e-9)) + 1
    xs = xmin + resolution * np.arange(nx)
    ys = ymin + resolution * np.arange(ny)
    gx, gy = np.meshgrid(xs, ys)
    pts = np.stack([gx.ravel(), gy.ravel()], axis=1)
    best = np.full(len(pts), far)
    # Large footprints first, so the bounding-circle test prunes the small ones.
    order = sorted(footprints, key=lambda f: -np.ptp(f.vertices, axis=0).sum() - f.radius)
    for fp in order:
        centre = fp.vertices.mean(axis=0)
        reach = np.linalg.norm(fp.vertices - centre, axis=1).max() + fp.radius
        lower = np.linalg.norm(pts - centre, axis=1) - reach
        idx = np.flatnonzero(lower < best)
        for chunk in np.array_split(idx, max(1, len(idx) // 20000)):
            if len(chunk):
                best[chunk] = np.minimum(best[chunk], fp.signed_distance(pts[chunk]))
    return ClearanceField(xmin, ymin, resolution, best.reshape(ny, nx))
