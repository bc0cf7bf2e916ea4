"""Walk faces of a mesh that its convex hull hides: a mesh concave in elevation.

MuJoCo collides a mesh geom as its convex hull. A stair and its landing modelled as one mesh (CAD
exports do this) has a convex footprint, yet its hull is a wedge over the nosings: a foot on a
tread would stand inside the hull. :func:`hidden_walk_faces` finds such faces: the mesh's
upward faces no steeper than a ramp (``norms.MAX_RAMP_SLOPE``), grouped by plane, where the hull
stands more than :data:`HIDDEN_DEPTH` above them over a patch a person can stand on
(``norms.MIN_TREAD`` by ``norms.STAND_WIDTH``). A convex mesh has none; a mesh concave only in
plan (an L- or U-shaped bench, its top on the hull) has none either.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.world.norms import (
    LEVEL_TOLERANCE,
    MAX_RAMP_SLOPE,
    MIN_TREAD,
    ROUNDING_SLACK,
    SLOPE_ROUNDING_SLACK,
    STAND_WIDTH,
)

#: How far a mesh's hull may stand above one of its walk faces before the face counts as hidden,
#: metres: ``norms.LEVEL_TOLERANCE`` (4 mm; a height step over 4 mm is already a trip point,
#: ASR A1.5/1,2): MuJoCo would put a foot standing there into contact with the hull.
HIDDEN_DEPTH = LEVEL_TOLERANCE
#: Faces are grouped into planes by their unit normal and offset rounded to this (metres for
#: the offset): CAD tessellates a flat face into triangles coplanar to far better than 0.1 mm.
PLANE_ROUND = 1e-4


class HiddenWalkFaceWarning(UserWarning):
    """A mesh geom has walk faces under its convex hull (MuJoCo's collision shape)."""


@dataclass(frozen=True)
class HiddenFace:
    """A patch of a mesh's upward faces hidden under its hull.

    Attributes:
        z: the patch's mean height, frame of the vertices given, metres.
        depth: its hidden part's least extent (the oriented envelope's short side), metres.
        width: the envelope's long side, metres.
        area: the hidden part's area in plan, square metres.
    """

    z: float
    depth: float
    width: float
    area: float


def _clip(poly: np.ndarray, a: np.ndarray, b: float) -> np.ndarray:
    """The part of a convex polygon (K, 2) where ``a . p <= b`` (Sutherland-Hodgman)."""
    s = poly @ a - b
    out = []
    for i in range(len(poly)):
        j = (i + 1) % len(poly)
        if s[i] <= 0:
            out.append(poly[i])
        if s[i] * s[j] < 0:
            out.append(poly[i] + s[i] / (s[i] - s[j]) * (poly[j] - poly[i]))
    return np.array(out).reshape(-1, 2)


def _lifted_inside(bounds: np.ndarray, plane: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """The plan region (convex, (K, 2)) within ``bounds`` (x0, y0, x1, y1) where the plane
    ``u . p = o`` (``plane`` = (ux, uy, uz, o)) lifted by HIDDEN_DEPTH lies inside the hull
    whose upward facets are ``upper`` (rows n_x, n_y, n_z, d: inside where n . p + d <= 0)."""
    x0, y0, x1, y1 = bounds
    poly = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)
    ux, uy, uz, o = plane
    for nx, ny, nz, d in upper:  # z(x, y) = (o - ux x - uy y) / uz + HIDDEN_DEPTH
        a = np.array([nx - nz * ux / uz, ny - nz * uy / uz])
        poly = _clip(poly, a, -d - nz * (o / uz + HIDDEN_DEPTH))
        if len(poly) < 3:
            return poly
    return poly


@dataclass(frozen=True)
class FacePlane:
    """The upward faces of a mesh that share one plane (to :data:`PLANE_ROUND`).

    Attributes:
        normal: (3,) the plane's mean unit normal, z > 0, frame of the vertices given.
        offset: its mean offset ``normal . p``, metres.
        triangles: (K, 3, 3) its faces' corners, metres.
    """

    normal: np.ndarray
    offset: float
    triangles: np.ndarray

    @property
    def plan_area(self) -> float:
        """The faces' area in plan, square metres."""
        t = self.triangles
        d1, d2 = t[:, 1, :2] - t[:, 0, :2], t[:, 2, :2] - t[:, 0, :2]
        return float(np.sum(0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])))

    def z_at(self, xy: np.ndarray) -> np.ndarray:
        """The plane's height over plan points.

        Args:
            xy: (N, 2) plan points, metres.

        Returns:
            (N,) heights, metres.
        """
        ux, uy, uz = self.normal
        xy = np.asarray(xy, float).reshape(-1, 2)
        return (self.offset - ux * xy[:, 0] - uy * xy[:, 1]) / uz


