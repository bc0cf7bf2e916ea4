"""The exact decomposition of a mesh without overhangs, and the check of an approximate one."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
import trimesh

from mjwalk.world.meshextrude import (
    GEOM_TOL,
    approximate_walk_faces,
    convex_pieces,
    extruded_parts,
)


def prism(poly: shapely.Polygon, height: float) -> trimesh.Trimesh:
    """A closed prism over a simple polygon, z from 0 to ``height`` (shapely's constrained
    Delaunay triangles for its ends: trimesh's own needs an optional engine)."""
    ext = np.asarray(shapely.orient_polygons(poly).exterior.coords)[:-1]
    n = len(ext)
    index = {tuple(p): i for i, p in enumerate(ext.round(9))}
    faces = []
    for t in shapely.get_parts(shapely.constrained_delaunay_triangles(poly)):
        c = np.asarray(t.exterior.coords)[:-1]
        ids = [index[tuple(p)] for p in c.round(9)]
        d = (c[1, 0] - c[0, 0]) * (c[2, 1] - c[0, 1]) - (c[2, 0] - c[0, 0]) * (c[1, 1] - c[0, 1])
        ids = ids if d > 0 else ids[::-1]
        faces += [[ids[2], ids[1], ids[0]], [i + n for i in ids]]
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, j + n], [i, j + n, i + n]]
    verts = np.vstack([np.c_[ext, np.zeros(n)], np.c_[ext, np.full(n, height)]])
    mesh = trimesh.Trimesh(verts, np.array(faces))
    assert mesh.is_volume
    return mesh


def side_view(profile: list[tuple[float, float]], width: float) -> trimesh.Trimesh:
    """A closed mesh: the (x, z) ``profile`` extruded ``width`` along y, centred on y = 0."""
    mesh = prism(shapely.Polygon(profile), width)
    mesh.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [1, 0, 0]))
    mesh.apply_translation([0, width / 2, 0])
    assert mesh.is_volume
    return mesh


def stair_profile(risers: int = 3, platform: float = 2.0) -> list[tuple[float, float]]:
    """Risers of 0.17 m, treads of 0.28 m, then a platform ``platform`` long (x, z)."""
    end = risers * 0.28 + platform
    pts = [(0.0, 0.0), (end, 0.0), (end, risers * 0.17)]
    for i in range(risers - 1, 0, -1):
        pts += [(i * 0.28, (i + 1) * 0.17), (i * 0.28, i * 0.17)]
    return pts + [(0.0, 0.17)]


#: A table as one closed mesh: a 1.2 m top 0.03 m thick at 0.72 m on a 0.3 m pedestal.
TABLE = [(0.45, 0), (0.75, 0), (0.75, 0.72), (1.2, 0.72), (1.2, 0.75), (0, 0.75), (0, 0.72)]
TABLE += [(0.45, 0.72)]
#: A shelf as one closed mesh: a back and three boards (a vertical line meets it three times).
SHELF = [(0, 0), (1.0, 0), (1.0, 0.03), (0.05, 0.03), (0.05, 0.8), (1.0, 0.8), (1.0, 0.83)]
SHELF += [(0.05, 0.83), (0.05, 1.6), (1.0, 1.6), (1.0, 1.63), (0, 1.63)]


def _volume(parts) -> float:
    return sum(trimesh.Trimesh(v, f).volume for v, f in parts)


@pytest.mark.parametrize("platform", [2.0, 10.0])
def test_a_one_mesh_stair_is_one_prism_per_tread_exactly(platform):
    mesh = side_view(stair_profile(3, platform), 1.0)
    parts = extruded_parts(mesh.vertices, mesh.faces)
    assert parts is not None and len(parts) == 3  # the last tread and platform: one plane
    assert sorted(v[:, 2].max() for v, _ in parts) == pytest.approx([0.17, 0.34, 0.51], abs=1e-12)
    assert all(v[:, 2].min() == pytest.approx(0.0, abs=1e-12) for v, _ in parts)
    assert _volume(parts) == pytest.approx(mesh.volume, abs=1e-9)
    assert approximate_walk_faces(mesh.vertices, mesh.faces, parts) == []


