"""The 2-D clearance field: metres from a floor point to the nearest obstacle footprint."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from mjwalk._args import finite_points
from mjwalk._jit import njit
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
        """The node coordinates.

        Returns:
            (x (nx,), y (ny,)), metres.
        """
        ny, nx = self.values.shape
        return (
            self.x0 + self.resolution * np.arange(nx),
            self.y0 + self.resolution * np.arange(ny),
        )

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        """Bilinear clearance at points ``xy`` (..., 2), metres. Vectorized over any shape.

        NaN or infinite coordinates raise :class:`~mjwalk.errors.InputError`."""
        xy = finite_points(xy, "clearance lookup")
        v = self.values
        if v.dtype == np.float64 and xy.ndim >= 1 and xy.shape[-1] == 2:
            # compiled, point by point (bilinear_at: the same arithmetic, the same numbers;
            # NumPy's dozen whole-array passes and four gathers cost about 60 us a call)
            flat = np.ascontiguousarray(xy).reshape(-1, 2)
            out = _bilinear_rows(v, float(self.x0), float(self.y0), float(self.resolution), flat)
            return out.reshape(xy.shape[:-1])[()]  # (one point: a scalar, as NumPy's)
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

    @cached_property
    def lipschitz(self) -> float:
        """The Lipschitz constant of the bilinear lookup (:meth:`__call__`), computed once:
        no two points x, y have values further apart than ``lipschitz * |x - y|``.

        Within a cell the lookup's x-derivative is a convex combination (weights 1 - ty, ty)
        of the cell's two node differences along x over the spacing, and its y-derivative
        one of the two along y (weights 1 - tx, tx); the first depends on ty alone and the
        second on tx alone, so the gradient norm's supremum over the cell is
        hypot(max |dx|, max |dy|) / resolution, reached at one of its corners. The lookup is
        continuous and piecewise smooth on a convex domain and clamps points beyond the nodes
        onto them (a 1-Lipschitz projection), so its Lipschitz constant is the largest of
        these over the cells: exact, not a bound. For nodes holding a distance (each node
        difference at most the spacing) it is at most sqrt(2), and reaches sqrt(2) wherever a
        cell's corner sees the distance grow by the spacing along both axes: the nodes 0, 1,
        1, sqrt(2) (in spacings) about an obstacle's corner, or the nodes of min(x, y) about a
        room's corner, whose bilinear lookup x·y has the gradient (1, 1) at (1, 1).

        Returns:
            The constant (metres of clearance per metre); a field one node wide or high
            gives its largest node difference over the spacing (0 for a single node).
        """
        v = np.asarray(self.values, dtype=float)
        if v.shape[0] < 2 or v.shape[1] < 2:
            d = np.abs(np.diff(v.ravel()))
            return float(d.max()) / self.resolution if d.size else 0.0
        dx = np.abs(np.diff(v, axis=1))
        dy = np.abs(np.diff(v, axis=0))
        gx = np.maximum(dx[:-1, :], dx[1:, :])  # per cell, its larger difference along x
        gy = np.maximum(dy[:, :-1], dy[:, 1:])
        return float(np.sqrt(np.max(gx * gx + gy * gy))) / self.resolution


@njit
def bilinear_at(values, x0, y0, res, x, y):
    """:meth:`ClearanceField.__call__` at one point, compiled for the planners' loops:
    the same arithmetic in the same order. (numba caches a caller by its own source: edit a
    comment in the callers, ``plan/occupancy.py`` and ``plan/stepcheck.py``, if this changes.)

    Args:
        values: (ny, nx) the field's node values, metres.
        x0: x of node (0, 0), metres.
        y0: y of node (0, 0), metres.
        res: node spacing, metres.
        x: the point's x, metres.
        y: the point's y, metres.

    Returns:
        The bilinear clearance, metres; beyond the grid the nearest border's.
    """
    ny, nx = values.shape
    fx = min(max((x - x0) / res, 0.0), nx - 1.000001)
    fy = min(max((y - y0) / res, 0.0), ny - 1.000001)
    ix = int(fx)
    iy = int(fy)
    tx = fx - ix
    ty = fy - iy
    return (values[iy, ix] * (1 - tx) + values[iy, ix + 1] * tx) * (1 - ty) + (
        values[iy + 1, ix] * (1 - tx) + values[iy + 1, ix + 1] * tx
    ) * ty


@njit
def _bilinear_rows(values, x0, y0, res, xy):
    """:func:`bilinear_at` of each point of ``xy`` (n, 2), metres: (n,) metres."""
    out = np.empty(xy.shape[0])
    for i in range(xy.shape[0]):
        out[i] = bilinear_at(values, x0, y0, res, xy[i, 0], xy[i, 1])
    return out


def _pack(footprints: Sequence[Footprint]):
    """Footprints as flat arrays for the compiled kernels: per footprint the first edge and
    edge count, round radius (0: polygon) and bounding circle (centre, reach); per edge its
    start a (2,), direction ab (2,), squared length and outward unit normal (2,)."""
    n = len(footprints)
    first = np.zeros(n, dtype=np.int64)
    count = np.zeros(n, dtype=np.int64)
    rad = np.zeros(n)
    circle = np.zeros((n, 3))
    edges = []
    k = 0
    for f, fp in enumerate(footprints):
        v = np.asarray(fp.vertices, dtype=float)
        centre = v.mean(axis=0)
        circle[f] = (*centre, np.linalg.norm(v - centre, axis=1).max() + fp.radius)
        rad[f] = fp.radius
        if fp.is_polygon:
            a = v
            ab = np.roll(v, -1, axis=0) - v
        else:  # the segment first -> last (one "edge"; a circle when they coincide)
            a = v[:1]
            ab = v[-1:] - v[:1]
        length2 = np.einsum("ij,ij->i", ab, ab)
        with np.errstate(divide="ignore", invalid="ignore"):
            normal = np.stack([ab[:, 1], -ab[:, 0]], axis=1) / np.sqrt(length2)[:, None]
        edges.append(np.column_stack([a, ab, length2, normal]))
        first[f], count[f] = k, len(a)
        k += len(a)
    table = np.vstack(edges) if edges else np.zeros((0, 7))
    return first, count, rad, circle, np.ascontiguousarray(table)


@njit
def _signed_distance(px, py, f, first, count, rad, table):
    """:meth:`Footprint.signed_distance` of footprint ``f`` at (px, py), metres, with the same
    arithmetic (:func:`mjwalk.world.footprint._polygon_signed_distance` and
    ``_segment_distance``)."""
    e0 = first[f]
    if rad[f] != 0.0:
        ax, ay, abx, aby, denom = (
            table[e0, 0],
            table[e0, 1],
            table[e0, 2],
            table[e0, 3],
            table[e0, 4],
        )
        rx, ry = px - ax, py - ay
        if denom == 0.0:
            return math.sqrt(rx * rx + ry * ry) - rad[f]
        t = min(max((rx * abx + ry * aby) / denom, 0.0), 1.0)
        cx, cy = px - (ax + t * abx), py - (ay + t * aby)
        return math.sqrt(cx * cx + cy * cy) - rad[f]
    best = math.inf
    line = -math.inf
    for e in range(e0, e0 + count[f]):
        rx, ry = px - table[e, 0], py - table[e, 1]
        abx, aby = table[e, 2], table[e, 3]
        t = min(max((rx * abx + ry * aby) / table[e, 4], 0.0), 1.0)
        cx, cy = rx - t * abx, ry - t * aby
        d2 = cx * cx + cy * cy
        if d2 < best:
            best = d2
        ln = rx * table[e, 5] + ry * table[e, 6]
        if ln > line:
            line = ln
    if line > 0.0:
        return math.sqrt(best)
    return line


@njit
def _buckets(circle, x0, y0, size, nbx, nby):
    """Footprints by square buckets of ``size`` metres (origin x0, y0): a footprint is listed
    in every bucket its bounding circle overlaps. CSR: bucket b's footprints are
    ``items[start[b]:start[b + 1]]``, b = by * nbx + bx."""
    nf = circle.shape[0]
    lo = np.empty((nf, 2), dtype=np.int64)
    hi = np.empty((nf, 2), dtype=np.int64)
    start = np.zeros(nbx * nby + 1, dtype=np.int64)
    for f in range(nf):
        cx, cy, r = circle[f, 0], circle[f, 1], circle[f, 2]
        lo[f, 0] = min(max(math.floor((cx - r - x0) / size), 0), nbx - 1)
        hi[f, 0] = min(max(math.floor((cx + r - x0) / size), 0), nbx - 1)
        lo[f, 1] = min(max(math.floor((cy - r - y0) / size), 0), nby - 1)
        hi[f, 1] = min(max(math.floor((cy + r - y0) / size), 0), nby - 1)
        for by in range(lo[f, 1], hi[f, 1] + 1):
            for bx in range(lo[f, 0], hi[f, 0] + 1):
                start[by * nbx + bx + 1] += 1
    for b in range(nbx * nby):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    items = np.empty(start[-1], dtype=np.int64)
    for f in range(nf):
        for by in range(lo[f, 1], hi[f, 1] + 1):
            for bx in range(lo[f, 0], hi[f, 0] + 1):
                items[fill[by * nbx + bx]] = f
                fill[by * nbx + bx] += 1
    return start, items


@njit
def _fill(values, x0, y0, res, first, count, rad, circle, table, tile, bucket, far):
    """Every node's minimum signed distance over the footprints (``far`` without any), tile by
    tile. A tile gathers the footprints of the buckets (``bucket`` metres) in growing rings
    around its centre, computing the exact clearance at the centre on the way, until no
    footprint beyond the ring can be the nearest one of any of its nodes; each node then takes
    the minimum over those candidates in order of nearness, skipping a candidate whose
    bounding circle lies farther than its running minimum (the old build's test)."""
    ny, nx = values.shape
    nf = first.shape[0]
    nbx = int((nx - 1) * res / bucket) + 1
    nby = int((ny - 1) * res / bucket) + 1
    start, items = _buckets(circle, x0, y0, bucket, nbx, nby)
    lower = np.empty(nf)
    seen = np.full(nf, -1, dtype=np.int64)
    cand = np.empty(nf, dtype=np.int64)
    tid = 0
    for tj in range(0, ny, tile):
        j1 = min(tj + tile, ny)
        for ti in range(0, nx, tile):
            i1 = min(ti + tile, nx)
            tid += 1
            mx = x0 + 0.5 * (ti + i1 - 1) * res
            my = y0 + 0.5 * (tj + j1 - 1) * res
            half = 0.5 * res * math.hypot(i1 - 1 - ti, j1 - 1 - tj)
            bx0 = min(max(int((mx - x0) / bucket), 0), nbx - 1)
            by0 = min(max(int((my - y0) / bucket), 0), nby - 1)
            upper = far  # the exact clearance at the tile's centre, over the footprints seen
            nc = 0
            ring = 0
            while True:
                for by in range(by0 - ring, by0 + ring + 1):
                    if by < 0 or by >= nby:
                        continue
                    edge = by == by0 - ring or by == by0 + ring
                    for bx in range(bx0 - ring, bx0 + ring + 1):
                        if (
                            bx < 0
                            or bx >= nbx
                            or not (edge or bx == bx0 - ring or bx == bx0 + ring)
                        ):
                            continue
                        b = by * nbx + bx
                        for k in range(start[b], start[b + 1]):
                            f = items[k]
                            if seen[f] == tid:
                                continue
                            seen[f] = tid
                            lo = math.hypot(mx - circle[f, 0], my - circle[f, 1]) - circle[f, 2]
                            lower[f] = lo
                            cand[nc] = f
                            nc += 1
                            if lo < upper:
                                d = _signed_distance(mx, my, f, first, count, rad, table)
                                if d < upper:
                                    upper = d
                # a footprint listed in no bucket of rings <= ring lies outside their square,
                # at least ring * bucket from the centre
                if ring * bucket > upper + 2.0 * half or (ring > nbx and ring > nby):
                    break
                ring += 1
            # candidates: footprints that can be the nearest for some node of the tile (no
            # node is farther than ``half`` from the centre: its clearance is at most
            # upper + half, and its distance to f at least lower[f] - half)
            keep = 0
            for c in range(nc):
                if lower[cand[c]] <= upper + 2.0 * half:
                    cand[keep] = cand[c]
                    keep += 1
            order = cand[:keep][np.argsort(lower[cand[:keep]])]
            for j in range(tj, j1):
                py = y0 + j * res
                for i in range(ti, i1):
                    px = x0 + i * res
                    best = far
                    for f in order:
                        if lower[f] - half >= best:
                            break  # this and every later candidate is farther
                        if math.hypot(px - circle[f, 0], py - circle[f, 1]) - circle[f, 2] >= best:
                            continue
                        d = _signed_distance(px, py, f, first, count, rad, table)
                        if d < best:
                            best = d
                    values[j, i] = best
    return values


#: Tile edge (nodes) of :func:`build_clearance`: 0.5 m at 0.02 m. Smaller tiles have fewer
#: candidate footprints each but cost more candidate searches (measured on the generated 100 m
#: hall with 4000 obstacles, ``benchmarks/bench_scale.py``).
TILE = 25
#: Bucket edge (metres) of the footprint lookup of :func:`build_clearance`.
BUCKET = 1.0


def build_clearance(
    footprints: Sequence[Footprint],
    bounds: tuple[float, float, float, float],
    resolution: float = 0.02,
    *,
    far: float = 100.0,
) -> ClearanceField:
    """Sample the clearance to footprints over a floor rectangle.

    Exact signed distances (to within the footprints' tessellation) at every node, the
    minimum over the footprints, computed in a compiled loop tile by tile (0.5 m tiles): each
    tile evaluates only the footprints that can be nearest to one of its nodes (bounding-circle
    tests), so the work grows with the floor area times the few obstacles around each place,
    not with floor area times obstacles. Same values as :func:`build_clearance_bruteforce`, to
    rounding (1e-15 m).

    Args:
        footprints: the obstacle footprints.
        bounds: (xmin, ymin, xmax, ymax), metres.
        resolution: node spacing, metres.
        far: the value where there is no obstacle at all, metres.

    Returns:
        The field, nodes from (xmin, ymin) every ``resolution``.
    """
    xmin, ymin, xmax, ymax = bounds
    nx = int(np.floor((xmax - xmin) / resolution + 1e-9)) + 1
    ny = int(np.floor((ymax - ymin) / resolution + 1e-9)) + 1
    first, count, rad, circle, table = _pack(footprints)
    values = np.empty((ny, nx))
    _fill(values, float(xmin), float(ymin), float(resolution), first, count, rad, circle, table,
          TILE, BUCKET, float(far))  # fmt: skip
    return ClearanceField(xmin, ymin, resolution, values)


def build_clearance_bruteforce(
    footprints: Sequence[Footprint],
    bounds: tuple[float, float, float, float],
    resolution: float = 0.02,
    *,
    far: float = 100.0,
) -> ClearanceField:
    """:func:`build_clearance` the way it was first written (kept as the reference of
    tests and ``benchmarks/bench_scale.py``): NumPy over the whole floor for every footprint.

    Each footprint is evaluated only where it can still lower the running minimum (a cheap
    bounding-circle test).

    Args:
        footprints: the obstacle footprints.
        bounds: (xmin, ymin, xmax, ymax), metres.
        resolution: node spacing, metres.
        far: the value where there is no obstacle at all, metres.

    Returns:
        The field (the same nodes as :func:`build_clearance`).
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
