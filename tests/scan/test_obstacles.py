"""mjwalk.scan.obstacles: the floor plan of a levelled cloud and its box cover."""

from __future__ import annotations

import numpy as np
from test_scene import _room_cloud

from mjwalk.scan.obstacles import floor_plan, rectangles


def _cell(plan, x, y):
    return int((y - plan.y0) // plan.resolution), int((x - plan.x0) // plan.resolution)


def test_room_floor_plan_has_the_box_as_obstacle_and_free_middle():
    plan = floor_plan(_room_cloud(), resolution=0.05)
    assert plan is not None
    xmin, ymin, xmax, ymax = plan.bounds
    assert 3.8 < xmax - xmin < 4.2 and 2.8 < ymax - ymin < 3.2
    assert plan.obstacles[_cell(plan, 1.0, 1.0)] > 0  # the box
    label = plan.obstacles[_cell(plan, 1.0, 1.0)]
    assert 0.85 <= plan.tops[label] <= 0.95 + 1e-9  # its top, to a TOP_STEP bin
    assert plan.floor[_cell(plan, 2.5, 2.0)]  # under the lamp: floor, not obstacle
    assert not (plan.floor & (plan.obstacles > 0)).any()
    assert not (plan.void & plan.floor).any()


def test_no_floor_points_no_plan():
    assert floor_plan(np.array([[0.0, 0.0, 1.0], [1.0, 1.0, 1.5]])) is None


def test_rectangles_cover_each_label_exactly():
    labels = np.array([[1, 1, 0, 2], [1, 1, 0, 2], [0, 1, 0, 0]])
    rects = rectangles(labels)
    cover = np.zeros_like(labels)
    for iy0, iy1, ix0, ix1, lab in rects:
        assert (cover[iy0:iy1, ix0:ix1] == 0).all()
        cover[iy0:iy1, ix0:ix1] = lab
    np.testing.assert_array_equal(cover, labels)
    assert sorted(rects) == [(0, 2, 0, 2, 1), (0, 2, 3, 4, 2), (2, 3, 1, 2, 1)]
