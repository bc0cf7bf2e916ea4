"""Tests of mjwalk.gait.speedprofile: speed-up, slow-down and curve speed of a walk."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.speedprofile import MOVING_SPEED, curve_speed_ratio, start_stop_distances


def _walk(fps: float = 120.0) -> np.ndarray:
    """Standing 1 s, speeding up over 2 s, 6 s at 1.2 m/s, slowing over 2 s, standing 1 s."""
    v = np.concatenate(
        [np.zeros(120), np.linspace(0, 1.2, 240), np.full(720, 1.2), np.linspace(1.2, 0, 240)]
    )
    v = np.concatenate([v, np.zeros(120)])
    x = np.cumsum(v) / fps
    return np.column_stack([x, np.zeros_like(x)])


def test_start_stop_distances_of_a_symmetric_walk():
    up, down, steady = start_stop_distances(_walk(), 120.0)
    assert steady == pytest.approx(1.2, rel=1e-3)
    # 90 % of 1.2 m/s reached after 1.8 s of uniform speeding up: about 0.97 m
    assert up == pytest.approx(down, rel=0.05) and 0.8 < up < 1.1
    assert start_stop_distances(np.zeros((600, 2)), 120.0) is None  # never moves
    assert MOVING_SPEED < 1.2


def test_curve_speed_ratio_needs_curves():
    assert np.isnan(curve_speed_ratio(_walk(), 120.0))  # straight: no curve samples
    t = np.arange(1200) / 120.0
    circle = np.column_stack([np.cos(0.8 * t), np.sin(0.8 * t)])  # 0.8 m/s, 46 deg/s
    assert np.isnan(curve_speed_ratio(circle, 120.0))  # curve only: no straight samples
