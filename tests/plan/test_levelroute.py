"""Crossings between levels and the route helpers (mjwalk.plan.levelroute)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import PlanningError
from mjwalk.plan.levelroute import (
    DEFAULT_STEP_UP,
    RouteLeg,
    crossings,
    dijkstra,
    head_fits_crossing,
    place_on_edge,
    step_up_limit,
)
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def test_the_station_has_a_step_a_ramp_and_a_stair(station):
    by_kind = {c.kind: c for c in crossings(station.levels, 0.33)}
    assert set(by_kind) == {"step", "ramp", "stair"}
    stair = by_kind["stair"]
    assert len(stair.risers) == 6 and stair.tread == pytest.approx(0.28, abs=1e-6)
    # footfalls: half a tread before the first riser, the five tread centres, half a tread on top
    np.testing.assert_allclose(np.diff(stair.track), 0.28, atol=1e-6)
    np.testing.assert_allclose(stair.track_z, np.arange(7) * 0.17, atol=1e-6)
    np.testing.assert_allclose(stair.point(stair.track[1])[1], -0.24, atol=1e-6)  # tread 1
    step = by_kind["step"]
    assert step.risers == pytest.approx((0.17, 0.17)) and step.lower == 0
    assert step.height_at(np.array([-0.2, 0.1, 0.4])) == pytest.approx([0.0, 0.17, 0.34])
    ramp = by_kind["ramp"]
    assert ramp.slope == pytest.approx(np.radians(5.5), abs=1e-6)
    assert float(ramp.height_at(ramp.track[-1] / 2)) == pytest.approx(0.17, abs=1e-6)
    for c in by_kind.values():
        assert c.exit - c.track[-1] > 0 and c.approach < 0


def test_step_up_limit_and_fits(station):
    assert step_up_limit(None) == DEFAULT_STEP_UP == 0.19
    assert step_up_limit(None, 0.1) == 0.1
    with pytest.raises(PlanningError, match="step-up limit"):
        step_up_limit(None, -1.0)
    kinds = {c.kind: c for c in crossings(station.levels, 0.33)}
    assert kinds["ramp"].fits(0.0) and not kinds["stair"].fits(0.15)
    assert head_fits_crossing(station.levels, kinds["stair"], 1.75)


def test_dijkstra_finds_the_cheapest_path():
    edges = {0: [(1, 5.0), (2, 1.0)], 2: [(1, 1.0)], 1: []}
    assert dijkstra(3, edges, 0, 1) == ([0, 2, 1], 2.0)
    assert dijkstra(3, {0: []}, 0, 1) == (None, float("inf"))


def test_crossings_know_their_width_and_shift_across_it(station):
    by_kind = {c.kind: c for c in crossings(station.levels, 0.33)}
    assert by_kind["stair"].half_width == pytest.approx(0.5)  # the 1.0 m flight
    assert by_kind["ramp"].half_width == pytest.approx(0.5)
    assert by_kind["step"].half_width == pytest.approx(0.4)
    stair = by_kind["stair"]
    moved = stair.shifted(0.2)
    left = np.array([-stair.axis[1], stair.axis[0]])
    np.testing.assert_allclose(moved.end(stair.lower) - stair.end(stair.lower), 0.2 * left)
    np.testing.assert_allclose(moved.track, stair.track)  # along the axis: unchanged
    assert stair.shifted(0.0) is stair
    # its width and sides stay about its middle, however often it is moved
    assert moved.centre is stair.origin and moved.shifted(-0.1).centre is stair.origin
    assert (moved.half_width, moved.sides) == (stair.half_width, stair.sides)


def test_place_on_edge_walks_the_side_nearest_the_walk(station):
    stair = {c.kind: c for c in crossings(station.levels, 0.33)}["stair"]
    left = np.array([-stair.axis[1], stair.axis[0]])
    lo, hi = stair.end(stair.lower), stair.end(stair.upper)
    start = lo + 3.0 * left - 1.0 * stair.axis  # far off to the stair's left
    goal = hi + 0.1 * left + 1.0 * stair.axis
    legs = [
        RouteLeg("level", stair.lower, start, lo),
        RouteLeg("cross", stair.lower, lo, hi, stair, "up"),
        RouteLeg("level", stair.upper, hi, goal),
    ]
    placed = place_on_edge(legs, margin=0.25)
    offset = float((placed[1].crossing.origin - stair.origin) @ left)
    assert offset == pytest.approx(0.25)  # as far left as the body stays within the width
    np.testing.assert_allclose(placed[0].end, placed[1].start)
    np.testing.assert_allclose(placed[1].end, placed[2].start)
    np.testing.assert_allclose(placed[0].start, start)
    np.testing.assert_allclose(placed[2].end, goal)
    # a walk straight up the middle stays in the middle; a narrow crossing is never moved
    straight = [
        RouteLeg("level", stair.lower, lo - stair.axis, lo),
        RouteLeg("cross", stair.lower, lo, hi, stair, "up"),
        RouteLeg("level", stair.upper, hi, hi + stair.axis),
    ]
    assert place_on_edge(straight, margin=0.25)[1].crossing is stair
    assert place_on_edge(legs, margin=0.5)[1].crossing is stair


def test_riser_lines_lie_halfway_between_the_footfalls(station):
    """Each riser's edge line crosses the axis halfway between the footfalls on either side
    (where :meth:`Crossing.height_at` changes height), with the heights below and above it;
    a ramp has none. The legs' swing takes its edges from these (landing47)."""
    by_kind = {c.kind: c for c in crossings(station.levels, 0.33)}
    stair = by_kind["stair"]
    lines = stair.riser_lines(station.floor_z)
    assert len(lines) == 6 and by_kind["ramp"].riser_lines(station.floor_z) == []
    for k, e in enumerate(lines):
        s = float((np.asarray(e["xy"]) - stair.origin) @ stair.axis)
        assert s == pytest.approx(0.5 * (stair.track[k] + stair.track[k + 1]), abs=1e-9)
        assert float(stair.height_at(s - 1e-3)) - station.floor_z == pytest.approx(e["low"])
        assert float(stair.height_at(s + 1e-3)) - station.floor_z == pytest.approx(e["high"])
        assert e["high"] - e["low"] == pytest.approx(0.17, abs=1e-6)
        np.testing.assert_allclose(e["normal"], stair.axis)
        assert e["half_width"] == pytest.approx(0.5)


