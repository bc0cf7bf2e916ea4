"""Joining the parts of a walk over levels (mjwalk.plan.levelstitch)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import cross_walk
from mjwalk.plan.levelroute import RouteLeg, crossings
from mjwalk.plan.levelstitch import level_meta, stitch
from mjwalk.plan.synthetic import synthetic_walk
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
    assert rec["per_kind"]["stairs"]["steps"] == 2 * len(cross.steps)
    assert rec["route"][0]["to"] == stair.upper


def test_a_level_walk_gets_its_level_height(scenes_dir):
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    level = wp.levels.levels[-1]
    flat = synthetic_walk()
    walk = stitch(wp, [(RouteLeg("level", level.index, flat.xy[0], flat.xy[-1]), flat)])
    assert walk.ground == pytest.approx(level.height)
    assert all(s.foot_z == pytest.approx(level.height) for s in walk.steps)
