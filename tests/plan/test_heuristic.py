"""The planner's obstacle-aware heuristic (mjwalk.plan.heuristic): the goal's distance field."""

from __future__ import annotations

import numpy as np
import pytest
from test_planner_fastpaths import SCENE_NAMES, _points

from mjwalk.conventions import BODY_RADIUS
from mjwalk.plan import heuristic
from mjwalk.plan.heuristic import (
    PELVIS_SWAY,
    goal_distance,
    grid_excess,
    walkable_distance,
)
from mjwalk.plan.occupancy import MOVES_16, occupancy_grid
from mjwalk.plan.options import SAFETY_MARGIN
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


def _gap_wall(tmp_path, gap: float, *, closed: bool = False):
    """A 4 x 4 m floor cut at y = 0 by a wall with a ``gap`` (m) at x = 0; the wall leaves a
    2 m way round at its east end (none with ``closed``)."""
    east = 4.0 if closed else 2.0
    west_half = (4.0 - gap / 2) / 2
    east_half = (east - gap / 2) / 2
    scene = tmp_path / "gap.xml"
    scene.write_text(
        '<mujoco model="gap"><worldbody>'
        '<geom name="floor" type="plane" size="4 2 0.05" pos="0 0 0"/>'
        f'<geom name="wall_w" type="box" size="{west_half} 0.05 1" '
        f'pos="{-gap / 2 - west_half} 0 1"/>'
        f'<geom name="wall_e" type="box" size="{east_half} 0.05 1" '
        f'pos="{gap / 2 + east_half} 0 1"/>'
        "</worldbody></mujoco>"
    )
    return load_workplace(scene)


def test_walkable_distance_avoids_a_gap_the_sway_does_not_fit(tmp_path):
    """A 0.58 m gap (the station's between trolley and car: 0.29 m walk clearance at its very
    middle) is a route for the body radius's grid but not for body radius + margin + pelvis
    sway (0.29 m): the planner's field routes round the wall's end instead; with no way
    round, through the gap."""
    assert BODY_RADIUS + SAFETY_MARGIN + PELVIS_SWAY == pytest.approx(0.29)
    goal, behind = np.array([0.0, 1.0]), np.array([[0.0, -1.0]])
    for closed in (False, True):
        wp = _gap_wall(tmp_path, 0.58, closed=closed)
        grid = occupancy_grid(wp, radius=BODY_RADIUS, moves=MOVES_16)
        roomy = occupancy_grid(wp, radius=BODY_RADIUS + SAFETY_MARGIN + PELVIS_SWAY, moves=MOVES_16)
        narrow = goal_distance(grid, goal, 0.25)
        field = walkable_distance(grid, roomy, goal, 0.25)
        assert float(narrow(behind)[0]) == pytest.approx(2.0, abs=0.15)  # through the gap
        if closed:  # no way round: through the gap, on to the roomy route beyond it
            assert float(field(behind)[0]) == pytest.approx(float(narrow(behind)[0]), abs=0.1)
        else:  # round the wall's end at x = 2: at least 2 x hypot(2, 1)
            assert float(field(behind)[0]) > 4.4
            free = np.isfinite(narrow.cells) & grid.free  # (blocked cells: the rims)
            assert np.all(field.cells[free] >= narrow.cells[free] - 1e-9)
        np.testing.assert_array_equal(field.in_sight, narrow.in_sight)  # the sight: the grid's


def test_walkable_distance_keeps_a_gap_wide_enough(tmp_path):
    """A 0.70 m gap (0.35 m walk clearance) keeps body radius + margin + sway: the field goes
    through it, as the body radius's does."""
    wp = _gap_wall(tmp_path, 0.70)
    goal, behind = np.array([0.0, 1.0]), np.array([[0.0, -1.0]])
    grid = occupancy_grid(wp, radius=BODY_RADIUS, moves=MOVES_16)
    roomy = occupancy_grid(wp, radius=BODY_RADIUS + SAFETY_MARGIN + PELVIS_SWAY, moves=MOVES_16)
    field = walkable_distance(grid, roomy, goal, 0.25)
    assert float(field(behind)[0]) == pytest.approx(
        float(goal_distance(grid, goal, 0.25)(behind)[0])
    )


def test_walkable_distance_of_one_grid_is_goal_distance(tmp_path):
    """Without a roomier grid (``PlannerOptions.field_sway`` off, the default) the planner's
    field is :func:`goal_distance`'s, cell for cell."""
    wp = _gap_wall(tmp_path, 0.58)
    grid = occupancy_grid(wp, radius=BODY_RADIUS, moves=MOVES_16)
    goal = np.array([0.0, 1.0])
    np.testing.assert_array_equal(
        walkable_distance(grid, grid, goal, 0.25).cells, goal_distance(grid, goal, 0.25).cells
    )


def test_planners_of_one_goal_share_the_field_and_sight(tmp_path):
    """A second field of the same grid, goal and tolerance is the first's (found before the
    goal cells are worked out), its sight flags and bounds too; another tolerance taking in
    other goal cells gets its own field, equal to one built from scratch."""
    wp = _gap_wall(tmp_path, 1.2)
    grid = occupancy_grid(wp, radius=BODY_RADIUS, moves=MOVES_16)
    goal = np.array([0.3, 1.0])
    first = goal_distance(grid, goal, 0.25)
    again = goal_distance(grid, goal, 0.25)
    assert again.cells is first.cells
    assert again.in_sight is first.in_sight
    assert again.flat_bound() is first.flat_bound()
    wide = goal_distance(grid, goal, 0.6)
    assert wide.cells is not first.cells
    heuristic._FIELDS.clear()
    heuristic._FIELD_KEYS.clear()
    heuristic._SIGHTS.clear()
    fresh = goal_distance(grid, goal, 0.6)
    assert fresh.cells is not wide.cells
    np.testing.assert_array_equal(fresh.cells, wide.cells)
    np.testing.assert_array_equal(fresh.flat_bound(), wide.flat_bound())
    np.testing.assert_array_equal(goal_distance(grid, goal, 0.25).in_sight, first.in_sight)
