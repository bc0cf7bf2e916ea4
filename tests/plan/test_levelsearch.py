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


def test_a_route_through_a_stance_it_does_not_cross_is_one_level_walk(tmp_path):
    """Generated hall 136 (seen first in bench_unseen's seeds 100-140): the route from floor_1
    to the stair landing passes through the floor stance of a crossing it does not take (level
    walk, level walk, stair, level walk), which plan_level_walk met with an AssertionError. The
    two floor walks are one walk now, and the walk is planned up the stair to the landing."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walk
    from mjwalk.world.levelgen import generate_levels

    hall = generate_levels(136)
    wp = load_workplace(hall.write(tmp_path / "levels_136.xml"), cache=False)
    walker, options = Walker(), PlannerOptions()
    a, b = _ends(wp, "floor_1", "landing_0")
    legs = level_route(wp, a, b, walker, options, step_up_limit(walker))
    kinds = [leg.kind for leg in legs]
    assert kinds == ["level", "cross", "level"]
    assert legs[0].start == pytest.approx(a.xy) and legs[-1].end == pytest.approx(b.xy)
    walk = plan_walk(wp, "floor_1", "landing_0", default_model(), rng=13602)
    z = walk.z - wp.floor_z
    assert z[0] == pytest.approx(hall.site("floor_1").pos[2], abs=0.02)
    assert z[-1] == pytest.approx(hall.site("landing_0").pos[2], abs=0.02)
