"""A level walk that comes to a flight from the side turns into it while walking
(mjwalk.plan.turnin). Seeded."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH, ENTRY_TURN, cross_walk, flight_start
from mjwalk.plan.levelroute import crossings
from mjwalk.plan.turnin import (
    BACK_STRIDE,
    CUT_STEPS,
    TURN_STEP_SHARES,
    turn_in_steps,
    turn_in_time,
    turned_steps,
    walked_back,
)
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.plan.walks import plan_walk
from mjwalk.world import load_workplace
from mjwalk.world.levelview import level_view


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


@pytest.fixture(scope="module")
def stair(station):
    return next(c for c in crossings(station.levels, 0.30) if c.kind == "stair")


def _walk_north(x: float, y0: float, y1: float, yaw: float = math.pi / 2) -> WalkPath:
    """A straight synthetic level walk north along x from y0 to y1, 0.7 m steps, 120 Hz, its
    last step a closing step (feet together)."""
    ys = np.arange(y0, y1 + 1e-9, 0.7)
    steps, t = [], 0
    for k in range(1, len(ys)):
        side = "left" if k % 2 else "right"
        sign = 1.0 if side == "left" else -1.0
        foot = np.array([x - sign * 0.06, ys[k], yaw])
        stance = np.array([x + sign * 0.06, ys[k - 1], yaw])
        steps.append(PathStep(side, t, t + 60, foot, stance))
        t += 60
    closing = PathStep("left" if len(ys) % 2 else "right", t, t + 60,
                       np.array([x, ys[-1], yaw]), np.array([x, ys[-1], yaw]))  # fmt: skip
    steps.append(closing)
    n = t + 61
    y = np.interp(np.arange(n), [0, t, n - 1], [y0, ys[-1], ys[-1]])
    return WalkPath(np.arange(n) / 120.0, np.stack([np.full(n, x), y], 1), np.full(n, yaw), steps)


def test_a_walk_up_beside_the_stair_turns_into_it_in_steps_of_at_most_entry_turn(station, stair):
    """A walk coming north up the gap east of the stair (x = -4.0; the stair goes up to -y at
    x = -4.9) that ends beside its approach point turns into it after one of its last walking
    steps: every turning step turns at most ENTRY_TURN (Patla 1991), is no longer than the
    walker's step length, keeps the body radius clear, and the last lands a step before the
    flight's first footfall on its axis facing up it."""
    walker = Walker()
    view = level_view(station, stair.lower, walker.stature + 0.1)
    walk = _walk_north(-4.0, -1.2, 0.9)
    first = flight_start(stair, "up", walker)
    found = turn_in_steps(view, walk, stair.yaw, walker, 0.25, first)
    assert found is not None
    j, points, headings, end = found
    assert 0 <= j < len(walk.steps) - 1
    yaws = np.concatenate([[walk.yaw[walk.steps[j].end]], headings])
    assert np.abs(np.diff(yaws)).max() <= ENTRY_TURN + 1e-6
    here = np.vstack([walk.xy[walk.steps[j].end], points])
    assert np.hypot(*np.diff(here, axis=0).T).max() <= walker.step_length + 1e-9
    assert np.all(view.walk_clearance(points) >= 0.25)
    assert math.remainder(end - stair.yaw, math.tau) == pytest.approx(0.0, abs=1e-9)
    assert headings[-1] == pytest.approx(end)
    assert np.hypot(*(points[-1] - first)) == pytest.approx(walker.step_length, abs=1e-6)
    assert min(TURN_STEP_SHARES) > 0.0 and max(TURN_STEP_SHARES) == 1.0


def test_no_turn_fits_against_a_wall(station, stair):
    """A walk ending 0.2 m from the stair's east wall facing it leaves no room for any turn
    within its last steps' reach: None (the crossing then turns on the spot)."""
    walker = Walker()
    view = level_view(station, stair.lower, walker.stature + 0.1)
    walk = _walk_north(-6.4, -1.2, -0.5, yaw=math.pi / 2)  # west of the stair, under the wall
    assert (
        turn_in_steps(view, walk, stair.yaw, walker, 0.25, flight_start(stair, "up", walker))
        is None
    )


