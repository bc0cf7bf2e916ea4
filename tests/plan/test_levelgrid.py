"""mjwalk.plan.levelgrid: the grid-A* baseline of a walk over levels goes up only by the
station's step, ramp or stair, keeps the body radius on every level, and is no longer than a
walk over the same crossing."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.gait.default import default_model
from mjwalk.plan.grid import plan_grid
from mjwalk.plan.levelgrid import level_grid_route
from mjwalk.plan.walks import plan_walk
from mjwalk.world import load_workplace
from mjwalk.world.levelview import level_view
from mjwalk.world.norms import HEAD_MARGIN


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def test_a_route_onto_the_platform_takes_the_step_and_keeps_its_radius(station):
    r = level_grid_route(station, "stand_rack1", "stand_platform2")
    assert r.meta["levels"] == ["L0", "step up", "L3"]
    assert r.z[0] == 0.0 and r.z[-1] == pytest.approx(0.34)
    assert set(np.round(r.z, 6)) == {0.0, 0.34}  # on a level, or a crossing's stance
    a, b = station.station("stand_rack1").xy, station.station("stand_platform2").xy
    assert r.length >= float(np.hypot(*(b - a)))
    assert r.xy[0] == pytest.approx(a) and r.xy[-1] == pytest.approx(b)
    head = 1.75 + HEAD_MARGIN
    for level, height in ((0, 0.0), (3, 0.34)):  # every grid point clear on its own level
        on = np.isclose(r.z, height)
        view = level_view(station, level, head)
        assert np.all(view.walk_clearance(r.xy[on]) >= 0.25 - 0.02)  # 0.25 m, the field's cells


def test_the_route_is_no_longer_than_a_walk_between_the_same_ends(station):
    """The baseline is the shortest way the grid and the route over levels find: a planned
    walk between the same ends (the same step up) is no shorter, up to the grid's 8-direction
    excess (plan.grid.shortfall_bound: at most 8.24 %)."""
    model = default_model()
    for seed in range(3):
        walk = plan_walk(station, "stand_rack1", "stand_platform2", model, rng=seed)
        ends = [(*walk.xy[k], walk.z[k]) for k in (0, -1)]
        base = level_grid_route(station, *ends)
        assert walk.length >= base.length / 1.0824 - 0.05


def test_a_walker_who_takes_no_step_goes_by_the_ramp(station):
    step = level_grid_route(station, "stand_rack1", "stand_platform2")
    ramp = level_grid_route(station, "stand_rack1", "stand_platform2", max_riser=0.0)
    assert ramp.meta["levels"] == ["L0", "ramp up", "L3"]
    assert ramp.length > step.length


def test_the_mezzanine_is_reached_by_the_stair(station):
    r = level_grid_route(station, "stand_stair", "stand_mezz_rack")
    assert r.meta["levels"] == ["L0", "stair up", "L8"]
    assert r.z[-1] == pytest.approx(1.02)


def test_a_route_on_one_level_is_its_views_grid_route(station):
    r = level_grid_route(station, "stand_platform1", "stand_platform2")
    view = level_view(station, 3, 1.75 + HEAD_MARGIN)
    flat = plan_grid(
        view, station.station("stand_platform1").xy, station.station("stand_platform2").xy
    )
    assert r.meta["levels"] == ["L3"]
    assert r.length == pytest.approx(flat.length, abs=1e-12)


def test_an_end_given_at_a_height_stands_on_that_level(station):
    xy = station.station("stand_platform1").xy
    r = level_grid_route(station, (*station.station("stand_rack1").xy, 0.0), (*xy, 0.34))
    assert r.meta["levels"][-1] == "L3"
