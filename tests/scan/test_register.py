"""mjwalk.scan.register: the free-space clash that verifies an alignment, and its report line
(the alignment itself, with Open3D, is exercised in test_merge.py)."""

from __future__ import annotations

import numpy as np

from mjwalk.scan.register import Alignment, clash


def _floor_with_post(post_x: float) -> np.ndarray:
    gx, gy = np.meshgrid(np.arange(0, 4, 0.03), np.arange(0, 4, 0.03))
    floor = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    far = np.hypot(floor[:, 0] - post_x, floor[:, 1] - 2.0) > 0.4
    px, pz = np.meshgrid(np.arange(post_x - 0.2, post_x + 0.2, 0.02), np.arange(0.1, 1.0, 0.02))
    post = np.column_stack([px.ravel(), np.full(px.size, 2.0), pz.ravel()])
    return np.vstack([floor[far], post])


def test_a_cloud_does_not_clash_with_itself_but_a_post_on_seen_floor_does():
    a = _floor_with_post(1.0)
    assert clash(a, a) == 0.0
    moved = _floor_with_post(3.0)  # its post stands where the other saw empty floor
    assert clash(moved, a) > 0.5


def test_alignment_line_names_the_figures():
    line = Alignment(np.eye(4), 0.8123, 0.0042, 0.011, 0.2, "b.ply").line()
    assert line.startswith("b.ply: registered, fitness 0.812")
    assert "RMSE 4.2 mm" in line and "clash 1.1 %" in line
