"""Tests of mjwalk.mocap.take: the Take's frame count, duration and sample times."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.mocap.take import TAKE_FPS, Take


def _take(n: int, fps: float = TAKE_FPS) -> Take:
    pelvis = np.zeros((n, 3))
    return Take("toy", fps, pelvis, np.zeros(n), pelvis, pelvis, pelvis, pelvis)


def test_take_rate_is_the_package_rate():
    assert TAKE_FPS == 120.0


def test_take_frames_duration_and_times():
    take = _take(241)
    assert take.n_frames == 241
    assert take.duration == pytest.approx(2.0)  # (n - 1) / fps
    np.testing.assert_allclose(take.time[[0, 1, -1]], [0.0, 1 / 120, 2.0])
    assert _take(31, fps=30.0).duration == pytest.approx(1.0)
    assert take.joints == {} and take.meta == {}