def test_a_shifted_crossing_keeps_its_riser_lines_about_its_middle(station):
    """A step or stair walked off its middle (:meth:`Crossing.shifted`) has the same riser lines:
    each edge's point and ``half_width`` stay about the crossing's middle, not the walked line
    (before, the point moved with the walk while ``half_width`` stayed: the side test of the
    legs' swing measured from the wrong place); the middle is the ramp plane's foot too."""
    by_kind = {c.kind: c for c in crossings(station.levels, 0.33)}
    for c in (by_kind["stair"], by_kind["step"]):
        moved = c.shifted(0.3).shifted(-0.1)
        assert moved.riser_lines(station.floor_z) == c.riser_lines(station.floor_z)
        np.testing.assert_array_equal(moved.middle, c.origin)
        assert not np.allclose(moved.point(0.0), c.point(0.0))  # the walk itself moved
    assert by_kind["ramp"].middle is by_kind["ramp"].origin


def test_crossing_headroom_decides_the_head_check_for_every_stature(station):
    from mjwalk.plan.levelroute import crossing_headroom
    from mjwalk.world.norms import HEAD_MARGIN

    for c in crossings(station.levels, 0.33):
        room = crossing_headroom(station.levels, c)
        assert room > 0
        for stature in (1.40, 1.75, 2.05, room - HEAD_MARGIN + 1e-6):
            assert head_fits_crossing(station.levels, c, stature) == (stature + HEAD_MARGIN <= room)


