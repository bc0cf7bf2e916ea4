"""The planned path and footprints as flat boxes in a video frame (mjwalk.render.pathgeoms)."""

from __future__ import annotations

from types import SimpleNamespace

import mujoco
import numpy as np

from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.render.pathgeoms import FOOT_RGBA, PATH_RGBA, add_path_geoms, path_geoms


def test_path_boxes_follow_the_walk_and_one_box_per_footprint():
    walk = synthetic_walk(n_steps=4)
    geoms = path_geoms(SimpleNamespace(walk=walk), width=0.02, spacing=0.05)
    path = [g for g in geoms if g[3] is PATH_RGBA]
    feet = [g for g in geoms if g[3] is not PATH_RGBA]
    assert len(feet) == len(walk.steps)
    assert all(any(g[3] is c for c in FOOT_RGBA) for g in feet)
    arc = np.sum(np.linalg.norm(np.diff(walk.xy, axis=0), axis=1))
    assert len(path) == int(np.ceil(arc / 0.05))
    # the segments lie flat 3 mm above the floor, overlapping by the path's width
    assert all(g[1][2] == 0.003 and g[0][1] == 0.01 for g in path)
    chords = sum(2 * g[0][0] - 0.02 for g in path)  # resampled: chords cut the curves' corners
    assert 0.99 * arc < chords <= arc + 1e-9
    for size, _, mat, _ in geoms:
        assert size.shape == (3,) and np.allclose(np.linalg.det(mat.reshape(3, 3)), 1.0)
    assert path_geoms(SimpleNamespace(walk=None)) == []


def test_add_path_geoms_adds_as_many_as_fit():
    model = mujoco.MjModel.from_xml_string("<mujoco/>")
    scn = mujoco.MjvScene(model, maxgeom=3)
    geoms = path_geoms(SimpleNamespace(walk=synthetic_walk(n_steps=2)))
    assert len(geoms) > 3
    add_path_geoms(scn, geoms)
    assert scn.ngeom == 3
    np.testing.assert_allclose(scn.geoms[0].pos, geoms[0][1])
