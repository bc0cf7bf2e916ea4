"""The minimum-jerk guide a walk's heading follows between its end poses (issue 38, curved
starts and ends): its geometry, and seeded statistics of walks planned along it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.ndimage import uniform_filter1d

from mjwalk import InputError
from mjwalk.gait.default import default_model
from mjwalk.plan.guide import (
    PURSUIT_AHEAD,
    guide_aim,
    guide_is_clear,
    guide_start_heading,
    minimum_jerk_guide,
    resample_guide,
    via_point_guide,
    via_points_guide,
)
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.request import WalkRequest
from mjwalk.world import load_workplace

WALKS = 12


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


@pytest.fixture(scope="module")
def open_floor(scenes_dir):
    return load_workplace(scenes_dir / "open_floor.xml")


def _direction(points: np.ndarray, k: int) -> float:
    d = points[k + 1] - points[k] if k >= 0 else points[-1] - points[-2]
    return math.atan2(d[1], d[0])


def test_the_guide_leaves_and_arrives_along_its_headings():
    """The curve runs from start to goal, leaves along the start heading and arrives along the
    goal heading (to the resolution of 400 points), and with both headings along the chord it
    is the chord."""
    g = minimum_jerk_guide((-3.0, 1.0), (3.0, 1.0), math.radians(40), math.radians(-20))
    assert np.allclose(g[0], (-3.0, 1.0)) and np.allclose(g[-1], (3.0, 1.0))
    assert abs(math.degrees(_direction(g, 0)) - 40.0) < 1.0
    assert abs(math.degrees(_direction(g, -1)) + 20.0) < 1.0
    straight = minimum_jerk_guide((-3.0, 1.0), (3.0, 1.0), 0.0, None)
    assert np.abs(straight[:, 1] - 1.0).max() < 1e-12
    with pytest.raises(ValueError):
        minimum_jerk_guide((1.0, 1.0), (1.0, 1.0), 0.0, 0.0)


def test_the_aim_is_the_guides_direction_on_it_and_steers_back_onto_a_straight_guide():
    """On the guide the aim is its direction (within the polyline's few degrees); off a
    straight guide by s it is the direction to the goal turned back towards the guide by
    atan(s / PURSUIT_AHEAD) (the guide's point two steps on), and without a guide the
    direction to the goal."""
    g = resample_guide(minimum_jerk_guide((0.0, 0.0), (6.0, 0.0), math.radians(40), None))
    goal = complex(6.0, 0.0)
    for k in (2, 8, 14, 20):
        aim = guide_aim(g.ravel(), complex(*g[k]), goal)
        seg = _direction(g, k)
        assert abs(math.remainder(aim - seg, math.tau)) < math.radians(4.0), k
    line = resample_guide([(0.0, 0.0), (6.0, 0.0)]).ravel()
    assert PURSUIT_AHEAD == pytest.approx(1.455, abs=1e-3)  # two 0.73 m steps
    for p in (complex(1.0, 0.7), complex(3.0, -1.2), complex(4.0, 0.3)):
        d = goal - p
        back = math.atan2(p.imag, PURSUIT_AHEAD)  # left of the line: turned right
        want = math.atan2(d.imag, d.real) - back
        assert guide_aim(line, p, goal) == pytest.approx(want, abs=1e-9)
        assert guide_aim(np.array([np.nan]), p, goal) == pytest.approx(
            math.atan2(d.imag, d.real), abs=1e-9
        )
    # near the goal it steers for the goal point itself: within PURSUIT_AHEAD of it
    p = complex(5.5, 0.1)
    assert guide_aim(line, p, goal) == pytest.approx(
        math.atan2(-0.1, 0.5) - math.atan2(0.1, 0.5), abs=1e-9
    )


def test_a_walking_start_bends_towards_the_goal_over_the_walk(model, open_floor):
    """A walker already walking 40 deg off the way to a goal 6 m ahead curves onto it over the
    walk, as the minimum-jerk path between the two poses does (largest sideways excursion
    0.76 m), rather than turning onto the goal within a few steps: 12 seeded walks, median
    largest excursion within 60-130 % of the guide's (measured 0.67 m, 88 %) and 0.1 m more
    than walks aiming straight at the goal from the same start (measured 0.50 m)."""
    planner = HybridPlanner(open_floor, (3.0, 0.0), model)
    start = (-3.0, 0.0, math.radians(40))
    guide_lat = minimum_jerk_guide(start[:2], (3.0, 0.0), start[2], None)[:, 1].max()
    bent, aimed = [], []
    for k in range(WALKS):
        bent.append(planner.plan(start, np.random.default_rng(k)).xy[:, 1].max())
        straight = [(-3.0, 0.0), (3.0, 0.0)]  # the straight guide: aim at the goal
        aimed.append(
            planner.plan(WalkRequest(start, guide=straight), np.random.default_rng(k))
            .xy[:, 1]
            .max()
        )
    assert 0.6 * guide_lat <= np.median(bent) <= 1.3 * guide_lat, (np.median(bent), guide_lat)
    assert np.median(bent) >= np.median(aimed) + 0.1, (np.median(bent), np.median(aimed))


def test_a_walk_bends_into_its_goal_heading(model, open_floor):
    """Given the heading the walker means to arrive at (-50 deg, the chord at 0 deg), the last
    fifth of the walk comes in along it: 12 seeded walks, median direction of the last fifth
    between -50 and -20 deg (measured -34 deg); without it, within 10 deg of the chord
    (measured -1 deg)."""
    planner = HybridPlanner(open_floor, (3.0, 0.0), model)
    into, plain = [], []
    for k in range(WALKS):
        for out, heading in ((into, math.radians(-50)), (plain, None)):
            p = planner.plan(
                WalkRequest((-3.0, 0.0), goal_heading=heading), np.random.default_rng(k)
            )
            d = p.xy[-1] - p.xy[int(0.8 * len(p.xy))]
            out.append(math.degrees(math.atan2(d[1], d[0])))
    assert -50.0 <= np.median(into) <= -20.0, np.median(into)
    assert abs(np.median(plain)) <= 10.0, np.median(plain)


def _bend(xy: np.ndarray, s: np.ndarray, g: np.ndarray) -> tuple[float, float]:
    """The largest offset (m) of the path ``xy`` from the chord s -> g and its excess over
    that chord (m)."""
    u = (g - s) / np.hypot(*(g - s))
    rel = xy - s
    lat = np.abs(u[0] * rel[:, 1] - u[1] * rel[:, 0]).max()
    walked = np.hypot(*np.diff(xy, axis=0).T).sum()
    return float(lat), float(walked - np.hypot(*(xy[-1] - xy[0])))


def test_free_walks_between_two_headings_keep_their_guides_bend(model, open_floor):
    """Issue 48: where nothing is in the way the planner does not cut the bend of the
    minimum-jerk path between a walk's two headings, nor lose either heading. A walker already
    walking 20 deg left of a 6 m chord, meaning to arrive 20 deg right of it (a C-shaped bow)
    or 20 deg left (an S), 6 seeded walks each: after THOR's 800 ms moving average (how
    people's tracks are measured: benchmarks/bench_thor.py) the median walk's largest offset
    from the chord is within 0.85-1.3 of the guide's and its excess over the chord within
    0.75-1.25 of the guide's (measured C 1.00 and 0.90, S 1.15 and 1.00; over 27 such cases,
    4-8 m and 10-30 deg, medians 1.06 and 1.01: benchmarks/bench_freebend.py)."""
    s, g = np.array((-3.0, -1.0)), np.array((3.0, -1.0))
    planner = HybridPlanner(open_floor, tuple(g), model)
    a = math.radians(20.0)
    for end in (-a, a):
        lat0, excess0 = _bend(minimum_jerk_guide(s, g, a, end, 2000), s, g)
        lats, excesses = [], []
        for k in range(6):
            p = planner.plan(WalkRequest((*s, a), goal_heading=end), np.random.default_rng(k))
            size = max(1, round(0.8 / float(np.median(np.diff(p.t)))))
            lat, excess = _bend(uniform_filter1d(p.xy, size=size, axis=0, mode="nearest"), s, g)
            lats.append(lat / lat0)
            excesses.append(excess / excess0)
        assert 0.85 <= np.median(lats) <= 1.3, (end, lats)
        assert 0.75 <= np.median(excesses) <= 1.25, (end, excesses)


def test_a_guide_through_an_obstacle_is_not_followed(model, scenes_dir):
    """A guide that does not keep the body's clearance is left to the route search: the walk
    is planned, and keeps its clearance."""
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    a, b = wp.station("stand_car1").pos[:2], wp.station("stand_rack3").pos[:2]
    through = [a, (0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]) + 8.0), b]  # off the floor
    assert not guide_is_clear(wp, np.array(through), 0.25)
    planner = HybridPlanner(wp, "stand_rack3", model)
    p = planner.plan(WalkRequest("stand_car1", guide=through), np.random.default_rng(0))
    assert np.all(wp.walk_clearance(p.xy) >= 0.25 - 1e-6)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"goal_heading": float("nan")}, "goal_heading"),
        ({"goal_heading": "north"}, "goal_heading"),
        ({"guide": [(0.0, 0.0)]}, "guide"),
        ({"guide": [(0.0, 0.0), (float("inf"), 1.0)]}, "guide"),
    ],
)
def test_bad_guides_are_named(kwargs, message):
    with pytest.raises(InputError, match=message):
        WalkRequest((-3.0, 0.0), **kwargs)


def test_the_via_point_path_is_smooth_through_its_waypoint():
    """Flash & Hogan's via-point path passes its waypoint with no kink (the direction turns by
    less than a degree between neighbouring samples there), starts and ends along the given
    headings, and among paths through the waypoint has less jerk than two independent pieces
    meeting parallel to the chord (the integrated squared third difference)."""
    from mjwalk.plan.guide import via_point_guide

    g = via_point_guide((0.0, 0.0), (2.0, 0.8), (6.0, 0.0), 0.0, 0.0)
    k = int(np.argmin(np.hypot(*(g - (2.0, 0.8)).T)))
    assert np.hypot(*(g[k] - (2.0, 0.8))) < 1e-9
    turn = [_direction(g, j) for j in (k - 1, k)]
    assert abs(math.degrees(math.remainder(turn[1] - turn[0], math.tau))) < 1.0
    assert abs(_direction(g, 0)) < math.radians(1.0) and abs(_direction(g, -1)) < math.radians(1.0)
    two = np.vstack(
        [
            minimum_jerk_guide((0.0, 0.0), (2.0, 0.8), 0.0, 0.0, 160),
            minimum_jerk_guide((2.0, 0.8), (6.0, 0.0), 0.0, 0.0, 241)[1:],
        ]
    )

    def jerk(p):
        q = resample_guide(p, 400)
        return float(np.sum(np.diff(q, n=3, axis=0) ** 2))

    assert jerk(g) < jerk(two)


def test_walkable_paths_turn_no_sharper_than_a_quarter_turn_per_step():
    """A circle of radius r is walkable for steps up to r * pi / 2 long, not longer."""
    from mjwalk.plan.detour import walkable

    a = np.linspace(0.0, math.pi, 400)
    arc = 0.5 * np.stack([np.cos(a), np.sin(a)], axis=1)
    assert walkable(arc, 0.5 * math.pi / 2 * 0.95)
    assert not walkable(arc, 0.5 * math.pi / 2 * 1.05)


def test_the_way_left_along_a_guide():
    """guide_ahead: the distance to the guide plus its length from the nearest point on; 0
    without a guide."""
    from mjwalk.plan.guide import guide_ahead

    line = resample_guide([(0.0, 0.0), (6.0, 0.0)]).ravel()
    assert guide_ahead(line, complex(1.0, 0.5)) == pytest.approx(5.5)
    assert guide_ahead(line, complex(6.0, 0.0)) == pytest.approx(0.0, abs=1e-12)
    assert guide_ahead(line, complex(-1.0, 0.0)) == pytest.approx(7.0)
    arc = resample_guide(minimum_jerk_guide((0.0, 0.0), (6.0, 0.0), math.radians(40), None))
    length = float(np.hypot(*np.diff(arc, axis=0).T).sum())
    assert guide_ahead(arc.ravel(), complex(*arc[0])) == pytest.approx(length)
    assert guide_ahead(np.full(4, np.nan), complex(1.0, 1.0)) == 0.0


def test_the_compiled_clearance_scan_finds_the_densified_lookups_first_low_point(scenes_dir):
    """first_below (one compiled pass that stops at the first point below the limit) finds
    the point the 5 cm densify and the workplace's own walk_clearance lookup find, on 400
    random polylines through a station with obstacles and floor edges, or finds none where
    they find none."""
    from mjwalk.plan.guide import densify, first_below

    wp = load_workplace(scenes_dir / "assembly_station.xml")
    xmin, ymin, xmax, ymax = wp.floor_bounds
    rng = np.random.default_rng(5)
    found = 0
    for _ in range(400):
        start = rng.uniform((xmin, ymin), (xmax, ymax))
        pts = start + np.cumsum(rng.normal(0.0, 0.5, (int(rng.integers(2, 12)), 2)), axis=0)
        limit = rng.uniform(0.1, 0.5)
        dense = densify(pts)
        low = np.flatnonzero(wp.walk_clearance(dense) < limit)
        got = first_below(wp, pts, limit)
        assert (got is None) == (len(low) == 0)
        if len(low):
            found += 1
            assert np.allclose(got, dense[low[0]], atol=1e-9)
    assert 50 < found < 390  # both outcomes were exercised
    with pytest.raises(ValueError, match="length"):
        first_below(wp, [(1.0, 1.0), (1.0, 1.0)], 0.3)


def _quintic_basis() -> np.ndarray:
    """Monomial coefficients (6, 6) of the quintic Hermite basis in the order position 0,
    velocity 0, acceleration 0, acceleration 1, velocity 1, position 1, derived here from its
    end conditions (an independent reference for mjwalk.plan.guide)."""
    k = np.arange(6)
    rows = [
        (k == 0).astype(float),  # value at 0
        (k == 1).astype(float),  # first derivative at 0
        2.0 * (k == 2),  # second derivative at 0
        k * (k - 1.0),  # second derivative at 1
        k.astype(float),  # first derivative at 1
        np.ones(6),  # value at 1
    ]
    return np.linalg.inv(np.array(rows))  # column j: the basis function of condition j


def _via_point_reference(p0, w, p1, h0, h1, n=400) -> np.ndarray:
    """The via-point minimum-jerk path by NumPy least squares over the sampled jerk (Flash &
    Hogan 1985), from the basis derived above: what via_point_guide must give."""
    basis = _quintic_basis()
    l1, l2 = np.hypot(*(w - p0)), np.hypot(*(p1 - w))
    length = l1 + l2
    t1, t2 = l1 / length, l2 / length
    v0 = length * (np.array([math.cos(h0), math.sin(h0)]) if h0 is not None else (w - p0) / l1)
    v1 = length * (np.array([math.cos(h1), math.sin(h1)]) if h1 is not None else (p1 - w) / l2)
    s = np.linspace(0.0, 1.0, 64)
    third = np.stack([np.zeros_like(s)] * 3 + [6.0 + 0 * s, 24.0 * s, 60.0 * s * s])  # (6, 64)
    jerk = basis.T @ third  # (6 conditions, 64): each condition's jerk in s

    def pieces(vw, aw):
        zero = np.zeros(2)
        return (
            np.stack([p0, v0 * t1, zero, aw * t1**2, vw * t1, w]),
            np.stack([w, vw * t2, aw * t2**2, zero, v1 * t2, p1]),
        )

    def sampled_jerk(vw, aw):  # per axis, time-weighted, in real time units
        a, b = pieces(vw, aw)
        return np.concatenate(
            [math.sqrt(t1) * jerk.T @ a / t1**3, math.sqrt(t2) * jerk.T @ b / t2**3]
        )

    base = sampled_jerk(np.zeros(2), np.zeros(2))
    unit = np.zeros(2)
    a_v = sampled_jerk(unit + 1.0, unit) - base  # linear in vw (same coefficient per axis)
    a_a = sampled_jerk(unit, unit + 1.0) - base
    sol = [
        np.linalg.lstsq(np.stack([a_v[:, k], a_a[:, k]], axis=1), -base[:, k], rcond=None)[0]
        for k in range(2)
    ]
    vw, aw = np.array([sol[0][0], sol[1][0]]), np.array([sol[0][1], sol[1][1]])
    a, b = pieces(vw, aw)
    m1 = min(n - 1, max(2, round(n * t1)))

    def points(ends, m):
        u = np.linspace(0.0, 1.0, m)
        return (u[:, None] ** np.arange(6)) @ (basis @ ends)

    return np.vstack([points(a, m1), points(b, n - m1 + 1)[1:]])


def test_the_via_point_path_is_the_least_squares_one():
    """via_point_guide's path (its via velocity and acceleration solved by the normal
    equations of the sampled jerk, compiled) is the path NumPy's least squares gives on the
    basis derived from the end conditions, to 1e-9 m (random poses); and walkable's compiled
    curvature test agrees with np.gradient's."""
    from mjwalk.plan.detour import walkable
    from mjwalk.plan.guide import via_point_guide

    rng = np.random.default_rng(2)
    for i in range(60):
        p0, w, p1 = rng.uniform(-4.0, 4.0, (3, 2))
        h0 = None if i % 3 == 0 else rng.uniform(-3.0, 3.0)
        h1 = None if i % 4 == 0 else rng.uniform(-3.0, 3.0)
        got = via_point_guide(p0, w, p1, h0, h1)
        assert np.allclose(got, _via_point_reference(p0, w, p1, h0, h1), atol=1e-9)
    for _ in range(200):
        path = np.cumsum(rng.normal(0.0, 0.3, (int(rng.integers(2, 40)), 2)), axis=0)
        step = rng.uniform(0.05, 1.5)
        d = np.gradient(path, axis=0)
        dd = np.gradient(d, axis=0)
        bend = np.abs(d[:, 0] * dd[:, 1] - d[:, 1] * dd[:, 0])
        speed = np.maximum(np.hypot(*d.T), 1e-12)
        assert walkable(path, step) == bool(np.all(bend * step <= (math.pi / 2) * speed**3))


