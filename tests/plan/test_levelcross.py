"""A walk over one crossing (mjwalk.plan.levelcross): footfalls on treads, stair and ramp timing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.gait.slope import slope_gait
from mjwalk.gait.stairs import ASCENT_STEP_TIME, DESCENT_STEP_TIME
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import (
    ENTRY_TURN,
    RISER_GAP,
    approach_point,
    arrival_heading,
    cross_walk,
    crossing_time,
    departure,
    entry_time,
    entry_turn,
    level_time,
    line_clear,
    route_leads,
    spot_turn,
    tread_setback,
    walked_distance,
)
from mjwalk.plan.levelroute import crossings
from mjwalk.plan.turnsplit import WALKING_TURN_MAX
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def by_kind(scenes_dir):
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    return {c.kind: c for c in crossings(wp.levels, 0.33)}


@pytest.mark.parametrize("direction", ["up", "down"])
def test_stair_walk_puts_a_foot_on_every_tread_at_the_stair_cadence(by_kind, direction):
    stair, walker = by_kind["stair"], Walker()
    start = stair.end(stair.lower if direction == "up" else stair.upper)
    facing = stair.yaw if direction == "up" else stair.yaw + math.pi  # no turn on the spot
    walk = cross_walk(stair, direction, walker, (start, facing), None, 0.0)
    walk.validate()
    heights = sorted({round(z, 3) for s in walk.steps for z in (s.foot_z, s.stance_z)})
    assert heights == pytest.approx([0.0, 0.17, 0.34, 0.51, 0.68, 0.85, 1.02])
    climbing = [s for s in walk.steps if abs(s.foot_z - s.stance_z) > 1e-6]
    assert len(climbing) == 6  # one riser per step, never two
    step_time = ASCENT_STEP_TIME if direction == "up" else DESCENT_STEP_TIME
    for s in climbing:
        assert (s.end - s.start) / 120.0 == pytest.approx(step_time, abs=1 / 120)
    assert walk.ground[-1] == pytest.approx(1.02 if direction == "up" else 0.0)
    assert crossing_time(stair, direction, walker) == pytest.approx(walk.duration, abs=0.05)
    assert walk.meta["edges"] == stair.riser_lines(0.0)  # for the legs' swing (landing47)


def test_slower_walkers_take_longer_on_the_stair(by_kind):
    stair = by_kind["stair"]
    fast = crossing_time(stair, "up", Walker(speed=1.5))
    slow = crossing_time(stair, "up", Walker(speed=0.9))
    assert slow > fast


def test_ramp_walk_follows_the_plane_at_the_ramp_pace(by_kind):
    ramp, walker = by_kind["ramp"], Walker()
    walk = cross_walk(ramp, "up", walker, (ramp.end(ramp.lower), ramp.yaw), None, 0.0)
    walk.validate()
    gait = slope_gait(walker, ramp.slope)
    for s in walk.steps:
        assert (s.end - s.start) / 120.0 == pytest.approx(gait.step_time, abs=1 / 120)
        x = float(s.foot[0])
        expected = float(np.clip((5.731033 - x) * np.tan(ramp.slope), 0.0, 0.34))
        assert s.foot_z == pytest.approx(expected, abs=0.01)
    assert walk.ground[-1] == pytest.approx(0.34)


@pytest.mark.parametrize("direction", ["up", "down"])
def test_stair_feet_are_centred_on_their_treads(by_kind, direction):
    """Every foot on a tread stands heel to toe tip within its tread's depth (the ankle set
    back by half the foot's front less its back: :func:`tread_setback`); the foot on the level
    before the first riser going up (past the last going down) keeps its toes (heel)
    :data:`RISER_GAP` off that riser's face; and no step spans the stance's clearance and a
    tread at once: each foot moves at most two treads' depth (and that gap)."""
    stair, walker = by_kind["stair"], Walker()
    start = stair.end(stair.lower if direction == "up" else stair.upper)
    facing = stair.yaw if direction == "up" else stair.yaw + math.pi  # no turn on the spot
    walk = cross_walk(stair, direction, walker, (start, facing), None, 0.0)
    g = leg_geometry(walker.stature)
    back = tread_setback(stair, stair.track, walker.stature, direction)
    assert back[1:-1] == pytest.approx(0.5 * (g.foot_front - g.foot_back))
    ahead = 1.0 if direction == "up" else -1.0  # the walking direction along the axis
    edges = 0.5 * (stair.track[:-1] + stair.track[1:])  # the risers
    bounds = np.concatenate([[edges[0] - stair.tread], edges, [edges[-1] + stair.tread]])
    on_flight = 0
    for s in walk.steps:
        along = float((s.foot[:2] - stair.origin) @ stair.axis)
        heel, toe = along - ahead * g.foot_back, along + ahead * g.foot_front
        k = np.searchsorted(bounds, along)
        if 1 <= k < len(bounds):  # on a tread or a half tread of the track
            on_flight += 1
            lo, hi = bounds[k - 1], bounds[k]
            lo, hi = (-np.inf if k == 1 else lo), (np.inf if k == len(bounds) - 1 else hi)
            assert lo - 1e-9 <= min(heel, toe) and max(heel, toe) <= hi + 1e-9
            if direction == "up" and k == 1:  # the toes before the first riser
                assert edges[0] - toe >= RISER_GAP - 1e-9
            if direction == "down" and k == len(bounds) - 1:  # the heel past the last riser
                assert heel - edges[-1] >= RISER_GAP - 1e-9
    assert on_flight == len(stair.track)
    feet = {}
    for s in walk.steps:
        if s.side in feet:
            # two treads, and the level foot's step back off the riser (less than RISER_GAP)
            assert np.hypot(*(s.foot[:2] - feet[s.side])) <= 2 * stair.tread + RISER_GAP
        feet[s.side] = s.foot[:2]


