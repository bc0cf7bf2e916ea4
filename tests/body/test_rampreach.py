"""A foot turned about its sole and the trailing foot on a ramp (mjwalk.body.legs.rampreach)."""

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footcheck import foot_points
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.legheights import step_surfaces
from mjwalk.body.legs.rampreach import crest_ground, plane_pitch, roll_foot, trailing_reach
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
    ("ends", "rng"),
    [
        (("stand_ramp", "stand_platform2"), 3),
        (("stand_platform2", "stand_ramp"), 3),
        (("stand_platform2", "stand_ramp"), 4),
    ],
)
def test_ramp_walks_clear_the_ramp_s_top_edge(scenes_dir, ends, rng):
    """Up and down the shipped multi-level station's 5.5 deg ramp (planned) the animated walk
    has no contact: the swing foot passes over the ramp's top edge (:func:`crest_ground`;
    before, its toes went 2-3 cm into the edge: 6 contacts up, 15 down; seed 4 down kept one,
    the toes 3.4 mm into the edge between heel and toe, before the crest itself was checked),
    and every footprint on the ramp is pitched to its true 5.5 deg (the route's plane; the
    walk's smoothed heights read 4.4-6.3 deg)."""
    scene = scenes_dir / "multilevel_station.xml"
    walk = plan_walk(load_workplace(scene), *ends, default_model(progress=False), rng=rng)
    assert "ramp" in [part["kind"] for part in walk.meta["levels"]["route"]]
    lands = {round(abs(np.rad2deg(s.land_pitch)), 6) for s in step_surfaces(walk)}
    assert lands == {0.0, 5.5}
    assert collision_report(timeline_from_walk(walk, scene)) == []


def test_plane_pitch_on_the_ramp_only():
    """A footprint on a ramp's plane is pitched by the slope along its heading (uphill +,
    across 0, downhill -); beyond its foot or head, 0."""
    plane = {"slope": np.deg2rad(5.5), "uphill": np.pi / 2, "foot": [1.0, 2.0], "run": 3.0}
    assert plane_pitch(plane, np.array([1.0, 3.0, np.pi / 2])) == pytest.approx(np.deg2rad(5.5))
    assert plane_pitch(plane, np.array([1.0, 3.0, -np.pi / 2])) == pytest.approx(-np.deg2rad(5.5))
    assert plane_pitch(plane, np.array([1.0, 3.0, 0.0])) == pytest.approx(0.0, abs=1e-12)
    assert plane_pitch(plane, np.array([1.0, 5.1, np.pi / 2])) == 0.0
    assert plane_pitch(plane, np.array([1.0, 1.9, np.pi / 2])) == 0.0


def test_crest_checked_between_heel_and_toe():
    """A foot pitched toes down with its heel over a platform and its toe over the ramp below
    its top edge: the ground offset keeps the sole above the edge between them."""
    g = leg_geometry(DEFAULT_STATURE)
    t = np.tan(np.deg2rad(5.5))
    fr = StepFrames("l", "r", 0, 10, np.array([-0.5, 0.0, 0.0]), np.array([0.6, 0.0, 0.0]),
                    np.zeros(3), False, False)  # fmt: skip
    sf = StepSurfaces(lift=0.34, stance=0.34, land=0.34 - 0.6 * t, land_pitch=-np.deg2rad(5.5))
    ankle = np.array([[-0.05, 0.0, 0.0]])  # the edge at x = 0, between heel and toe
    half = np.tan(np.deg2rad(2.75))  # halfway through its pitch toward the ramp's
    z = crest_ground(ankle, np.zeros(1), fr, sf, g, np.array([-np.deg2rad(2.75)]))
    # the sole's height at the edge (0.05 m ahead of the ankle) is z - 0.05 tan(2.75 deg):
    # on the edge, not 0.7 mm into it (heel, ankle and toe only)
    assert z[0] - 0.05 * half == pytest.approx(0.34)
