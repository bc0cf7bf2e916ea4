"""Tests of mjwalk.mocap.skeletons: the skeleton presets, the up-axis check, the hip-line yaw."""

from __future__ import annotations

import numpy as np
import pytest
from test_bvh import TOY

from mjwalk.errors import CaptureError
from mjwalk.mocap.skeletons import SKELETONS, SkeletonMap, get_skeleton, hip_line_yaw


def test_presets_by_name():
    assert set(SKELETONS) >= {"bandai", "cmu", "cmu_bvh"}
    assert get_skeleton("bandai").pelvis == "Hips"
    assert get_skeleton("bandai").scale == pytest.approx(0.01)
    assert get_skeleton("cmu").scale == pytest.approx((1 / 0.45) * 2.54 / 100, rel=1e-4)
    assert get_skeleton(TOY) is TOY
    with pytest.raises(CaptureError, match="nosuch"):
        get_skeleton("nosuch")
    with pytest.raises(CaptureError, match="up axis must be"):
        SkeletonMap("bad", "a", "b", "c", "d", "e", "f", "g", up="x")


# ---------------------------------------------------------------- BVH forward kinematics


def test_hip_line_yaw_faces_forward_of_the_hips():
    # left hip on +y of the right one: the walker faces +x (yaw 0); left hip on -x: faces +y
    hip_r = np.zeros((3, 3))
    hip_l = np.array([[0.0, 0.2, 0.9], [-0.2, 0.0, 0.9], [0.0, -0.2, 0.9]])
    yaw = hip_line_yaw(hip_l, hip_r)
    np.testing.assert_allclose(yaw, [0.0, np.pi / 2, np.pi], atol=1e-12)  # unwrapped
