"""The side a walker passes an obstacle on, from the room each side leaves (issue 48): the
gap weight's cited points and the gap measured beside an obstacle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.anthropometry import SEG
from mjwalk.gait.walker import REFERENCE_SPEED
from mjwalk.plan.detour import GuideBody, abreast, detour_guide
from mjwalk.plan.guide import via_point_guide
from mjwalk.plan.sides import (
    CONFINED_APERTURE,
    CRITICAL_APERTURE,
    PASSING_GAP,
    boxes_meeting,
    gap_log_weight,
    intruding,
    obstacle_bounds,
    passing_berth,
    passing_gap,
    side_gap,
    side_log_odds,
)
from mjwalk.world import load_workplace

SHOULDER = SEG["shoulder_width"] * 1.75


def pillar_by_wall(tmp_path, gap: float):
    """A 0.6 m pillar at the origin of a 10 x 6 m floor and a 2 m wall piece ``gap`` m to
    its left (+y)."""
    scene = tmp_path / f"gap{gap}.xml"
    wall_y = 0.3 + gap + 0.1
    scene.write_text(
        '<mujoco model="gap"><worldbody>'
        '<geom name="floor" type="plane" size="5 3 0.05"/>'
        '<geom name="pillar" type="box" size="0.3 0.3 1.0" pos="0 0 1.0"/>'
        f'<geom name="wall" type="box" size="1.0 0.1 1.0" pos="0 {wall_y} 1.0"/>'
        "</worldbody></mujoco>"
    )
    return load_workplace(scene)


def test_the_gap_weight_has_the_cited_points():
    """A gap of 1.4 shoulder widths (Hackney & Cinelli 2013) weighs 1/2, 1.3 (Warren & Whang
    1987) 1/4, a wide one 1; a wide side against one at the critical aperture: 2:1."""
    assert math.exp(gap_log_weight(CRITICAL_APERTURE * SHOULDER, SHOULDER)) == pytest.approx(0.5)
    assert math.exp(gap_log_weight(CONFINED_APERTURE * SHOULDER, SHOULDER)) == pytest.approx(0.25)
    assert gap_log_weight(2.0, SHOULDER) == pytest.approx(0.0, abs=1e-9)
    assert gap_log_weight(-1.0, SHOULDER) < -30.0  # no overflow for a closed side
    z = side_log_odds(0.0, 2.0, CRITICAL_APERTURE * SHOULDER, SHOULDER)
    assert z == pytest.approx(math.log(2.0))


def test_obstacle_boxes_are_kept_and_met_as_each_footprint_bounds_them(tmp_path):
    """The kept bounds are each footprint's own; a query box meets exactly the footprints
    whose bounds it overlaps (edges included), in the scene's order."""
    wp = pillar_by_wall(tmp_path, 0.6)
    b = obstacle_bounds(wp)
    assert b.tolist() == [list(fp.bounds()) for fp in wp.obstacles]
    assert obstacle_bounds(wp) is b  # kept on the workplace
    names = [fp.name for fp in wp.obstacles]
    pillar, wall = names.index("pillar"), names.index("wall")
    assert boxes_meeting(wp, (-5.0, -3.0, 5.0, 3.0)).tolist() == sorted([pillar, wall])
    assert boxes_meeting(wp, (0.3, -0.1, 0.5, 0.1)).tolist() == [pillar]  # touches its edge
    assert boxes_meeting(wp, (0.31, -0.1, 0.5, 0.1)).tolist() == []
    assert boxes_meeting(wp, (-0.5, 1.0, 0.5, 1.2)).tolist() == [wall]


def test_the_gap_beside_an_obstacle_is_the_free_width(tmp_path):
    """The left route round the pillar passes between it and a wall 0.6 m from it: its gap is
    0.6 m; the right route has the open floor (at least the cited look-out, 1.5 m, more)."""
    wp = pillar_by_wall(tmp_path, 0.6)
    pillar = next(fp for fp in wp.obstacles if fp.name == "pillar")
    s, g = (-3.0, 0.0), (3.0, 0.0)
    berth = 0.5 * SHOULDER + 0.30
    body = GuideBody(0.25)
    assert body.stature == pytest.approx(1.75)
    gaps = []
    for left in (True, False):
        route = via_point_guide(s, abreast(pillar, s, g, berth, left), g, None, None)
        gaps.append(side_gap(wp, pillar, route, s, g))
    assert gaps[0] == pytest.approx(0.6, abs=0.01), gaps
    assert gaps[1] > 1.5 + 0.9 * berth, gaps


