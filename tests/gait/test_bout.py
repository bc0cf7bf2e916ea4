"""Tests of mjwalk.gait.bout: a step plan rendered into a take."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.bout import ANKLE_HEIGHT, TOE_HEIGHT, BoutPlan, render_bout
from mjwalk.gait.subjects import sample_subject
from mjwalk.mocap.take import TAKE_FPS

PLAN = BoutPlan(
    fwd=[0.5, 0.6, 0.6, 0.3], lat=[0.0] * 4, dtheta=[0.0] * 4, dur=[0.6, 0.55, 0.55, 0.55]
)


def _render(seed: int = 0):
    p = sample_subject(np.random.default_rng(1), 0)
    rng = np.random.default_rng(seed)
    return p, render_bout(PLAN, p, rng, "bout", np.zeros(2), 0.0, {"protocol": "test"})


def test_bout_walks_its_plan_and_closes_side_by_side():
    p, take = _render()
    assert take.name == "bout" and take.fps == TAKE_FPS
    assert take.meta["protocol"] == "test" and take.meta["n_steps"] == 4
    hs = take.meta["heel_strikes"]
    assert len(hs["left"]) + len(hs["right"]) == 4
    assert abs(len(hs["left"]) - len(hs["right"])) <= 1
    # heading +x: the walking line advances 0.5 + 0.6 + 0.6 m, the closing step lands beside
    end_l, end_r = take.ankle_l[-1], take.ankle_r[-1]
    assert end_l[0] == pytest.approx(1.7) and end_r[0] == pytest.approx(1.7)
    assert end_l[1] > 0.0 > end_r[1]  # left foot on the left (+y), half a width each
    assert end_l[1] - end_r[1] == pytest.approx(p.step_width, abs=0.05)
    assert end_l[2] == pytest.approx(ANKLE_HEIGHT) and take.toe_l[-1, 2] == pytest.approx(
        TOE_HEIGHT
    )
    # the pendulum pelvis starts and settles over the middle of the feet
    assert np.allclose(take.pelvis[0, :2], 0.0, atol=0.01)
    assert take.pelvis[-1, 0] == pytest.approx(1.7, abs=0.01)
    assert take.pelvis[-1, 1] == pytest.approx(0.0, abs=0.01)


def test_bout_is_deterministic_in_its_generator():
    _, a = _render(3)
    _, b = _render(3)
    _, c = _render(4)
    assert np.array_equal(a.pelvis, b.pelvis) and np.array_equal(a.ankle_l, b.ankle_l)
    assert a.n_frames != c.n_frames or not np.array_equal(a.pelvis, c.pelvis)
