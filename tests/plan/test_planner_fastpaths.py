"""The planners' fast paths give the answers of the plain routines they stand in for."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan.occupancy import MOVES_16, check_endpoint, occupancy_grid, shared_grid
from mjwalk.world import load_workplace

SCENE_NAMES = ["assembly_station", "corridor", "open_floor"]


@pytest.fixture(scope="module", params=SCENE_NAMES)
def workplace(request, scenes_dir):
    return load_workplace(scenes_dir / f"{request.param}.xml")


def _points(wp, n, seed, margin=0.3):
    """Random points over the floor and a band ``margin`` beyond its edge (metres)."""
    xmin, ymin, xmax, ymax = wp.floor_bounds
    rng = np.random.default_rng(seed)
    return rng.uniform([xmin - margin, ymin - margin], [xmax + margin, ymax + margin], (n, 2))


def _compiled_lookup(field, pts):
    """The planner's compiled bilinear lookup (stepgeom.field_clearance) at points (n, 2)."""
    from mjwalk.plan.stepgeom import field_clearance

    (ny, nx) = field.values.shape
    args = (field.values, field.x0, field.y0, field.resolution, nx, ny)
    return np.array([field_clearance(*args, x, y) for x, y in pts])


def test_compiled_field_lookup_equals_call(workplace):
    pts = _points(workplace, 5000, 0)
    c = workplace.clearance
    np.testing.assert_allclose(_compiled_lookup(c, pts), c(pts), rtol=0, atol=1e-12)


def test_walk_field_never_exceeds_walk_clearance(workplace):
    """One lookup in the combined field is at most the obstacle clearance and at most the
    exact distance to the floor's edge on the floor, and at most one node spacing off it."""
    pts = _points(workplace, 20000, 1)
    field = workplace.walk_field()
    combined = _compiled_lookup(field, pts)
    exact = workplace.walk_clearance(pts)
    assert np.all(combined <= np.maximum(exact, field.resolution) + 1e-12)
    assert np.all(combined[exact >= 0] <= exact[exact >= 0] + 1e-12)
    # and it gives up little: on the floor, at most a few millimetres below it
    on = workplace.on_floor(pts)
    assert np.percentile(workplace.walk_clearance(pts[on]) - combined[on], 99) < 0.005


def test_quick_endpoint_accept_never_passes_a_bad_point(workplace):
    """check_endpoint accepts through the field only points the exact test accepts too."""
    from mjwalk.plan import occupancy as occupancy_mod

    for xy in _points(workplace, 400, 2):
        for radius in (0.05, 0.25):
            if occupancy_mod._clearly_free(workplace, xy, radius):
                dist = min(
                    (float(f.signed_distance(xy[None])[0]) for f in workplace.obstacles),
                    default=np.inf,
                )
                assert dist >= radius and float(workplace.edge_distance(xy)) >= radius
            else:  # the exact test still decides; it must not crash
                try:
                    check_endpoint(workplace, xy, radius, "start")
                except PlanningError:
                    pass


def test_sample_next_features_are_sample_next_draws():
    model = default_model()
    prev = model.sample_first(3, np.random.default_rng(0), "right")
    a = model.sample_next(prev, 7, np.random.default_rng(9))
    b = model.sample_next_features(prev.features, "right", 7, np.random.default_rng(9))
    np.testing.assert_array_equal(a.features, b)
    assert set(a.side) == {"left"}


def test_kde_starters_are_gaussian_kde_draws():
    """sample_first draws what scipy's gaussian_kde.resample draws from the same stream (the
    kernel factor is computed once instead of per call, without building the kde)."""
    from scipy.stats import gaussian_kde

    model = default_model()
    for side in ("left", "right"):
        got = model.sample_first(25, np.random.default_rng(8), side).features
        kde = gaussian_kde(model.kde_data[side], bw_method=model.kde_factor[side])
        ref = kde.resample(25, seed=np.random.default_rng(8)).T
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12)


def test_shared_grid_is_built_once_per_workplace(scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    a = shared_grid(wp, moves=MOVES_16)
    assert shared_grid(wp, moves=MOVES_16) is a
    fresh = occupancy_grid(wp, moves=MOVES_16)
    np.testing.assert_array_equal(a.moves, fresh.moves)
    assert shared_grid(wp, radius=0.3, moves=MOVES_16) is not a


def _numpy_gp_sample(gp, x, n, rng):
    """TransitionGP.sample as the NumPy code it was before it was compiled (the reference)."""
    from mjwalk.gait.transition import POOL_SHARPNESS

    p, d = x.shape
    h = x @ gp._neg_zs_t + gp._half_zs2
    h += np.einsum("pd,pd->p", x * gp._half_inv_l2, x)[:, None]
    np.maximum(h, 0.0, out=h)
    e = np.exp(-h)
    mean = e @ gp._c_alpha
    var = gp.signal_var - np.einsum("pm,pm->p", e @ gp._c2_w, e)
    c = np.cumsum(np.exp(-POOL_SHARPNESS * (h - h.min(axis=1, keepdims=True))), axis=1)
    u = rng.random((p, n)) * c[:, -1:]
    cell = np.array([c[i].searchsorted(u[i]) for i in range(p)])
    k = gp.res_pool.shape[1]
    cell = cell * k + rng.integers(k, size=(p, n))
    eps = rng.standard_normal((p, n, d)) * np.sqrt(np.maximum(var, 0.0))[:, None, None]
    return eps + mean[:, None, :] + gp._pool_flat[cell]


@pytest.mark.parametrize("p", [1, 2, 5])
def test_compiled_gp_draws_are_the_numpy_draws(p):
    """The compiled successor draws (packed variance for 1-2 rows, BLAS for more) give the
    NumPy formulas' draws from the same random stream, and leave the stream where NumPy
    would (the variance is a cancellation: it agrees to about 1e-10)."""
    model = default_model()
    x = model.sample_first(p, np.random.default_rng(5), "right").features
    for side, gps in (("left", model.gp), ("left", model.stop_gp)):
        gp = gps[side]
        ra, rb = np.random.default_rng(11), np.random.default_rng(11)
        got = gp.sample(x, 10, ra)
        want = _numpy_gp_sample(gp, x, 10, rb)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-8)
        assert ra.random() == rb.random()