def _open_stair(tmp_path, open_stair_xml, overlap: float):
    """The shared open stair (tests/conftest.py) written to a file; its path and the nosing
    lines' x, bottom up."""
    path = tmp_path / f"open_stair_{overlap}.xml"
    path.write_text(open_stair_xml(overlap))
    return path, [i * 0.27 for i in range(6)]


def test_an_open_stair_s_risers_are_its_nosings_over_the_treads(tmp_path, open_stair_xml):
    """Each tread of an open stair reaches 3 cm under the next: the riser a foot keeps off is
    the next tread's nosing, not the tread's own far edge under it (before: risers at 0.30,
    0.54, 0.84, 1.08, 1.38 m, every other one under a nosing, and the toes caught it)."""
    path, nosings = _open_stair(tmp_path, open_stair_xml, 0.03)
    graph = load_workplace(path, cache=False).levels
    (stair,) = [c for c in crossings(graph, 0.3) if c.kind == "stair"]
    risers = 0.5 * (stair.track[:-1] + stair.track[1:])
    assert risers == pytest.approx(nosings, abs=1e-6)
    assert stair.tread == pytest.approx(0.27, abs=1e-6)


@pytest.mark.slow
def test_walks_up_and_down_an_open_stair_touch_nothing(tmp_path, open_stair_xml):
    """Up and down the open stair with 3 cm nosing overlap (before: 8-9 toe contacts with the
    nosings going up, up to 1.4 cm, and the foot under the deck's nosing going down)."""
    import mjwalk
    from mjwalk.gait.default import default_model

    path, _ = _open_stair(tmp_path, open_stair_xml, 0.03)
    wp, model = load_workplace(path, cache=False), default_model()
    for a, b in (("a", "b"), ("b", "a")):
        walk = mjwalk.plan_walk(wp, a, b, model, rng=0)
        assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "stair", "level"]
        assert mjwalk.check_collisions(walk, path) == []


def test_a_dog_leg_stair_is_two_flights_through_its_landing(tmp_path, dogleg_xml):
    """A half-turn stair: its landing is a level of its own, each flight a stair of four
    0.17 m risers and 0.28 m treads, the first up +y and the second up -y, and a walk from the
    floor to the mezzanine takes both through the landing."""
    path = tmp_path / "dogleg.xml"
    path.write_text(dogleg_xml)
    wp = load_workplace(path, cache=False)
    stairs = sorted(
        (c for c in crossings(wp.levels, 0.3) if c.kind == "stair"), key=lambda c: c.z_lower
    )
    assert [round(c.z_lower, 3) for c in stairs] == [0.0, 0.68]
    assert [round(c.z_upper, 3) for c in stairs] == [0.68, 1.36]
    for c, up in zip(stairs, (1.0, -1.0), strict=True):
        assert c.risers == pytest.approx((0.17,) * 4, abs=1e-6)
        assert c.tread == pytest.approx(0.28, abs=1e-6)
        np.testing.assert_allclose(c.axis, (0.0, up), atol=1e-9)


@pytest.mark.slow
def test_walks_over_a_dog_leg_stair_touch_nothing(tmp_path, dogleg_xml):
    """Up both flights and down again, and onto the landing: 0 contacts (the walls between the
    flights and round the landing included), and the half turn on the landing stepped: no
    pelvis heading turns faster than a turn on the spot's peak (1.5 pi rad/s; before
    plan.stepturn, 52-83 deg in one 1/120 s sample)."""
    import mjwalk  # the slow tier's end-to-end imports (as in the open stair's test above)
    from mjwalk.gait.default import default_model

    path = tmp_path / "dogleg.xml"
    path.write_text(dogleg_xml)
    wp, model = load_workplace(path, cache=False), default_model()
    for a, b in (("floor", "mezz"), ("mezz", "landing"), ("landing", "floor")):
        walk = mjwalk.plan_walk(wp, a, b, model, rng=0)
        kinds = [r["kind"] for r in walk.meta["levels"]["route"]]
        assert kinds.count("stair") == (2 if "mezz" in (a, b) and "floor" in (a, b) else 1)
        assert mjwalk.check_collisions(walk, path) == []
        rate = np.abs(np.diff(np.unwrap(walk.yaw))) / np.diff(walk.t)
        assert float(rate.max()) < 1.5 * np.pi, (a, b, float(np.degrees(rate.max())))


