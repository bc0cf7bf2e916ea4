"""The planning geometry both planners share: endpoint and segment checks, the occupancy grid."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import InputError, PlanningError
from mjwalk.plan.occupancy import (
    CELL_SIZE,
    MOVES_8,
    MOVES_16,
    SAMPLE_SPACING,
    check_endpoint,
    occupancy_grid,
    occupancy_grid_sampled,
    segment_is_free,
    shared_grid,
)
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "assembly_station.xml")


def test_endpoint_check_names_what_is_wrong(station):
    check_endpoint(station, station.point("stand_rack2"), BODY_RADIUS, "start")  # a stand is free
    with pytest.raises(PlanningError, match=r"goal \(0.000, 1.400\) is inside obstacle 'car_body'"):
        check_endpoint(station, np.array([0.0, 1.4]), BODY_RADIUS, "goal")
    with pytest.raises(PlanningError, match="off the floor"):
        check_endpoint(station, np.array([9.0, 0.0]), BODY_RADIUS, "start")
    with pytest.raises(PlanningError, match=r"from obstacle .* closer than the body radius"):
        check_endpoint(station, np.array([3.3, -0.9]), BODY_RADIUS, "start")
    xmin, _, _, _ = station.floor_bounds
    edge = np.array([xmin + 0.1, -2.5])  # 0.1 m in from the floor's west edge, clear of racks
    assert float(station.edge_distance(edge)) == pytest.approx(0.1)
    with pytest.raises(PlanningError, match="from the floor's edge, closer than the body radius"):
        check_endpoint(station, edge, BODY_RADIUS, "start")
    check_endpoint(station, edge, 0.05, "start")  # a thinner body fits there
    for bad in (0.0, -0.2, float("nan"), True, "0.25"):
        with pytest.raises(InputError, match="body radius must be a positive number"):
            check_endpoint(station, edge, bad, "start")  # type: ignore[arg-type]


def test_segment_check_samples_the_whole_segment(station):
    a, b = station.point("stand_rack2"), station.point("stand_car1")
    n = max(2, int(np.ceil(np.linalg.norm(b - a) / SAMPLE_SPACING)) + 1)
    pts = a + np.linspace(0.0, 1.0, n)[:, None] * (b - a)
    least = float(station.walk_clearance(pts).min())
    assert segment_is_free(station, a, b, least)
    assert not segment_is_free(station, a, b, least + 1e-6)
    # through the car body: never free
    assert not segment_is_free(station, np.array([-3.0, 1.4]), np.array([3.0, 1.4]), 0.01)


def test_grid_cells_and_moves_keep_the_radius(station):
    grid = occupancy_grid(station, moves=MOVES_16)
    ny, nx = grid.shape
    assert grid.cell == CELL_SIZE and grid.offsets == tuple(MOVES_16)
    assert grid.moves.shape == (len(MOVES_16), ny, nx)
    xs = grid.x0 + CELL_SIZE * np.arange(nx)
    ys = grid.y0 + CELL_SIZE * np.arange(ny)
    centres = np.stack(np.meshgrid(xs, ys), axis=-1)
    np.testing.assert_array_equal(grid.free, station.walk_clearance(centres) >= BODY_RADIUS)
    assert 0.3 < grid.free.mean() < 0.95  # the station has floor and obstacles both
    for k, (di, dj) in enumerate(MOVES_16):
        js, is_ = np.nonzero(grid.moves[k])
        assert grid.free[js, is_].all() and grid.free[js + dj, is_ + di].all()
    j, i = ny // 2, nx // 3
    assert grid.index(grid.centre(j, i)) == (j, i)
    assert grid.index(np.array([1e3, -1e3])) == (0, nx - 1)  # clipped to the grid


def test_fast_grid_equals_the_sampled_reference(scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    for moves in (MOVES_8, MOVES_16):
        fast, ref = occupancy_grid(wp, moves=moves), occupancy_grid_sampled(wp, moves=moves)
        np.testing.assert_array_equal(fast.free, ref.free)
        np.testing.assert_array_equal(fast.moves, ref.moves)
        assert (fast.x0, fast.y0) == pytest.approx((ref.x0, ref.y0), abs=1e-12)


def test_shared_grid_is_built_once_per_key(station):
    a = shared_grid(station, moves=MOVES_16)
    assert shared_grid(station, moves=MOVES_16) is a
    b = shared_grid(station, radius=0.3, moves=MOVES_16)
    assert b is not a and b.radius == 0.3 and b.free.sum() < a.free.sum()
