"""Legs from footprints (mjwalk.body.legs.synthesis): foot contact, floor, joint ranges, no
jumps, on synthetic, planned and stored awkward walks."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, leg_geometry
from mjwalk.body.legs.footcheck import foot_points, stance_drift
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.synthesis import LegMotion, legs_from_walk
from mjwalk.errors import PlanningError
from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.plan.walkpath import WalkPath

#: The synthetic walk of the library (straight or curved, no planner).
make_walk = synthetic_walk


def _ball_xy(foot):
    b = ball_offset(leg_geometry())
    return np.asarray(foot[:2]) + b * np.array([np.cos(foot[2]), np.sin(foot[2])])


@pytest.mark.parametrize("radius", [None, 2.5, -2.0])
def test_stance_foot_fixed_floor_and_ranges(radius):
    walk = make_walk(n_steps=6, radius=radius)
    legs = legs_from_walk(walk)
    assert isinstance(legs, LegMotion) and legs.root.shape == (len(walk.t), 3)
    pts, pitch, low = foot_points(legs)
    worst = stance_drift(walk, pts, pitch)
    assert worst <= 0.01, f"stance foot drifted {worst * 100:.2f} cm"
    for st in walk.steps:
        k = 1 if st.side == "left" else 0
        assert np.linalg.norm(pts[st.start + 30, k, 1, :2] - _ball_xy(st.stance)) < 0.01
    assert low.min() >= -0.01, f"foot {-low.min() * 100:.1f} cm below the floor"
    # landing footprints are reached
    for st in walk.steps:
        k = 0 if st.side == "left" else 1
        heel = np.asarray(st.foot[:2]) - leg_geometry().foot_back * np.array(
            [np.cos(st.foot[2]), np.sin(st.foot[2])]
        )
        assert np.linalg.norm(pts[st.end, k, 0, :2] - heel) < 0.01
    _, jm = humanoid_model()
    for name, v in legs.angles.items():
        lo, hi = jm.limits(name)
        assert v.min() >= lo - 1e-9 and v.max() <= hi + 1e-9, name
    # pelvis height oscillates by a few centimetres around ~0.9 m
    z = legs.root[walk.steps[2].start : walk.steps[-1].end, 2]
    assert 0.02 < np.ptp(z) < 0.09
    assert 0.82 < z.mean() < 0.93


def test_turning_uses_hip_rotation():
    """On a 1.5 m arc the hip rotation swings through > 25 deg (measured 32); walking straight
    it stays within 10 deg (measured 4.4, 8 with the Bandai-calibrated gait: the rotation that
    keeps the foot's heading while the hip flexes and abducts over a flexed knee, with a 2-dof
    ankle)."""
    legs = legs_from_walk(make_walk(n_steps=6, radius=1.5))
    assert np.ptp(legs.angles["hip_l_rot"]) > np.deg2rad(25)
    straight = legs_from_walk(make_walk(n_steps=6))
    for s in "lr":
        assert np.abs(straight.angles[f"hip_{s}_rot"]).max() < np.deg2rad(10)


def test_no_steps_is_an_error():
    walk = make_walk(n_steps=2)
    walk.steps = []
    with pytest.raises(PlanningError, match="no steps"):
        legs_from_walk(walk)


def test_step_outside_the_path_is_an_error():
    walk = make_walk(n_steps=2)
    walk.steps[-1].end = len(walk.t) + 5
    with pytest.raises(PlanningError, match=rf"step 1 has sample range \d+\.\.{len(walk.t) + 5}"):
        legs_from_walk(walk)


#: Walks the hybrid A* planned in the assembly-station cycle (seed 0, runs 3, 9 and 13, saved
#: with WalkPath.save) on which clipped legs put a foot 0.9-3 cm into the floor: a landing
#: behind the other foot (ankle at its dorsiflexion limit during the heel roll-down) and long
#: steps followed by short turning ones (trailing hip at its extension limit before toe-off).
AWKWARD_WALKS = sorted((Path(__file__).parents[1] / "data").glob("station_walk_seed0_*.npz"))


@pytest.mark.parametrize("path", AWKWARD_WALKS, ids=lambda p: p.stem)
def test_feet_stay_above_floor_on_awkward_steps(path):
    """Where the joint ranges keep a foot from its target, the foot is pitched or lifted,
    never sunk: MuJoCo's lowest foot point stays above -2 mm at every 120 Hz sample (the
    floor_tolerance of the collision report is 1 cm)."""
    walk = WalkPath.load(path)
    legs = legs_from_walk(walk)
    _, _, low = foot_points(legs)
    assert low.min() >= -0.002, f"foot {-low.min() * 100:.1f} cm below the floor"
    _, jm = humanoid_model()
    for name, v in legs.angles.items():
        lo, hi = jm.limits(name)
        assert v.min() >= lo - 1e-9 and v.max() <= hi + 1e-9, name


#: Planned paths for issue 5's leg test: hybrid-A* walks (default model, seed 0, 5 each) on
#: three assembly-station routes and through the corridor, sharp turning steps included.
PLANNED_ROUTES = (
    ("assembly_station", "stand_rack2", "stand_car1"),
    ("assembly_station", "stand_car1", "stand_rack3"),
    ("assembly_station", "stand_rack1", "stand_car2"),
    ("corridor", "entry", "exit"),
)


@pytest.fixture(scope="module")
def planned_walks(scenes_dir):
    """20 planned walks: (scene path, walk, leg motion, FK heel/ball points, foot pitch,
    lowest foot point) each."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world import load_workplace

    model = default_model(progress=False)
    out = []
    for scene, start, goal in PLANNED_ROUTES:
        path = scenes_dir / f"{scene}.xml"
        wp = load_workplace(path)
        for walk in plan_walks(wp, start, goal, model, n=5, seed=0):
            legs = legs_from_walk(walk)
            out.append((path, walk, legs, *foot_points(legs)))
    return out


