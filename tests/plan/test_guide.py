"""The minimum-jerk guide a walk's heading follows between its end poses (issue 38, curved
starts and ends): its geometry, and seeded statistics of walks planned along it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan.guide import guide_aim, guide_is_clear, minimum_jerk_guide, resample_guide
from mjwalk.plan.hybrid import HybridPlanner
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


def test_the_aim_is_the_guides_direction_on_it_and_the_goals_for_a_straight_guide():
    """On the guide the aim is its direction (within the polyline's few degrees); for a
    straight guide it is the direction to the goal from anywhere."""
    g = resample_guide(minimum_jerk_guide((0.0, 0.0), (6.0, 0.0), math.radians(40), None))
    goal = complex(6.0, 0.0)
    for k in (2, 8, 14, 20):
        aim = guide_aim(g.ravel(), complex(*g[k]), goal)
        seg = _direction(g, k)
        assert abs(math.remainder(aim - seg, math.tau)) < math.radians(4.0), k
    line = resample_guide([(0.0, 0.0), (6.0, 0.0)]).ravel()
    for p in (complex(1.0, 0.7), complex(3.0, -1.2), complex(5.0, 0.3)):
        d = goal - p
        assert guide_aim(line, p, goal) == pytest.approx(math.atan2(d.imag, d.real), abs=1e-9)


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
        aimed.append(planner.plan(start, np.random.default_rng(k), guide=straight).xy[:, 1].max())
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
            p = planner.plan((-3.0, 0.0), np.random.default_rng(k), goal_heading=heading)
            d = p.xy[-1] - p.xy[int(0.8 * len(p.xy))]
            out.append(math.degrees(math.atan2(d[1], d[0])))
    assert -50.0 <= np.median(into) <= -20.0, np.median(into)
    assert abs(np.median(plain)) <= 10.0, np.median(plain)


def test_a_guide_through_an_obstacle_is_not_followed(model, scenes_dir):
    """A guide that does not keep the body's clearance is left to the route search: the walk
    is planned, and keeps its clearance."""
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    a, b = wp.station("stand_car1").pos[:2], wp.station("stand_rack3").pos[:2]
    through = [a, (0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]) + 8.0), b]  # off the floor
    assert not guide_is_clear(wp, np.array(through), 0.25)
    planner = HybridPlanner(wp, "stand_rack3", model)
    p = planner.plan("stand_car1", np.random.default_rng(0), guide=through)
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
def test_bad_guides_are_named(model, open_floor, kwargs, message):
    planner = HybridPlanner(open_floor, (3.0, 0.0), model)
    with pytest.raises(PlanningError, match=message):
        planner.plan((-3.0, 0.0), np.random.default_rng(0), **kwargs)


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
