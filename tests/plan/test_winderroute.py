"""Tests of mjwalk.plan.winderroute: a conforming winder taken by the route over levels and
walked end to end, led in from a level walk (issue 47, item 3). The scenes are
``tests/conftest.py``'s quarter-turn winders; every test here fails on the tree before this
module (no winder was routed: "walks over levels take straight flights only")."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from mjwalk.errors import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan import windercross
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH
from mjwalk.plan.levelplan import endpoint, plan_level_walk
from mjwalk.plan.levelroute import RouteLeg, crossings, step_up_limit
from mjwalk.plan.levelsearch import level_route
from mjwalk.plan.levelstitch import KIND_NAMES
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.treadshare import flight_refusal
from mjwalk.plan.walkpath import PathStep
from mjwalk.plan.windercross import winder_footfalls
from mjwalk.plan.winderroute import (
    WinderWay,
    foot_refusal,
    oriented,
    oriented_legs,
    route_winders,
    way_in,
    winder_cross_walk,
    winder_entry_time,
    winder_notes,
    winder_time,
)
from mjwalk.world import load_workplace

CLEAR = PlannerOptions().radius + CELL_SIZE


def _workplace(tmp_path_factory, xml: str, name: str):
    path = tmp_path_factory.mktemp(name) / f"{name}.xml"
    path.write_text(xml)
    return load_workplace(path)


@pytest.fixture(scope="module")
def balanced(tmp_path_factory, winder_xml):
    """The conforming quarter-turn winder: seven treads (five turned), floor to deck, 8 x 0.17 m."""
    return _workplace(tmp_path_factory, winder_xml("balanced"), "balanced")


@pytest.fixture(scope="module")
def way(balanced) -> WinderWay:
    (c,) = route_winders(balanced.levels, CLEAR)
    return c


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def test_the_winder_is_a_route_crossing_along_its_walk_line(way):
    w = way.winder
    assert w is not None and way.kind == "winder"
    assert (way.lower, way.upper) == (w.lower, w.upper)
    # its stances are the winder's, its bent axis through every nosing's middle
    for level in (way.lower, way.upper):
        assert np.allclose(way.end(level), w.end(level), atol=1e-9)
    assert np.allclose(way.point(way.knots[1:-1]), [e.mean(axis=0) for e in w.nosings], atol=1e-9)
    # beyond the stances along the first and last nosing's normals
    assert np.allclose(way.point(way.approach - 0.5), w.end(w.lower) - 0.5 * w.normal(0))
    assert np.allclose(way.point(way.exit + 0.5), w.end(w.upper) + 0.5 * w.normal(-1))
    # heights: the floor before the first nosing, each tread, the deck past the last
    nosing = way.knots[1:-1]
    assert np.allclose(way.height_at(nosing - 0.01), w.z[:-1])
    assert np.allclose(way.height_at(nosing + 0.01), w.z[1:])
    assert way.fits(0.17 + 1e-6) and not way.fits(0.16)


def test_the_winder_is_lined_up_with_at_the_end_it_is_entered_from(way):
    """Up: the first nosing's normal; down: the reverse of the last's (a quarter turn apart)."""
    w = way.winder
    assert w is not None
    up, down = oriented(way, "up"), oriented(way, "down")
    assert math.isclose(up.yaw, math.atan2(w.normal(0)[1], w.normal(0)[0]))
    back = -w.normal(-1)
    assert abs(math.remainder(down.yaw + math.pi - math.atan2(back[1], back[0]), math.tau)) < 1e-9
    assert abs(math.remainder(up.yaw - down.yaw, math.tau)) == pytest.approx(math.pi / 2, abs=0.05)


def test_a_walk_over_levels_joined_only_by_the_winder_goes_up_and_down_it(balanced, model):
    """Before: PlanningError "... walks over levels take straight flights only"."""
    walker = Walker()
    conditioned = model.for_walker(walker)
    top = balanced.levels.levels[way_upper(balanced)].height - balanced.floor_z
    for a, b, first, last in (("low", "high", 0.0, top), ("high", "low", top, 0.0)):
        walk = plan_level_walk(balanced, a, b, conditioned, np.random.default_rng(0))
        route = walk.meta["levels"]["route"]
        assert [r["kind"] for r in route] == ["level", "winder", "level"]
        assert route[1]["direction"] == ("up" if a == "low" else "down")
        assert walk.z is not None
        assert walk.z[0] == pytest.approx(first) and walk.z[-1] == pytest.approx(last)
        # every riser a step on the stairs, the trailing foot's step off the last tread too
        stairs = walk.meta["levels"]["per_kind"]["stairs"]
        assert stairs["steps"] == 8 + 1
        assert stairs["seconds"] > 0.0
        # the walk turns with the winder, smoothly: no jump of the pelvis, yaw within a step's
        assert float(np.max(np.linalg.norm(np.diff(walk.xy, axis=0), axis=1))) < 0.03
        assert float(np.max(np.abs(np.diff(np.unwrap(walk.yaw))))) < 0.05


def way_upper(balanced) -> int:
    (c,) = route_winders(balanced.levels, CLEAR)
    return c.upper


def test_the_winder_counts_as_stairs_in_the_walk_record():
    assert KIND_NAMES["winder"] == "stairs"


def test_the_walk_over_the_winder_is_led_in_from_the_level_walk(way):
    """The walker arrives walking at the line-up point a step length before the stance: the
    crossing's first step swings the other foot than the step that brought it there, from
    that step's landing, and level steps along the first nosing's normal lead into the stair
    (never a standing start at the first footfall)."""
    walker = Walker()
    w = way.winder
    assert w is not None
    n0 = w.normal(0)
    at = w.end(w.lower) - walker.step_length * n0  # the line-up point
    yaw = math.atan2(n0[1], n0[0])
    left = np.array([-n0[1], n0[0]])
    landed = np.array([*(at + 0.06 * left), yaw])
    stance = np.array([*(at - 0.06 * left - 0.3 * n0), yaw])
    last = PathStep("left", 0, 60, landed, stance, foot_z=0.0, stance_z=0.0)
    walk = winder_cross_walk(way, "up", walker, (at, yaw), last, 0.0)
    first = walk.steps[0]
    assert first.side == "right"
    assert np.allclose(first.stance, landed)
    sides = [s.side for s in walk.steps]
    assert all(a != b for a, b in itertools.pairwise(sides))
    # level steps before the first tread, none longer than the step length
    on_level = [s for s in walk.steps if s.foot_z == 0.0]
    assert len(on_level) >= 2
    feet = np.array([s.foot[:2] for s in on_level])
    gaps = np.linalg.norm(np.diff(np.vstack([landed[:2], feet]), axis=0), axis=1)
    assert float(np.max(gaps)) <= walker.step_length + DEFAULT_STEP_WIDTH + 1e-9
    # then every tread once and the deck
    assert [round(s.foot_z, 3) for s in walk.steps[len(on_level) :]][:8] == [
        round(0.17 * i, 3) for i in range(1, 9)
    ]


def test_a_walker_arriving_off_the_winders_heading_turns_on_the_spot_first(way):
    walker = Walker()
    w = way.winder
    assert w is not None
    at = w.end(w.lower) - walker.step_length * w.normal(0)
    yaw = math.atan2(w.normal(0)[1], w.normal(0)[0]) + math.radians(150)
    walk = winder_cross_walk(way, "up", walker, (at, yaw), None, 0.0)
    turns = np.abs(np.diff(np.unwrap([yaw, *[s.foot[2] for s in walk.steps]])))
    assert float(np.max(turns)) <= math.radians(60) + 1e-6


def test_the_route_times_the_winder_by_its_footfalls(way):
    walker = Walker()
    assert way.winder is not None
    for direction in ("up", "down"):
        want = float(np.sum(winder_footfalls(way.winder, direction, walker).times))
        assert winder_time(way, direction, walker) == pytest.approx(want)


def test_a_tall_walker_takes_the_winder_as_it_takes_a_straight_flight(balanced, way, scenes_dir):
    """A 1.85 m walker's 0.281 m foot fits no 0.29 m tread wholly keeping 5 mm off its edges
    and hangs over the nosings, as on the multi-level station's straight 0.28 m flight: one rule
    (mjwalk.world.norms.MIN_TREAD_SHARE), both taken (before it the winder was refused and the
    flight, with no limit on the overhang, taken)."""
    tall = Walker(stature=1.85)
    assert foot_refusal(way, tall) is None and foot_refusal(way, Walker()) is None
    station = load_workplace(scenes_dir / "multilevel_station.xml")
    stair = next(c for c in crossings(station.levels, 0.33) if c.kind == "stair")
    assert flight_refusal(stair, tall) is None
    a, b = endpoint(balanced, "low", "start"), endpoint(balanced, "high", "goal")
    legs = level_route(balanced, a, b, tall, PlannerOptions(), step_up_limit(tall))
    assert [leg.crossing.kind for leg in legs if leg.crossing is not None] == ["winder"]


def test_a_foot_the_treads_hold_too_little_of_is_refused_naming_it(balanced, way, monkeypatch):
    """With a share of the foot no tread holds (the whole foot with 5 mm to spare: the rule's
    machinery, not its figure) the route refuses the winder and names the tread."""
    monkeypatch.setattr(windercross, "MIN_TREAD_SHARE", 1.0)
    tall = Walker(stature=1.86)  # not the cached route of the test before
    assert foot_refusal(way, tall) is not None and foot_refusal(way, Walker()) is None
    a, b = endpoint(balanced, "low", "start"), endpoint(balanced, "high", "goal")
    options = PlannerOptions()
    with pytest.raises(PlanningError) as err:
        level_route(balanced, a, b, tall, options, step_up_limit(tall))
    msg = str(err.value)
    assert f"the winder from L{way.lower} to L{way.upper} is not taken: winder tread" in msg
    assert "foot (stature 1.86 m)" in msg and "\n" not in msg


def test_a_riser_above_the_step_up_limit_is_refused_naming_it(balanced, way):
    a, b = endpoint(balanced, "low", "start"), endpoint(balanced, "high", "goal")
    with pytest.raises(PlanningError, match=r"0.170 m riser, above the walker's step-up limit"):
        level_route(balanced, a, b, Walker(), PlannerOptions(), 0.15)
    assert winder_notes(balanced.levels, CLEAR, Walker(), 0.19) == []


@pytest.mark.parametrize("ends", [("low", "high"), ("high", "low")])
def test_a_winder_breaking_the_step_rule_stays_refused(tmp_path_factory, winder_xml, ends):
    wedges = _workplace(tmp_path_factory, winder_xml("wedges"), "wedges")
    assert route_winders(wedges.levels, CLEAR) == []
    a, b = endpoint(wedges, ends[0], "start"), endpoint(wedges, ends[1], "goal")
    with pytest.raises(PlanningError, match="break DIN 18065"):
        level_route(wedges, a, b, Walker(), PlannerOptions(), 0.19)


def _with_straight_flight(xml: str) -> str:
    """``xml`` with a straight flight of seven 0.29 m treads, 0.17 m risers, 1 m wide, from the
    floor at x 4.53 m up -x to the deck's edge at x 2.5 m (y 1-2 m)."""
    treads = "".join(
        f'<geom name="flight{i}" type="box" size="0.145 0.5 {0.085 * i:.4f}" '
        f'pos="{2.5 + (7.5 - i) * 0.29:.4f} 1.5 {0.085 * i:.4f}"/>'
        for i in range(1, 8)
    )
    return xml.replace("</worldbody>", treads + "</worldbody>")