def test_a_stair_with_a_sloped_soffit_keeps_each_tread_whole():
    """The flat base meets the rising soffit under tread 1: its two cells are one convex part
    (under the platform the soffit meets the flat underside, a concave bottom: two parts)."""
    profile = [(0, 0), (0, 0.17), (0.28, 0.17), (0.28, 0.34), (0.56, 0.34), (0.56, 0.51)]
    profile += [(2.84, 0.51), (2.84, 0.31), (0.84, 0.31), (0.2, 0.0)]
    mesh = side_view(profile[::-1], 3.0)
    parts = extruded_parts(mesh.vertices, mesh.faces)
    assert parts is not None and len(parts) == 4
    assert _volume(parts) == pytest.approx(mesh.volume, abs=1e-9)
    tops = sorted((v[:, 2].max(), np.ptp(v[:, 0])) for v, _ in parts)
    assert [t for t, _ in tops] == pytest.approx([0.17, 0.34, 0.51, 0.51], abs=1e-12)
    assert tops[0][1] == pytest.approx(0.28, abs=1e-12)  # tread 1 whole


def test_an_l_shaped_footprint_is_cut_into_convex_pieces_that_fill_it():
    ell = shapely.Polygon([(0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3)])
    pieces = convex_pieces(ell)
    assert len(pieces) == 2
    for p in pieces:
        assert p.convex_hull.area == pytest.approx(p.area, abs=1e-12)
    assert shapely.union_all(pieces).symmetric_difference(ell).area == pytest.approx(0, abs=1e-12)
    assert sum(p.area for p in pieces) == pytest.approx(ell.area, abs=1e-12)
    square = shapely.box(0, 0, 2, 2)
    assert convex_pieces(square)[0].equals(square)
    # a platform on that footprint: two prisms, its volume
    platform = prism(ell, 0.5)
    parts = extruded_parts(platform.vertices, platform.faces)
    assert len(parts) == 2 and _volume(parts) == pytest.approx(platform.volume, abs=1e-9)


def test_a_table_s_parts_leave_the_floor_under_its_top_free():
    from scipy.spatial import Delaunay

    mesh = side_view(TABLE, 0.8)
    parts = extruded_parts(mesh.vertices, mesh.faces)
    assert parts is not None and _volume(parts) == pytest.approx(mesh.volume, abs=1e-9)
    under_top = np.array([0.2, 0.0, 0.4])  # beside the pedestal, under the top
    assert all(Delaunay(v).find_simplex(under_top) < 0 for v, _ in parts)
    assert max(v[:, 2].max() for v, _ in parts) == pytest.approx(0.75, abs=1e-12)


def test_a_shelf_or_an_open_mesh_is_not_decomposed_exactly():
    shelf = side_view(SHELF, 1.2)
    assert extruded_parts(shelf.vertices, shelf.faces) is None
    stair = side_view(stair_profile(), 1.0)
    open_mesh = stair.copy()
    open_mesh.update_faces(np.arange(len(open_mesh.faces)) != 0)
    assert extruded_parts(open_mesh.vertices, open_mesh.faces) is None


def test_walk_faces_no_part_top_reproduces_are_named():
    mesh = side_view(stair_profile(), 1.0)
    hull = mesh.convex_hull
    off = approximate_walk_faces(mesh.vertices, mesh.faces, [(hull.vertices, hull.faces)])
    assert [z for z, _ in off] == pytest.approx([0.17, 0.34])
    # the hull's top over each tread rises 0.17 per 0.28 m: parallel to it nowhere
    assert all(d == math.inf for _, d in off)
    parts = extruded_parts(mesh.vertices, mesh.faces)
    lifted = [(v + [0, 0, 0.006], f) if v[:, 2].max() < 0.2 else (v, f) for v, f in parts]
    assert [z for z, _ in approximate_walk_faces(mesh.vertices, mesh.faces, lifted)] == [
        pytest.approx(0.17)
    ]
    tilted = [
        (v + np.c_[np.zeros((len(v), 2)), 0.012 * v[:, 0]], f) if v[:, 2].max() < 0.2 else (v, f)
        for v, f in parts
    ]  # tread 1 rising 1.2 %, at most 3.4 mm off: parallel it is not
    assert len(approximate_walk_faces(mesh.vertices, mesh.faces, tilted)) == 1
    assert GEOM_TOL < 0.001