@pytest.mark.parametrize("direction", ["up", "down"])
def test_lead_in_and_departure_walk_on_the_axis_in_steps_no_longer_than_a_step(by_kind, direction):
    c, w = by_kind["stair"], Walker()
    lead = w.step_length
    up = direction == "up"
    here, there = (c.lower, c.upper) if up else (c.upper, c.lower)
    point = approach_point(c, direction, lead)
    assert float(np.hypot(*(point - c.end(here)))) == pytest.approx(lead)
    # away from the flight: before the approach stance going up, past the exit going down
    s_point = float(np.dot(point - c.origin, c.axis))
    assert (s_point < c.approach) if up else (s_point > c.exit)
    yaw = c.yaw if up else c.yaw + np.pi
    plain = cross_walk(c, direction, w, (c.end(here), yaw), None, 0.0)
    walked = departure(c, direction, lead)
    assert float(np.hypot(*(walked.end(there) - c.end(there)))) == pytest.approx(lead)
    # the level step that brought the walker to the approach point: its left foot lands
    # beside it, the right one stands a step behind
    left = np.array([-np.sin(yaw), np.cos(yaw)])
    behind = point - lead * np.array([np.cos(yaw), np.sin(yaw)]) - 0.06 * left
    h = float(c.height_at(s_point)) - c.z_lower
    last = PathStep(
        "left", 0, 60, np.array([*(point + 0.06 * left), yaw]), np.array([*behind, yaw]), h, h
    )
    start = (point, yaw)
    longer = cross_walk(walked, direction, w, start, last, 0.0, lead_in=True)
    # the lead-in and the departure add level steps, none longer than the walker's step
    assert len(longer.steps) > len(plain.steps)
    feet = np.array([s.foot[:2] for s in longer.steps])
    along = np.abs(np.diff((feet - c.origin) @ c.axis))
    assert along.max() <= w.step_length + 1e-9
    assert np.hypot(*(longer.xy[-1] - walked.end(there))) < 0.01
    # without either, the crossing's walk is as before
    again = cross_walk(c, direction, w, (c.end(here), yaw), None, 0.0)
    assert np.array_equal(again.xy, plain.xy)


