"""WalkSurface arithmetic: heights on a ramp, free height under overheads, head clearance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.world.footprint import Footprint
from mjwalk.world.norms import HEAD_MARGIN
from mjwalk.world.walksurface import Overhead, WalkSurface, head_fits


def square(name: str, x0: float, y0: float, x1: float, y1: float) -> Footprint:
    return Footprint(name, 0, np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]))


def scattered(rng, xs: tuple, ys: tuple, size: float) -> list[Overhead]:
    """40 rectangular overheads 0.2 m deep: corners drawn in ``xs`` x ``ys``, sides 0.05 m to
    ``size``, bottoms 0.3-2.5 m (each drawn x, y, sides, bottom in turn)."""
    over = []
    for k in range(40):
        x, y = rng.uniform(*xs), rng.uniform(*ys)
        w, d = rng.uniform(0.05, size, size=2)
        bottom = rng.uniform(0.3, 2.5)
        over.append(Overhead(f"o{k}", square(f"o{k}", x, y, x + w, y + d), bottom, bottom + 0.2))
    return over


def ramp(overhead=()) -> WalkSurface:
    slope = math.atan(0.1)  # rising 10 % towards +y
    return WalkSurface(
        0, "r", "ramp", 0.5, square("r", 0, 0, 1, 10), 10.0, (0.5, 5.0), slope, math.pi / 2,
        0.0, 1.0, 1.0, 10.0, tuple(overhead),
    )  # fmt: skip


def test_height_on_a_ramp():
    r = ramp()
    assert r.height_at(np.array([[0.5, 0.0], [0.2, 10.0], [0.9, 5.0]])) == pytest.approx(
        [0.0, 1.0, 0.5]
    )


def test_free_height_and_head_fits():
    beam = Overhead("beam", square("beam", -1, 4, 2, 6), bottom=2.4, top=2.6)
    r = ramp([beam])
    xy = np.array([[0.5, 5.0], [0.5, 2.0]])
    assert r.free_height(xy) == pytest.approx([1.9, math.inf])
    assert list(head_fits(r, xy, 1.90)) == [False, True]
    assert list(head_fits(r, xy, 1.60)) == [True, True]
    assert bool(head_fits(r, xy[0], 1.9 - HEAD_MARGIN))
    # under the beam the ramp rises from 0.4 to 0.6 m: 2.0 down to 1.8 m free (nodes 5 cm apart)
    assert r.lowest_ceiling == pytest.approx(1.8, abs=0.006)
    assert r.headroom.clear_area(2.0) == pytest.approx(8.0, abs=0.2)
    with pytest.raises(InputError, match="stature"):
        head_fits(r, xy, 0.0)


def _free_height_one_by_one(surface: WalkSurface, xy: np.ndarray) -> np.ndarray:
    """The free height as first written: every overhead tested against every point (the
    surface's 1e-3 m overhead reach and 1e-6 m edge tolerance)."""
    z = surface.height_at(xy)
    out = np.full(xy.shape[:-1], np.inf)
    for o in surface.overhead:
        x0, y0, x1, y1 = o.footprint.bounds()
        near = np.all((xy >= [x0, y0]) & (xy <= [x1, y1]), axis=-1) & (o.top > z + 1e-3)
        under = np.zeros_like(near)
        if np.any(near):
            under[near] = o.footprint.signed_distance(xy[near]) < -1e-6
        out = np.where(under, np.minimum(out, np.maximum(o.bottom - z, 0.0)), out)
    return out


def test_free_height_skipping_far_geoms_equals_testing_every_geom():
    # 40 overheads scattered over and beside a ramp, some under its high end (their tops below
    # the face there), points in batches, one by one, beyond the footprint and with a NaN
    rng = np.random.default_rng(47)
    r = ramp(scattered(rng, (-3, 4), (-3, 13), 2.0))
    xy = rng.uniform([-4, -4], [5, 14], size=(3000, 2))
    np.testing.assert_array_equal(r.free_height(xy), _free_height_one_by_one(r, xy))
    grid = xy[:600].reshape(20, 30, 2)
    np.testing.assert_array_equal(r.free_height(grid), _free_height_one_by_one(r, grid))
    for p in xy[:200]:
        assert r.free_height(p) == _free_height_one_by_one(r, p)
    holed = xy[:50].copy()
    holed[7] = np.nan
    np.testing.assert_array_equal(r.free_height(holed), _free_height_one_by_one(r, holed))
    assert np.isfinite(r.free_height(xy)).sum() > 300  # many points under some geom
    np.testing.assert_array_equal(ramp().free_height(xy[:5]), np.full(5, np.inf))


def test_headroom_grid_equals_free_height_of_every_node_bit_for_bit():
    # the map searches each overhead's box in the grid's axes instead of testing every node:
    # its values equal free_height of the nodes on the footprint (the general test) exactly,
    # on a ramp with 40 boxes, a round and a rotated overhead, some across its edges or with
    # edges exactly on nodes, and with nothing over it; NaN off the footprint
    rng = np.random.default_rng(7)
    over = scattered(rng, (-1, 1.5), (-1, 11), 1.5)
    over.append(Overhead("node", square("node", 0.075, 1.025, 0.425, 2.475), 1.5, 1.7))
    pipe = Footprint("pipe", 0, np.array([[0.2, 3.0], [0.8, 7.0]]), 0.1)
    over.append(Overhead("pipe", pipe, 1.2, 1.4))
    turned = np.array([[0.5, 8.0], [1.2, 8.6], [0.6, 9.3], [-0.1, 8.7]])
    over.append(Overhead("turned", Footprint("turned", 0, turned), 1.0, 1.3))
    for r in (ramp(over), ramp()):
        hm = r.headroom
        ny, nx = hm.values.shape
        x0, y0 = r.footprint.bounds()[:2]  # the map's nodes as it places them, cell centres
        gx = x0 + hm.spacing * (np.arange(nx) + 0.5)
        gy = y0 + hm.spacing * (np.arange(ny) + 0.5)
        assert (gx[0], gy[0]) == (hm.x0, hm.y0)
        xy = np.stack(np.meshgrid(gx, gy), axis=-1)
        inside = r.footprint.signed_distance(xy) < 0.0
        want = np.full((ny, nx), np.nan)
        want[inside] = r.free_height(xy[inside])
        np.testing.assert_array_equal(hm.values, want)
    assert np.isfinite(ramp(over).headroom.values).sum() > 1000


def test_kind_is_checked():
    with pytest.raises(InputError, match="kind"):
        WalkSurface(0, "x", "roof", 0.0, square("x", 0, 0, 1, 1), 1.0, (0.5, 0.5), 0, 0, 0, 0, 1, 1)
