"""How a standing walker splits a large turn into a walk (issue 48, station spread): the
residual turned along the first steps is Patla et al.'s one-step direction change, the rest is
turned on the spot, never less than square away from the work."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.plan.turnsplit import (
    AWAY_FROM_WORK,
    STARTER_SPREAD,
    WALKING_TURN_MAX,
    WALKING_TURN_MIN,
    residual_turn,
    starter_frames,
    wrap,
)


def test_wrap_keeps_the_direction_within_a_half_turn():
    assert wrap(3.0 * math.pi / 2.0) == pytest.approx(-math.pi / 2.0)
    assert wrap(-3.0 * math.pi / 2.0) == pytest.approx(math.pi / 2.0)
    assert wrap(0.3) == pytest.approx(0.3)


def test_the_residual_lies_between_the_cited_one_step_changes():
    rng = np.random.default_rng(0)
    r = np.array([residual_turn(rng) for _ in range(2000)])
    assert r.min() >= WALKING_TURN_MIN and r.max() <= WALKING_TURN_MAX
    # uniform between 30 and 60 degrees: mean 45 (SE about 0.2 degrees over 2000 draws)
    assert math.degrees(r.mean()) == pytest.approx(45.0, abs=1.0)


@pytest.mark.parametrize("turn_deg", [0.0, 50.0, -89.0, 90.0])
def test_a_turn_up_to_a_quarter_is_left_to_the_search(turn_deg):
    rng = np.random.default_rng(1)
    assert starter_frames(0.4, 0.4 + math.radians(turn_deg), 8, rng) is None


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_half_turn_sets_off_the_residual_short_of_the_way(sign):
    """Facing 1 rad, the way 160 deg to one side: the starters head 100-130 deg from the
    facing (within the starter spread), to the same side; 200 seeded walks."""
    facing, turn = 1.0, sign * math.radians(160.0)
    rng = np.random.default_rng(2)
    for _ in range(200):
        frames = starter_frames(facing, facing + turn, 16, rng)
        assert frames is not None and frames.shape == (16,)
        on_spot = np.array([wrap(f - facing) for f in frames]) * sign
        lo = math.radians(160.0) - WALKING_TURN_MAX - STARTER_SPREAD
        hi = math.radians(160.0) - WALKING_TURN_MIN + STARTER_SPREAD
        assert on_spot.min() >= lo - 1e-9 and on_spot.max() <= hi + 1e-9


def test_the_first_step_never_heads_nearer_the_work_than_square():
    """A 110 deg turn: the residual would leave the first step 50-80 deg from the facing
    (towards the work faced); it sets off square to it instead (90 deg, within the spread)."""
    rng = np.random.default_rng(3)
    for _ in range(100):
        frames = starter_frames(0.0, math.radians(110.0), 8, rng)
        assert frames is not None
        assert np.all(np.abs(frames - AWAY_FROM_WORK) <= STARTER_SPREAD + 1e-9)
