"""The planners' fast paths give the answers of the plain routines they stand in for."""

from __future__ import annotations

import zlib

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan.grid import MOVES_16, check_endpoint, occupancy_grid, shared_grid
from mjwalk.plan.heuristic import goal_distance, grid_excess
from mjwalk.plan.hybrid import HybridPlanner, _Decoder
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


def test_field_lookup_at_equals_call(workplace):
    pts = _points(workplace, 5000, 0).reshape(50, 100, 2)
    c = workplace.clearance
    np.testing.assert_allclose(c.at(pts), c(pts), rtol=0, atol=1e-12)


def test_walk_field_never_exceeds_walk_clearance(workplace):
    """One lookup in the combined field is at most the obstacle clearance and at most the
    exact distance to the floor's edge on the floor, and at most one node spacing off it."""
    pts = _points(workplace, 20000, 1)
    field = workplace.walk_field()
    combined = field.at(pts)
    exact = workplace.walk_clearance(pts)
    assert np.all(combined <= np.maximum(exact, field.resolution) + 1e-12)
    assert np.all(combined[exact >= 0] <= exact[exact >= 0] + 1e-12)
    # and it gives up little: on the floor, at most a few millimetres below it
    on = workplace.on_floor(pts)
    assert np.percentile(workplace.walk_clearance(pts[on]) - combined[on], 99) < 0.005


def test_quick_endpoint_accept_never_passes_a_bad_point(workplace):
    """check_endpoint accepts through the field only points the exact test accepts too."""
    from mjwalk.plan import grid as grid_mod

    for xy in _points(workplace, 400, 2):
        for radius in (0.05, 0.25):
            if grid_mod._clearly_free(workplace, xy, radius):
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


def test_decoder_matches_model_decoding():
    """The planner's affine map gives the model's decoded pelvis samples, landing foot and
    yaws (to rounding) for sampled features, including the far tails."""
    model = default_model()
    rng = np.random.default_rng(4)
    z = np.vstack(
        [
            model.sample_first(20, rng).features,
            model.sample_next_features(
                model.sample_first(2, rng, "left").features, "left", 50, rng
            ),
            3.0 * rng.standard_normal((20, model.n_dims)),
        ]
    )
    m = 16
    dec = _Decoder(model, m)
    got = z @ dec.matrix + dec.offset
    batch = model.decode(z, "left")
    local, _ = batch.resample(m)
    np.testing.assert_allclose(got[:, :m].real, local[..., 0], atol=1e-9)
    np.testing.assert_allclose(got[:, :m].imag, local[..., 1], atol=1e-9)
    np.testing.assert_allclose(got[:, 0], 0.0, atol=1e-12)  # every step starts at its origin
    np.testing.assert_allclose(got[:, m].real, batch.footprint[:, 0], atol=1e-9)
    np.testing.assert_allclose(got[:, m].imag, batch.footprint[:, 1], atol=1e-9)
    np.testing.assert_allclose(got[:, m + 1].real, batch.footprint[:, 2], atol=1e-9)
    np.testing.assert_allclose(got[:, m + 1].imag, batch.end_yaw, atol=1e-9)


def test_sample_next_features_are_sample_next_draws():
    model = default_model()
    prev = model.sample_first(3, np.random.default_rng(0), "right")
    a = model.sample_next(prev, 7, np.random.default_rng(9))
    b = model.sample_next_features(prev.features, "right", 7, np.random.default_rng(9))
    np.testing.assert_array_equal(a.features, b)
    assert set(a.side) == {"left"}


def test_kde_starters_are_gaussian_kde_draws():
    """sample_first draws what scipy's gaussian_kde.resample draws from the same stream (the
    kernel factor is computed once instead of per call)."""
    model = default_model()
    for side in ("left", "right"):
        got = model.sample_first(25, np.random.default_rng(8), side).features
        ref = model._kde[side].resample(25, seed=np.random.default_rng(8)).T
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12)


class _KeyedDraws:
    """The default model, except that a predecessor's successors depend on the predecessor
    alone (a seed from its features), not on when the search asks for them."""

    def __init__(self, model):
        self.model = model

    def __getattr__(self, name):
        return getattr(self.model, name)

    def sample_next_features(self, x, side, n, rng, stop=False):
        return np.concatenate(
            [
                self.model.sample_next_features(
                    row[None],
                    side,
                    n,
                    np.random.default_rng(zlib.crc32(row.tobytes()) + stop),
                    stop=stop,
                )
                for row in x
            ]
        )


@pytest.mark.parametrize(
    ("scene", "start", "goal"),
    [("assembly_station", "-3.6,-1.0", "3.6,0.6"), ("corridor", "entry", "door")],
)
def test_drawing_ahead_leaves_the_search_unchanged(scenes_dir, scene, start, goal):
    """Successor sets drawn ahead for open nodes (batch > 1) change only when draws are made:
    with draws that do not depend on their order, every batch size expands the same nodes
    and returns the same walk as drawing one node's successors at a time (batch=1)."""
    wp = load_workplace(scenes_dir / f"{scene}.xml")
    model = _KeyedDraws(default_model())
    walks = {
        b: HybridPlanner(wp, goal, model, batch=b).plan(start, np.random.default_rng(2))
        for b in (1, 3, 4)
    }
    for b in (3, 4):
        np.testing.assert_array_equal(walks[b].xy, walks[1].xy)
        for k in ("expansions", "generated", "rejected"):
            assert walks[b].meta[k] == walks[1].meta[k]


def test_shared_grid_is_built_once_per_workplace(scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    a = shared_grid(wp, moves=MOVES_16)
    assert shared_grid(wp, moves=MOVES_16) is a
    fresh = occupancy_grid(wp, moves=MOVES_16)
    np.testing.assert_array_equal(a.moves, fresh.moves)
    assert shared_grid(wp, radius=0.3, moves=MOVES_16) is not a
