"""Walk faces a mesh's convex hull hides: a stair as one mesh has them, a bench has none."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from mjwalk.world.hiddenfaces import HIDDEN_DEPTH, hidden_walk_faces, upward_planes
from mjwalk.world.norms import MAX_RAMP_SLOPE


def _boxes(spec: list[tuple[float, float, float]], width: float = 1.0) -> trimesh.Trimesh:
    """Touching boxes (x0, x1, height) on z = 0, ``width`` along y, as one mesh."""
    parts = []
    for x0, x1, h in spec:
        b = trimesh.creation.box(extents=[x1 - x0, width, h])
        b.apply_translation([(x0 + x1) / 2, 0, h / 2])
        parts.append(b)
    return trimesh.util.concatenate(parts)


#: Three 0.17 m risers, 0.28 m treads, to a 2 m platform at 0.51 m (the steps and platform as
#: touching boxes, one mesh, as a CAD export of several bodies).
STAIR = [(0.0, 0.28, 0.17), (0.28, 0.56, 0.34), (0.56, 0.84, 0.51), (0.84, 2.84, 0.51)]


def test_a_one_mesh_stair_has_its_treads_hidden_under_its_hull():
    m = _boxes(STAIR)
    hidden = hidden_walk_faces(m.vertices, m.faces)
    assert [round(h.z, 3) for h in hidden] == [0.17, 0.34]
    # The hull rises from each nosing at 0.17 / 0.28: a sliver of HIDDEN_DEPTH / slope is free.
    for h in hidden:
        assert h.depth == pytest.approx(0.28 - HIDDEN_DEPTH * 0.28 / 0.17, abs=1e-5)
        assert h.width == pytest.approx(1.0, abs=1e-5)
    # Turned about z and moved, the same.
    rot = trimesh.transformations.rotation_matrix(0.7, [0, 0, 1])[:3, :3]
    turned = hidden_walk_faces(m.vertices @ rot.T + [3.0, -2.0, 1.0], m.faces)
    assert [round(h.z, 3) for h in turned] == [1.17, 1.34]


def test_no_hidden_faces_on_convex_or_narrow_or_plan_concave_meshes():
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    assert hidden_walk_faces(box.vertices, box.faces) == []
    # Treads 0.4 m wide: too narrow to stand on (norms.STAND_WIDTH 0.6 m).
    narrow = _boxes(STAIR, width=0.4)
    assert hidden_walk_faces(narrow.vertices, narrow.faces) == []
    # A U in plan of one height: its top is the hull's top.
    u = _boxes([(0.0, 0.4, 0.9), (1.8, 2.2, 0.9)], width=2.0)
    base = trimesh.creation.box(extents=[1.4, 0.4, 0.9])
    base.apply_translation([1.1, -0.8, 0.45])
    u = trimesh.util.concatenate([u, base])
    assert hidden_walk_faces(u.vertices, u.faces) == []
    # A flat mesh (one square) has no volume to hide anything.
    sq = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    assert hidden_walk_faces(sq, np.array([[0, 1, 2], [0, 2, 3]])) == []


def test_a_step_lower_than_the_tolerance_hides_nothing():
    """A 3 mm step onto a 2 m platform: its hull stands at most 3 mm over the lower part."""
    m = _boxes([(0.0, 1.0, 0.2), (1.0, 3.0, 0.203)])
    assert hidden_walk_faces(m.vertices, m.faces) == []


def test_a_face_at_exactly_the_ramp_limit_is_an_upward_plane_and_one_over_it_is_not():
    """A ramp face 0.3 m long rising 0.3 tan(10 deg): its normal's z came out 1e-16 under
    cos(10 deg), and the face was no walk face (before: ``upward_planes`` returned none); a
    face 0.01 deg steeper is still left out."""
    faces = np.array([[0, 1, 2], [0, 2, 3]])

    def ramp(slope: float) -> np.ndarray:
        rise = 0.3 * math.tan(slope)
        return np.array([[0, 0, 0], [0.3, 0, rise], [0.3, 1, rise], [0, 1, 0]], float)

    (plane,) = upward_planes(ramp(MAX_RAMP_SLOPE), faces)
    assert plane.normal[2] == pytest.approx(math.cos(MAX_RAMP_SLOPE), abs=1e-12)
    assert upward_planes(ramp(MAX_RAMP_SLOPE + math.radians(0.01)), faces) == []