def test_resampling_is_numpys_interpolation_along_the_length():
    """resample_guide (compiled) gives np.interp's points at np.linspace's stations along the
    cumulative length, to 1e-12 m, on random polylines with repeated points."""
    rng = np.random.default_rng(4)
    for i in range(300):
        pts = np.cumsum(rng.normal(0.0, 0.5, (int(rng.integers(3, 40)), 2)), axis=0)
        if i % 5 == 0:
            pts[2] = pts[1]
        n = int(rng.integers(2, 200))
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
        u = np.linspace(0.0, s[-1], n)
        ref = np.stack([np.interp(u, s, pts[:, 0]), np.interp(u, s, pts[:, 1])], axis=1)
        assert np.allclose(resample_guide(pts, n), ref, atol=1e-12)


def test_a_guide_through_several_points_passes_each_smoothly():
    """Through two via points: the path starts and ends at the ends, passes within 1 cm of
    each via point, along the direction from the point before to the point after, and its
    direction turns by less than 10 deg between neighbouring points (no kinks); one via point
    is via_point_guide's path."""
    vias = np.array([(-1.5, 0.8), (1.5, 0.9)])
    path = via_points_guide((-4.0, 0.0), vias, (4.0, 0.0), 0.0, 0.0)
    assert np.allclose(path[0], (-4.0, 0.0)) and np.allclose(path[-1], (4.0, 0.0))
    for w in vias:
        assert np.hypot(*(path - w).T).min() < 0.01
    d = np.diff(path, axis=0)
    turn = np.diff(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))
    assert np.abs(turn).max() < np.radians(10.0)
    one = via_points_guide((-4.0, 0.0), vias[:1], (4.0, 0.0), None, None)
    assert np.allclose(one, via_point_guide((-4.0, 0.0), vias[0], (4.0, 0.0), None, None))


