"""Floor footprints of MuJoCo geoms: the part of a geom inside a height slab, projected onto z = 0.

Every MuJoCo primitive is convex, so the projection of (geom ∩ slab) is a convex 2-D set. Boxes and
meshes (their convex hull) are clipped exactly as polytopes; curved primitives (sphere, capsule,
cylinder, ellipsoid) are first tessellated into an inscribed polytope fine enough that the
footprint is within 0.2 mm of the true one for geoms up to 1 m in size. Vertical capsules,
cylinders and spheres keep their exact round footprints (circles), capsules lying wholly inside
the slab their stadiums, and vertical (yaw-rotated) boxes their rectangles.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import mujoco
import numpy as np

from mjwalk._jit import njit
from mjwalk.boundedmemo import Memo
from mjwalk.world.hullstore import clear_memo, point_digest, point_hull_edges

#: Angular resolution of the tessellation of curved primitives (segments per full turn).
_N_AROUND = 128
#: Latitude rings of the sphere/ellipsoid tessellation.
_N_RINGS = 48


#: Footprints of :func:`geom_footprint` past its exact shapes, by name, geom, the world points'
#: digest and the slab faces that cut them (exact: equal keys, equal answers).
_FOOTPRINTS: Memo[tuple, Footprint | None] = Memo(limit=4096)


def clear_memos() -> None:
    """Forget the kept hull edges and footprints (a benchmark's cold start)."""
    clear_memo()
    _FOOTPRINTS.clear()


@dataclass(frozen=True)
class Footprint:
    """A convex floor footprint in world x, y (metres).

    Either a polygon (``vertices`` (V, 2), counter-clockwise, ``radius`` 0) or a rounded segment:
    all points within ``radius`` of the segment ``vertices[0]``-``vertices[-1]`` (a circle when the
    two ends coincide; a stadium otherwise).
    """

    name: str
    geom_id: int
    vertices: np.ndarray
    radius: float = 0.0

    @property
    def is_polygon(self) -> bool:
        return self.radius == 0.0

    def bounds(self) -> tuple[float, float, float, float]:
        """The footprint's bounding box (worked out once: a level graph asks a surface's
        thousands of times).

        Returns:
            (xmin, ymin, xmax, ymax), metres.
        """
        return self._box

    @functools.cached_property
    def _box(self) -> tuple[float, float, float, float]:
        """:meth:`bounds`, computed on first use (the dataclass is frozen, its vertices fixed)."""
        lo = self.vertices.min(axis=0) - self.radius
        hi = self.vertices.max(axis=0) + self.radius
        return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])

    def signed_distance(self, pts: np.ndarray) -> np.ndarray:
        """Signed distance from points to the footprint.

        Args:
            pts: (..., 2) world x, y, metres.

        Returns:
            (...) metres; negative inside.
        """
        pts = np.asarray(pts, dtype=float)
        if not self.is_polygon:
            return _segment_distance(pts, self.vertices[0], self.vertices[-1]) - self.radius
        return _polygon_signed_distance(pts, self.vertices)


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    denom = float(ab @ ab)
    if denom == 0.0:
        return np.linalg.norm(p - a, axis=-1)
    t = np.clip(((p - a) @ ab) / denom, 0.0, 1.0)
    return np.linalg.norm(p - (a + t[..., None] * ab), axis=-1)


