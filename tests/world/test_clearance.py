"""mjwalk.world.clearance: the tiled field equals the reference build; bilinear lookups."""

from __future__ import annotations

import numpy as np

from mjwalk.world.clearance import (
    ClearanceField,
    bilinear_at,
    build_clearance,
    build_clearance_bruteforce,
)
from mjwalk.world.footprint import Footprint

SQUARE = Footprint("box", 0, np.array([[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]))
DISC = Footprint("post", 1, np.array([[3.0, 0.5], [3.0, 0.5]]), radius=0.25)


def test_tiled_build_equals_the_bruteforce_one_and_exact_distances():
    bounds = (0.0, 0.0, 4.0, 3.0)
    field = build_clearance([SQUARE, DISC], bounds, 0.05)
    ref = build_clearance_bruteforce([SQUARE, DISC], bounds, 0.05)
    assert field.shape == ref.shape == (61, 81)
    np.testing.assert_allclose(field.values, ref.values, atol=1e-12)
    assert field.extent == (0.0, 0.0, 4.0, 3.0)
    # node (0, 0): nearest is the square's corner (1, 1); inside the square: negative
    assert field.values[0, 0] == np.hypot(1.0, 1.0)
    assert field(np.array([1.5, 1.5])) == -0.5
    assert field(np.array([3.0, 1.0])) == np.float64(0.25)  # 0.5 from the post's centre


def test_empty_scene_is_far_everywhere():
    field = build_clearance([], (0.0, 0.0, 1.0, 1.0), 0.1, far=7.0)
    assert (field.values == 7.0).all()


def test_bilinear_lookup_and_compiled_twin_agree():
    values = np.array([[0.0, 1.0], [2.0, 3.0]])
    field = ClearanceField(10.0, 20.0, 0.5, values)
    gx, gy = field.grid_xy()
    np.testing.assert_array_equal(gx, [10.0, 10.5])
    np.testing.assert_array_equal(gy, [20.0, 20.5])
    assert field(np.array([10.25, 20.25])) == 1.5  # the mean of the four nodes
    assert field(np.array([-5.0, -5.0])) == 0.0  # beyond the grid: the nearest border node
    for x, y in [(10.1, 20.3), (10.4, 20.05), (9.0, 21.0)]:
        assert bilinear_at(values, 10.0, 20.0, 0.5, x, y) == field(np.array([x, y]))
