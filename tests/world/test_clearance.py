"""mjwalk.world.clearance: the tiled field equals the reference build; bilinear lookups."""

from __future__ import annotations

import numpy as np
import pytest

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


def _numpy_lookup(field: ClearanceField, xy: np.ndarray) -> np.ndarray:
    """The lookup's NumPy arithmetic (the compiled lookup must give these numbers)."""
    ny, nx = field.values.shape
    fx = np.clip((xy[..., 0] - field.x0) / field.resolution, 0.0, nx - 1.000001)
    fy = np.clip((xy[..., 1] - field.y0) / field.resolution, 0.0, ny - 1.000001)
    ix, iy = fx.astype(np.intp), fy.astype(np.intp)
    tx, ty = fx - ix, fy - iy
    v = field.values
    return (v[iy, ix] * (1 - tx) + v[iy, ix + 1] * tx) * (1 - ty) + (
        v[iy + 1, ix] * (1 - tx) + v[iy + 1, ix + 1] * tx
    ) * ty


def test_lookup_gives_the_numpy_arithmetics_numbers_bit_for_bit():
    rng = np.random.default_rng(5)
    field = ClearanceField(-1.3, 0.7, 0.05, rng.normal(size=(23, 31)))
    # inside, on and beyond the grid, in several shapes (one point: a scalar)
    for shape in [(2,), (1, 2), (40, 2), (5, 9, 2)]:
        xy = rng.uniform(-2.0, 2.5, size=shape)
        got, want = field(xy), _numpy_lookup(field, xy)
        assert np.shape(got) == np.shape(want) == shape[:-1]
        assert np.asarray(got).tobytes() == np.asarray(want).tobytes()
    assert isinstance(field(np.array([0.1, 0.9])), np.float64)
    nodes = np.array([[-1.3 + 0.05 * 4, 0.7 + 0.05 * 6], [-1.3 + 0.05 * 30, 0.7 + 0.05 * 22]])
    assert field(nodes).tobytes() == _numpy_lookup(field, nodes).tobytes()


def test_lipschitz_of_a_cell_about_an_obstacles_corner_is_sqrt2():
    # nodes 0, 1, 1, sqrt(2) spacings (the distance from a box's corner at node (0, 0)): the
    # lookup's gradient at that corner is (1, 1), not a unit vector
    res = 0.5
    field = ClearanceField(0.0, 0.0, res, res * np.array([[0.0, 1.0], [1.0, np.sqrt(2.0)]]))
    assert field.lipschitz == np.sqrt(2.0)
    h = 1e-7
    grad = (field(np.array([[h, 0.0], [0.0, h]])) - field(np.array([0.0, 0.0]))) / h
    np.testing.assert_allclose(grad, [1.0, 1.0], rtol=1e-6)
    # a plane has its slope, whatever its direction
    gx, gy = np.meshgrid(np.arange(4.0), np.arange(3.0))
    plane = ClearanceField(0.0, 0.0, 0.1, 0.1 * (0.6 * gx + 0.8 * gy))
    assert abs(plane.lipschitz - 1.0) < 1e-12


def test_lipschitz_bounds_every_pair_and_is_reached():
    # a distance field (boxes, posts, a room corner from the floor's edge as walk fields have
    # it): no two points differ by more than lipschitz times their distance, the bound is
    # reached near a cell's corner, and a distance's lookup never exceeds sqrt(2)
    rng = np.random.default_rng(3)
    posts = [
        Footprint(f"p{k}", k, np.repeat(rng.uniform(0.3, 2.7, (1, 2)), 2, axis=0), radius=0.1)
        for k in range(6)
    ]
    field = build_clearance([SQUARE, *posts], (0.0, 0.0, 3.0, 3.0), 0.05)
    gx, gy = field.grid_xy()
    edge = np.minimum(np.minimum(gx, 3.0 - gx)[None, :], np.minimum(gy, 3.0 - gy)[:, None])
    field = ClearanceField(0.0, 0.0, 0.05, np.minimum(field.values, edge))
    lip = field.lipschitz
    assert 1.0 < lip <= np.sqrt(2.0) + 1e-12
    a = rng.uniform(-0.2, 3.2, (20000, 2))
    b = a + rng.normal(scale=0.05, size=a.shape)
    assert np.all(np.abs(field(a) - field(b)) <= lip * np.linalg.norm(a - b, axis=1) + 1e-12)
    # the steepest cell's corner: a one-sided difference there reaches the bound
    v = field.values
    dx, dy = np.abs(np.diff(v, axis=1)), np.abs(np.diff(v, axis=0))
    best = 0.0
    h = 1e-7
    for j in range(v.shape[0] - 1):
        for i in range(v.shape[1] - 1):
            for cj in (0, 1):
                for ci in (0, 1):
                    g = np.hypot(dx[j + cj, i], dy[j, i + ci]) / 0.05
                    if g > best - 1e-12:
                        best, corner = g, (j, i, cj, ci)
    j, i, cj, ci = corner
    p = np.array([gx[i + ci] - (2 * ci - 1) * 2 * h, gy[j + cj] - (2 * cj - 1) * 2 * h])
    slope = np.hypot(
        *((field(p + d) - field(p - d)) / (2 * h) for d in (np.array([h, 0.0]), np.array([0.0, h])))
    )
    assert best == pytest.approx(lip, rel=1e-12)
    assert slope == pytest.approx(lip, rel=1e-4)


def test_the_shipped_stations_walk_field_is_sqrt2_lipschitz(scenes_dir):
    # not 1: the floor's corners (the edge distance min(x, y)) and the obstacles' corners
    from mjwalk.world import load_workplace

    field = load_workplace(scenes_dir / "assembly_station.xml").walk_field()
    assert field.lipschitz == pytest.approx(np.sqrt(2.0), abs=1e-9)