def test_route_leads_line_up_at_every_crossing_and_depart_from_stairs_only(by_kind):
    """Ramps line up too (the platform cycle's run 14 came to the ramp's stance facing 120 deg
    off its axis and turned onto it in one step)."""
    lead = 0.7
    for kind, c in by_kind.items():
        for lv, direction in ((c.lower, "up"), (c.upper, "down")):
            dep, line = route_leads(c, lv, lead)
            point = approach_point(c, direction, lead)
            assert line is not None
            assert (dep is not None) == (kind == "stair")
            for p in (dep, line):
                if p is not None:
                    assert p == pytest.approx(point)
                    assert float(np.hypot(*(p - c.end(lv)))) == pytest.approx(lead)


def test_walked_distance_adds_the_line_up_and_the_departure_detours():
    """Open floor (the field is the straight distance): a walk arriving from the side of a
    flight walks to its line-up point a step length out on the axis and then along the axis;
    one leaving a stair walks a step length on first; a walk already on the axis, or too short
    for a line-up, keeps its direct distance."""
    goal = np.array([0.0, 0.0])

    def field(xy):
        return float(np.hypot(*(np.asarray(xy) - goal)))

    lead, reach = 0.7, (0.7, 0.2)
    line = np.array([-lead, 0.0])  # the line-up point of a flight going +x from ``goal``
    side = np.array([0.0, -3.0])
    d = walked_distance(field(side), field, (side, None), (goal, line), reach)
    assert d == pytest.approx(float(np.hypot(*(line - side))) + lead)
    behind = np.array([-3.0, 0.0])  # on the axis: the line-up is on the way
    assert walked_distance(3.0, field, (behind, None), (goal, line), reach) == pytest.approx(3.0)
    near = np.array([0.0, -0.8])
    assert walked_distance(0.8, field, (near, None), (goal, line), reach) == 0.8
    # leaving a stair whose departure point lies away from the goal: out and back
    start, dep = np.array([2.0, 0.0]), np.array([2.0 + lead, 0.0])
    d = walked_distance(2.0, field, (start, dep), (goal, None), reach)
    assert d == pytest.approx(lead + 2.0 + lead)


def test_entry_turn_is_the_last_headings_turn_onto_the_axis(by_kind):
    """The ramp goes up towards -x (yaw pi): a walk ending at yaw 60 deg turns 120 deg onto it
    going up and 60 deg going down; ENTRY_TURN is Patla et al.'s one-step direction change."""
    ramp = by_kind["ramp"]
    walk = WalkPath(t=np.array([0.0, 0.1]), xy=np.zeros((2, 2)), yaw=np.radians([0.0, 60.0]))
    assert np.degrees(entry_turn(walk, ramp, "up")) == pytest.approx(120.0)
    assert np.degrees(entry_turn(walk, ramp, "down")) == pytest.approx(60.0)
    assert ENTRY_TURN == WALKING_TURN_MAX


def test_line_clear_checks_the_body_radius_along_the_segment():
    class Wall:  # clearance: distance to the wall x = 1
        @staticmethod
        def walk_clearance(xy):
            return np.abs(1.0 - np.asarray(xy)[..., 0])

    a = np.array([0.0, 0.0])
    assert line_clear(Wall, a, np.array([0.0, 2.0]), 0.3)
    assert not line_clear(Wall, a, np.array([0.8, 0.0]), 0.3)