def test_a_walker_whose_foot_no_winder_tread_holds_takes_the_straight_flight(
    tmp_path_factory, winder_xml, monkeypatch
):
    """Both the winder and a straight flight join floor and deck: the 1.75 m and the 1.85 m
    walker take the nearer winder (the 1.85 m walker's foot over its nosings, as on the flight);
    a walker whose foot no winder tread holds (here, with the whole foot asked of a winder
    tread: the machinery, not the rule's figure) takes the flight."""
    both = _workplace(tmp_path_factory, _with_straight_flight(winder_xml("balanced")), "both")
    a, b = endpoint(both, "low", "start"), endpoint(both, "high", "goal")
    for stature, kind in ((1.75, "winder"), (1.85, "winder"), (1.86, "stair")):
        if kind == "stair":
            monkeypatch.setattr(windercross, "MIN_TREAD_SHARE", 1.0)
        walker = Walker(stature=stature)
        legs = level_route(both, a, b, walker, PlannerOptions(), step_up_limit(walker))
        assert [leg.crossing.kind for leg in legs if leg.crossing is not None] == [kind]


def test_a_routes_winder_legs_are_oriented_and_the_others_kept(way):
    level = RouteLeg("level", 0, np.zeros(2), np.ones(2))
    down = RouteLeg("cross", way.upper, way.end(way.upper), way.end(way.lower), way, "down")
    legs = oriented_legs([level, down])
    assert legs[0] is level
    assert legs[1].crossing is not None and legs[1].crossing.yaw == oriented(way, "down").yaw
    assert legs[1].crossing.yaw != way.yaw


