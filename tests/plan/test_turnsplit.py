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


def test_the_floor_is_square_to_the_work_not_to_the_last_reach():
    """A walker whose last reach turned it 20 deg off the work's front (facing 70 deg, the
    work's front 90 deg) and whose way lies at -40 deg (a 110 deg turn): the first steps go no
    nearer the work than square to its front (heading 0 deg), so the residual along them spans
    the cited 30-40 deg the work leaves (against a floor from the facing: heading -20 deg, 20 deg
    left); with the work's front given as the facing, the frames are those of no ``work``."""
    facing, work, way = (math.radians(d) for d in (70.0, 90.0, -40.0))
    rng = np.random.default_rng(4)
    residual = []
    for _ in range(300):
        frames = starter_frames(facing, way, 64, rng, work)
        assert frames is not None
        mid = wrap(float(np.mean(frames)) - way)  # the spread's mean, about the split
        residual.append(math.degrees(mid))
        # never nearer the work than square to its front (within the starter spread)
        assert np.all(frames <= work - AWAY_FROM_WORK + STARTER_SPREAD + 1e-9)
    r = np.array(residual)
    # 64 starters' mean: within 3 deg of the split (SD of the mean 0.7 deg)
    assert r.min() >= 30.0 - 3.0 and r.max() <= 40.0 + 3.0
    assert np.percentile(r, 90) - np.percentile(r, 10) >= 5.0  # spread, not pinned
    a, b = np.random.default_rng(5), np.random.default_rng(5)
    np.testing.assert_array_equal(
        starter_frames(1.0, 1.0 + math.radians(150.0), 8, a, work=1.0),
        starter_frames(1.0, 1.0 + math.radians(150.0), 8, b),
    )


def test_the_split_never_turns_past_the_way():
    """Facing 0 deg and turning 100 deg to the left. The work's front at -30 deg: square to it
    lies 60 deg from the facing, so the on-the-spot part is the turn less the residual (40-70
    deg). The work's front at 60 deg: square to it lies 150 deg away, past the way, so the whole
    turn is made on the spot (the starters about the way itself)."""
    way = math.radians(100.0)
    rng = np.random.default_rng(6)
    for _ in range(200):
        frames = starter_frames(0.0, way, 64, rng, math.radians(-30.0))
        assert frames is not None
        on_spot = math.degrees(float(np.mean(frames)))  # 64 starters: within 3 deg of the split
        assert 40.0 - 3.0 <= on_spot <= 70.0 + 3.0
        frames = starter_frames(0.0, way, 64, rng, math.radians(60.0))
        assert frames is not None
        assert np.all(np.abs(frames - way) <= STARTER_SPREAD + 1e-9)