def test_level_time_adds_a_step_for_walking_from_standing_to_standing(scenes_dir):
    """A route's level leg costs its distance at the walker's speed plus one step duration
    where it is walked; the planner's own walks from rest to rest on the open floor take that
    extra step (seeds 0-2, 2.5 and 4 m: within half a step of it, ending in the goal area)."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.request import WalkRequest

    walker = Walker()
    assert level_time(2.0, True, walker) == pytest.approx(2.0 / walker.speed + walker.step_duration)
    assert level_time(2.0, False, walker) == pytest.approx(2.0 / walker.speed)
    wp = load_workplace(scenes_dir / "open_floor.xml")
    model = default_model(progress=False).for_walker(walker)
    for d in (2.5, 4.0):
        planner = HybridPlanner(wp, (d / 2, 0.0), model)
        times = [
            planner.plan(WalkRequest((-d / 2, 0.0, 0.0)), np.random.default_rng(s)).duration
            for s in range(3)
        ]
        assert abs(float(np.mean(times)) - level_time(d, True, walker)) < 0.5 * walker.step_duration


def test_spot_turn_splits_a_large_turn_into_steps_within_entry_turn():
    """A turn over ENTRY_TURN is made in equal parts of at most ENTRY_TURN, the last part left
    to the crossing's first step; a turn within it needs no step on the spot."""
    assert spot_turn(0.3, 0.3 + 0.9 * ENTRY_TURN).size == 0
    for turn in (math.radians(106.0), -math.radians(147.0), math.pi, 2 * ENTRY_TURN):
        heads = spot_turn(0.2, 0.2 + turn)
        parts = np.diff(np.concatenate([[0.2], heads, [0.2 + turn]]))
        assert heads.size == math.ceil(abs(turn) / ENTRY_TURN - 1e-9) - 1
        assert np.all(np.abs(parts) <= ENTRY_TURN + 1e-12)
        assert np.allclose(parts, parts[0])


def test_a_walker_facing_away_turns_on_the_spot_before_the_flight(by_kind):
    """Standing a step before a stair facing 140 deg off its axis (rack1 -> mezzanine's floor
    leg, issue 47), the walker turns on the spot first: no step turns the pelvis more than
    ENTRY_TURN, the steps on the spot keep the pelvis where it stood, then the lead-in."""
    c = by_kind["stair"]
    walker = Walker()
    xy0 = approach_point(c, "up", walker.step_length)
    yaw0 = c.yaw + math.radians(140.0)
    last = PathStep(
        "left", 0, 1, np.array([*(xy0 + [0.05, 0.0]), yaw0]), np.array([*(xy0 - [0.05, 0.0]), yaw0])
    )
    walk = cross_walk(c, "up", walker, (xy0, yaw0), last, 0.0, lead_in=True)
    turns = [abs(math.remainder(walk.yaw[s.end] - walk.yaw[s.start], math.tau)) for s in walk.steps]
    assert max(turns) <= ENTRY_TURN + 1e-9
    assert turns[0] > math.radians(45.0) and turns[1] > math.radians(45.0)
    assert np.hypot(*(walk.xy[walk.steps[0].end] - xy0)) < 0.07
    assert abs(math.remainder(walk.yaw[-1] - c.yaw, math.tau)) < 1e-9


@pytest.mark.parametrize("off", [0.0, 50.0, 100.0, 140.0, -170.0])
def test_crossing_time_counts_the_turn_on_the_spot_as_the_walk_takes_it(by_kind, off):
    """A walker standing at the stair's stance facing ``off`` degrees from its axis: the
    crossing's estimate with that arrival heading is the walk's duration (its steps on the
    spot included, one level step each), and the turn adds ceil(|off| / 60) - 1 level steps."""
    c, walker = by_kind["stair"], Walker()
    yaw0 = c.yaw + math.radians(off)
    walk = cross_walk(c, "up", walker, (c.end(c.lower), yaw0), None, 0.0)
    assert crossing_time(c, "up", walker, yaw0) == pytest.approx(walk.duration, abs=0.05)
    steps = max(0, math.ceil(abs(off) / math.degrees(ENTRY_TURN) - 1e-9) - 1)
    assert entry_time(c, "up", walker, yaw0) == pytest.approx(steps * walker.step_duration)
    assert crossing_time(c, "up", walker) == pytest.approx(
        crossing_time(c, "up", walker, yaw0) - steps * walker.step_duration
    )