def upward_planes(
    verts: np.ndarray, faces: np.ndarray, max_slope: float = MAX_RAMP_SLOPE
) -> list[FacePlane]:
    """A mesh's upward faces no steeper than ``max_slope``, grouped by plane.

    Args:
        verts: (V, 3) vertices, z up, metres.
        faces: (F, 3) vertex indices.
        max_slope: the steepest face kept, radians (``norms.MAX_RAMP_SLOPE``: walk faces), with
            ``norms.SLOPE_ROUNDING_SLACK`` (a face at exactly the limit is kept).

    Returns:
        One :class:`FacePlane` per plane (faces of one plane in several places together).
    """
    verts = np.asarray(verts, float)
    tri = verts[np.asarray(faces, np.int64)]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(n, axis=1)
    ok = norm > 1e-12
    unit = n[ok] / norm[ok, None]
    # a face at the limit is one: its corners' rounding is no excess (norms.SLOPE_ROUNDING_SLACK)
    up = unit[:, 2] >= max(math.cos(max_slope + SLOPE_ROUNDING_SLACK), 1e-12)
    if not up.any():
        return []
    tri, unit = tri[ok][up], unit[up]
    offset = np.einsum("ij,ij->i", unit, tri[:, 0])
    keys = np.round(np.c_[unit, offset] / PLANE_ROUND).astype(np.int64)
    _, group = np.unique(keys, axis=0, return_inverse=True)
    group = group.ravel()
    out = []
    for k in range(int(group.max()) + 1):
        mine = np.flatnonzero(group == k)
        out.append(FacePlane(unit[mine].mean(axis=0), float(offset[mine].mean()), tri[mine]))
    return out


def hidden_walk_faces(
    verts: np.ndarray,
    faces: np.ndarray,
    min_depth: float = MIN_TREAD,
    min_width: float = STAND_WIDTH,
) -> list[HiddenFace]:
    """The patches of a mesh's walk faces (upward, at most ``norms.MAX_RAMP_SLOPE`` steep) that
    its convex hull covers by more than :data:`HIDDEN_DEPTH`, each large enough to stand on.

    Args:
        verts: (V, 3) vertices, z up (world orientation; any origin), metres.
        faces: (F, 3) vertex indices.
        min_depth: least extent of a hidden patch, metres (``norms.MIN_TREAD``, 0.26 m).
        min_width: least extent across it, metres (``norms.STAND_WIDTH``, 0.6 m).

    Returns:
        The hidden patches (one per connected region of each plane), lowest first; empty for a
        convex mesh, a flat one, or one whose only walk faces are on its hull's top.
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it
    from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

    planes = [
        p
        for p in upward_planes(verts, faces)
        if p.plan_area >= min_depth * min_width - ROUNDING_SLACK  # planes one can stand on
    ]
    if not planes:
        return []
    try:
        hull = ConvexHull(np.asarray(verts, float))
    except QhullError:  # flat or degenerate: no volume for a hull to hide a face in
        return []
    upper = hull.equations[hull.equations[:, 2] > 1e-12]
    found = []
    for p in planes:
        plan = shapely.union_all(
            [shapely.buffer(q, 1e-6) for q in shapely.polygons(p.triangles[:, :, :2])]
        )
        region = _lifted_inside(np.asarray(plan.bounds), np.r_[p.normal, p.offset], upper)
        if len(region) < 3:
            continue
        hidden = plan.intersection(shapely.Polygon(region))
        for part in shapely.get_parts(hidden):
            env = np.asarray(shapely.oriented_envelope(part).exterior.coords)
            if len(env) < 4:
                continue
            sides = sorted(float(np.linalg.norm(env[i + 1] - env[i])) for i in range(2))
            # a tread exactly MIN_TREAD deep is one: the vertices' rounding is no shortfall
            if sides[0] >= min_depth - ROUNDING_SLACK and sides[1] >= min_width - ROUNDING_SLACK:
                z = float(p.triangles[:, :, 2].mean())
                found.append(HiddenFace(z, sides[0], sides[1], float(part.area)))
    return sorted(found, key=lambda h: h.z)
