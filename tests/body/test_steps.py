"""A walk's steps as the leg synthesis sees them (mjwalk.body.legs.steps)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.legs.reference import DEFAULT_REFERENCE
from mjwalk.body.legs.steps import STANCE_KEYS, stance_angle, step_frames
from mjwalk.plan.synthetic import synthetic_walk


def test_step_frames_chain_the_footprints():
    """One frame per step, sides alternating, first/final flagged; each step lifts the foot
    the previous step stood on, and the first lifts a foot mirrored beside the stance foot."""
    walk = synthetic_walk(n_steps=4)
    frames = step_frames(walk)
    assert len(frames) == 4
    assert [f.first for f in frames] == [True, False, False, False]
    assert [f.final for f in frames] == [False, False, False, True]
    for k, (fr, st) in enumerate(zip(frames, walk.steps, strict=True)):
        assert fr.side == ("l" if st.side == "left" else "r") and fr.other != fr.side
        assert (fr.start, fr.end) == (st.start, st.end)
        assert np.array_equal(fr.land, st.foot) and np.array_equal(fr.stance, st.stance)
        if k:
            assert np.array_equal(fr.lift, walk.steps[k - 1].stance)
    f0 = frames[0]
    mid = 0.5 * (f0.lift[:2] + f0.stance[:2])
    n = np.array([-np.sin(walk.yaw[f0.start]), np.cos(walk.yaw[f0.start])])
    assert (mid - walk.xy[f0.start]) @ n == pytest.approx(0.0, abs=1e-12)


def test_stance_angle_meets_boundaries_and_keys():
    """The stance angle starts at th0, ends at th1 and equals the reference at the keys."""
    phi = np.array([0.0, *STANCE_KEYS, 1.0])
    a = stance_angle(DEFAULT_REFERENCE, "knee", phi, 0.3, 0.0, 0.1, 0.0)
    assert a[0] == pytest.approx(0.3) and a[-1] == pytest.approx(0.1)
    assert np.allclose(a[1:4], DEFAULT_REFERENCE("knee", 0.5 * np.array(STANCE_KEYS)))
