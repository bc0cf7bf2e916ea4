"""Foot checks by MuJoCo forward kinematics (mjwalk.body.legs.footcheck)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.legs.footcheck import foot_points, lowest_point, posed, stance_drift
from mjwalk.body.legs.synthesis import legs_from_walk
from mjwalk.plan.synthetic import synthetic_walk


@pytest.fixture(scope="module")
def short_walk():
    walk = synthetic_walk(n_steps=4)
    return walk, legs_from_walk(walk)


def test_posed_frames_follow_the_leg_motion(short_walk):
    """posed yields every frame with the pelvis where the motion puts it and the feet on
    the floor at the start (lowest sole corner within 2 mm of z = 0)."""
    _, legs = short_walk
    frames = 0
    for i, model, data in posed(legs):
        assert np.allclose(data.xpos[model.body("pelvis").id], legs.root[i])
        if i == 0:
            feet = [model.geom(g).id for g in ("foot_l", "foot_r", "toes_l", "toes_r")]
            assert lowest_point(model, data, feet) == pytest.approx(0.0, abs=2e-3)
        frames += 1
    assert frames == len(legs.t)


def test_foot_points_and_stance_drift(short_walk):
    """Shapes of foot_points; the synthetic walk's stance feet stay within 1 cm, and moving
    one foot's ball during a stance shows up as drift."""
    walk, legs = short_walk
    pts, pitch, low = foot_points(legs)
    n = len(legs.t)
    assert pts.shape == (n, 2, 2, 3) and pitch.shape == (n, 2) and low.shape == (n,)
    assert stance_drift(walk, pts, pitch) <= 0.01
    st = walk.steps[1]
    k = 0 if st.side == "right" else 1  # the stance foot's index (l = 0, r = 1)
    moved = pts.copy()
    moved[st.start + (st.end - st.start) // 2 :, k, :, 0] += 0.05
    assert stance_drift(walk, moved, pitch) > 0.04