@pytest.mark.parametrize("direction", ["up", "down"])
def test_the_route_times_the_turn_on_the_spot_before_the_winder_as_walked(way, direction):
    """A walker standing at the winder's stance facing 150 deg off the way in turns on the
    spot in two steps before it (:func:`way_in`, Patla et al.'s 60 deg a step): the route's
    time with that arrival (:func:`winder_time`, the search's :func:`winder_entry_time`) counts
    them and is within one step time of the walk's; without them (the route's time before) it
    missed the walk by two step times."""
    walker = Walker()
    w = way.winder
    assert w is not None
    level, n = (w.lower, w.normal(0)) if direction == "up" else (w.upper, -w.normal(-1))
    yaw = math.atan2(n[1], n[0]) + math.radians(150)
    assert way_in(way, direction, yaw)[1].size == 2
    plain = winder_time(way, direction, walker)
    timed = winder_time(way, direction, walker, yaw)
    assert timed == pytest.approx(plain + 2 * walker.step_duration)
    assert winder_entry_time(way, direction, walker, yaw) == pytest.approx(timed - plain)
    start = (w.end(level), yaw)
    walk = winder_cross_walk(oriented(way, direction), direction, walker, start, None, 0.0)
    assert abs(walk.duration - timed) <= walker.step_duration
    assert abs(walk.duration - plain) > walker.step_duration
    # facing the way in there is nothing to turn
    assert winder_time(way, direction, walker, math.atan2(n[1], n[0])) == plain


