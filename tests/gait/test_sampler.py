"""The step-sampler protocol (mjwalk.gait.sampler): the straight walks and the pace take any
sampler, not only a StepModel."""

import numpy as np
import pytest

from mjwalk.gait.features import StepBatch
from mjwalk.gait.model import StepModel
from mjwalk.gait.pace import PACE_WALKS, SKIP_END, SKIP_START, model_pace
from mjwalk.gait.sampler import StepSampler
from mjwalk.gait.straight import model_straight_walks

LENGTH, DURATION, WIDTH = 0.7, 0.55, 0.1  # every step: metres ahead, seconds, metres apart


class MetronomeSampler:
    """Every step the same: ``LENGTH`` straight ahead in ``DURATION``, feet ``WIDTH`` apart."""

    def _steps(self, sides: np.ndarray) -> StepBatch:
        n = len(sides)
        landmarks = np.zeros((n, 6, 2))
        landmarks[:, :, 1] = np.linspace(0.0, LENGTH, 6)
        swing_x = np.where(sides == "left", -WIDTH / 2, WIDTH / 2)
        return StepBatch(
            side=sides,
            features=np.zeros((n, 3)),
            landmarks=landmarks,
            yaw_landmarks=np.zeros((n, 6)),
            duration=np.full(n, DURATION),
            footprint=np.column_stack([swing_x, np.full(n, LENGTH), np.zeros(n)]),
            stance=np.column_stack([-swing_x, np.full(n, LENGTH / 2), np.zeros(n)]),
        )

    def sample_first(self, n, rng, side=None):
        sides = ["left"] * (n - n // 2) + ["right"] * (n // 2) if side is None else [side] * n
        return self._steps(np.array(sides, dtype="<U5"))

    def sample_next(self, prev, n, rng):
        return self._steps(np.repeat(np.where(prev.side == "left", "right", "left"), n))


def test_the_step_model_and_a_hand_made_sampler_are_step_samplers():
    assert issubclass(StepModel, StepSampler)
    assert isinstance(MetronomeSampler(), StepSampler)
    assert not isinstance(object(), StepSampler)


def test_straight_walks_stop_at_the_last_step_that_brings_the_walker_closer():
    # 7.2 m: ten 0.7 m steps end 0.2 m short; an eleventh would overshoot to 0.5 m
    (walk,) = model_straight_walks(MetronomeSampler(), np.array([7.2]), np.random.default_rng(0))
    assert walk["n_steps"] == 10
    assert walk["step_time"] == pytest.approx(10 * DURATION)
    assert walk["path_length"] == pytest.approx(10 * LENGTH)
    assert walk["end_error"] == pytest.approx(0.2)


def test_the_pace_of_any_sampler_is_its_steady_steps():
    pace = model_pace(MetronomeSampler())
    # 8 m walks: 11 steps each (the 12th would overshoot), of which the steady ones count
    assert pace.n_steps == PACE_WALKS * (11 - SKIP_START - SKIP_END)
    assert (pace.step_length, pace.step_duration, pace.step_width) == pytest.approx(
        (LENGTH, DURATION, WIDTH)
    )