def test_turned_steps_prepend_the_turn_as_the_crossing_walks_it(stair):
    """cross_walk with a turn as its lead-in: the turning footfalls come first (feet the step
    width apart across each one's heading), then the flight's, no step on the spot; the pelvis
    ends facing up the flight, unwrapped from the turn."""
    walker = Walker()
    first = flight_start(stair, "up", walker)
    pts = np.array([first + (0.6, 1.4), first + (0.0, 1.3), first + (0.0, walker.step_length)])
    heads = np.array([2.4, 3.6, 3 * math.pi / 2])
    lead = (pts, heads, 3 * math.pi / 2)
    out = turned_steps(lead, (np.zeros((2, 2)), np.zeros(2), np.ones(2)), (pts[0], 0.0),
                       (2.0, 3 * math.pi / 2), 0.5, np.array([1.0, 0.0]))  # fmt: skip
    assert out[-1] == 3 and len(out[0]) == 5 and np.allclose(out[2], [0.5, 0.5, 0.5, 1.0, 1.0])
    last = PathStep("left", 0, 1, np.array([*(first + (1.0, 1.5)), 2.0]),
                    np.array([*(first + (1.1, 1.4)), 2.0]))  # fmt: skip
    walk = cross_walk(stair, "up", walker, (first + (1.05, 1.45), 2.0), last, 0.0, lead_in=lead)
    walk.validate()
    for k in range(3):
        foot = walk.steps[k].foot
        assert np.hypot(*(foot[:2] - pts[k])) == pytest.approx(
            0.5 * (walker.step_width or DEFAULT_STEP_WIDTH)
        )
        assert foot[2] == pytest.approx(heads[k])
    assert walk.yaw[-1] == pytest.approx(3 * math.pi / 2)


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def test_rack1_to_the_mezzanine_turns_into_the_stair_while_walking(station, model):
    """rack1 -> mezzanine's floor leg comes up the gap between the stair's east wall and the
    trolley and arrives at the stair's approach point 106-148 deg off the flight (seeds 0-9):
    main e749e69 stopped there and turned on the spot (10 of 10 seeds). Now it turns into the
    stair while walking on all 10 (at least 9 asserted): no step before the first riser stays
    on the spot (each moves the pelvis more than 0.15 m; a step on the spot under 0.07 m) or
    turns more than ENTRY_TURN, and the walker faces up the flight (within 1 deg) as it steps
    onto it. Measured: 0 of 10 turn on the spot; the walk 7.75 -> 8.59 m, 11.98 -> 12.22 s
    (medians)."""
    turned = 0
    for seed in range(10):
        walk = plan_walk(station, "stand_rack1", "stand_mezz_rack", model, rng=seed)
        first = next(k for k, s in enumerate(walk.steps) if s.foot_z > 0.05)  # onto the flight
        before = walk.steps[max(0, first - 8) : first]
        moved = [np.hypot(*(walk.xy[s.end] - walk.xy[s.start])) for s in before]
        turns = [abs(math.remainder(walk.yaw[s.end] - walk.yaw[s.start], math.tau)) for s in before]
        facing = abs(math.remainder(walk.yaw[walk.steps[first].start] + math.pi / 2, math.tau))
        turned += min(moved) > 0.15 and max(turns) <= ENTRY_TURN + 1e-6 and facing < math.radians(1)
    assert turned >= 9


def test_walked_back_follows_the_shortest_route_back_a_step_length_apart(station):
    """On the open floor the route back to a start due south is the straight line: the poses
    lie on it a step length apart, nearest the end first, each facing the end (north)."""
    start, end = np.array([1.0, -2.0]), np.array([1.0, 0.5])
    poses = walked_back(lambda p: np.hypot(*(np.atleast_2d(p) - start).T), end, 0.6)
    assert len(poses) == CUT_STEPS
    for k, (xy, yaw) in enumerate(poses, start=1):
        assert xy[0] == pytest.approx(1.0, abs=1e-9)
        assert xy[1] == pytest.approx(0.5 - k * 0.6, abs=BACK_STRIDE)
        assert yaw == pytest.approx(math.pi / 2, abs=1e-9)
    short = walked_back(lambda p: np.hypot(*(np.atleast_2d(p) - start).T), start + (0, 1.0), 0.6)
    assert len(short) == 1  # the start is reached after 1.0 m


def test_the_route_prices_a_turn_into_the_stair_as_walked(station, stair):
    """Arriving along the flight adds nothing; arriving up the gap east of the stair, facing
    away from it (a hairpin: 180 deg, at least three turning steps of 60 deg), adds the turn's
    steps over the straight ones they replace: more than the two steps on the spot a standing
    walker turns 180 deg in (levelcross.spot_turn), fewer than CUT_STEPS + 4 steps; under the
    wall no turn fits: None (the route then prices the turn on the spot)."""
    walker = Walker()
    view = level_view(station, stair.lower, walker.stature + 0.1)
    first = flight_start(stair, "up", walker)
    flight = (stair.yaw, first)
    ahead = first - walker.step_length * np.array([math.cos(stair.yaw), math.sin(stair.yaw)])
    along = [(ahead - k * 0.7 * np.array([0.0, -1.0]), -math.pi / 2) for k in (1, 2)]
    assert turn_in_time(view, along, flight, walker, 0.25) == pytest.approx(0.0, abs=0.3)
    gap = [(np.array([-4.0, 0.9 - 0.7 * k]), math.pi / 2) for k in range(1, CUT_STEPS + 1)]
    t = turn_in_time(view, gap, flight, walker, 0.25)
    assert t is not None
    assert 2 * walker.step_duration < t < (CUT_STEPS + 4) * walker.step_duration
    wall = [(np.array([-6.4, -0.5 - 0.7 * k]), math.pi / 2) for k in range(1, CUT_STEPS + 1)]
    assert turn_in_time(view, wall, flight, walker, 0.25) is None
