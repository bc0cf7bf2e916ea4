"""An exact convex decomposition of a mesh without overhangs, and a check of an approximate one.

A CAD stair, platform, plinth or table modelled as one closed mesh meets every vertical line
through it in one interval: from its bottom (a flat base, a stair's sloped soffit, a table
top's underside) up to its top. Such a solid is exactly the union of prisms between its bottom
and top faces: :func:`extruded_parts` cuts each plane's footprint into convex pieces
(:func:`convex_pieces`) and makes each cell where a top piece meets a bottom piece a prism
(its top on the top face's plane, its bottom on the bottom face's; over a flat base, each
upward face extruded straight down), so every tread, landing and ramp is a part's top to float
precision and the parts fill the mesh and nothing else. CoACD (``meshimport.convex_parts``)
approximates: on one clean stair mesh it dropped a 10 m platform and split a tread in two levels.

A mesh with an overhang (a vertical line meets it twice: a shelf's boards, a stair under a
stair) stays with CoACD; :func:`approximate_walk_faces` then names its walk faces that no
part's top reproduces within ``norms.STAIR_TOLERANCE``, so the import can say it is
approximate.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.world.hiddenfaces import PLANE_ROUND, FacePlane, upward_planes
from mjwalk.world.norms import (
    HORIZONTAL_SLOPE,
    MIN_TREAD,
    ROUNDING_SLACK,
    STAIR_TOLERANCE,
    STAND_WIDTH,
)

#: Geometric tolerance of the one-interval test (footprints overlapping), the convexity test,
#: the outlines' simplification and the volume check, metres: ``hiddenfaces.PLANE_ROUND``
#: (0.1 mm; CAD tessellates a flat face coplanar to far better, and MuJoCo's float32 vertices
#: of a 10 m part are good to 1 um). A face whose top view is thinner than this is a wall.
GEOM_TOL = PLANE_ROUND
#: Spacing of the points at which a walk face is compared with the parts' tops, metres: about
#: half a foot's breadth (``anthropometry.SEG["foot_width"]``, 0.055 of stature after Winter
#: 2009 Fig. 4.1: 0.096 m at the default 1.75 m), so no place a foot stands on misses a point.
SAMPLE_SPACING = 0.05


def _plan_thickness(tri: np.ndarray) -> np.ndarray:
    """Each triangle's top view's least width (twice its area over its longest side), metres."""
    xy = tri[:, :, :2]
    d1, d2 = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    sides = np.linalg.norm(xy - np.roll(xy, -1, axis=1), axis=2).max(axis=1)
    return np.where(sides > 0, 2.0 * area / np.maximum(sides, 1e-300), 0.0)


def _plane_plans(verts: np.ndarray, faces: np.ndarray) -> list[tuple[FacePlane, object]]:
    """Each plane of a mesh's upward faces (any slope; faces whose top view is thinner than
    :data:`GEOM_TOL` are walls) with its footprint (shapely, exact: the faces share corners)."""
    import shapely  # deferred: shapely is slow to import; only meshes need it

    out = []
    for plane in upward_planes(verts, faces, max_slope=0.5 * math.pi):
        tri = plane.triangles[_plan_thickness(plane.triangles) > GEOM_TOL]
        if not len(tri):
            continue
        polys = shapely.polygons(tri[:, :, :2])
        try:  # the faces share their corners exactly: a coverage
            plan = shapely.coverage_union_all(polys)
        except shapely.errors.GEOSException:
            plan = shapely.union_all(polys)
        out.append((plane, plan))
    return out


def _single_cover(plans: list) -> bool:
    """Whether footprints overlap by no more than a :data:`GEOM_TOL` strip along them."""
    import shapely  # deferred: shapely is slow to import; only meshes need it

    union = shapely.union_all([p for _, p in plans])
    return sum(p.area for _, p in plans) - union.area <= GEOM_TOL * max(union.length, 1e-9)


def _is_convex(poly) -> bool:
    """Whether a shapely polygon has no hole and none of its corners lies more than
    :data:`GEOM_TOL` inside its convex hull's outline (the deepest point of a dent is a
    corner), so the hull of its prism holds it to within that."""
    import shapely  # deferred: shapely is slow to import; only meshes need it

    if len(poly.interiors):
        return False
    corners = shapely.points(np.asarray(poly.exterior.coords))
    return float(np.max(shapely.distance(poly.convex_hull.exterior, corners))) <= GEOM_TOL


def convex_pieces(poly) -> list:
    """A polygon cut into convex pieces whose union is the polygon.

    The constrained Delaunay triangles of the polygon (shapely, holes kept, no new vertices),
    merged across each shared side in turn where the merge stays convex (Hertel and Mehlhorn
    1983: at most four times the fewest convex pieces); shapely has no convex partition.

    Args:
        poly: a shapely Polygon, plan metres.

    Returns:
        Convex shapely Polygons, the polygon itself when it is convex.
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it

    # outline vertices within GEOM_TOL of collinear go (float32, turned: not exactly collinear)
    poly = shapely.simplify(poly, GEOM_TOL)
    if _is_convex(poly):
        return [poly]
    tris = [
        t
        for t in shapely.get_parts(shapely.constrained_delaunay_triangles(poly))
        if t.area > ROUNDING_SLACK
    ]
    sides: dict[tuple, list[int]] = {}
    for k, t in enumerate(tris):
        c = [tuple(p) for p in np.asarray(t.exterior.coords)[:3]]
        for i in range(3):
            sides.setdefault(tuple(sorted((c[i], c[(i + 1) % 3]))), []).append(k)
    owner = list(range(len(tris)))  # union-find: each triangle's piece
    pieces = dict(enumerate(tris))

    def find(k: int) -> int:
        while owner[k] != k:
            owner[k] = owner[owner[k]]
            k = owner[k]
        return k

    for pair in sides.values():
        if len(pair) != 2:
            continue  # on the outline
        a, b = find(pair[0]), find(pair[1])
        if a == b:
            continue
        both = shapely.simplify(shapely.union(pieces[a], pieces[b]), GEOM_TOL)
        if both.geom_type == "Polygon" and _is_convex(both):
            pieces[a] = both
            del pieces[b]
            owner[b] = a
    return list(pieces.values())


