"""One walk surface of a scene -- a floor, platform, tread or ramp top -- and the room above it.

A :class:`WalkSurface` is a plane face a person can stand on: its height (and for a ramp its slope
and uphill direction), its footprint in the world xy plane and the geoms over it
(:class:`Overhead`), from which the free height at any point follows
(:meth:`WalkSurface.free_height`) and whether a walker's head fits there (:func:`head_fits`).
:class:`HeadroomMap` is the free height on a grid over the surface, for planners. Metres,
radians; world z up, yaw from +x CCW.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from mjwalk.errors import InputError
from mjwalk.world.footprint import Footprint
from mjwalk.world.norms import HEAD_MARGIN, OVERHEAD_MIN

#: A segment in the world xy plane: ((x0, y0), (x1, y1)), metres.
Segment = tuple[tuple[float, float], tuple[float, float]]
#: Kinds of walk surface.
SURFACE_KINDS = ("floor", "platform", "ramp", "tread")
#: Finest spacing of a :class:`HeadroomMap`, metres (coarser on large surfaces, see
#: :data:`HEADROOM_NODES`).
HEADROOM_SPACING = 0.05
#: Most nodes of one :class:`HeadroomMap` (a 10 x 10 m floor at 5 cm; larger floors get a coarser
#: grid so a hall's map stays small).
HEADROOM_NODES = 40_000
#: Points within this of a footprint's boundary count as on it (metres).
_ON_EDGE = 1e-6
#: An overhead must reach this far above the surface to stand over it (metres).
_ABOVE = 1e-3


@dataclass(frozen=True)
class Overhead:
    """A geom over a walk surface.

    Attributes:
        name: the geom's name.
        footprint: its footprint in the height band above the surface (world xy, metres).
        bottom: world z of its underside, metres (its bounding box's: exact for level boxes,
            lower than the geom elsewhere, so the free height is never overstated).
        top: world z of its top, metres (its bounding box's).
    """

    name: str
    footprint: Footprint
    bottom: float
    top: float


@dataclass(frozen=True, eq=False)
class HeadroomMap:
    """Free height above a surface on a grid (nodes ``x0 + i * spacing``, ``y0 + j * spacing``).

    Attributes:
        x0, y0: world xy of node (0, 0), metres.
        spacing: node spacing, metres.
        values: (ny, nx) free height above the surface at each node, metres: 0 where a geom
            stands on it, inf where nothing is within ``mjwalk.world.norms.HEADROOM_SCAN``,
            NaN off the surface.
    """

    x0: float
    y0: float
    spacing: float
    values: np.ndarray

    def at(self, xy: np.ndarray) -> np.ndarray:
        """Free height at points (..., 2) from the nearest node, metres (NaN off the grid).

        Args:
            xy: world points (..., 2), metres.

        Returns:
            (...) free heights, metres.
        """
        xy = np.asarray(xy, dtype=float)
        ny, nx = self.values.shape
        i = np.rint((xy[..., 0] - self.x0) / self.spacing).astype(int)
        j = np.rint((xy[..., 1] - self.y0) / self.spacing).astype(int)
        inside = (i >= 0) & (i < nx) & (j >= 0) & (j < ny)
        out = np.full(i.shape, np.nan)
        out[inside] = self.values[j[inside], i[inside]]
        return out

    def clear_area(self, height: float) -> float:
        """Area of the surface with at least ``height`` free above it, square metres.

        Args:
            height: free height asked for, metres.

        Returns:
            Node count at or above ``height`` times the node area, square metres.
        """
        with np.errstate(invalid="ignore"):
            n = int(np.count_nonzero(self.values >= height))
        return n * self.spacing**2


@dataclass(frozen=True, eq=False)
class WalkSurface:
    """A plane face a person can stand on (the top of a geom, or the floor).

    Attributes:
        geom_id: the MuJoCo geom it is the top of.
        name: the geom's name.
        kind: "floor", "platform" (horizontal, deeper than a tread), "tread" (horizontal, no
            deeper than ``mjwalk.world.norms.MAX_TREAD``) or "ramp" (inclined).
        z: height of the face at its centre, world metres.
        footprint: the face projected onto the world xy plane (a convex polygon, CCW).
        area: the footprint's area, square metres.
        centre: world xy of the face's centre, metres.
        slope: the face's inclination, radians (0 for a horizontal face).
        uphill: direction in which the face rises, yaw from +x CCW, radians (0 when horizontal).
        z_low, z_high: heights of the face's low and high ends, metres (both ``z`` if horizontal).
        depth, width: the footprint's least width and its extent across that, metres.
        overhead: the geoms over the face, up to ``mjwalk.world.norms.HEADROOM_SCAN`` above it.
    """

    geom_id: int
    name: str
    kind: str
    z: float
    footprint: Footprint
    area: float
    centre: tuple[float, float]
    slope: float
    uphill: float
    z_low: float
    z_high: float
    depth: float
    width: float
    overhead: tuple[Overhead, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in SURFACE_KINDS:
            raise InputError(
                f"walk surface {self.name!r}: kind {self.kind!r} not in {SURFACE_KINDS}"
            )

    @property
    def is_ramp(self) -> bool:
        """Whether the surface is inclined (a ramp)."""
        return self.kind == "ramp"

    def height_at(self, xy: np.ndarray) -> np.ndarray:
        """Height of the face's plane above points (..., 2), world metres.

        Args:
            xy: world points (..., 2), metres.

        Returns:
            (...) heights, metres.
        """
        xy = np.asarray(xy, dtype=float)
        if self.slope == 0.0:
            return np.full(xy.shape[:-1], self.z)
        u = np.array([math.cos(self.uphill), math.sin(self.uphill)])
        d = (xy - np.asarray(self.centre)) @ u
        return self.z + math.tan(self.slope) * d

    def contains(self, xy: np.ndarray) -> np.ndarray:
        """Whether points (..., 2) lie on the footprint (its boundary included).

        Args:
            xy: world points (..., 2), metres.

        Returns:
            (...) booleans.
        """
        return self.footprint.signed_distance(np.asarray(xy, dtype=float)) <= _ON_EDGE

    def free_height(self, xy: np.ndarray) -> np.ndarray:
        """Free height above the face at points (..., 2): from the face up to the lowest geom
        over the point, metres (0 where a geom stands on or in the face, inf where nothing is
        over it). Points off the footprint are measured as if the face went on.

        Args:
            xy: world points (..., 2), metres.

        Returns:
            (...) free heights, metres, at least 0.
        """
        xy = np.asarray(xy, dtype=float)
        shape = xy.shape[:-1]
        flat = xy.reshape(-1, 2)
        z = self.height_at(xy).reshape(-1)  # as the points came (the same arithmetic)
        out = np.full(len(flat), np.inf)
        if not self.overhead or out.size == 0:
            return out.reshape(shape)
        box, _ = self._overhead_boxes
        for k in self._meeting(flat, z):
            o = self.overhead[k]
            lo, hi = box[k, :2], box[k, 2:]
            near = np.all((flat >= lo) & (flat <= hi), axis=-1) & (o.top > z + _ABOVE)
            if np.any(near):
                self._lower_under(out, flat, z, k, np.flatnonzero(near))
        return out.reshape(shape)

    def _meeting(self, flat: np.ndarray, z: np.ndarray) -> np.ndarray:
        """The overheads that can be over one of the points (n, 2) at heights z (n,): only the
        geoms whose box meets the points' box and whose top clears the lowest point can be near
        one (the test point by point needs both); every geom when a NaN hides the extent."""
        box, top = self._overhead_boxes
        pmin, pmax = flat.min(axis=0), flat.max(axis=0)
        meets = np.all(box[:, 2:] >= pmin, axis=1) & np.all(box[:, :2] <= pmax, axis=1)
        meets &= top > float(np.min(z)) + _ABOVE
        if np.isnan(pmin).any() or np.isnan(pmax).any() or np.isnan(z).any():
            meets[:] = True  # a NaN hides the others' extent: test every geom
        return np.flatnonzero(meets)

    def _lower_under(
        self, out: np.ndarray, flat: np.ndarray, z: np.ndarray, k: int, idx: np.ndarray
    ) -> None:
        """Lower ``out`` to overhead k's free height at the points ``idx`` (ascending) of
        ``flat`` that lie in its box and under its top, where its footprint is over them."""
        o = self.overhead[k]
        at = idx[o.footprint.signed_distance(flat[idx]) < -_ON_EDGE]  # the points under it
        out[at] = np.minimum(out[at], np.maximum(o.bottom - z[at], 0.0))

    def _grid_free_height(
        self, gx: np.ndarray, gy: np.ndarray, xy: np.ndarray, inside: np.ndarray
    ) -> np.ndarray:
        """:meth:`free_height` of ``xy[inside]`` (the nodes of the grid ``gx`` x ``gy``, both
        increasing, on the footprint), bit for bit: a box's points are found as the block of
        nodes in its x and y ranges (a search in gx and gy, not a test of every point), taken
        in the same ascending order, and measured by the same arithmetic."""
        flat = xy[inside]
        box, _ = self._overhead_boxes
        if not self.overhead or not len(flat) or np.isnan(box).any():
            return self.free_height(flat)  # (a NaN box tests no point: the general test)
        z = self.height_at(flat).reshape(-1)
        out = np.full(len(flat), np.inf)
        rank = (np.cumsum(inside.ravel()) - 1).reshape(inside.shape)  # node -> index in flat
        for k in self._meeting(flat, z):
            i0, i1 = np.searchsorted(gx, box[k, 0], "left"), np.searchsorted(gx, box[k, 2], "right")
            j0, j1 = np.searchsorted(gy, box[k, 1], "left"), np.searchsorted(gy, box[k, 3], "right")
            block = rank[j0:j1, i0:i1][inside[j0:j1, i0:i1]]  # row-major: ascending
            idx = block[self.overhead[k].top > z[block] + _ABOVE]
            if len(idx):
                self._lower_under(out, flat, z, k, idx)
        return out

    @functools.cached_property
    def _overhead_boxes(self) -> tuple[np.ndarray, np.ndarray]:
        """The overheads' bounding boxes (k, 4: xmin, ymin, xmax, ymax) and tops (k,), metres."""
        box = np.array([o.footprint.bounds() for o in self.overhead], dtype=float).reshape(-1, 4)
        return box, np.array([o.top for o in self.overhead], dtype=float)

    @functools.cached_property
    def headroom(self) -> HeadroomMap:
        """The free height on a grid over the footprint (:class:`HeadroomMap`; built once)."""
        x0, y0, x1, y1 = self.footprint.bounds()
        spacing = max(HEADROOM_SPACING, math.sqrt((x1 - x0) * (y1 - y0) / HEADROOM_NODES))
        gx = x0 + spacing * (np.arange(int((x1 - x0) / spacing) + 1) + 0.5)
        gy = y0 + spacing * (np.arange(int((y1 - y0) / spacing) + 1) + 0.5)
        xy = np.stack(np.meshgrid(gx, gy), axis=-1)
        values = np.full(xy.shape[:2], np.nan)
        inside = self.footprint.signed_distance(xy) < 0.0
        values[inside] = self._grid_free_height(gx, gy, xy, inside)
        return HeadroomMap(float(gx[0]), float(gy[0]), spacing, values)

    @property
    def lowest_ceiling(self) -> float:
        """Least free height over the surface that some walker passes under, metres: the
        smallest value of :attr:`headroom` of at least ``mjwalk.world.norms.OVERHEAD_MIN``
        (lower ones are obstacles to all); inf when nothing is over the surface."""
        v = self.headroom.values
        with np.errstate(invalid="ignore"):
            ceil = v[v >= OVERHEAD_MIN]
        return float(ceil.min()) if ceil.size else math.inf


def head_fits(
    surface: WalkSurface, xy: np.ndarray, stature: float, margin: float = HEAD_MARGIN
) -> np.ndarray:
    """Whether a walker's head fits above points of a surface: free height at least stature
    plus margin.

    Args:
        surface: the surface the walker stands on.
        xy: world points (..., 2), metres.
        stature: the walker's body height, metres (> 0).
        margin: room added to the stature (shoes, helmet), metres (>= 0); default
            :data:`mjwalk.world.norms.HEAD_MARGIN`.

    Returns:
        (...) booleans.

    Raises:
        InputError: a stature not above 0 or a negative margin.
    """
    if not (math.isfinite(stature) and stature > 0):
        raise InputError(f"stature {stature} m must be a positive number")
    if not (math.isfinite(margin) and margin >= 0):
        raise InputError(f"head margin {margin} m must be >= 0")
    return surface.free_height(xy) >= stature + margin
