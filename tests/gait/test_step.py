"""Tests of mjwalk.gait.step: the Step record's derived figures."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.step import Step


def test_step_duration_length_and_end_yaw():
    pelvis = np.column_stack([np.linspace(0.0, 0.03, 61), np.linspace(0.0, 0.4, 61)])
    step = Step(
        side="left",
        fps=120.0,
        pelvis=pelvis,
        yaw=np.linspace(0.0, 0.1, 61),
        footprint=np.array([-0.05, 0.6, 0.0]),
        stance=np.array([0.05, 0.0, 0.0]),
    )
    assert step.n_samples == 61
    assert step.duration == pytest.approx(0.5)
    assert step.length == pytest.approx(np.hypot(0.03, 0.4))
    assert step.end_yaw == pytest.approx(0.1)
    assert step.take == "" and step.index == 0 and step.meta == {}
