"""Joining the parts of a walk over levels (mjwalk.plan.levelstitch)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.stairs import ASCENT_STEP_TIME, DESCENT_STEP_TIME
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import approach_point, cross_walk, departure
from mjwalk.plan.levelroute import RouteLeg, crossings
from mjwalk.plan.levelstitch import level_meta, step_kinds, stitch, surface_levels
from mjwalk.plan.synthetic import synthetic_stair_walk, synthetic_walk
from mjwalk.plan.walkpath import PathStep
from mjwalk.plan.walks import plan_walk
from mjwalk.world import load_workplace


def test_stitch_keeps_the_shared_sample_once_and_counts_each_kind(scenes_dir):
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    stair = next(c for c in crossings(wp.levels, 0.33) if c.kind == "stair")
    cross = cross_walk(stair, "up", Walker(), (stair.end(0), stair.yaw), None, 0.0)
    leg = RouteLeg("cross", 0, stair.end(0), stair.end(stair.upper), stair, "up")
    parts = [(leg, cross), (leg, cross)]
    walk = stitch(wp, parts)
    walk.validate()
    assert len(walk.t) == 2 * len(cross.t) - 1
    assert len(walk.steps) == 2 * len(cross.steps)
    assert np.all(np.diff(walk.t) > 0)
    rec = level_meta(wp, parts, 0.19)
    # each crossing: its risers' steps and the trailing foot's step off the last tread
    assert rec["per_kind"]["stairs"]["steps"] == 2 * (len(stair.risers) + 1)
    assert rec["per_kind"]["stairs"]["steps"] + rec["per_kind"]["level"]["steps"] == len(walk.steps)
    assert rec["route"][0]["to"] == stair.upper


def test_a_level_walk_gets_its_level_height(scenes_dir):
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    level = wp.levels.levels[-1]
    flat = synthetic_walk()
    walk = stitch(wp, [(RouteLeg("level", level.index, flat.xy[0], flat.xy[-1]), flat)])
    assert walk.ground == pytest.approx(level.height)
    assert all(s.foot_z == pytest.approx(level.height) for s in walk.steps)


@pytest.mark.parametrize("direction", ["up", "down"])
def test_a_flight_counts_its_risers_steps_and_the_step_off_its_last_tread(direction):
    """The synthetic stair walk (6 risers, step-over-step): every step touches a tread or
    climbs a riser, none stands on one level; n risers take n + 1 steps (the trailing foot's
    step off the last tread)."""
    walk = synthetic_stair_walk(n=6, direction=direction)
    top = 6 * 0.17
    start = 0.0 if direction == "up" else top
    assert surface_levels(walk.steps, {0: 0.0, 1: top}, start) == [None] * 7


@pytest.mark.parametrize(
    ("direction", "step_time"), [("up", ASCENT_STEP_TIME), ("down", DESCENT_STEP_TIME)]
)
def test_a_crossing_counts_its_line_up_and_departure_steps_as_level_walking(
    scenes_dir, direction, step_time
):
    """The shipped stair walked with a line-up from a step length before its stance and on a
    step length past it (levelcross.approach_point / departure): the level steps before and
    after the flight are level walking on their levels; the flight's time is its risers' steps
    at the stair step time (the reference adult's, 0.58 s up and 0.46 s down, mjwalk.gait.
    stairs) and one level step off the last tread."""
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    stair = next(c for c in crossings(wp.levels, 0.33) if c.kind == "stair")
    walker = Walker()
    lead = walker.step_length
    lo, hi = stair.lower, stair.upper
    frm = lo if direction == "up" else hi
    walked = departure(stair, direction, lead)
    before = approach_point(stair, direction, 2 * lead)  # two line-up steps
    facing = stair.yaw if direction == "up" else stair.yaw + np.pi
    # the level step that brought the walker there: its feet beside ``before`` on its level
    left = 0.06 * np.array([-np.sin(facing), np.cos(facing)])
    h = (stair.z_lower if direction == "up" else stair.z_upper) - wp.floor_z
    last = PathStep("right", 0, 1, np.r_[before - left, facing], np.r_[before + left, facing], h, h)
    cross = cross_walk(walked, direction, walker, (before, facing), last, wp.floor_z, lead_in=True)
    leg = RouteLeg(
        "cross", frm, stair.end(frm), walked.end(hi if frm == lo else lo), stair, direction
    )
    kinds = step_kinds(wp, leg, cross)
    n = len(stair.risers)
    assert kinds.count(None) == n + 1
    on = [k for k in kinds if k is not None]
    assert on.count(frm) >= 2 and on.count(hi if frm == lo else lo) >= 2  # line-up, departure
    rec = level_meta(wp, [(leg, cross)], 0.19)
    stairs = rec["per_kind"]["stairs"]["seconds"]
    assert stairs == pytest.approx(n * step_time + walker.step_duration, abs=(n + 1) / 120)
    assert stairs + rec["route"][0]["level_seconds"] == pytest.approx(cross.duration)
    assert set(rec["per_level"]) == {f"L{lo}", f"L{hi}"}


def test_a_walk_over_levels_turns_no_faster_than_on_the_spot(scenes_dir):
    """The shipped multi-level scene's walk from the mezzanine's rack down the stair and back
    past it to rack 1: no pelvis heading turns faster than a turn on the spot's peak (a half
    turn a second, eased: 1.5 pi rad/s)."""
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    for seed in range(3):
        walk = plan_walk(wp, "stand_mezz_rack", "stand_rack1", rng=seed)
        rate = np.abs(np.diff(np.unwrap(walk.yaw))) / np.diff(walk.t)
        assert rate.max() < 1.5 * np.pi * 1.05, (seed, float(np.degrees(rate.max())))