def _step_block(tmp_path, depth: float):
    """A 0.34 m platform reached by a step block ``depth`` deep and 1.2 m wide before its
    edge (risers 0.17, 0.17). Returns the scene's path."""
    path = tmp_path / f"step_block_{depth}.xml"
    path.write_text(
        '<mujoco><worldbody><geom name="floor" type="plane" size="8 8 0.1"/>'
        '<geom name="plat" type="box" size="1.5 1.0 0.17" pos="2 0 0.17"/>'
        f'<geom name="block" type="box" size="0.6 {depth / 2} 0.085" '
        f'pos="2 {-1 - depth / 2} 0.085"/>'
        '<site name="a" pos="-4 -2 0"/><site name="b" pos="2.5 0.3 0.34"/>'
        "</worldbody></mujoco>"
    )
    return path


@pytest.mark.parametrize("depth", [0.4, 0.5])
def test_a_step_block_deeper_than_a_tread_is_stepped_over(tmp_path, depth):
    """A step block deeper than a stair's tread (0.37 m, DIN 18065) but too shallow for a
    stance a body clearance from both its edges is passed in one footfall, like a tread: one
    step crossing of two 0.17 m risers from the floor to the platform (before: two step links
    through a 'platform' level nobody can walk on, and 'no route' for every walker)."""
    graph = load_workplace(_step_block(tmp_path, depth), cache=False).levels
    (step,) = [c for c in crossings(graph, 0.3) if c.kind == "step"]
    assert step.risers == pytest.approx((0.17, 0.17))
    assert graph.levels[step.lower].height == 0.0
    assert graph.levels[step.upper].height == pytest.approx(0.34)
    assert step.tread == pytest.approx(depth)


def test_a_step_block_with_room_to_stand_stays_a_level(tmp_path):
    """0.7 m deep, the block holds a stance a clearance (0.3 m) from both edges: a level walked on,
    reached by single-riser steps (from the floor at its front and both sides), as before."""
    graph = load_workplace(_step_block(tmp_path, 0.7), cache=False).levels
    steps = [c for c in crossings(graph, 0.3) if c.kind == "step"]
    assert [len(c.risers) for c in steps] == [1, 1, 1, 1]


@pytest.mark.slow
def test_walks_over_a_deep_step_block_touch_nothing(tmp_path):
    """Up onto the platform over the 0.4 m block and back down, one step crossing each way,
    0 contacts (before: no route)."""
    import mjwalk
    from mjwalk.gait.default import default_model

    path = _step_block(tmp_path, 0.4)
    wp, model = load_workplace(path, cache=False), default_model()
    for a, b in (("a", "b"), ("b", "a")):
        walk = mjwalk.plan_walk(wp, a, b, model, rng=0)
        assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "step", "level"]
        assert mjwalk.check_collisions(walk, path) == []


def test_a_two_riser_step_over_a_max_tread_deep_tread_is_one_crossing(tmp_path):
    """Generated hall 710 (``benchmarks/bench_unseen.py``): a platform reached by two risers
    over a tread exactly ``MAX_TREAD`` (0.37 m) deep. Before, the tread (0.37 m + 3e-16 as
    computed) was a platform, the two steps two crossings with no room to stand between them,
    and the walk to the platform had no route. (The platform 0.2964 m up: its risers drawn on
    the written 0.2 mm grid, ``mjwalk.world.levelgendims``; 0.2966 m before.)"""
    from mjwalk.world.levelgen import generate_levels

    hall = generate_levels(710)
    graph = load_workplace(hall.write(tmp_path / "levels_710.xml"), cache=False).levels
    (step,) = [c for c in crossings(graph, 0.3) if c.kind == "step"]
    assert graph.levels[step.lower].kind == "floor"
    assert graph.levels[step.upper].height == pytest.approx(0.2964, abs=1e-6)
