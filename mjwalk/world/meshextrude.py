"""An exact convex decomposition of a mesh without overhangs, and a check of an approximate one.

A CAD stair, platform or plinth modelled as one closed mesh is, seen from above, a terrain over a
flat base: every vertical line through it meets the solid in one interval from the base up.
Such a solid is exactly the union of its upward faces each extruded straight down to the base:
:func:`extruded_parts` cuts each upward plane's footprint into convex pieces
(:func:`convex_pieces`) and makes each piece a prism (its top on the face's plane, its bottom
on the base), so every tread, landing and ramp is a part's top to float precision and the
parts fill the mesh and nothing else. CoACD (``meshimport.convex_parts``) approximates: on one
clean stair mesh it dropped a 10 m platform and split a tread in two levels.

A mesh with an overhang (a table, a shelf, a stair's sloped soffit) is no such terrain and stays
with CoACD; :func:`approximate_walk_faces` then names its walk faces that no part's top
reproduces within ``norms.STAIR_TOLERANCE``, so the import can say it is approximate.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.world.hiddenfaces import PLANE_ROUND, upward_planes
from mjwalk.world.norms import MIN_TREAD, ROUNDING_SLACK, STAIR_TOLERANCE, STAND_WIDTH

#: Geometric tolerance of the overhang test, the convexity test and the volume check, metres:
#: ``hiddenfaces.PLANE_ROUND`` (0.1 mm; CAD tessellates a flat face coplanar to far better, and
#: MuJoCo's float32 vertices of a 10 m part are good to 1 um). A face whose top view is thinner
#: than this is a wall; a downward face within it of the base is the base.
GEOM_TOL = PLANE_ROUND
#: Spacing of the points at which a walk face is compared with the parts' tops, metres: half a
#: foot's breadth (about 0.1 m, DIN 33402-2 foot breadth of adults, 5th-95th percentile
#: 0.09-0.11 m), so no place a foot can stand on misses a point.
SAMPLE_SPACING = 0.05


def _plan_thickness(tri: np.ndarray) -> np.ndarray:
    """Each triangle's top view's least width (twice its area over its longest side), metres."""
    xy = tri[:, :, :2]
    d1, d2 = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    sides = np.linalg.norm(xy - np.roll(xy, -1, axis=1), axis=2).max(axis=1)
    return np.where(sides > 0, 2.0 * area / np.maximum(sides, 1e-300), 0.0)


def overhang_free(verts: np.ndarray, faces: np.ndarray) -> bool:
    """Whether a closed mesh is a terrain over a flat base: every face that faces down (its top
    view thicker than :data:`GEOM_TOL`) lies on the mesh's lowest plane.

    For a closed, consistently wound volume that is exact: a vertical line enters the solid
    through a downward face and leaves through an upward one, alternately; with all downward
    faces on one plane it enters once, so it meets the solid in one interval from the base.

    Args:
        verts: (V, 3) vertices, z up, metres.
        faces: (F, 3) vertex indices, wound outwards.

    Returns:
        True when the mesh has no overhang.
    """
    tri = np.asarray(verts, float)[np.asarray(faces, np.int64)]
    nz = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2]
    down = (nz < 0) & (_plan_thickness(tri) > GEOM_TOL)
    base = float(np.asarray(verts, float)[:, 2].min())
    return bool(np.all(tri[down][:, :, 2] <= base + GEOM_TOL))


def _is_convex(poly) -> bool:
    """Whether a shapely polygon falls short of its hull by at most a :data:`GEOM_TOL` strip
    along the hull's outline (and has no hole)."""
    hull = poly.convex_hull
    return len(poly.interiors) == 0 and hull.area - poly.area <= GEOM_TOL * hull.length


