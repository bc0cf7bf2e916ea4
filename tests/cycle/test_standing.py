"""Stand zones: walks end where the work is within reach, not on one point (issue 14 item 3)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.anthropometry import hand_reach
from mjwalk.cycle.simulate import plan_cycle_walks, prepare
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.standing import (
    REACH_MARGIN,
    SIDE_SLACK,
    ZONE_STEPS,
    StandZones,
    stand_zone,
    work_zone,
)
from mjwalk.errors import InputError, PlanningError
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.request import WalkRequest


def test_hand_reach_grows_with_stature_and_lean_and_shrinks_below_the_shoulder():
    assert hand_reach(1.1, 1.90) > hand_reach(1.1, 1.75) > hand_reach(1.1, 1.60)
    assert hand_reach(1.1, lean_deg=20.0) > hand_reach(1.1) > hand_reach(1.1, lean_deg=0.0)
    assert hand_reach(0.8) < hand_reach(1.1)  # a low shelf: the arm goes down, not out
    assert hand_reach(3.0) == 0.0  # above the fingertips
    # the arm of a 1.75 m person (Winter: 0.386 H to the grip) plus shoulder and lean
    assert 0.6 < hand_reach(1.1) < 0.8


def test_zone_keeps_every_target_in_reach_and_never_excludes_the_site():
    """A stand site at the origin facing -y (a shelf ahead): one far target (beyond reach from
    the site) and one near target, both picked with the left hand."""
    far = (0.0, -0.9, 1.1)
    near = (0.1, -0.5, 1.1)
    zone = stand_zone((0.0, 0.0), [near, far], 0.7, facing=-np.pi / 2, hands=["left", "left"])
    assert zone.radius == pytest.approx(ZONE_STEPS * 0.7)
    assert zone.contains((0.0, 0.0))
    assert not zone.contains((0.0, 0.05))  # farther from the far target than the site
    r_near = hand_reach(1.1) - REACH_MARGIN
    assert (0.1, -0.5, r_near) in zone.discs
    assert not zone.contains((0.0, 0.4))  # beyond half a step
    # facing -y the walker's left is +x: the left shoulder is in front of a target when the
    # body stands half a shoulder width to the target's right (-x), not farther
    slack = SIDE_SLACK * 1.75
    assert zone.contains((-slack + 0.01, -0.1))
    assert not zone.contains((-slack - 0.02, -0.1))
    assert not zone.contains((0.15, -0.1))  # left of both targets: the arm would cross over


def test_planner_refuses_goal_discs_that_exclude_the_goal(scenes_dir):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.world import load_workplace

    wp = load_workplace(scenes_dir / "open_floor.xml")
    with pytest.raises(PlanningError, match="outside disc 0"):
        HybridPlanner(
            wp,
            (2.0, 0.0),
            default_model(progress=False),
            PlannerOptions(goal_within=((5.0, 5.0, 0.5),)),
        )
    with pytest.raises(InputError, match="radius > 0"):
        PlannerOptions(goal_within=((2, 0, -1),))


@pytest.fixture(scope="module")
def station_walks(scenes_dir):
    ctx = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    walks = []
    for run in range(200):
        rng = np.random.default_rng(np.random.SeedSequence([0, run]))
        walks += plan_cycle_walks(ctx, rng)
    return ctx, walks


def test_station_walks_end_in_their_zones_and_spread_there(station_walks):
    """Seeded, 200 cycles: every walk ends in its stand zone; the end points of walks to the
    car spread (standard deviation > 4 cm along the car, where the screws are well within
    reach)."""
    ctx, walks = station_walks
    step = ctx.step_model.pace().step_length
    ends: dict[str, list] = {}
    for i, _, goal, path in walks:
        assert ctx.zone(i, ctx.spec.stature, step).contains(path.xy[-1])
        ends.setdefault(goal, []).append(path.xy[-1])
    along_car = np.array(ends["stand_car1"])[:, 0]
    assert along_car.std() > 0.04


def test_walks_end_at_the_spot_they_aim_at_and_spread_over_the_zone(station_walks):
    """Seeded, 200 cycles: every walk aims at a spot of its stand zone (``meta["spot"]``) and
    ends within SPOT_REACH step lengths of it; where people stand is not one point, so route
    T3's walk from car 2 to rack 1 spreads: length IQR/median >= 3.5 % (1000 cycles: 4.9 %;
    2.0 % when walks ended at the first place in the zone their steps reached)."""
    from mjwalk.cycle.walking import SPOT_REACH

    ctx, walks = station_walks
    step = ctx.step_model.pace().step_length
    t3 = []
    for i, here, goal, path in walks:
        spot = np.asarray(path.meta["spot"])
        assert path.meta["spot_tolerance"] == pytest.approx(SPOT_REACH * step)
        assert np.hypot(*(path.xy[-1] - spot)) <= SPOT_REACH * step + 1e-9
        assert ctx.zone(i, ctx.spec.stature, step).contains(spot)
        if (here, goal) == ("stand_car2", "stand_rack1"):
            t3.append(path.length)
    q25, q50, q75 = np.percentile(t3, [25, 50, 75])
    assert (q75 - q25) / q50 >= 0.035


def test_operators_zones_share_one_distance_field_per_site(station_walks):
    """The planners of one site for operators of different step lengths (stand zones of
    different radii) start their distance fields from the same goal cells: one field, computed
    once (in a 100 m hall a field takes about a second)."""
    ctx, walks = station_walks
    i = next(k for k, _, goal, _ in walks if goal == "stand_car1")
    short = ctx.planner("stand_car1", ctx.zone(i, 1.60, 0.55))
    long = ctx.planner("stand_car1", ctx.zone(i, 1.90, 0.80))
    assert short.options.goal_tolerance != pytest.approx(long.options.goal_tolerance)
    assert short.distance.cells is long.distance.cells


def test_planner_walks_to_a_spot_of_its_goal_area_only(scenes_dir):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.world import load_workplace

    wp = load_workplace(scenes_dir / "open_floor.xml")
    planner = HybridPlanner(
        wp, (2.0, 0.0), default_model(progress=False), PlannerOptions(goal_tolerance=0.5)
    )
    path = planner.plan(WalkRequest((-2.0, 0.0), spot=(2.3, 0.2, 0.1)), np.random.default_rng(0))
    assert np.hypot(path.xy[-1, 0] - 2.3, path.xy[-1, 1] - 0.2) <= 0.1
    assert path.meta["spot"] == [2.3, 0.2]
    with pytest.raises(PlanningError, match="outside the goal area"):
        planner.plan(WalkRequest((-2.0, 0.0), spot=(3.0, 0.0, 0.1)), np.random.default_rng(0))
    with pytest.raises(InputError, match="tolerance > 0"):
        WalkRequest((-2.0, 0.0), spot=(2.1, 0.0, 0.0))


@pytest.fixture(scope="module")
def workforce_walks(scenes_dir):
    """The walks of 200 cycles, each by the operator its run draws from the shipped
    workforce (as simulate_cycle draws it: the run generator's first spawned stream)."""
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    ctx = prepare(spec)
    walks = []
    for run in range(200):
        rng = np.random.default_rng(np.random.SeedSequence([0, run]))
        walker = spec.population.draw(rng.spawn(3)[0])
        walks += plan_cycle_walks(ctx, rng, walker)
    return ctx, walks


@pytest.mark.slow  # among the fast tier's longest in a quiet warm run (9-10 s): its 5 min budget
@pytest.mark.parametrize("route", ["T2", "T3", "T5"])
@pytest.mark.parametrize("who", ["model", "workforce"])
def test_no_wandering(station_walks, workforce_walks, route, who):
    """Seeded, 200 cycles: the 99th percentile of a route's walk lengths is at most 1.35 times
    its grid-A* length (issue 14: walks that loop around a rack are wandering, not variance),
    for the model's own walker and for the shipped workforce (slow operators with short steps
    looped on the short T5 until WANDER_SEARCHES: p99 1.38)."""
    ctx, walks = station_walks if who == "model" else workforce_walks
    ratios = [
        path.length / ctx.baseline(here, goal)
        for i, here, goal, path in walks
        if ctx.spec.tasks[i].route == route
    ]
    assert np.percentile(ratios, 99) <= 1.35


def test_wandering_walks_are_planned_again(scenes_dir, monkeypatch):
    """A walk longer than WANDER_FACTOR times the route is searched again with fresh steps; when
    every one of the WANDER_SEARCHES searches wanders the shortest is returned, marked."""
    import mjwalk.plan.hybrid as hybrid
    from mjwalk.gait.default import default_model
    from mjwalk.world import load_workplace

    wp = load_workplace(scenes_dir / "assembly_station.xml")
    planner = hybrid.HybridPlanner(wp, "stand_car1", default_model(progress=False))
    walk = planner.plan("stand_rack2", np.random.default_rng(0))
    assert walk.meta["wandering"] is False and walk.meta["attempts"] == 1
    monkeypatch.setattr(hybrid, "WANDER_FACTOR", 0.5)  # every walk "wanders"
    walk = planner.plan("stand_rack2", np.random.default_rng(0))
    assert walk.meta["wandering"] is True and walk.meta["searches"] == hybrid.WANDER_SEARCHES
    assert (
        hybrid.WANDER_SEARCHES >= planner.options.attempts
    )  # loops get as many searches as dead ends


def test_cycle_starts_anywhere_in_the_start_zone_and_every_start_sets_off(scenes_dir):
    """The cycle's operator starts where the work at the start site left them: 60 seeded runs'
    starts all lie in the start's stand zone, clear of obstacles by the radius and the start
    margin, spread over it (not on the site's mark), and a walk can set off from each."""
    from mjwalk.cycle.walking import START_MARGIN, cycle_start, start_zone

    ctx = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    step = ctx.step_model.pace().step_length
    zone = start_zone(ctx.spec, ctx.workplace, ctx.spec.stature, step)
    field = ctx.workplace.walk_field()
    starts = []
    for run in range(60):
        rng = np.random.default_rng(np.random.SeedSequence([0, run]))
        xy = cycle_start(ctx, rng.spawn(3)[2], None)  # simulate_cycle's standing stream
        assert zone.contains(xy)
        assert field(np.array(xy)) >= ctx.spec.radius + START_MARGIN - 1e-9
        starts.append(xy)
        if run < 20:
            plan_cycle_walks(ctx, rng, None, xy)  # raises PlanningError if it cannot set off
    s = np.array(starts)
    site = ctx.workplace.station(ctx.spec.start).pos[:2]
    # spread over the zone: depth (y) and width (x) both vary by several centimetres
    assert s.std(axis=0).min() > 0.03
    assert np.median(np.hypot(*(s - site).T)) > 0.05


def test_kept_zones_are_the_operators_own(scenes_dir):
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    ctx = prepare(spec)
    zones = StandZones(spec, ctx.workplace, limit=4)  # the sites' work kept once per walk
    walks = [i for i, t in enumerate(spec.tasks) if t.kind in ("walk", "carry")]
    for stature, step in ((1.6, 0.6), (1.9, 0.75), (1.6, 0.6)):
        for i in walks:
            assert zones.get(i, stature, step) == work_zone(spec, ctx.workplace, i, stature, step)