@pytest.fixture(scope="module")
def empty_hall_offsets(open_floor, model):
    """12 seeded 5 m walks across the open floor, from a stand (odd seeds) and already walking
    along the chord (even): per walk the pelvis's largest offset from the chord (m), raw and
    after the tracks' 800 ms moving average (THOR's, benchmarks/bench_thor.py: how people's
    walked paths are measured, the step-to-step sway averaged out)."""
    (x0, y0, x1, y1) = (float(v) for v in open_floor.floor_bounds)
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    s, g = (cx - 2.5, cy), (cx + 2.5, cy)
    planner = HybridPlanner(open_floor, g, model)
    raw, smooth = [], []
    for k in range(WALKS):
        start = s if k % 2 else (*s, 0.0)
        p = planner.plan(start, np.random.default_rng(k))
        size = max(1, round(0.8 / float(np.median(np.diff(p.t)))))
        averaged = uniform_filter1d(p.xy[:, 1], size=size, mode="nearest")
        raw.append(float(np.abs(p.xy[:, 1] - cy).max()))
        smooth.append(float(np.abs(averaged - cy).max()))
    return np.array(raw), np.array(smooth)


def test_straight_walks_in_an_empty_hall_are_drawn_back_to_their_chord(empty_hall_offsets):
    """Steering for the guide's point two steps on (PURSUIT_AHEAD) draws a walk that drifts
    with its sampled steps back onto its chord, and a walker standing with no known facing
    sets off along its guide (guide_start_heading): of the 12 walks the worst stays within
    0.10 m of it (measured 0.070 m; 0.089 m when the stand starts set off anywhere within
    START_SPREAD of the downhill heading, 0.124 m when nothing drew a walk back), and within
    0.06 m after the tracks' 800 ms average (measured 0.045 m; 0.063 m and up to 0.10 m
    before); the median walk within 0.06 m (measured 0.051 m)."""
    raw, smooth = empty_hall_offsets
    assert raw.max() <= 0.10, raw
    assert smooth.max() <= 0.06, smooth
    assert np.median(raw) <= 0.06, raw


