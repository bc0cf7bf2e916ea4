"""The synthetic walk helper (mjwalk.plan.synthetic): footprints, timing and arcs as specified."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.plan.synthetic import synthetic_walk


def test_straight_walk_footprints_and_timing():
    w = synthetic_walk(n_steps=6, step_len=0.7, width=0.2, step_time=0.5, hold=0.25)
    assert [s.side for s in w.steps] == ["left", "right"] * 3
    feet = np.array([w.steps[0].stance] + [s.foot for s in w.steps])
    assert np.allclose(np.diff(feet[1:, 0]), 0.7)  # a full step between landings
    assert feet[1, 0] == pytest.approx(0.35)  # the first step is a half step
    assert np.allclose(np.abs(feet[:, 1]), 0.1) and np.allclose(feet[:, 2], 0.0)
    assert w.duration == pytest.approx(6 * 0.5 + 0.25)
    assert all(b.start == a.end for a, b in zip(w.steps, w.steps[1:], strict=False))
    # the pelvis ends midway between the last two feet and sways towards the stance foot
    assert w.xy[-1, 0] == pytest.approx(0.5 * (feet[-1, 0] + feet[-2, 0]))
    mid = (w.steps[1].start + w.steps[1].end) // 2  # left foot stands (step 1 swings right)
    assert w.xy[mid, 1] > 0.02


@pytest.mark.parametrize("radius", [2.5, -2.0])
def test_curved_walk_stays_on_its_arc(radius):
    w = synthetic_walk(n_steps=8, radius=radius, sway=0.0, start=(1.0, -1.0, 0.5))
    c, s = np.cos(0.5), np.sin(0.5)
    centre = np.array([1.0, -1.0]) + radius * np.array([-s, c])  # left of the start heading
    r = np.linalg.norm(w.xy - centre, axis=1)
    assert np.allclose(r, abs(radius), atol=1e-9)
    turned = w.yaw[-1] - w.yaw[0]
    assert np.sign(turned) == np.sign(radius)


def test_bad_arguments_are_refused():
    with pytest.raises(MjwalkError, match="n_steps >= 1"):
        synthetic_walk(n_steps=0)


def test_synthetic_stair_walk_heights_and_timing():
    from mjwalk.plan.synthetic import synthetic_stair_walk

    up = synthetic_stair_walk(0.17, 0.28, 6, "up")
    up.validate()
    assert [s.foot_z for s in up.steps] == pytest.approx([0.17 * k for k in range(1, 7)] + [1.02])
    assert abs(up.steps[1].end - up.steps[1].start - 0.58 * 120) <= 1  # the reference ascent step
    down = synthetic_stair_walk(0.17, 0.28, 6, "down")
    assert down.steps[0].stance_z == pytest.approx(1.02) and down.steps[-1].foot_z == 0.0
    assert float(down.z[0]) == pytest.approx(1.02) and float(down.z[-1]) == 0.0


def test_synthetic_stair_walk_starts_its_steps_with_the_pelvis_midway():
    """Every step of a stair walk down after the first starts with the pelvis midway between
    its two feet (the footprints, set back from the treads' centres), the second too (the first
    step is a whole tread, unlike synthetic_walk's half step; a quarter tread there put the
    first step off the top landing 7 cm nearer above its lifting foot than the flight's, knee
    100.1 against 95.5-95.7 deg)."""
    from mjwalk.plan.synthetic import synthetic_stair_walk

    w = synthetic_stair_walk(0.17, 0.28, 6, "down")
    for k in range(1, len(w.steps)):
        feet = (w.steps[k - 1].stance[0], w.steps[k].stance[0])  # the feet down at its start
        assert float(w.xy[w.steps[k].start, 0]) == pytest.approx(0.5 * sum(feet))


@pytest.mark.parametrize("direction", ["up", "down"])
def test_synthetic_stair_walk_puts_the_pelvis_where_the_planner_does(scenes_dir, direction):
    """Up and down a stair the synthetic walk's pelvis at every foot contact of the flight
    stands midway between the two feet (their footprints, the points under the ankles, set
    back from the treads' centres: levelcross.flight_setback), as the level planner's walk
    over the station's stair puts it (levelcross.cross_walk, plan.footfallwalk), so that the
    stair tests and benchmarks/bench_levels.py measure the legs of the walk the planner makes.
    Before hip47d (up) and descent47 (down) it stood midway between the treads' centres, the
    setback (6.65 cm at 1.75 m) further on: up the swing hip peaked 3.5 deg lower, down the
    swing knee 1.9-3.8 deg lower (this test failed there, down until descent47)."""
    from mjwalk.gait.walker import Walker
    from mjwalk.plan.levelcross import cross_walk
    from mjwalk.plan.levelroute import crossings
    from mjwalk.plan.synthetic import synthetic_stair_walk
    from mjwalk.world import load_workplace

    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    stair = next(c for c in crossings(wp.levels, 0.33) if c.kind == "stair")
    up = direction == "up"
    stance = stair.end(stair.lower if up else stair.upper)
    start = (stance, stair.yaw if up else stair.yaw + np.pi)
    planned = cross_walk(stair, direction, Walker(), start, None, 0.0)
    synthetic = synthetic_stair_walk(0.17, 0.28, 6, direction)
    for walk in (planned, synthetic):
        flight = [s for s in walk.steps if abs(s.foot_z - s.stance_z) > 0.1]
        assert len(flight) == 6
        for s in flight:
            mid = 0.5 * (np.asarray(s.foot[:2]) + np.asarray(s.stance[:2]))
            assert np.hypot(*(walk.xy[s.end] - mid)) < 1e-6
    # and the footprints stand back from the treads' centres by the setback
    assert synthetic.steps[2].stance[0] == pytest.approx(2 * 0.28 - 0.0665, abs=1e-3)


def test_synthetic_ramp_walk_rises_along_the_heading():
    from mjwalk.plan.synthetic import synthetic_ramp_walk

    w = synthetic_ramp_walk(np.deg2rad(5.5), start=(1.0, 2.0, np.pi / 2))
    s = w.steps[-1]
    assert s.foot_z == pytest.approx(np.tan(np.deg2rad(5.5)) * (s.foot[1] - 2.0))
    assert not w.is_flat
