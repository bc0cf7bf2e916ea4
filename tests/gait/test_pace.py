"""Tests of mjwalk.gait.pace: the Pace record, stretching a step, measuring on capture."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait.pace import PACE_VERSION, Pace, capture_pace, normalize_paces, stretch_step
from mjwalk.gait.step import Step


def test_pace_figures_and_dict_roundtrip():
    pace = Pace(step_length=0.7, step_duration=0.5, step_width=0.08, n_steps=12)
    assert pace.speed == pytest.approx(1.4) and pace.cadence == pytest.approx(120.0)
    d = pace.as_dict()
    assert d["version"] == PACE_VERSION and d["speed"] == 1.4
    assert Pace.from_dict(d) == pace


def test_stretch_step_scales_its_local_frame_and_time():
    step = Step(
        side="right",
        fps=120.0,
        pelvis=np.column_stack([np.full(61, 0.01), np.linspace(0, 0.6, 61)]),
        yaw=np.zeros(61),
        footprint=np.array([0.05, 0.7, 0.1]),
        stance=np.array([-0.05, 0.0, -0.1]),
    )
    out = stretch_step(step, lateral=2.0, forward=1.5, time=1.25)
    assert out.duration == pytest.approx(1.25 * step.duration)
    assert out.length == pytest.approx(np.hypot(0.02, 0.9))
    assert np.allclose(out.footprint, [0.1, 1.05, 0.1]) and np.allclose(out.stance, [-0.1, 0, -0.1])
    assert step.footprint[0] == 0.05  # the original is untouched


def test_capture_pace_needs_straight_steps():
    with pytest.raises(MjwalkError, match="steady straight steps"):
        capture_pace([])
    assert normalize_paces([]) == ([], {})