def test_arrival_heading_is_the_straight_line_or_the_routes_last_stretch(scenes_dir):
    """On open floor a walk arrives along the straight line (the field is not built); round the
    corridor's first corner, from its west leg to 1 m up its north-going leg, it arrives as the
    route comes in: heading north (within 15 deg), not along the blocked straight line (50 deg)."""
    from mjwalk.plan.heuristic import goal_distance
    from mjwalk.plan.occupancy import MOVES_16, shared_grid

    wp = load_workplace(scenes_dir / "open_floor.xml")
    a, b = np.array([-1.0, -1.0]), np.array([1.0, 1.0])
    unused = lambda: pytest.fail("field built for a clear line")  # noqa: E731
    assert arrival_heading(wp, (a, b), unused, 0.25, 0.7) == pytest.approx(math.pi / 4)
    corridor = load_workplace(scenes_dir / "corridor.xml")
    a, b = np.array([-3.0, -2.5]), np.array([0.0, 1.0])
    assert not line_clear(corridor, a, b, 0.25)
    field = goal_distance(shared_grid(corridor, 0.05, 0.25, MOVES_16), a, 0.1)
    yaw = arrival_heading(corridor, (a, b), lambda: field, 0.25, 0.7)
    assert abs(yaw - math.pi / 2) < math.radians(15.0)


def test_repeated_crossing_walks_are_equal_and_own_their_riser_lines(by_kind):
    stair, walker = by_kind["stair"], Walker()
    start = (stair.end(stair.lower), stair.yaw)
    first = cross_walk(stair, "up", walker, start, None, 0.0)  # setbacks and lines kept here
    first.meta["edges"][0]["xy"][0] = 99.0  # a caller changing its walk's record
    first.meta["edges"].pop()
    again = cross_walk(stair, "up", walker, start, None, 0.0)
    assert again.meta["edges"] == stair.riser_lines(0.0)  # not the first walk's changes
    fresh = cross_walk(stair, "up", Walker(stature=1.76), start, None, 0.0)  # another walker
    np.testing.assert_array_equal(first.xy, again.xy)
    feet = [np.asarray([s.foot for s in w.steps]) for w in (first, again, fresh)]
    np.testing.assert_array_equal(feet[0], feet[1])
    assert not np.array_equal(feet[2], feet[0])  # its own setbacks


def test_a_walk_ending_off_the_stairs_axis_lines_its_feet_up_before_the_first_riser(by_kind):
    """The multi-level station's cycle, seed 7 run 1 (issue 47): the level walk to the stair
    ended with its pelvis 0.24 m east of the axis (within its goal area) and its left foot 0.48
    m off it, 2.4 cm from the plane of the stair's east wall; the crossing's first climbing step
    swung that foot onto the first tread, the knee along the foot's 50 deg turn, 8 cm into the
    wall's end. Now a level step lines the feet up first: the foot that climbs the first riser
    leaves from its lane on the axis (half the step width off it), not from where the walk put
    it. Fails on f4101d8 (0.476 m)."""
    c = by_kind["stair"]
    walker = Walker(stature=1.73, speed=1.7098660834296446, cadence=117.27030734072214)
    xy0, yaw0 = np.array([-4.659708142775202, 0.2611763282807874]), -0.8504138548933419
    last = PathStep(
        "left", 0, 67, np.array([-4.423712931143495, 0.08412105145243914, -0.6906953392457857]),
        np.array([-4.962227759972261, 0.5484032479299258, -0.9190364448726835]), 0.0, 0.0,
    )  # fmt: skip
    # its level leg began within a step of the stance: no approach point, no lead_in
    walk = cross_walk(c, "up", walker, (xy0, yaw0), last, 0.0)
    walk.validate()
    k = next(i for i, s in enumerate(walk.steps) if abs(s.foot_z - s.stance_z) > 1e-6)
    leaves = walk.steps[k - 1].stance[:2] if k else last.foot[:2]  # the climbing foot's start
    off = (leaves - c.origin) @ np.array([-c.axis[1], c.axis[0]])
    assert abs(abs(off) - 0.06) < 0.01  # DEFAULT_STEP_WIDTH / 2: in its lane
