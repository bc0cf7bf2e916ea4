"""The found chain's decode (mjwalk.plan.assemble): local step frames to the world."""

from __future__ import annotations

import math

import numpy as np

from mjwalk.plan.assemble import FPS, to_world


def test_to_world_turns_local_axes_by_the_heading():
    # local x is right of the heading, y along it
    local = np.array([[0.0, 1.0], [1.0, 0.0], [0.0, 0.0]])
    east = to_world(2.0, 3.0, 0.0, local)  # heading +x: forward is +x, right is -y
    np.testing.assert_allclose(east, [[3.0, 3.0], [2.0, 2.0], [2.0, 3.0]], atol=1e-12)
    north = to_world(0.0, 0.0, math.pi / 2, local)  # heading +y: forward +y, right +x
    np.testing.assert_allclose(north, [[0.0, 1.0], [1.0, 0.0], [0.0, 0.0]], atol=1e-12)


def test_to_world_broadcasts_frames_and_keeps_lengths():
    rng = np.random.default_rng(0)
    local = rng.normal(size=(5, 2))
    heading = rng.uniform(-math.pi, math.pi, 5)
    out = to_world(np.zeros(5), np.zeros(5), heading, local)
    assert out.shape == (5, 2)
    np.testing.assert_allclose(np.linalg.norm(out, axis=1), np.linalg.norm(local, axis=1))
    assert FPS == 120.0