def _polygon_signed_distance(p: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Signed distance to a convex CCW polygon: outside, to the nearest edge; inside, minus the
    distance to the boundary (the largest signed distance to an edge line). Compiled
    (:func:`polygon_distances`): as NumPy code (a roll, einsums and a stack per call on a few
    points) it was a third of a walk guide's time (``benchmarks/bench_scale.py``)."""
    flat = np.ascontiguousarray(p, dtype=float).reshape(-1, 2)
    out = polygon_distances(flat, np.ascontiguousarray(v, dtype=float))
    return out.reshape(p.shape[:-1])


@njit
def polygon_distances(p, v):
    """Signed distances of points to a convex CCW polygon, compiled: what
    :meth:`Footprint.signed_distance` gives for a polygon footprint, callable from other
    compiled code (:func:`mjwalk.plan.nearcut.gap_room`). The NumPy version's arithmetic in
    its order (per edge ab = b - a, t = clip((rel·ab)/|ab|², 0, 1), the nearest point's squared
    distance, the edge line's (rel·n) with n = (ab_y, -ab_x) / |ab|), a NaN in any edge's terms
    (a repeated vertex's 0/0) propagating as np.min and np.max propagate it.

    Args:
        p: (n, 2) points, world x, y, metres (C-contiguous).
        v: (e, 2) the polygon's vertices, counter-clockwise, metres (C-contiguous).

    Returns:
        (n,) metres; negative inside (minus the distance to the boundary).
    """
    n = p.shape[0]
    e = v.shape[0]
    ab = np.empty((e, 2))
    length2 = np.empty(e)
    normal = np.empty((e, 2))
    for k in range(e):
        nxt = k + 1 if k + 1 < e else 0
        ab[k, 0] = v[nxt, 0] - v[k, 0]
        ab[k, 1] = v[nxt, 1] - v[k, 1]
        length2[k] = ab[k, 0] * ab[k, 0] + ab[k, 1] * ab[k, 1]
        norm = math.sqrt(length2[k])
        if norm == 0.0:  # a repeated vertex: 0/0 in NumPy, NaN for every point
            normal[k, 0] = np.nan
            normal[k, 1] = np.nan
        else:
            normal[k, 0] = ab[k, 1] / norm
            normal[k, 1] = -ab[k, 0] / norm
    out = np.empty(n)
    for i in range(n):
        best = np.inf
        line = -np.inf
        for k in range(e):
            rx = p[i, 0] - v[k, 0]
            ry = p[i, 1] - v[k, 1]
            t = np.nan
            if length2[k] != 0.0:
                t = (rx * ab[k, 0] + ry * ab[k, 1]) / length2[k]
                if t == t:  # (np.clip keeps a NaN)
                    t = min(max(t, 0.0), 1.0)
            cx = rx - t * ab[k, 0]
            cy = ry - t * ab[k, 1]
            d2 = cx * cx + cy * cy
            if d2 < best or d2 != d2:
                best = d2 if best == best else best
            s = rx * normal[k, 0] + ry * normal[k, 1]
            if s > line or s != s:
                line = s if line == line else line
        out[i] = math.sqrt(best) if line > 0.0 else line
    return out


def _unit_circle(n: int) -> np.ndarray:
    ang = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.stack([np.cos(ang), np.sin(ang)], axis=1)


def _local_points(model: mujoco.MjModel, g: int) -> np.ndarray | None:
    """Points in the geom frame whose convex hull is the geom (or an inscribed tessellation)."""
    gtype = int(model.geom_type[g])
    size = model.geom_size[g]
    circle = _unit_circle(_N_AROUND)
    if gtype == mujoco.mjtGeom.mjGEOM_BOX:
        corners = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1], indexing="ij")).reshape(3, -1).T
        return corners * size
    if gtype == mujoco.mjtGeom.mjGEOM_CYLINDER:
        r, h = size[0], size[1]
        rim = np.column_stack([r * circle, np.zeros(len(circle))])
        return np.vstack([rim + [0, 0, -h], rim + [0, 0, h]])
    if gtype in (
        mujoco.mjtGeom.mjGEOM_SPHERE,
        mujoco.mjtGeom.mjGEOM_ELLIPSOID,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
    ):
        lat = np.linspace(-np.pi / 2, np.pi / 2, _N_RINGS + 1)
        ring = np.concatenate(
            [np.column_stack([np.cos(la) * circle, np.full(len(circle), np.sin(la))]) for la in lat]
        )
        if gtype == mujoco.mjtGeom.mjGEOM_SPHERE:
            return ring * size[0]
        if gtype == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
            return ring * size[:3]
        r, h = size[0], size[1]
        sphere = ring * r
        return np.vstack([sphere + [0, 0, -h], sphere + [0, 0, h]])
    if gtype == mujoco.mjtGeom.mjGEOM_MESH:
        mesh = model.geom_dataid[g]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        return np.asarray(model.mesh_vert[start : start + count], dtype=float)
    return None


