"""The swing foot of one step, compiled (mjwalk.body.legs.swing)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import leg_geometry, pelvis_height
from mjwalk.body.legs import steps
from mjwalk.body.legs.footpivot import pivot_ankle
from mjwalk.body.legs.reference import DEFAULT_REFERENCE
from mjwalk.body.legs.steps import TOE_OFF, step_frames
from mjwalk.body.legs.swing import swing_foot
from mjwalk.plan.synthetic import synthetic_walk


def test_swing_lands_on_its_footprint_as_the_numpy_swing():
    """The second step of a straight walk: the foot leaves its lift-off footprint flat-toed,
    lands on its landing footprint with the landing pitch and heading, toes straight, toe-off
    no later than TOE_OFF; the same numbers as steps.swing_foot (to 1e-12)."""
    g = leg_geometry(1.75)
    walk = synthetic_walk(n_steps=4)
    fr = step_frames(walk)[1]
    fr.land_p = 0.1
    idx = np.arange(fr.start, fr.end + 1)
    phi = (idx - fr.start) / (fr.end - fr.start)
    s = 1.0 if fr.side == "l" else -1.0
    yaw = walk.yaw[idx]
    hip_xy = walk.xy[idx] + s * g.hip_y * np.column_stack([-np.sin(yaw), np.cos(yaw)])
    z_hip = np.full(len(idx), pelvis_height(1.75) - 0.03)
    pos, p, toe, fyaw, phi_to = swing_foot(fr, phi, hip_xy, z_hip, DEFAULT_REFERENCE, g, 0.1)
    assert pos.shape == (len(idx), 3) and p.shape == toe.shape == fyaw.shape == (len(idx),)
    assert 0 < phi_to <= TOE_OFF
    assert np.allclose(pos[0], pivot_ankle(fr.lift, np.array([p[0]]), g)[0])
    assert np.allclose(pos[-1], pivot_ankle(fr.land, np.array([0.1]), g)[0])
    assert p[-1] == pytest.approx(0.1) and fyaw[-1] == pytest.approx(fr.land[2])
    assert toe[-1] == pytest.approx(0.0, abs=1e-9)
    assert pos[:, 2].min() >= g.ankle_height * 0.99
    want = steps.swing_foot(
        fr, phi, np.arange(len(phi)), z_hip,
        lambda i, side, zz=None: hip_xy[i] if zz is None else np.column_stack([hip_xy[i], zz]),
        DEFAULT_REFERENCE, g, 0.1,
    )  # fmt: skip
    for x, y in zip(want, (pos, p, toe, fyaw, phi_to), strict=True):
        assert np.allclose(x, y, rtol=0, atol=1e-12)