def _pillar(tmp_path):
    """A 0.6 m pillar at the origin of a 10 x 6 m floor."""
    scene = tmp_path / "pillar.xml"
    scene.write_text(
        '<mujoco model="pillar"><worldbody>'
        '<geom name="floor" type="plane" size="5 3 0.05"/>'
        '<geom name="pillar" type="box" size="0.3 0.3 1.0" pos="0 0 1.0"/>'
        "</worldbody></mujoco>"
    )
    return load_workplace(scene)


def test_the_berth_grows_with_speed():
    """The cited 0.30 m gap at the reference pace; Seyfried et al. 2005's space ratio gives
    0.235 m at 1.0 m/s and 0.340 m at 1.6 m/s; the berth adds half the shoulder width (a
    taller walker keeps more) and falls back to the reference pace for no speed."""
    assert passing_gap(REFERENCE_SPEED) == pytest.approx(PASSING_GAP)
    assert passing_gap(1.0) == pytest.approx(0.2351, abs=1e-3)
    assert passing_gap(1.6) == pytest.approx(0.3404, abs=1e-3)
    speeds = np.linspace(0.5, 2.0, 16)
    assert np.all(np.diff([passing_gap(v) for v in speeds]) > 0.0)
    assert passing_gap(0.0) == passing_gap(math.nan) == pytest.approx(PASSING_GAP)
    assert passing_berth(1.75, 1.2) == pytest.approx(0.5 * SHOULDER + passing_gap(1.2))
    assert passing_berth(1.90, 1.2) > passing_berth(1.60, 1.2)


def test_a_faster_walker_passes_the_pillar_wider(tmp_path):
    """The way round a pillar in the way passes abreast of it at the walker's own berth: a
    walker at 1.6 m/s 0.105 m wider than one at 1.0 m/s (each within 2 cm)."""
    wp = _pillar(tmp_path)
    s, g = (-3.0, 0.0), (3.0, 0.0)
    abreast_at = {}
    for v in (1.0, 1.6):
        path = detour_guide(
            wp, np.array([s, g]), s, g, None, None, GuideBody(0.25, speed=v),
            np.random.default_rng(0),
        )  # fmt: skip
        assert path is not None
        abreast_at[v] = abs(float(path[np.argmin(np.abs(path[:, 0])), 1])) - 0.3
        assert abreast_at[v] == pytest.approx(passing_berth(1.75, v), abs=0.02), (v, abreast_at)
    assert abreast_at[1.6] - abreast_at[1.0] == pytest.approx(0.105, abs=0.02)


def test_an_obstacle_beside_the_way_is_passed_at_the_berth(tmp_path):
    """A straight way 0.30 m from the pillar's side (clear of the 0.25 m body radius, inside
    the 0.53 m berth) is bent out to pass it at the berth on the near side, in 20 of 20
    seeded draws (the cited side model gives the near side 1.00); a way 0.8 m off, a walk
    ending beside the pillar and a way along a wall are left alone."""
    wp = _pillar(tmp_path)
    s, g = (-3.0, 0.6), (3.0, 0.6)
    assert intruding(wp, np.array([s, g]), (s, g), passing_berth(1.75, 0.0)) is wp.obstacles[0]
    berth = passing_berth(1.75, 0.0)
    for k in range(20):
        path = detour_guide(
            wp, np.array([s, g]), s, g, None, None, GuideBody(0.25), np.random.default_rng(k)
        )
        assert path is not None
        gap = float(wp.obstacles[0].signed_distance(path).min())
        assert path[np.argmin(np.abs(path[:, 0])), 1] > 0.0
        assert 0.9 * berth <= gap <= berth + 0.01, (gap, berth)
    far = np.array([(-3.0, 1.1), (3.0, 1.1)])
    assert intruding(wp, far, (far[0], far[1]), berth) is None
    own = np.array([(-3.0, 0.6), (0.0, 0.55)])  # to a spot beside the pillar
    assert intruding(wp, own, (own[0], own[1]), berth) is None
    along = np.array([(-0.2, 0.6), (0.2, 0.6)])  # the pillar reaches past both ends
    assert intruding(wp, along, (along[0], along[1]), berth) is None
