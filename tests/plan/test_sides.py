"""The side a walker passes an obstacle on, from the room each side leaves (issue 48): the
gap weight's cited points and the gap measured beside an obstacle."""

from __future__ import annotations

import math

import pytest

from mjwalk.anthropometry import SEG
from mjwalk.plan.detour import GuideBody, abreast
from mjwalk.plan.guide import via_point_guide
from mjwalk.plan.sides import (
    CONFINED_APERTURE,
    CRITICAL_APERTURE,
    gap_log_weight,
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