def test_the_turn_before_the_winder_sends_a_walker_from_behind_it_up_the_flight(
    tmp_path_factory, winder_xml
):
    """From (3.5, -1.5) m the winder's line-up point lies behind the walker: it arrives there
    facing about 180 deg off the way in, two steps on the spot (0.53 s each) before it. With
    them counted the straight flight is the quicker way, as walked (plan_level_walk, seeds
    0-2: 12.8-13.2 s by the flight, 13.1-13.9 s by the winder, which ``both`` forced the
    route over before: the turn was not counted)."""
    both = _workplace(tmp_path_factory, _with_straight_flight(winder_xml("balanced")), "behind")
    a, b = endpoint(both, (3.5, -1.5), "start"), endpoint(both, "high", "goal")
    legs = level_route(both, a, b, Walker(), PlannerOptions(), 0.19)
    assert [leg.crossing.kind for leg in legs if leg.crossing is not None] == ["stair"]


def _spiral(tmp_path_factory, spiral_xml, kind: str):
    """A spiral stair scene (``tests/conftest.py``'s ``SPIRALS[kind]``) and its path."""
    path = tmp_path_factory.mktemp(kind) / f"spiral_{kind}.xml"
    path.write_text(spiral_xml(kind))
    return load_workplace(path), path


@pytest.mark.parametrize("kind", ["half", "quarter"])
def test_a_spiral_stair_is_routed_as_a_winder_along_its_walk_line(
    tmp_path_factory, spiral_xml, kind
):
    """Round its post, a spiral stair meeting DIN 18065 on its walk line (0.19 m risers, 0.268 m
    treads) is a winder crossing the 1.55 m and 1.75 m walkers take, up and down. Before, its
    treads' narrow ends at the post (0.04-0.05 m) refused it: "0.045 m deep at its narrow end,
    under 0.10 m"."""
    spiral, _ = _spiral(tmp_path_factory, spiral_xml, kind)
    (c,) = route_winders(spiral.levels, CLEAR)
    assert c.winder is not None and c.fits(0.19)
    for stature in (1.55, 1.75):
        walker = Walker(stature=stature)
        assert foot_refusal(c, walker) is None
        for ends in (("low", "high"), ("high", "low")):
            a, b = endpoint(spiral, ends[0], "start"), endpoint(spiral, ends[1], "goal")
            legs = level_route(spiral, a, b, walker, PlannerOptions(), step_up_limit(walker))
            assert [leg.crossing.kind for leg in legs if leg.crossing is not None] == ["winder"]