def test_planned_walks_stance_feet_stay_put(planned_walks):
    """Issue 5: on 20 planned paths each stance foot's contact point (heel while flat or toes
    up, ball while flat or heel up) drifts at most 1 cm over its stance, turning steps
    included (a foot whose hip cannot rotate further spins about its ball or heel); no foot
    goes more than 1 cm below the floor; every joint stays in its range. Measured (seed 0):
    drift <= 0.31 cm (before the spin turns and the exact IK: 10 walks > 1 cm, up to 7.4 cm),
    lowest foot point -0.2 cm."""
    _, jm = humanoid_model()
    assert len(planned_walks) == 20
    for k, (_, walk, legs, pts, pitch, low) in enumerate(planned_walks):
        drift = stance_drift(walk, pts, pitch)
        assert drift <= 0.01, f"walk {k}: a stance foot drifted {drift * 100:.2f} cm"
        assert low.min() >= -0.01, f"walk {k}: foot {-low.min() * 100:.1f} cm below the floor"
        for name, v in legs.angles.items():
            lo, hi = jm.limits(name)
            assert v.min() >= lo - 1e-9 and v.max() <= hi + 1e-9, (k, name)


#: Largest leg-joint change allowed between two 120 Hz samples (degrees): 720 deg/s, about
#: twice the peak knee velocity of normal gait (~350-400 deg/s, ~3.3 deg a sample) and well
#: below the pops seen before (10-30 deg at the walk start, toe-off, landing, late swing).
MAX_STEP_DEG = 6.0


