"""The planner's obstacle-aware heuristic (mjwalk.plan.heuristic): the goal's distance field."""

from __future__ import annotations

import numpy as np
import pytest
from test_planner_fastpaths import SCENE_NAMES, _points

from mjwalk.plan.heuristic import goal_distance, grid_excess
from mjwalk.plan.occupancy import occupancy_grid
from mjwalk.world import load_workplace


@pytest.fixture(scope="module", params=SCENE_NAMES)
def workplace(request, scenes_dir):
    return load_workplace(scenes_dir / f"{request.param}.xml")


def test_goal_distance_bound(workplace):
    """The obstacle-aware distance is the larger of the straight line and the cell's grid
    distance over the worst detour factor minus the point's offset from the cell centre."""
    grid = occupancy_grid(workplace)
    goal = np.array(workplace.floor_bounds[:2]) + 1.0
    gd = goal_distance(grid, goal, 0.25)
    pts = _points(workplace, 3000, 3, margin=0.0)
    ny, nx = grid.free.shape
    i = np.clip(np.rint((pts[:, 0] - grid.x0) / grid.cell), 0, nx - 1).astype(int)
    j = np.clip(np.rint((pts[:, 1] - grid.y0) / grid.cell), 0, ny - 1).astype(int)
    offset = np.hypot(pts[:, 0] - (grid.x0 + i * grid.cell), pts[:, 1] - (grid.y0 + j * grid.cell))
    want = np.maximum(
        np.hypot(*(pts - goal).T), gd.cells[j, i] / grid_excess(tuple(grid.offsets)) - offset
    )
    np.testing.assert_array_equal(gd(pts), want)