@pytest.mark.slow
@pytest.mark.parametrize("stature", [1.55, 1.75])
def test_a_walk_up_and_down_the_spiral_stair_touches_nothing(
    tmp_path_factory, spiral_xml, model, stature
):
    """The half-turn spiral walked up and down (seed 0) with the legs synthesised and lifted
    onto its treads: no humanoid-vs-scene contact, the post included."""
    from mjwalk.timeline import collision_report, timeline_from_walk  # deferred: slow tier only

    spiral, path = _spiral(tmp_path_factory, spiral_xml, "half")
    conditioned = model.for_walker(Walker(stature=stature))
    for a, b in (("low", "high"), ("high", "low")):
        walk = plan_level_walk(spiral, a, b, conditioned, np.random.default_rng(0))
        assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "winder", "level"]
        assert walk.meta["levels"]["per_kind"]["stairs"]["steps"] == 8 + 1
        contacts = collision_report(timeline_from_walk(walk, path, stature=stature))
        assert contacts == [], (a, b, contacts[:3])


@pytest.mark.parametrize("ends", [("low", "high"), ("high", "low")])
def test_a_spiral_too_steep_on_its_walk_line_is_refused_in_one_line(
    tmp_path_factory, spiral_xml, ends
):
    """Three 30 deg treads turning a quarter: 0.304 m on the walk line, 2R + T = 0.684 m.
    Before, the walk line lay mid-nosing and the refusal gave 0.280 m and the narrow ends."""
    steep, _ = _spiral(tmp_path_factory, spiral_xml, "steep")
    a, b = endpoint(steep, ends[0], "start"), endpoint(steep, ends[1], "goal")
    with pytest.raises(PlanningError) as err:
        level_route(steep, a, b, Walker(), PlannerOptions(), 0.19)
    msg = str(err.value)
    assert "tread spiral1: 2R + T = 2 x 0.190 + 0.304 = 0.684 m on the walk line" in msg
    assert "narrow end" not in msg and "\n" not in msg