def convex_pieces(poly) -> list:
    """A polygon cut into convex pieces whose union is the polygon.

    The constrained Delaunay triangles of the polygon (shapely, holes kept, no new vertices),
    merged greedily across shared sides while the merge stays convex (Hertel and Mehlhorn
    1983: at most four times the fewest convex pieces); shapely has no convex partition.

    Args:
        poly: a shapely Polygon, plan metres.

    Returns:
        Convex shapely Polygons, the polygon itself when it is convex.
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it

    poly = shapely.simplify(poly, 0.0)  # collinear outline vertices go
    if _is_convex(poly):
        return [poly]
    pieces = [
        t
        for t in shapely.get_parts(shapely.constrained_delaunay_triangles(poly))
        if t.area > ROUNDING_SLACK
    ]
    merged = True
    while merged:
        merged = False
        for i in range(len(pieces)):
            for j in range(i + 1, len(pieces)):
                if pieces[i].boundary.intersection(pieces[j].boundary).length <= GEOM_TOL:
                    continue  # no common side
                both = shapely.simplify(shapely.union(pieces[i], pieces[j]), 0.0)
                if both.geom_type == "Polygon" and _is_convex(both):
                    pieces[i] = both
                    del pieces[j]
                    merged = True
                    break
            if merged:
                break
    return pieces


def _prism(xy: np.ndarray, top: np.ndarray, base: float) -> tuple[np.ndarray, np.ndarray]:
    """The convex prism over a convex plan polygon ``xy`` (K, 2) from ``base`` up to the
    heights ``top`` (K,) (trimesh's hull of its corners, which keeps them as given)."""
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    pts = np.vstack([np.c_[xy, top], np.c_[xy, np.full(len(xy), base)]])
    hull = trimesh.convex.convex_hull(pts)
    return np.asarray(hull.vertices, float), np.asarray(hull.faces, np.int64)


def extruded_parts(
    verts: np.ndarray, faces: np.ndarray
) -> list[tuple[np.ndarray, np.ndarray]] | None:
    """The exact convex decomposition of a closed mesh without overhangs.

    Each plane of upward faces (``hiddenfaces.upward_planes``, any slope; faces whose top view
    is thinner than :data:`GEOM_TOL` are walls), each connected region of its footprint cut
    into :func:`convex_pieces`, each piece a prism from the face's plane down to the mesh's
    lowest height.

    Args:
        verts: (V, 3) vertices, z up (world orientation; any origin), metres.
        faces: (F, 3) vertex indices.

    Returns:
        The parts, (vertices (V_k, 3), faces (F_k, 3)) each, vertices in the frame given; None
        when the mesh is not a closed volume or has an overhang (:func:`overhang_free`), or
        the parts' volume differs from the mesh's by more than a :data:`GEOM_TOL` layer over
        its footprint (a mesh whose faces overlap: no terrain after all).
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    mesh = trimesh.Trimesh(np.asarray(verts, float), np.asarray(faces, np.int64), process=True)
    if not mesh.is_volume or not overhang_free(mesh.vertices, mesh.faces):
        return None
    base = float(mesh.vertices[:, 2].min())
    parts = []
    plan_area = 0.0
    for plane in upward_planes(mesh.vertices, mesh.faces, max_slope=0.5 * math.pi):
        tri = plane.triangles[_plan_thickness(plane.triangles) > GEOM_TOL]
        if not len(tri):
            continue
        polys = shapely.polygons(tri[:, :, :2])
        try:  # the faces share their corners exactly: a coverage
            plan = shapely.coverage_union_all(polys)
        except shapely.errors.GEOSException:
            plan = shapely.union_all(polys)
        plan_area += plan.area
        for region in shapely.get_parts(plan):
            for piece in convex_pieces(region):
                xy = np.asarray(piece.exterior.coords)[:-1]
                top = plane.z_at(xy)
                if top.min() - base > GEOM_TOL:
                    parts.append(_prism(xy, top, base))
    volume = sum(trimesh.Trimesh(v, f).volume for v, f in parts)
    if not parts or abs(volume - mesh.volume) > GEOM_TOL * plan_area:
        return None
    return parts


def _tops(parts: list[tuple[np.ndarray, np.ndarray]], xy: np.ndarray) -> np.ndarray:
    """(P, N) each convex part's top over each plan point, metres (NaN where the vertical line
    misses the part)."""
    from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

    out = np.full((len(parts), len(xy)), np.nan)
    for k, (v, _) in enumerate(parts):
        try:
            eq = ConvexHull(v).equations  # inside where n . p + d <= 0
        except QhullError:
            continue
        up, down, side = eq[:, 2] > 1e-9, eq[:, 2] < -1e-9, np.abs(eq[:, 2]) <= 1e-9
        rest = -(xy @ eq[:, :2].T + eq[:, 3])  # n_z z <= rest
        hi = np.min(rest[:, up] / eq[up, 2], axis=1, initial=np.inf)
        lo = np.max(rest[:, down] / eq[down, 2], axis=1, initial=-np.inf)
        inside = (lo <= hi + GEOM_TOL) & np.all(rest[:, side] >= -GEOM_TOL, axis=1)
        out[k, inside] = hi[inside]
    return out


def approximate_walk_faces(
    verts: np.ndarray,
    faces: np.ndarray,
    parts: list[tuple[np.ndarray, np.ndarray]],
    tolerance: float = STAIR_TOLERANCE,
) -> list[tuple[float, float]]:
    """The mesh's walk faces that no part's top reproduces within ``tolerance``.

    A walk face is a plane of upward faces a person can stand on (no steeper than
    ``norms.MAX_RAMP_SLOPE``, at least ``norms.MIN_TREAD`` by ``norms.STAND_WIDTH`` in area, as
    ``hiddenfaces``); at points :data:`SAMPLE_SPACING` apart on it (and its centroid), the part
    top nearest to the face's height must lie within ``tolerance``.

    Args:
        verts: (V, 3) the mesh's vertices, z up, metres.
        faces: (F, 3) vertex indices.
        parts: its convex parts, (vertices (V_k, 3), faces) each, same frame.
        tolerance: the largest deviation accepted, metres (``norms.STAIR_TOLERANCE``, 5 mm).

    Returns:
        (height of the face, its largest deviation, metres; inf where no part is under or
        over a point) per face off, lowest first.
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it

    off = []
    for plane in upward_planes(verts, faces):
        if plane.plan_area < MIN_TREAD * STAND_WIDTH - ROUNDING_SLACK:
            continue
        plan = shapely.union_all(
            [shapely.buffer(q, 1e-6) for q in shapely.polygons(plane.triangles[:, :, :2])]
        )
        x0, y0, x1, y1 = plan.bounds
        gx, gy = np.meshgrid(
            np.arange(x0 + SAMPLE_SPACING / 2, x1, SAMPLE_SPACING),
            np.arange(y0 + SAMPLE_SPACING / 2, y1, SAMPLE_SPACING),
        )
        grid = np.c_[gx.ravel(), gy.ravel()]
        xy = np.vstack([grid[shapely.contains_xy(plan, grid[:, 0], grid[:, 1])], [0.0, 0.0]])
        xy[-1] = shapely.point_on_surface(plan).coords[0]
        gap = np.abs(_tops(parts, xy) - plane.z_at(xy)[None, :])
        worst = float(np.max(np.nanmin(np.where(np.isnan(gap), np.inf, gap), axis=0)))
        if worst > tolerance:
            off.append((float(plane.triangles[:, :, 2].mean()), worst))
    return sorted(off)