def test_compiled_step_checks_agree_with_the_workplace_geometry(scenes_dir):
    """check_steps accepts a sampled step only when its pelvis samples keep the body radius
    (+ margin) and its landing ankle the foot clearance by the workplace's own clearance (not
    the kernel's lookup), decoded by the model (not the planner's affine map), to the field's
    bilinear rounding; every step whose pelvis comes closer is rejected. Two start poses by
    the car body: one where most steps pass, one where many run into it."""
    from mjwalk.plan import stepcheck
    from mjwalk.plan.assemble import to_world
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.options import FOOT_CLEARANCE, SAFETY_MARGIN

    wp = load_workplace(scenes_dir / "assembly_station.xml")
    model = default_model()
    pl = HybridPlanner(wp, "stand_car1", model)
    par, ipar = pl.params.vectors()
    dec = pl.decoder()
    m = pl.options.samples_per_step
    rng = np.random.default_rng(3)
    z = model.sample_next_features(model.sample_first(1, rng, "right").features, "right", 400, rng)
    batch = model.decode(z, "left")
    local, _ = batch.resample(m)
    need = pl.radius + SAFETY_MARGIN
    passed = closer = 0
    for start, yaw in (((0.0, 0.0), 0.4), ((-0.5, 0.0), 0.5)):
        node = np.array([[complex(*start), np.nan, np.nan, 0.0]])
        rows, *_, accepted, drawn = stepcheck.check_steps(
            z, dec.matrix, dec.offset, len(z), len(z), np.array([yaw]), np.array([True]),
            np.zeros(1, bool), node, pl.params.thresholds, par, ipar,
            wp.walk_field().values, pl.distance.flat_bound(),
        )  # fmt: skip
        assert drawn[0] == len(z) and accepted[0] == len(rows)
        world = to_world(start[0], start[1], yaw, local)
        clear = wp.walk_clearance(world.reshape(-1, 2)).reshape(len(z), m).min(axis=1)
        ankle = wp.walk_clearance(to_world(start[0], start[1], yaw, batch.footprint[:, :2]))
        ok = np.zeros(len(z), bool)
        ok[rows] = True
        assert np.all(clear[ok] >= need - 0.005)
        assert np.all(ankle[ok] >= FOOT_CLEARANCE - 0.005)
        assert not ok[clear < need - 0.005].any()
        passed += ok.sum()
        closer += (clear < need - 0.005).sum()
    assert passed > 300 and closer > 50  # (measured: 368 and 63)


def test_start_in_the_goal_area_is_refused(scenes_dir):
    from mjwalk.plan.hybrid import HybridPlanner

    model_default = default_model()
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    with pytest.raises(PlanningError, match="already lies in the goal area"):
        HybridPlanner(wp, "stand_car1", model_default).plan(
            wp.point("stand_car1") + 0.05, np.random.default_rng(0)
        )


def _field_ref(grid, to_goal, inside):
    """The distance field with the whole graph (moves and goal edges) built per goal, as
    before the move graph was kept per grid."""
    import math

    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra

    from mjwalk.plan.heuristic import _rim

    ny, nx = grid.free.shape
    n = nx * ny
    idx = np.arange(n).reshape(ny, nx)
    rows, cols, weights = [], [], []
    for k, (di, dj) in enumerate(grid.offsets):
        src = idx[grid.moves[k]]
        rows.append(src + dj * nx + di)
        cols.append(src)
        weights.append(np.full(src.shape, grid.cell * math.hypot(di, dj)))
    rows.append(np.full(int(inside.sum()), n))
    cols.append(idx[inside])
    weights.append(to_goal[inside])
    graph = coo_matrix(
        (np.concatenate(weights), (np.concatenate(rows), np.concatenate(cols))),
        shape=(n + 1, n + 1),
    ).tocsr()
    return _rim(grid, dijkstra(graph, directed=True, indices=n)[:n].reshape(ny, nx))


def test_kept_move_graph_gives_the_same_fields(workplace):
    """Distance fields from the move graph kept per grid (the goal node's row appended) are
    those of the graph built whole for each goal, bit for bit."""
    from mjwalk.plan.heuristic import _dijkstra_field

    grid = shared_grid(workplace, 0.08, 0.25, MOVES_16)
    ny, nx = grid.free.shape
    gx, gy = grid.x0 + grid.cell * np.arange(nx), grid.y0 + grid.cell * np.arange(ny)
    cx, cy = np.meshgrid(gx, gy)
    rng = np.random.default_rng(5)
    done = 0
    for _ in range(8):
        goal = rng.uniform([gx[0], gy[0]], [gx[-1], gy[-1]])
        to_goal = np.hypot(cx - goal[0], cy - goal[1])
        inside = (to_goal <= rng.uniform(0.1, 0.6)) & grid.free
        if inside.any():
            ref = _field_ref(grid, to_goal, inside)
            assert np.array_equal(_dijkstra_field(grid, to_goal, inside), ref)
            done += 1
    assert done >= 4