def _prism(xy: np.ndarray, top: np.ndarray, bottom: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The convex prism over a convex plan polygon ``xy`` (K, 2) between the heights
    ``bottom`` and ``top`` (K,) at its corners (trimesh's hull, which keeps them as given)."""
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    hull = trimesh.convex.convex_hull(np.vstack([np.c_[xy, top], np.c_[xy, bottom]]))
    return np.asarray(hull.vertices, float), np.asarray(hull.faces, np.int64)


def _pieces(plans: list) -> list:
    """(plane, convex piece) for every region of every footprint of ``plans``."""
    import shapely  # deferred: shapely is slow to import; only meshes need it

    return [
        (plane, piece)
        for plane, plan in plans
        for region in shapely.get_parts(plan)
        for piece in convex_pieces(region)
    ]


def _whole(
    cells: list[tuple[np.ndarray, np.ndarray]], area: float
) -> list[tuple[np.ndarray, np.ndarray]]:
    """The prisms under one top piece as one part, their convex hull, where that hull holds
    no more than they do (to a :data:`GEOM_TOL` layer over the piece's ``area``: a bottom
    that is a convex function, a flat base meeting a rising soffit), so the top stays whole (a
    tread split in two is no tread for ``surfaces.find_walk_surfaces``); else the prisms."""
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    if len(cells) < 2:
        return cells
    hull = trimesh.convex.convex_hull(np.vstack([v for v, _ in cells]))
    if hull.volume - sum(trimesh.Trimesh(v, f).volume for v, f in cells) > GEOM_TOL * area:
        return cells
    return [(np.asarray(hull.vertices, float), np.asarray(hull.faces, np.int64))]


def extruded_parts(
    verts: np.ndarray, faces: np.ndarray
) -> list[tuple[np.ndarray, np.ndarray]] | None:
    """The exact convex decomposition of a closed mesh that every vertical line meets in one
    interval (no overhang: a stair, a plinth, a table, a soffit stair; not a shelf).

    A closed volume's boundary is crossed by a vertical line alternately downwards (into it)
    and upwards (out of it); when neither its upward nor its downward faces overlap in plan
    (``hiddenfaces.upward_planes``, any slope, each side's plane footprints covering the plan
    once; faces whose top view is thinner than :data:`GEOM_TOL` are walls), each line meets
    it once, so it is the union of the prisms between its bottom and top faces: each
    footprint cut into :func:`convex_pieces`, each top piece met with each bottom piece (a
    flat base: the top pieces extruded straight down), each cell a convex prism from the
    bottom plane to the top plane; a top piece's cells one part where their hull is
    (:func:`_whole`).

    Args:
        verts: (V, 3) vertices, z up (world orientation; any origin), metres.
        faces: (F, 3) vertex indices.

    Returns:
        The parts, (vertices (V_k, 3), faces (F_k, 3)) each, vertices in the frame given; None
        when the mesh is not a closed volume or has an overhang, or the parts' volume differs
        from the mesh's by more than a :data:`GEOM_TOL` layer over its footprint.
    """
    import shapely  # deferred: shapely is slow to import; only meshes need it
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    mesh = trimesh.Trimesh(np.asarray(verts, float), np.asarray(faces, np.int64), process=True)
    if not mesh.is_volume:
        return None
    v, f = np.asarray(mesh.vertices, float), np.asarray(mesh.faces, np.int64)
    tops = _plane_plans(v, f)
    bottoms = _plane_plans(v * [1.0, 1.0, -1.0], f[:, ::-1])  # mirrored: heights are -z
    if not tops or not _single_cover(tops) or not _single_cover(bottoms):
        return None  # a vertical line meets two faces of one side: an overhang
    parts = []
    lower = _pieces(bottoms)
    for top_plane, piece in _pieces(tops):
        cells = []
        for bottom_plane, under in lower:
            for cell in shapely.get_parts(shapely.intersection(piece, under)):
                if cell.geom_type != "Polygon" or cell.area <= GEOM_TOL * cell.length:
                    continue  # the pieces touch along a side or at a corner
                xy = np.asarray(shapely.simplify(cell, GEOM_TOL).exterior.coords)[:-1]
                top, bottom = top_plane.z_at(xy), -bottom_plane.z_at(xy)
                if np.min(top - bottom) > GEOM_TOL:
                    cells.append(_prism(xy, top, bottom))
        parts.extend(_whole(cells, piece.area))
    plan_area = shapely.union_all([p for _, p in tops]).area
    volume = sum(trimesh.Trimesh(pv, pf).volume for pv, pf in parts)
    if not parts or abs(volume - mesh.volume) > GEOM_TOL * plan_area:
        return None
    return parts


def _tops(
    parts: list[tuple[np.ndarray, np.ndarray]], xy: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Each convex part's top over each plan point: its height (P, N), metres (NaN where the
    vertical line misses the part), and its unit normal there (P, N, 3)."""
    from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

    out = np.full((len(parts), len(xy)), np.nan)
    normal = np.zeros((len(parts), len(xy), 3))
    for k, (v, _) in enumerate(parts):
        try:
            eq = ConvexHull(v).equations  # inside where n . p + d <= 0
        except QhullError:
            continue
        up, down, side = eq[:, 2] > 1e-9, eq[:, 2] < -1e-9, np.abs(eq[:, 2]) <= 1e-9
        rest = -(xy @ eq[:, :2].T + eq[:, 3])  # n_z z <= rest
        if not up.any():
            continue
        heights = rest[:, up] / eq[up, 2]
        hi = heights.min(axis=1)
        lo = np.max(rest[:, down] / eq[down, 2], axis=1, initial=-np.inf)
        inside = (lo <= hi + GEOM_TOL) & np.all(rest[:, side] >= -GEOM_TOL, axis=1)
        out[k, inside] = hi[inside]
        normal[k] = eq[up, :3][np.argmin(heights, axis=1)]
    return out, normal


def approximate_walk_faces(
    verts: np.ndarray,
    faces: np.ndarray,
    parts: list[tuple[np.ndarray, np.ndarray]],
    tolerance: float = STAIR_TOLERANCE,
) -> list[tuple[float, float]]:
    """The mesh's walk faces that no part's top reproduces within ``tolerance``.

    A walk face is a plane of upward faces a person can stand on (no steeper than
    ``norms.MAX_RAMP_SLOPE``, at least ``norms.MIN_TREAD`` by ``norms.STAND_WIDTH`` in area, as
    ``hiddenfaces``); at points :data:`SAMPLE_SPACING` apart on it (and a point on it), a part's
    top must lie within ``tolerance`` of it and be parallel to it within
    ``norms.HORIZONTAL_SLOPE`` (a top tilted more reads as another surface: a 0.28 m tread of
    CoACD's rising 3 mm is no tread for ``surfaces.find_walk_surfaces``).

    Args:
        verts: (V, 3) the mesh's vertices, z up, metres.
        faces: (F, 3) vertex indices.
        parts: its convex parts, (vertices (V_k, 3), faces) each, same frame.
        tolerance: the largest deviation accepted, metres (``norms.STAIR_TOLERANCE``, 5 mm).

    Returns:
        (height of the face, its largest deviation, metres; inf where no part's top is
        parallel to it at a point) per face off, lowest first.
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
        top, normal = _tops(parts, xy)
        gap = np.abs(top - plane.z_at(xy)[None, :])
        tilt = np.linalg.norm(np.cross(normal, plane.normal), axis=2)  # sine of the angle
        gap[tilt > HORIZONTAL_SLOPE] = np.nan
        worst = float(np.max(np.nanmin(np.where(np.isnan(gap), np.inf, gap), axis=0)))
        if worst > tolerance:
            off.append((float(plane.triangles[:, :, 2].mean()), worst))
    return sorted(off)