def test_a_walker_standing_with_no_facing_sets_off_along_its_guide(model, open_floor):
    """A walk from a stand with no start yaw sets off along its guide's first direction
    (guide_start_heading), not anywhere within START_SPREAD of the downhill heading (one of
    72 directions): along an oblique chord (13.5 deg, between those directions) the first
    two steps carry the pelvis within 4 deg of the chord in each of 8 seeded walks (measured
    at most 2.5 deg, median 1.7 deg; up to 5.7 deg with the spread, whose walks went up to
    0.12 m off the chord, now 0.08 m)."""
    (x0, y0, x1, y1) = (float(v) for v in open_floor.floor_bounds)
    s = np.array((0.5 * (x0 + x1) - 2.5, 0.5 * (y0 + y1) - 0.6))
    g = s + (5.0, 1.2)
    chord = math.atan2(1.2, 5.0)
    assert guide_start_heading(resample_guide([s, g])) == pytest.approx(chord, abs=1e-9)
    curve = resample_guide(minimum_jerk_guide(s, g, math.radians(40), None))
    assert abs(math.degrees(guide_start_heading(curve)) - 40.0) < 4.0  # its first segment
    planner = HybridPlanner(open_floor, tuple(g), model)
    off = []
    for k in range(8):
        p = planner.plan(tuple(s), np.random.default_rng(100 + k))
        e = p.xy[p.steps[1].end] - s
        off.append(math.degrees(math.remainder(math.atan2(e[1], e[0]) - chord, math.tau)))
    assert np.abs(off).max() <= 4.0, off


