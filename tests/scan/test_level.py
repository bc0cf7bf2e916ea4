"""mjwalk.scan.level: the floor of a cloud found and levelled; upside-down clouds refused."""

from __future__ import annotations

import numpy as np
import pytest
from test_scene import _room_cloud

from mjwalk.errors import ScanError
from mjwalk.scan.level import check_upright, find_floor, voxel_normals, walk_surfaces


def _tilted(pts: np.ndarray, deg: float) -> np.ndarray:
    t = np.radians(deg)
    rot = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(t), -np.sin(t)], [0.0, np.sin(t), np.cos(t)]])
    return pts @ rot.T + [0.0, 0.0, 0.8]


def test_a_tilted_lifted_room_is_levelled_onto_z_0():
    room = _room_cloud()
    lv = find_floor(_tilted(room, 2.0))
    assert lv.tilt_deg == pytest.approx(2.0, abs=0.05)
    assert lv.floor_area == pytest.approx(12.0, rel=0.1)
    levelled = lv.apply(_tilted(room, 2.0))
    floor = np.abs(room[:, 2]) < 0.01  # the floor points of the room as built
    assert np.abs(levelled[floor, 2]).max() < 0.03
    m = lv.matrix
    p = _tilted(room[:5], 2.0)
    np.testing.assert_allclose(p @ m[:3, :3].T + m[:3, 3], lv.apply(p), atol=1e-9)
    check_upright(levelled)  # the room's contents are above its floor


def test_upside_down_and_floorless_clouds_are_refused():
    room = _room_cloud()
    lv = find_floor(room)
    with pytest.raises(ScanError, match=r"upside down for --up=\+z; pass --up=-z"):
        check_upright(lv.apply(room) * [1.0, -1.0, -1.0], "+z", "room")
    wall = np.column_stack([np.zeros(2000), *np.random.default_rng(0).uniform(0, 3, (2, 2000))])
    with pytest.raises(ScanError, match="wall: no floor found"):
        find_floor(wall, source="wall")


def test_voxel_normals_of_a_floor_point_up_and_form_one_surface():
    gx, gy = np.meshgrid(np.arange(0, 2, 0.02), np.arange(0, 2, 0.02))
    floor = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    vn = voxel_normals(floor, 0.1)
    assert np.abs(vn.normal[:, 2]).min() > 0.999
    labels = walk_surfaces(vn)
    assert set(labels.tolist()) == {0}
