"""Tests of mjwalk.mocap.bvhwrite: a written file reads back to the same positions."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import CaptureError
from mjwalk.mocap import Take, load_bvh
from mjwalk.mocap.bvhwrite import write_bvh
from mjwalk.mocap.skeletons import SkeletonMap


def _take(n: int = 240) -> Take:
    t = np.arange(n) / 120.0
    x = 1.2 * t
    pelvis = np.stack([x, 0.1 * np.ones(n), 0.9 + 0.01 * np.sin(t)], axis=1)
    ankle = lambda dy: np.stack([x + 0.1 * np.sin(6 * t), dy + 0 * t, 0.08 + 0 * t], 1)  # noqa: E731
    toe = lambda dy: ankle(dy) + [0.14, 0.0, -0.06]  # noqa: E731
    return Take("w", 120.0, pelvis, np.zeros(n), ankle(0.18), ankle(0.02), toe(0.18), toe(0.02))


@pytest.mark.parametrize(("scale", "up"), [(0.01, "y"), (1.0, "z"), (0.0254, "y")])
def test_round_trip_exact(tmp_path, scale, up):
    take = _take()
    raw = SkeletonMap("raw", "Hips", "LeftFoot", "RightFoot", "LeftToeBase", "RightToeBase",
                      "LeftUpLeg", "RightUpLeg", scale=scale, up=up)  # fmt: skip
    back = load_bvh(write_bvh(take, tmp_path / "w.bvh", scale=scale, up=up), skeleton=raw)
    for k in ("pelvis", "ankle_l", "ankle_r", "toe_l", "toe_r"):
        np.testing.assert_allclose(getattr(back, k), getattr(take, k), atol=1e-5)
    np.testing.assert_allclose(back.pelvis_yaw, take.pelvis_yaw, atol=1e-6)


def test_names_prefix_and_rate(tmp_path):
    path = write_bvh(_take(), tmp_path / "m.bvh", "xsens_mvn", fps=30, prefix="ns:")
    text = path.read_text()
    assert "ROOT ns:Pelvis" in text and "JOINT ns:LeftUpperLeg" in text
    assert "Frames: 60" in text and "Frame Time: 0.03333333" in text


def test_bad_arguments(tmp_path):
    with pytest.raises(CaptureError, match="unknown convention"):
        write_bvh(_take(), tmp_path / "x.bvh", "nosuch")
    with pytest.raises(CaptureError, match="up axis"):
        write_bvh(_take(), tmp_path / "x.bvh", up="x")
