"""Tests of mjwalk.gait.straight: step geometry helpers and straight runs of a capture."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.step import Step
from mjwalk.gait.straight import (
    compose,
    path_length,
    resample_step,
    step_widths,
    straight_runs,
    time_at,
)


def _step(side, index, take="t", yaw_end=0.0):
    return Step(
        side=side,
        fps=100.0,
        pelvis=np.column_stack([np.zeros(51), np.linspace(0.0, 0.5, 51)]),
        yaw=np.linspace(0.0, yaw_end, 51),
        footprint=np.array([0.1 if side == "right" else -0.1, 0.6, 0.0]),
        stance=np.array([-0.1 if side == "right" else 0.1, 0.0, 0.0]),
        take=take,
        index=index,
    )


def test_resample_path_length_and_widths():
    s = _step("right", 0)
    pts = resample_step(s, 11)
    assert pts.shape == (11, 2) and np.allclose(pts[:, 1], np.linspace(0, 0.5, 11))
    assert path_length(pts[None]) == pytest.approx([0.5])
    assert step_widths(np.array([[0.0, 0.5]]), s.footprint[None], s.stance[None]) == pytest.approx(
        [0.2]
    )


def test_compose_turns_local_steps_into_the_world():
    world, phi = compose(np.array([1.0, 2.0]), np.pi / 2, np.array([0.0, 1.0]), 0.3)
    assert np.allclose(world, [0.0, 2.0]) and phi == pytest.approx(np.pi / 2 + 0.3)


def test_straight_runs_keep_the_longest_straight_run_per_take():
    steps = [_step("left", 0), _step("right", 1), _step("left", 2), _step("left", 3)]
    steps += [_step("left", 0, "turn", 0.3), _step("right", 1, "turn", 0.3)]
    runs = straight_runs(steps, straight_deg=20.0)
    assert [[s.index for s in r] for r in runs] == [[0, 1, 2]]  # "turn": 34 deg in total


def test_time_at_interpolates_and_extrapolates():
    track = [(0.0, 0.0), (0.5, 0.6), (1.0, 1.2)]
    assert time_at(track, 0.9) == pytest.approx(0.75)
    assert time_at(track, 1.5) == pytest.approx(1.25)
    assert time_at([(0.0, 0.0)], 1.0) == 0.0
