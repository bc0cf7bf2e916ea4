"""Tests of mjwalk.plan.levelsearch: the route over levels, its edges made as the search needs
them (issue 47)."""

from __future__ import annotations

import pytest

from mjwalk.gait.walker import Walker
from mjwalk.plan.levelplan import endpoint
from mjwalk.plan.levelroute import step_up_limit
from mjwalk.plan.levelsearch import level_route
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace
from mjwalk.world.levelview import level_at


@pytest.fixture
def fresh(scenes_dir):
    """The multi-level station loaded anew (no views, fields or routes kept on it)."""
    return load_workplace(scenes_dir / "multilevel_station.xml")


def _ends(wp, start, goal):
    return endpoint(wp, start, "start"), endpoint(wp, goal, "goal")


def _levels_set_up(wp) -> set[int]:
    """The levels whose distance fields the route built."""
    return {key[0] for key in wp.__dict__.get("_node_fields", {})}


def test_a_walk_onto_the_platform_sets_up_no_mezzanine(fresh):
    walker, options = Walker(), PlannerOptions()
    mezzanine = level_at(fresh, fresh.stations["stand_mezz_rack"].pos[:2], 1.02)
    a, b = _ends(fresh, "stand_step", "stand_platform1")
    legs = level_route(fresh, a, b, walker, options, step_up_limit(walker))
    assert [leg.kind for leg in legs] == ["level", "cross", "level"]
    assert mezzanine not in _levels_set_up(fresh)
    assert 0 in _levels_set_up(fresh)


def test_a_walk_from_the_mezzanine_to_the_floor_sets_up_no_platform(fresh):
    walker, options = Walker(), PlannerOptions()
    platform = level_at(fresh, fresh.stations["stand_platform1"].pos[:2], 0.34)
    a, b = _ends(fresh, "stand_mezz_rack", "stand_rack1")
    legs = level_route(fresh, a, b, walker, options, step_up_limit(walker))
    assert [leg.crossing.kind for leg in legs if leg.kind == "cross"] == ["stair"]
    assert platform not in _levels_set_up(fresh)