def polygon_area(v: np.ndarray) -> float:
    """The area of a simple polygon (the shoelace formula).

    Args:
        v: (K, 2) its corners in order (either way round), metres.

    Returns:
        Its area, square metres.
    """
    x, y = v[:, 0], v[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _clip_hull_to_slab(points: np.ndarray, z0: float, z1: float, disk: bool) -> np.ndarray:
    """Vertices of conv(points) ∩ {z0 <= z <= z1} (points in world coordinates; ``disk``: the
    hull's edges may be read from and kept in the workplace cache,
    :func:`mjwalk.world.hullstore.point_hull_edges`)."""
    inside = points[(points[:, 2] >= z0) & (points[:, 2] <= z1)]
    if points[:, 2].min() >= z0 and points[:, 2].max() <= z1:
        return points
    e = point_hull_edges(points, disk)
    if len(e) == 0:  # qhull refused the points (flat or degenerate): the points in the slab
        return inside
    pa, pb = points[e[:, 0]], points[e[:, 1]]
    out = [inside]
    for z in (z0, z1):
        za, zb = pa[:, 2] - z, pb[:, 2] - z
        cross = (za * zb) < 0.0
        if np.any(cross):
            t = za[cross] / (za[cross] - zb[cross])
            out.append(pa[cross] + t[:, None] * (pb[cross] - pa[cross]))
    return np.vstack(out)


def geom_footprint(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    g: int,
    z0: float,
    z1: float,
    disk: bool = False,
) -> Footprint | None:
    """Footprint of a geom within a horizontal slab.

    Args:
        model: the compiled scene.
        data: its data, kinematics done (``mj_kinematics``).
        g: the geom id.
        z0: the slab's bottom, world z, metres.
        z1: the slab's top, world z, metres.
        disk: whether a tessellated geom's or large mesh's 3-D hull may be read from and kept
            in the workplace cache (:mod:`mjwalk.world.hullstore`; the workplace's cache
            policy). The footprint is the same either way.

    Returns:
        The convex footprint of the part of the geom in ``z0 <= z <= z1`` (world x, y), or None
        when the geom does not reach into the slab.
    """
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
    pos = data.geom_xpos[g].copy()
    rot = data.geom_xmat[g].reshape(3, 3)
    gtype = int(model.geom_type[g])
    size = model.geom_size[g]
    axis = rot[:, 2]
    vertical = abs(abs(axis[2]) - 1.0) < 1e-9
    # Exact round footprints where the shape allows: a sphere, or a vertical capsule, cut by a
    # horizontal slab projects to a circle (of the radius of its widest cross-section in the
    # slab: r at a height within the capsule's cylinder, sqrt(r^2 - dz^2) dz above a centre).
    if gtype == mujoco.mjtGeom.mjGEOM_SPHERE or (
        gtype == mujoco.mjtGeom.mjGEOM_CAPSULE and vertical
    ):
        half = size[1] if gtype == mujoco.mjtGeom.mjGEOM_CAPSULE else 0.0
        dz = max(0.0, z0 - (pos[2] + half), (pos[2] - half) - z1)
        if dz > size[0]:
            return None
        return Footprint(name, g, pos[None, :2].copy(), float(np.sqrt(size[0] ** 2 - dz**2)))
    if gtype == mujoco.mjtGeom.mjGEOM_CYLINDER and vertical:
        if pos[2] + size[1] < z0 or pos[2] - size[1] > z1:
            return None
        return Footprint(name, g, pos[None, :2].copy(), float(size[0]))
    if gtype == mujoco.mjtGeom.mjGEOM_BOX and vertical:  # a yaw-rotated box: its rectangle
        if pos[2] + size[2] < z0 or pos[2] - size[2] > z1:
            return None
        ex, ey = rot[:2, 0] * size[0], rot[:2, 1] * size[1]
        c = pos[:2]
        verts = np.array([c - ex - ey, c + ex - ey, c + ex + ey, c - ex + ey])
        if (ex[0] * ey[1] - ex[1] * ey[0]) < 0:  # a mirrored frame: keep counter-clockwise
            verts = verts[::-1]
        return Footprint(name, g, verts)
    if gtype == mujoco.mjtGeom.mjGEOM_CAPSULE:
        a, b = pos - axis * size[1], pos + axis * size[1]
        if min(a[2], b[2]) - size[0] >= z0 and max(a[2], b[2]) + size[0] <= z1:
            return Footprint(name, g, np.array([a[:2], b[:2]]), float(size[0]))
    local = _local_points(model, g)
    if local is None:
        return None
    world = local @ rot.T + pos
    lo, hi = float(world[:, 2].min()), float(world[:, 2].max())
    # The answer from here on depends on the points and on each slab face only where it cuts
    # them: a face at or beyond their extent clips nothing (no point outside it, no edge across
    # it), so every such face gives the same footprint (the key's infinities).
    key = (name, g, point_digest(world), z0 if z0 > lo else -math.inf, z1 if z1 < hi else math.inf)

    def footprint() -> Footprint | None:
        fp = _slab_footprint(name, g, world, z0, z1, disk) if lo <= z1 and hi >= z0 else None
        if fp is not None:
            fp.vertices.setflags(write=False)  # shared by every later call with this key
        return fp

    return _FOOTPRINTS.get(key, footprint)


def _slab_footprint(
    name: str, g: int, world: np.ndarray, z0: float, z1: float, disk: bool
) -> Footprint | None:
    """The footprint of conv(``world``) within ``z0 <= z <= z1`` (:func:`geom_footprint`)."""
    clipped = _clip_hull_to_slab(world, z0, z1, disk)
    if len(clipped) == 0:
        return None
    xy = clipped[:, :2]
    from scipy.spatial import ConvexHull, QhullError  # deferred: scipy.spatial, ~1 s import

    try:
        hull = ConvexHull(xy)
        verts = xy[hull.vertices]  # counter-clockwise for 2-D input
    except QhullError:
        # Degenerate (a vertical sheet seen edge-on): treat as a thin segment.
        centred = xy - xy.mean(axis=0)
        direction = np.linalg.svd(centred, full_matrices=False)[2][0]
        proj = centred @ direction
        ends = xy.mean(axis=0) + np.outer([proj.min(), proj.max()], direction)
        return Footprint(name, g, ends, 1e-6)
    return Footprint(name, g, verts)
