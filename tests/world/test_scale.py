"""Factory scale (issue 18): generated halls, the tiled clearance field against MuJoCo and the
old build, occupancy grids derived from the field, and the on-disk workplace cache."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.plan.occupancy import MOVES_16, occupancy_grid, occupancy_grid_sampled, shared_grid
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace
from mjwalk.world.clearance import build_clearance_bruteforce
from mjwalk.world.generate import generate_hall
from mjwalk.world.probe import ClearanceProbe


@pytest.fixture(scope="module")
def hall10(tmp_path_factory):
    path = tmp_path_factory.mktemp("hall") / "hall10.xml"
    return generate_hall(10, seed=3).write(path)


def test_tiled_field_equals_the_old_build(hall10, scenes_dir):
    """The tiled compiled build gives the brute-force build's values (to rounding)."""
    for path in (hall10, scenes_dir / "assembly_station.xml"):
        wp = load_workplace(path, cache=False)
        ref = build_clearance_bruteforce(wp.obstacles, wp.floor_bounds)
        np.testing.assert_allclose(wp.clearance.values, ref.values, rtol=0, atol=1e-12)


@pytest.mark.slow
def test_large_hall_field_matches_mujoco(tmp_path):
    """On the generated 100 x 100 m hall (4000 boxes, cylinders, capsules), at 300 points of
    two 8 x 8 m windows (one in a corner, one in the middle), the field agrees with
    mj_geomDistance within 1 cm outside the obstacles. MuJoCo is asked about the geoms within
    4 m of a window (the field shows no point there farther than 3 m from an obstacle)."""
    hall = generate_hall(100, seed=1)
    path = hall.write(tmp_path / "hall100.xml")
    wp = load_workplace(path, cache=False)
    assert len(wp.obstacles) == 4000
    rng = np.random.default_rng(4)
    for lo in (np.array([-49.5, -49.5]), np.array([-4.0, 2.0])):
        pts = rng.uniform(lo, lo + 8.0, size=(150, 2))
        c = hall.circles
        d = np.maximum(np.abs(c[:, :2] - (lo + 4.0)) - 4.0, 0.0)
        near = np.hypot(d[:, 0], d[:, 1]) - c[:, 2] < 4.0
        names = [fp.name for fp, n in zip(wp.obstacles, near, strict=True) if n]
        field = wp.clearance(pts)
        assert field.max() < 3.0
        ref = ClearanceProbe(path, geoms=names).clearance(pts)
        outside = field > 0.01
        assert outside.sum() > 100
        np.testing.assert_allclose(field[outside], ref[outside], atol=0.01)


def test_grids_derived_from_the_field_equal_sampled_ones(hall10, scenes_dir):
    for path in (hall10, scenes_dir / "corridor.xml"):
        wp = load_workplace(path, cache=False)
        for moves, radius in (((1, 0), (1, 1), (-1, 1)), 0.25), (MOVES_16, 0.3):
            new = occupancy_grid(wp, radius=radius, moves=list(moves))
            old = occupancy_grid_sampled(wp, radius=radius, moves=list(moves))
            np.testing.assert_array_equal(new.free, old.free)
            np.testing.assert_array_equal(new.moves, old.moves)
            assert new.moves.any() and not new.moves.all()


def test_cached_workplace_equals_a_fresh_one(hall10, tmp_path, monkeypatch):
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path / "root"))
    monkeypatch.delenv("MJWALK_CACHE_DIR", raising=False)
    fresh = load_workplace(hall10, cache=False)
    assert fresh.cache_key is None
    first = load_workplace(hall10, cache=True)  # builds and stores, under the cache root
    files = sorted(p.name for p in (tmp_path / "root" / "workplaces").iterdir())
    assert files and all(f.endswith("-clearance.npy") for f in files)
    again = load_workplace(hall10, cache=True)  # maps the stored arrays
    assert again.cache_key == first.cache_key
    assert isinstance(again.clearance.values.base, np.memmap)
    for wp in (first, again):
        np.testing.assert_array_equal(wp.clearance.values, fresh.clearance.values)
        np.testing.assert_array_equal(wp.walk_field().values, fresh.walk_field().values)
        for moves in (None, MOVES_16):
            kw = {} if moves is None else {"moves": moves}
            g, f = shared_grid(wp, **kw), shared_grid(fresh, **kw)
            np.testing.assert_array_equal(g.free, f.free)
            np.testing.assert_array_equal(g.moves, f.moves)
            assert (g.x0, g.y0, g.cell) == (f.x0, f.y0, f.cell)
    stored = [p.name for p in (tmp_path / "root" / "workplaces").iterdir()]
    assert all(name.endswith(".npy") and not name.startswith(".") for name in stored)
    # another scene (one obstacle moved by 1 cm) gets another key
    lines = hall10.read_text().splitlines()
    k = next(i for i, ln in enumerate(lines) if "<geom" in ln and ' pos="' in ln)
    head, rest = lines[k].split(' pos="', 1)
    x, tail = rest.split(" ", 1)
    lines[k] = f'{head} pos="{float(x) + 0.01:.4f} {tail}'
    moved = tmp_path / "moved.xml"
    moved.write_text("\n".join(lines))
    assert load_workplace(moved, cache=True).cache_key != first.cache_key


def test_unwritable_cache_still_builds(hall10, tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("MJWALK_CACHE", str(blocker / "cache"))
    monkeypatch.delenv("MJWALK_CACHE_DIR", raising=False)
    wp = load_workplace(hall10, cache=True)
    ref = load_workplace(hall10, cache=False)
    np.testing.assert_array_equal(wp.clearance.values, ref.clearance.values)


@pytest.mark.slow
def test_long_walks_through_clutter(tmp_path):
    """30 m walks across the cluttered 36 x 10 m hall (144 boxes) plan within the default
    expansion budget (before the far weight of issue 18, 11 of 20 32 m walks spent it) and
    keep the body radius; a walk starting within LONG_WALK of its goal is the same walk with
    and without the far weight."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.options import LONG_WALK
    from mjwalk.plan.walks import plan_walk
    from mjwalk.world.generate import free_points

    hall = generate_hall(36, 10, kinds=("box",), seed=0)
    wp = load_workplace(hall.write(tmp_path / "hall36.xml"), cache=False)
    model = default_model(progress=False)
    pts = free_points(hall, 400, np.random.default_rng(2))
    far = pts[:, 0] < -14.0
    a = pts[far][0]
    b = pts[pts[:, 0] > a[0] + 29.5][0]
    for k in range(3):
        w = plan_walk(wp, a, b, model, rng=k)
        assert w.meta["expansions"] < 4000
        assert wp.walk_clearance(w.xy).min() >= 0.25 - 0.005
    c = pts[(np.hypot(*(pts - a).T) > 5.0) & (np.hypot(*(pts - a).T) < 7.0)][0]
    assert np.hypot(*(c - a)) < LONG_WALK
    w1 = plan_walk(wp, a, c, model, rng=5)
    w2 = plan_walk(wp, a, c, model, rng=5, options=PlannerOptions(far_weight=0.0))
    np.testing.assert_array_equal(w1.xy, w2.xy)