@pytest.mark.xfail(
    strict=True,
    reason="issue 48 target not met: the pelvis's sway over the first walking step (up to "
    "4.4 cm beyond its footfalls' midline) leaves the worst walk 0.070 m off its chord "
    "(0.045 m after the tracks' 800 ms average)",
)
def test_straight_walks_in_an_empty_hall_stay_within_6_cm_of_their_chord(empty_hall_offsets):
    """A smooth path over the whole way has nothing to bend for in an empty hall (issue 48):
    the 12 walks are to keep the pelvis within 0.06 m of the chord between their ends.
    Measured: worst 0.070 m (seed 3, from a stand; seed 6, walking, 0.066 m; seed 1 0.061 m),
    so the target is marked as not met. Since stand starts set off along their guide
    (guide_start_heading) the walk's line stays within 0.045 m of the chord after the 800 ms
    average; what is left is the pelvis's sway over the first walking step after the starter:
    seed 3 swings 4.4 cm beyond the midline of its footfalls (a 5 cm step width), seed 6
    4.3 cm, against about 2.5 cm in steady walking (Orendurff et al., "The effect of walking
    speed on center of mass displacement", J Rehabil Res Dev 41:829-834, 2004: 4-7 cm of
    side-to-side excursion, less the faster the walk). Before: worst 0.089 m (seed 7, a
    starter set off 5 deg left of the chord within START_SPREAD and a wide second step;
    seed 11 0.077 m). People's straight walks do not meet this target either: the 91
    captured straight walks of the shared data's bandai-walk (measured as here over their
    first 5 m, from the chord of those 5 m, every pelvis sample) are median 0.054 m, 90th
    percentile 0.073 m, worst 0.096 m off it, 41 % of them beyond 0.06 m; after the 800 ms
    average median 0.032 m, 90th percentile 0.050 m (these walks: 0.051 / 0.070 m raw,
    0.031 / 0.045 m averaged). Tried and not kept (stand starts still spread): the heading
    weight 4x (worst 0.118 m); the heading term on the direction of the last two steps'
    pelvis travel instead of the step frame's (worst 0.140 m). Measured before the stand
    starts set off along their guide: not the steering's doing: with a look-ahead of half a
    step instead of two (PURSUIT_AHEAD / 4, tried, not kept) the worst walk is 0.091 m and
    seed 7 unchanged; the offsets come from the sampled steps' own placement (seed 7: its
    footfalls' midline 5 cm left over steps 2-4), which a heading-error cost of a few
    hundredths of a radian barely tells apart. Nor does a cost on the footfalls' midline off
    the guide close it (tried, not kept: foot placement control after Bruijn & van Dieen 2018,
    the midline's offset s costed as the heading error atan(s / L) of the step L that takes it
    back, weight 5.2 as the heading term). Over 36 seeds (these 12 and 24 more), walks over
    0.06 m: 10 without it, 9 with L one step (0.73 m), 7 with L a third of a step, 8 with that
    and 90 starters instead of 30; the worst of seeds 0-11 0.089 / 0.099 / 0.094 / 0.067 m.
    The pelvis sways about 2.5 cm (median) beyond its footfalls' midline, so the midline must
    stay within about 3 cm. What leaves it: walks from a stand whose first two footfalls are
    already off (seed 7: the starter's right foot 0.8 cm right of the chord, the next left
    foot 13.5 cm left, midline 6.4 cm; seed 25: 17 cm), the 10 sampled successors offering no
    narrower next step (seed 7 with 40 successors and the cost: 0.071 m); and closing steps
    anywhere in the goal area (seed 22 of the last variant: 16 cm off in its last step)."""
    raw, _ = empty_hall_offsets
    assert raw.max() <= 0.06, raw