def test_planned_walks_joint_angles_do_not_jump(planned_walks):
    """Issue 5 (playback pops): on the 20 planned paths no leg joint (and not the pelvis
    yaw) changes by more than MAX_STEP_DEG between two samples, every walk alike (issue 13:
    no waivers by fixture index). Measured (seed 0, default step model v4): largest change
    5.5 deg (knee, late swing), 22 of 280 (walk, joint) pairs above 5 deg; before the issue 5
    fixes 21.5 deg (hip rotation at sample 0), knee 20.2 deg, 139 pairs above 5 deg."""
    for k, (_, walk, legs, *_) in enumerate(planned_walks):
        assert np.all(np.diff(walk.t) == pytest.approx(1 / 120)), k
        series = {**legs.angles, "pelvis_yaw": np.unwrap(legs.yaw)}
        for name, v in series.items():
            d = np.degrees(np.abs(np.diff(v)))
            i = int(np.argmax(d))
            assert d[i] <= MAX_STEP_DEG, (
                f"walk {k}: {name} changes {d[i]:.1f} deg between samples {i} and {i + 1}"
            )


def test_planned_walks_touch_nothing(planned_walks):
    """Issue 5: the played-back walks (legs, trunk turning, arms) of the 20 planned paths
    touch no scene geometry, the planner having certified each pelvis path clear."""
    from mjwalk.timeline import collision_report, timeline_from_walk
    from mjwalk.world import load_workplace

    for k, (path, walk, *_) in enumerate(planned_walks):
        clear = load_workplace(path).walk_clearance(walk.xy)
        assert clear.min() >= walk.meta["radius"] - 1e-6, f"walk {k} is not certified"
        contacts = collision_report(timeline_from_walk(walk, path))
        assert contacts == [], (
            k,
            [(c.body_part, c.scene_geom, round(c.depth, 4)) for c in contacts],
        )


