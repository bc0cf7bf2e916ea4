"""mjwalk.cycle.actions.wait_for: a wait stands still in the last pose for its duration."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.actions.base import CycleRun, CycleState
from mjwalk.cycle.actions.wait_for import Wait
from mjwalk.cycle.types import TASK_KINDS, Task


def _run(fps: float = 30.0) -> CycleRun:
    rng = np.random.default_rng(0)
    # a wait reads only the frame rate: no scene or models needed
    return CycleRun(None, None, fps, rng, rng, rng, np.zeros(5))  # type: ignore[arg-type]


def _state() -> CycleState:
    return CycleState(x=1.0, y=2.0, yaw=0.5, here="a", home=(1.0, 2.0), pose=np.arange(5.0))


@pytest.mark.parametrize(
    ("duration", "frames"),
    [(0.5, 15), (None, round(TASK_KINDS["wait"].default_hold * 30)), (0.001, 1)],
)
def test_a_wait_repeats_the_last_pose(duration, frames):
    state = _state()
    done = Wait(Task("wait", duration=duration), TASK_KINDS["wait"], 3).perform(_run(), state, None)
    ((poses, seconds),) = done.pieces
    assert poses.shape == (frames, 5)
    assert np.all(poses == state.pose[None])
    assert seconds == pytest.approx(frames / 30.0)
    assert done.state is state and done.record is None
