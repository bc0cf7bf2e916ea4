"""A foot turned about its sole and the trailing foot on a ramp (mjwalk.body.legs.rampreach)."""

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footcheck import foot_points
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.rampreach import crest_ground, roll_foot, trailing_reach
from mjwalk.body.legs.steps import FootTracks, StepFrames
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.gait.default import default_model
from mjwalk.plan.synthetic import synthetic_ramp_walk, synthetic_walk
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline import collision_report, timeline_from_walk
from mjwalk.world import load_workplace


def _feet(n, pitch, z=0.0):
    """Foot tracks of n samples, both feet at x = 0 heading +x, pitched ``pitch``."""
    g = leg_geometry(DEFAULT_STATURE)
    ankle = np.zeros((n, 3))
    ankle[:, 2] = z + g.ankle_height
    return FootTracks(
        ankle={s: ankle.copy() for s in "lr"},
        pitch={s: np.full(n, pitch) for s in "lr"},
        toe={s: np.zeros(n) for s in "lr"},
        fyaw={s: np.zeros(n) for s in "lr"},
        ground={s: np.ones(n, bool) for s in "lr"},
        prints={s: np.zeros((n, 3)) for s in "lr"},
    ), g


def _point(feet, g, fwd):
    """The (x, z) of the sole point ``fwd`` m ahead of the left ankle, sample 0."""
    p, a = feet.pitch["l"][0], feet.ankle["l"][0]
    return np.array(
        [
            a[0] + fwd * np.cos(p) + g.ankle_height * np.sin(p),
            a[2] + fwd * np.sin(p) - g.ankle_height * np.cos(p),
        ]
    )


@pytest.mark.parametrize("pivot", ["ball", "heel"])
def test_roll_foot_keeps_its_pivot(pivot):
    feet, g = _feet(1, 0.1)
    fwd = ball_offset(g) if pivot == "ball" else -g.foot_back
    before = _point(feet, g, fwd)
    roll_foot(feet, "l", np.array([0]), np.array([0.3]), np.array([fwd]), g)
    assert feet.pitch["l"][0] == pytest.approx(0.1 - 0.3)
    assert np.allclose(_point(feet, g, fwd), before, atol=1e-12)


def test_level_feet_are_left_alone():
    """Feet on level surfaces (slope 0) keep their tracks even where the leg is short."""
    n = 5
    feet, g = _feet(n, -0.2)
    root = np.zeros((n, 3))
    root[:, 2] = 2.0  # far above the feet
    before = {s: feet.ankle[s].copy() for s in "lr"}
    reach = {s: np.full(n, g.span(0.05) ** 2) for s in "lr"}
    flat = {s: np.zeros(n) for s in "lr"}
    assert not trailing_reach(feet, root, np.zeros(n), feet.ground, flat, reach, g)
    assert all(np.array_equal(feet.ankle[s], before[s]) for s in "lr")


def test_ramp_heel_strike_and_pelvis():
    """Up a 5.5 deg ramp (FK of the clipped angles): the landing foot touches the ramp with
    its heel (within 1 cm; it hung 7-9 cm above it, the knee at 56 deg, when the pelvis
    lowered for the trailing leg and the ankle's limit lifted the heel about the ball), the
    leading knee at heel strike stays under 30 deg, and the pelvis stands within 1 cm of the
    level walk's height above the ground under it (2.6 cm lower before)."""
    angle = np.deg2rad(5.5)
    walk = synthetic_ramp_walk(angle)
    motion = legs_from_walk(walk)
    flat = legs_from_walk(synthetic_walk(n_steps=6, step_len=0.6, step_time=0.55))
    pts, _, _ = foot_points(motion)
    t = np.tan(angle)
    for st in walk.steps[1:-1]:
        k, o = (1, "r") if st.side == "left" else (0, "l")
        heel = pts[st.start, k, 0]
        assert abs(heel[2] - heel[0] * t) < 0.01
        assert np.rad2deg(motion.angles[f"knee_{o}"][st.start]) < 30.0
    a, b = walk.steps[1].start, walk.steps[-2].end
    above = motion.root[a:b, 2] - motion.root[a:b, 0] * t
    assert np.abs(above - flat.root[a:b, 2]).max() < 0.01


@pytest.mark.parametrize(
    "ends", [("stand_ramp", "stand_platform2"), ("stand_platform2", "stand_ramp")]
)
def test_ramp_walks_clear_the_ramp_s_top_edge(scenes_dir, ends):
    """Up and down the shipped multi-level station's 5.5 deg ramp (planned, seed 3) the
    animated walk has no contact: the swing foot passes over the ramp's top edge
    (:func:`crest_ground`; before, its toes went 2-3 cm into the edge: 6 contacts up, 15
    down)."""
    scene = scenes_dir / "multilevel_station.xml"
    walk = plan_walk(load_workplace(scene), *ends, default_model(progress=False), rng=3)
    assert "ramp" in [part["kind"] for part in walk.meta["levels"]["route"]]
    assert collision_report(timeline_from_walk(walk, scene)) == []


def test_crest_ground_is_the_ramp_s_top_edge():
    """Between a footprint on a 5.5 deg ramp rising along +x to a 0.34 m level at x = 0 and
    a footprint on that level, the ground under a foot standing on the edge is the edge's
    0.34 m, not the 0.31 m interpolated between the prints; over the ramp alone it is the
    ramp."""
    g = leg_geometry(DEFAULT_STATURE)
    t = np.tan(np.deg2rad(5.5))
    fr = StepFrames("l", "r", 0, 10, np.array([-0.7, 0.0, 0.0]), np.array([0.5, 0.0, 0.0]),
                    np.zeros(3), False, False)  # fmt: skip
    sf = StepSurfaces(lift=0.34 - 0.7 * t, stance=0.34, land=0.34, lift_pitch=np.deg2rad(5.5))
    ankle = np.array([[-g.foot_front, 0.0, 0.0], [-1.0, 0.0, 0.0]])
    z = crest_ground(ankle, np.zeros(2), fr, sf, g)
    assert z[0] == pytest.approx(0.34)
    assert z[1] == pytest.approx(0.34 - (1.0 - g.foot_front) * t)