def test_stance_foot_ahead_of_the_hip_keeps_its_place():
    """A corridor-corner walk (hybrid A*, default model, seed 0, walk 3 of entry -> exit,
    saved with WalkPath.save) whose right foot lands 0.35 m ahead of the pelvis and stays
    there while the left foot steps behind it (step 16). The pelvis rises over the landing
    leg beyond the stance leg's reach; the stance heel used to rise to its 60 deg bound
    (further than the point of the ball roll nearest the hip, past the ankle's 50 deg of
    plantarflexion), and the clipped leg put the foot 0.4 m from its footprint (drift 81.5
    cm). Now the heel rises at most to the nearest point and no further than the ankle
    allows; the pelvis lowers instead. Measured: step 16 drift 0.00 cm; every step <= 1 cm
    but step 18 (2.58 cm: its right stance foot points ~40-55 deg left of where the pelvis
    travels and the hip passes lateral of it, the ankle would evert 20-33 deg, range 15). The
    planner now refuses that placement (plan/stepcheck.py's stance-lean check, which flags
    step 18 of this walk and no other): it is checked here, not waived."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan import stepcheck
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.world import load_workplace

    walk = WalkPath.load(
        Path(__file__).parents[1] / "data" / "stance_ahead_corridor_seed0_walk3.npz"
    )
    wp = load_workplace(Path(__file__).parents[2] / "scenes" / "corridor.xml")
    par = HybridPlanner(wp, "exit", default_model(progress=False)).params.vectors()[0]
    legs = legs_from_walk(walk)
    pts, pitch, low = foot_points(legs)
    refused = []
    for k, st in enumerate(walk.steps):
        sl = slice(st.start, st.end + 1)
        lean = stepcheck.stance_lean(walk.xy[sl], walk.yaw[sl], st.stance, st.side == "right", par)
        if not stepcheck.lean_in_range(*lean, par):
            refused.append(k)
            continue
        drift = stance_drift(type("OneStep", (), {"steps": [st]}), pts, pitch)
        assert drift <= 0.01, f"step {k}: stance foot drifted {drift * 100:.2f} cm"
    assert refused == [18]
    # the stance foot of step 16 (right) keeps its commanded pitch: no joint clipped it
    st = walk.steps[16]
    sl = slice(st.start, st.end + 1)
    assert np.abs(pitch[sl, 1] - legs.pitch["right"][sl]).max() < np.deg2rad(0.5)
    assert low.min() >= -0.002


#: Planned corridor walks of seeds 1, 2 and 5 (benchmarks/bench_leg_jumps.py --seeds 0-5,
#: walks 17, 16, 18, 15, 17: walk k of seed s is the k-th of its PLANNED_ROUTES walks), stored:
#: long steps after short ones (a trailing foot 0.54-0.58 m behind its hip at toe-off) and
#: sidesteps (short steps landing behind and beside the pelvis).
LEG_JUMP_WALKS = sorted((Path(__file__).parents[1] / "data").glob("legs_corridor_seed*_walk*.npz"))


@pytest.fixture(scope="module")
def leg_jump_walks():
    out = []
    for path in LEG_JUMP_WALKS:
        walk = WalkPath.load(path)
        legs = legs_from_walk(walk)
        out.append((path.stem, walk, legs, *foot_points(legs)))
    return out


def test_trailing_foot_lifts_off_without_a_knee_pop(leg_jump_walks):
    """Issue 13: a trailing foot far behind its hip lifts off where its heel rise reaches its
    bound (instead of being held on the floor by a stretched leg until TOE_OFF), and the
    swing starts from the foot's place and velocity at lift-off; so from the start of the step
    up to the landing approach (phi < 0.9) no swing-leg joint changes more than MAX_STEP_DEG
    between samples. Measured on the three long-step walks: largest 5.6 deg; before, the
    knee straightened (down to 9 deg) and flexed again by 6.9-7.3 deg a sample after
    toe-off. (The sidestep walk of seed 5, walk 15, is not one of them: see the report of
    benchmarks/bench_leg_jumps.py for the jumps left in its sideways swings and landings.)"""
    long_steps = (
        "legs_corridor_seed1_walk17",
        "legs_corridor_seed2_walk18",
        "legs_corridor_seed5_walk17",
    )
    walks = [w for w in leg_jump_walks if w[0] in long_steps]
    assert len(walks) == 3
    for stem, walk, legs, *_ in walks:
        for k, st in enumerate(walk.steps):
            sw = "_l" if st.side == "left" else "_r"
            phi = (np.arange(st.start, st.end) - st.start) / (st.end - st.start)
            for name, v in legs.angles.items():
                if sw + "_" not in name and not name.endswith(sw):
                    continue
                d = np.degrees(np.abs(np.diff(v[st.start : st.end + 1])))[phi < 0.9]
                assert d.max() <= MAX_STEP_DEG, f"{stem} step {k}: {name} {d.max():.1f} deg"


def test_airborne_foot_repitch_is_continuous(leg_jump_walks):
    """Issue 13: a foot pitched in the air (the corrections spread around a landing or a
    lift-off) moves its ankle as it would on a footprint under it, continuously through the
    flat foot. Pivoting about the heel while toes up and the ball while heel up, the ankle of
    a sidestep's landing foot dropped 4.4 cm in one sample (the knee 13.3 deg). Measured on
    the five walks: an ankle target moves at most 1.3 cm vertically between samples (the
    20 fixture walks: 1.3 cm)."""
    for stem, _, legs, *_ in leg_jump_walks:
        for side in ("left", "right"):
            dz = np.abs(np.diff(legs.ankle[side][:, 2]))
            assert dz.max() <= 0.02, f"{stem} {side}: ankle moves {dz.max() * 100:.1f} cm"


def test_leg_jump_walks_keep_feet_planted(leg_jump_walks):
    """The earlier lift-off hands the foot to the swing; the stance feet of these walks still
    drift <= 1 cm, no foot goes below the floor (-2 mm) and every joint stays in range."""
    _, jm = humanoid_model()
    for stem, walk, legs, pts, pitch, low in leg_jump_walks:
        assert stance_drift(walk, pts, pitch) <= 0.01, stem
        assert low.min() >= -0.002, f"{stem}: foot {-low.min() * 100:.1f} cm below the floor"
        for name, v in legs.angles.items():
            lo, hi = jm.limits(name)
            assert v.min() >= lo - 1e-9 and v.max() <= hi + 1e-9, (stem, name)