def test_the_way_left_from_segment_lengths_made_once_is_bit_equal():
    """guide_rest over guide_lengths (once per walk, slots.P_GUIDE_LEN0) gives the way left as
    the per-step loop before it did (a hypot per segment, summed from the nearest point on),
    bit for bit at every segment and share."""
    from numba import njit

    from mjwalk.plan.guide import guide_ahead_at, guide_nearest
    from mjwalk.plan.stepcost import guide_lengths, guide_rest

    @njit
    def per_step(guide, best_k, best_w, best_d2):  # guide_ahead_at before issue 50
        n = guide.shape[0] // 2
        rest = 0.0
        for k in range(best_k, n - 1):
            seg = math.hypot(guide[2 * k + 2] - guide[2 * k], guide[2 * k + 3] - guide[2 * k + 1])
            rest += seg * (1.0 - best_w) if k == best_k else seg
        return math.sqrt(best_d2) + rest

    arc = resample_guide(minimum_jerk_guide((0.0, 0.0), (6.0, 2.0), math.radians(40), None))
    flat = arc.ravel()
    lengths = guide_lengths(flat)
    rng = np.random.default_rng(0)
    for p in rng.uniform(-1.0, 7.0, (200, 2)):
        k, w, d2 = guide_nearest(flat, complex(*p))
        assert guide_rest(lengths, k, w, d2) == per_step(flat, k, w, d2)
        assert guide_ahead_at(flat, k, w, d2) == per_step(flat, k, w, d2)
