"""A foot turned about its sole and the trailing foot on a ramp (mjwalk.body.legs.rampreach)."""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footcheck import box_corners, foot_points, posed
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.legheights import step_surfaces
from mjwalk.body.legs.rampreach import (
    heel_face_need,
    level_feet_on_ramps,
    level_planes,
    plane_heights,
    plane_pitch,
    print_tracks,
    ramp_support,
    roll_foot,
    tilt,
    trailing_reach,
)
from mjwalk.body.legs.steps import FootTracks, StepFrames
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.lowtops import with_low_tops
from mjwalk.plan.rampside import surface_plane, with_ramps_beside
from mjwalk.plan.synthetic import synthetic_ramp_walk, synthetic_walk
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline import check_collisions, collision_report, timeline_from_walk
from mjwalk.world import load_workplace
from mjwalk.world.levelgen import generate_levels


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
    has no contact: the swing foot passes over the ramp's top edge (``crest.crest_ground``;
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


@pytest.mark.parametrize("slope_deg", [5.5, -5.5])
def test_tilt_turns_the_ankle_about_its_footprint(slope_deg):
    """An ankle 6 cm ahead of its footprint (heel rising over the ball) and 8 cm up keeps both
    distances in the ramp's plane: walking up a 5.5 deg ramp it rises 6 tan(5.5 deg) = 5.8 mm
    above the ramp's height at the footprint more than turned about the point under it (the
    toes 6 mm into the ramp by toe-off); on level ground it is returned bit for bit."""
    s = np.deg2rad(slope_deg)
    yaw, fp = 0.7, np.array([[1.0, 2.0]])
    f = np.array([np.cos(yaw), np.sin(yaw)])
    ankle = np.array([[*(fp[0] + 0.06 * f), 0.08]])
    out = tilt(ankle, np.array([yaw]), np.array([s]), fp)
    along = (out[0, :2] - fp[0]) @ f
    assert along * np.cos(s) + out[0, 2] * np.sin(s) == pytest.approx(0.06, abs=1e-12)
    assert -along * np.sin(s) + out[0, 2] * np.cos(s) == pytest.approx(0.08, abs=1e-12)
    assert np.allclose(out[0, :2] - fp[0], along * f, atol=1e-12)
    flat = tilt(ankle, np.array([yaw]), np.zeros(1), fp)
    assert np.array_equal(flat, ankle)


def test_print_tracks_follow_the_steps():
    """The stance foot stands on its footprint through a step; the swing foot on its lift
    footprint until the step's last sample, on its landing footprint from then."""
    p = {k: np.array([x, 0.0, 0.0]) for k, x in (("a", 0.0), ("b", 0.3), ("c", 0.6), ("d", 0.9))}
    frames = [
        StepFrames("l", "r", 2, 6, p["a"], p["c"], p["b"], True, False),
        StepFrames("r", "l", 6, 10, p["b"], p["d"], p["c"], False, True),
    ]
    out = print_tracks(frames, 13)
    assert out["l"][:, 0].tolist() == [0.0] * 6 + [0.6] * 7
    assert out["r"][:, 0].tolist() == [0.3] * 10 + [0.9] * 3


def _deepest_under_ramps(workplace, walk, stature=DEFAULT_STATURE):
    """The least height (m) of any foot box corner (feet and toes, MuJoCo forward kinematics)
    over the plane of a ramp's surface under it (those the walk crosses or passes beside), for
    the legs of ``walk`` as the cycles pose them (with its ramps beside); inf off every ramp."""
    walk = with_ramps_beside(workplace, walk, stature)
    meta = walk.meta
    planes = list(meta.get("ramps_beside", []))
    planes += [e["plane"] for e in (meta.get("levels") or {}).get("route", []) if "plane" in e]
    planes = [surface_plane(p) for p in planes]  # the ramps' whole surfaces
    legs = legs_from_walk(walk, stature)
    least = np.inf
    for _, model, data in posed(legs, stature):
        for name in ("foot_l", "toes_l", "foot_r", "toes_r"):
            g = model.geom(name).id
            c = box_corners(model, data, g)
            h = np.max([plane_heights(p, c[:, :2]) for p in planes], axis=0)
            least = min(least, float(np.min(c[:, 2] - workplace.floor_z - h)))
    return least


def test_an_edged_floor_swing_clears_a_ramp_beside_it(tmp_path):
    """Generated hall 8 (``benchmarks/bench_unseen.py``): the walk from the mezzanine to
    floor_1 ends past the ramp's low end; a foot landing on the ramp's foot (raised 1-2 cm,
    standing level on its highest point) made the next floor step an edged swing, planned over
    that one height, and the swing foot, hanging toes down, passed 6.0 mm into the ramp's side
    higher up its run (rng 4; 11.7 mm in the hall's 3-run cycle, run 0). A foot on a ramp's
    plane stands on no tread now (``StepSurfaces.lift_ramp``): no edged swing there, and every
    foot box corner is on or above the plane."""
    xml = generate_levels(8).write(tmp_path / "levels_8.xml")
    wp = load_workplace(xml, cache=False)
    walk = plan_walk(wp, "mezz_0", "floor_1", rng=4)
    assert _deepest_under_ramps(wp, walk) > -1e-4  # a sole on the plane: to 0.1 mm


def test_a_foot_whose_heel_and_ball_are_on_a_ramp_is_pitched_to_it():
    """A level step's footprint over a ramp beside the walk: where the ramp's plane carries
    its heel and its ball it stands on the plane pitched to the slope along it (its height the
    plane's under the footprint plus the rise across half the foot); where only its toes are
    over the ramp's foot it stands level (None: the highest point under the sole)."""
    g = leg_geometry(DEFAULT_STATURE)
    slope = np.radians(5.5)
    plane = {"slope": slope, "uphill": 0.0, "foot": [0.0, 0.0], "run": 3.0, "half_width": 0.6}
    h, pitch = ramp_support([plane], (1.0, 0.0, 0.0), g)  # walking up its axis
    assert pitch == pytest.approx(slope)
    assert h == pytest.approx(np.tan(slope))
    h, pitch = ramp_support([plane], (1.0, 0.0, np.pi / 2), g)  # across it
    assert pitch == pytest.approx(0.0, abs=1e-12)
    assert h == pytest.approx(np.tan(slope) * (1.0 + 0.5 * g.foot_width))
    assert ramp_support([plane], (0.02, 0.0, 0.0), g) is None  # the heel off its foot
    assert ramp_support([plane], (1.0, 0.65, 0.0), g) is None  # beside its side


def test_feet_on_a_ramp_beside_a_floor_walk_are_pitched_to_it(tmp_path):
    """Generated hall 8, mezz_0 -> floor_1 (rng 4): the floor steps past the ramp's low end
    whose heel and ball the ramp carries are pitched to its slope (before: all level, raised
    to the highest point under the sole); every step's surfaces stay within the ramp's
    heights."""
    xml = generate_levels(8).write(tmp_path / "levels_8.xml")
    wp = load_workplace(xml, cache=False)
    walk = with_ramps_beside(wp, plan_walk(wp, "mezz_0", "floor_1", rng=4), DEFAULT_STATURE)
    (plane,) = walk.meta["ramps_beside"]
    surfs = step_surfaces(walk)
    pitched = [s for s in surfs if abs(s.land_pitch) > 1e-3]
    assert pitched
    assert all(abs(s.land_pitch) <= plane["slope"] + 1e-9 for s in pitched)
    assert all(0.0 < s.land < np.tan(plane["slope"]) * plane["run"] for s in pitched)


def test_a_crossing_s_steps_at_one_height_are_level_steps():
    """:func:`level_planes`: a step's, a stair's or a ramp's crossing counts its steps that
    lift, stand and land at one height (to 1 um: the planner's heights carry 1e-16 m of
    rounding) as level, so that its walk up to the first riser or the ramp's foot is kept off
    a ramp beside it (generated hall 153's turn past a ramp's foot before a step up, hall
    511's turn into a ramp past its low corner); the riser steps and a ramp's steps on its
    slope are not."""
    zs = [(0.0, 0.0), (1e-16, 0.0), (0.19, 1e-16), (0.19, 0.19), (0.19, 0.19), (0.0, 0.0),
          (0.0, 0.0), (0.05, 0.0), (0.1, 0.05)]  # fmt: skip
    steps = [SimpleNamespace(foot_z=f, stance_z=s) for f, s in zs]
    plane = {"slope": 0.1, "uphill": 0.0, "foot": [5.0, 0.0], "run": 2.0, "half_width": 0.5}
    route = [{"kind": "level", "steps": 1}, {"kind": "step", "steps": 4},
             {"kind": "ramp", "steps": 4, "plane": plane}]  # fmt: skip
    walk = SimpleNamespace(meta={"levels": {"route": route}}, steps=steps)
    planes, level = level_planes(walk, len(steps))
    assert planes == [plane]
    assert level == [True, True, False, False, True, False, True, False, False]


def _ramp_crossing(foot_x: float, slope: float = 0.1):
    """A straight walk up a ramp (uphill +x, its foot line at ``foot_x``) from the floor, as
    one ramp crossing of the level planner's route (its plane recorded), its heights the
    plane's under each footprint and sample."""
    walk = synthetic_walk(n_steps=9, step_len=0.65, step_time=0.55)
    plane = {"slope": slope, "uphill": 0.0, "foot": [foot_x, 0.0], "run": 8.0, "half_width": 1.0,
             "z": 0.0, "sides": [-1.0, 1.0]}  # fmt: skip

    def height(p):
        return np.maximum(plane_heights(plane, np.asarray(p, float)[..., :2]), 0.0)

    walk.z = height(walk.xy)
    for s in walk.steps:
        s.foot_z, s.stance_z = float(height(s.foot)), float(height(s.stance))
    walk.meta["levels"] = {"route": [{"kind": "ramp", "steps": 9, "plane": plane}]}
    return walk, plane


@pytest.mark.parametrize("foot_x", [1.7, 2.3])
def test_a_ramp_crossing_s_floor_step_stands_off_the_ramp_s_foot(foot_x):
    """A ramp crossing's last footfall on the floor, its footprint before the ramp's foot and
    its toes over the ramp (a 5.7 deg ramp, the foot line 7.5 cm or 2.5 cm past the left or
    right footprint), lifts, stands and lands at the floor's height: a level step, stood level
    on the highest point of the plane under its sole (:func:`level_feet_on_ramps`) and swung
    over it. Before, a ramp crossing's steps were all ramp steps, and one whose footprint is
    off the plane stood on the floor unpitched: the toes 12.5 and 17.5 mm into the ramp
    (generated hall 511's stress cycle, run 0: a turn into the ramp past its low corner swung
    the left toes 0.74 mm into its side). Now no foot box corner (MuJoCo forward kinematics)
    is 0.1 mm below the floor or the ramp's plane."""
    walk, plane = _ramp_crossing(foot_x)
    legs = legs_from_walk(walk, DEFAULT_STATURE)
    least = np.inf
    for _, m, data in posed(legs, DEFAULT_STATURE):
        for name in ("foot_l", "toes_l", "foot_r", "toes_r"):
            c = box_corners(m, data, m.geom(name).id)
            ground = np.maximum(plane_heights(plane, c[:, :2]), 0.0)
            least = min(least, float(np.min(c[:, 2] - ground)))
    assert least > -1e-4  # before: -12.5 and -17.5 mm


def test_a_footprint_beside_a_ramp_is_not_pitched():
    """A ramp crossing's level steps may turn on the floor beside the ramp, within its run
    along the axis but off its sides: they stand level (generated hall 510, floor_0 ->
    platform_1: a turn 1.3 m beside the 3.5 deg ramp's foot stood pitched toes down, 1.2 cm
    into the floor); on its surface, pitched; a plane of unknown width, pitched as before."""
    slope = np.deg2rad(3.5)
    plane = {"slope": slope, "uphill": 0.0, "foot": [0.0, 0.0], "run": 3.0, "half_width": 0.6,
             "sides": [-0.6, 0.6]}  # fmt: skip
    down = np.array([0.2, 1.3, np.pi])
    assert plane_pitch(plane, down) == 0.0
    assert plane_pitch(plane, np.array([0.2, 0.5, np.pi])) == pytest.approx(-slope)
    wide = {k: v for k, v in plane.items() if k not in ("half_width", "sides")}
    assert plane_pitch(wide, down) == pytest.approx(-slope)


def test_a_foot_whose_toes_reach_past_a_ramp_s_foot_is_not_pitched():
    """:func:`ramp_support` needs the plane under the toe tip too: a foot pointing down a ramp
    with its heel and ball on it and its toe tip past its foot, pitched to the slope, has
    its toes below the floor; it stands level instead (None)."""
    g = leg_geometry(DEFAULT_STATURE)
    plane = {"slope": np.radians(9.8), "uphill": 0.0, "foot": [0.0, 0.0], "run": 3.0,
             "half_width": 0.6}  # fmt: skip
    x = 0.5 * (ball_offset(g) + g.foot_front)  # the ball on the ramp, the toe tip past it
    assert ramp_support([plane], (x, 0.0, np.pi), g) is None
    _, pitch = ramp_support([plane], (x + g.foot_front, 0.0, np.pi), g)
    assert pitch == pytest.approx(-np.radians(9.8))


def test_a_step_down_a_ramp_s_foot_keeps_its_toes_out_of_the_floor(tmp_path):
    """Generated hall 500, platform_1 -> floor_0 down its 9.8 deg ramp, by the older adult of
    the hall's stress cycle (run 5: 1.67 m, 0.95 m/s, 99 steps/min): the ramp's last footfall
    has its ankle 8 cm up the ramp from its foot, and the foot, pitched to the slope, had its
    toes 1.8 cm into the floor beyond (the cycle's 20 contacts). Now that foot stands level on
    the ramp under its heel: no foot box corner (MuJoCo forward kinematics) is 5 mm below the
    floor or the ramp's plane (half the contact check's 1 cm floor tolerance,
    :func:`mjwalk.timeline.collisions.check_collisions`; the toes on this ramp's own slope, as
    before, rest to 3 mm in it)."""
    xml = generate_levels(500).write(tmp_path / "levels_500.xml")
    wp = load_workplace(xml, cache=False)
    walker = Walker(stature=1.67, speed=0.9517, cadence=99.26, group="older_adult")
    model = default_model().for_walker(walker)
    walk = plan_walk(wp, "platform_1", "floor_0", model, rng=5)
    (plane,) = [e["plane"] for e in walk.meta["levels"]["route"] if "plane" in e]
    legs = legs_from_walk(walk, walker.stature)
    least = np.inf
    for _, m, data in posed(legs, walker.stature):
        for name in ("foot_l", "toes_l", "foot_r", "toes_r"):
            c = box_corners(m, data, m.geom(name).id)
            ground = np.maximum(plane_heights(surface_plane(plane), c[:, :2]), 0.0)
            least = min(least, float(np.min(c[:, 2] - wp.floor_z - ground)))
    assert least > -5e-3  # before: -18 mm


def test_a_foot_whose_toes_reach_past_a_ramp_s_head_stands_on_the_level_there():
    """A ramp's own footfall near its head, its toe tip past it over the level the head meets
    (generated hall 514's 9.5 deg ramp up to a 0.54 m deck, an adult's stress cycle): the
    ramp's plane does not carry the sole, so the foot stands level; on the highest point of
    the plane under its sole plus the grid's sag (before), its toes were 1.2 mm under the
    deck's edge and swung through it after toe-off. It stands at least at the deck's height."""
    g = leg_geometry(DEFAULT_STATURE)
    slope, run = np.radians(9.5), 3.0
    plane = {"slope": slope, "uphill": 0.0, "foot": [0.0, 0.0], "run": run, "half_width": 0.6,
             "z": 0.0}  # fmt: skip
    deck = np.tan(slope) * run
    # the sole grid's foremost point just past the head, the one behind it a spacing short
    x = run + 1e-3 - g.foot_front
    step = SimpleNamespace(side="left", foot=np.array([x, 0.0, 0.0]), foot_z=0.5 * deck,
                           stance=np.array([x - 0.6, 0.1, 0.0]), stance_z=0.4 * deck)  # fmt: skip
    route = [{"kind": "ramp", "steps": 1, "plane": plane}]
    walk = SimpleNamespace(meta={"levels": {"route": route}}, steps=[step])
    surf = StepSurfaces(lift=0.4 * deck, stance=0.4 * deck, land=0.5 * deck, lift_pitch=slope,
                        stance_pitch=slope, land_pitch=slope)  # fmt: skip
    (out,) = level_feet_on_ramps(walk, [surf], g)
    assert out.land_pitch == 0.0
    assert out.land >= deck - 1e-12  # before: 1.2 mm below
    assert out.land <= deck + 0.004
    inside = SimpleNamespace(**{**vars(step), "foot": np.array([run - 0.5, 0.0, 0.0])})
    walk.steps = [inside]  # carried whole by the plane: pitched to it, as before
    (on,) = level_feet_on_ramps(walk, [surf], g)
    assert on.land_pitch == pytest.approx(slope)


def test_a_swing_off_a_foot_level_on_a_ramp_beside_the_walk_keeps_out_of_the_floor():
    """A floor walk's left footprint over the low corner of a ramp beside it (8.6 deg, its
    foot line along the walk) stands level on the highest point of the plane under its sole,
    2.1 cm up (:func:`level_feet_on_ramps`). That height is the ramp's, no tread's: the swings
    around it are no edged steps. Before, the next step of that foot was swung as down a stair:
    held over its footprint until its toes, hanging down, cleared a nosing there is not, while
    the pelvis walked on; the leg, stretched to its knee's limit, put the foot 9.9 mm into the
    floor (0.8 m steps; generated halls 518 and 700's stress cycles, 3.1 and 1.1 cm). Now no
    foot box corner (MuJoCo forward kinematics) is under the floor."""
    walk = synthetic_walk(n_steps=8, step_len=0.8, step_time=0.55)
    x = float(walk.steps[4].foot[0])  # a left footprint, 0.09 m left of the walk's line
    plane = {"slope": 0.15, "uphill": np.pi / 2, "foot": [x, 0.0], "run": 2.0, "half_width": 0.2,
             "z": 0.0, "sides": [-0.2, 0.2]}  # fmt: skip
    walk = replace(walk, meta={**(walk.meta or {}), "ramps_beside": [plane]})
    legs = legs_from_walk(walk, DEFAULT_STATURE)
    least = np.inf
    for _, m, data in posed(legs, DEFAULT_STATURE):
        for name in ("foot_l", "toes_l", "foot_r", "toes_r"):
            least = min(least, float(box_corners(m, data, m.geom(name).id)[:, 2].min()))
    assert least > -1e-4  # before: -9.9 mm
    surfs = step_surfaces(walk)
    assert surfs[6].lift > 0.015 and surfs[6].lift_ramp  # the foot on the ramp's corner
    assert not any(s.edged for s in surfs)


def test_a_level_step_off_a_foot_raised_on_a_ramp_lands_on_its_heel():
    """A floor walk past a ramp's low end (``meta["ramps_beside"]``): the left foot whose heel
    is over the ramp's side stands level 2.7 cm up (the highest point of the plane under its
    sole), and the next steps swing from and land on the floor. A foot on a ramp's plane
    stands on no tread (``StepSurfaces.lift_ramp``), so they are no steps down off an edge:
    each foot lands on its heel as on the floor, and the pelvis stays
    within 5 mm of the floor walk's. Before, the step off the raised foot was taken for a
    stair's step down: it landed flat, its ankle 4 cm farther ahead and 2 cm lower than at heel
    strike, and the pelvis was lowered 4.0 cm to reach it (generated hall 201's seed-0 cycle,
    run 1: 0.73 m steps, 5.2 cm lowered, more than REACH_DROP_MAX: a PlanningError)."""
    g = leg_geometry(DEFAULT_STATURE)
    plane = {"slope": np.radians(5.5), "uphill": np.pi / 2, "foot": [1.475, -0.1], "run": 3.0,
             "half_width": 0.3, "z": 0.0}  # fmt: skip
    walk = synthetic_walk(n_steps=8, step_len=0.73, step_time=0.55)
    flat = legs_from_walk(walk, DEFAULT_STATURE)
    walk.meta["ramps_beside"] = [plane]
    surfs = step_surfaces(walk, g)
    assert surfs[2].land > 0.02 and surfs[2].land_pitch == 0.0  # the raised level foot
    assert not any(s.edged for s in surfs)
    legs = legs_from_walk(walk, DEFAULT_STATURE)
    for s in walk.steps:
        assert legs.pitch[s.side][s.end] == pytest.approx(flat.pitch[s.side][s.end])  # heel
    assert np.min(legs.root[:, 2] - flat.root[:, 2]) > -5e-3  # before: -40 mm


def _box_points(c, k=6):
    """(k**3, 3) points spread through a box from its 8 corners (:func:`box_corners`)."""
    u = np.linspace(0.0, 1.0, k)
    a, b, w = (x.ravel()[:, None] for x in np.meshgrid(u, u, u, indexing="ij"))
    C = c.reshape(2, 2, 2, 3)
    lerp = [[(1 - w) * C[i, j, 0] + w * C[i, j, 1] for j in (0, 1)] for i in (0, 1)]
    return (1 - a) * ((1 - b) * lerp[0][0] + b * lerp[0][1]) + a * (
        (1 - b) * lerp[1][0] + b * lerp[1][1]
    )


def test_a_heel_strike_beside_a_ramp_s_side_keeps_its_back_face_out_of_the_ramp():
    """A level landing whose heel lands 7 mm in front of a ramp's side (a 5.5 deg ramp beside a
    floor walk, its side across the walk; generated hall 511's stress cycle, run 5, once the
    crossed ramp's plane is its own: a floor heel 7 mm from the ramp's side, its back face
    1.3 mm into it): the foot lands on its heel pitched 26 deg toes up, and the foot box's
    back face, turned about the heel, leans back over the ramp. The stance check tests that
    pitched foot (:func:`heel_face_need`), not the flat footprint alone: no point of the foot
    box lies under the ramp's plane (before: 27 mm under it in the heel strike)."""
    g = leg_geometry(DEFAULT_STATURE)
    walk = synthetic_walk(n_steps=8, step_len=0.73, step_time=0.55)
    s4 = walk.steps[4]
    heel = float(s4.foot[0]) - g.foot_back
    plane = {"slope": np.radians(5.5), "uphill": np.pi / 2, "foot": [heel - 0.037, -0.3],
             "run": 1.0, "half_width": 0.03, "z": 0.0}  # fmt: skip
    walk = replace(walk, meta={**(walk.meta or {}), "ramps_beside": [plane]})
    need = heel_face_need([plane], s4.foot, np.radians(26.0), g)
    flat = step_surfaces(walk, g)[4].land  # the flat sole is not over the ramp: on the floor
    assert flat == 0.0 and need > 0.01
    assert heel_face_need([plane], s4.foot, 0.0, g) == -np.inf  # a flat landing needs nothing
    legs = legs_from_walk(walk, DEFAULT_STATURE)
    assert np.degrees(legs.pitch[s4.side][s4.end]) > 20.0  # it lands on its heel
    least = np.inf
    for i, m, data in posed(legs, DEFAULT_STATURE):
        if abs(i - s4.end) > 30:
            continue
        pts = _box_points(box_corners(m, data, m.geom("foot_l").id))
        h = plane_heights(plane, pts[:, :2])
        if np.isfinite(h).any():
            least = min(least, float(np.min((pts[:, 2] - h)[np.isfinite(h)])))
    assert least > -1e-4  # before: -27 mm


def _stepmat(tmp_path, gap: float):
    """A 0.34 m platform reached by a step block of two 0.17 m risers at its west end (x =
    -2.5 m) and a 5.5 deg ramp at its east end, a 15 mm mat on it (site ``p_mat``), and a
    0.9 x 1.0 m floor mat 15 mm thick whose east edge lies ``gap`` metres short of the step
    (site ``stand_step`` on it); ``stand_ramp`` on the floor before the ramp. Returns the
    scene's path."""
    x = -2.5 - gap - 0.45
    path = tmp_path / "stepmat.xml"
    path.write_text(f"""<mujoco model="stepmat"><worldbody>
<geom name="floor" type="plane" pos="0.5 0 0" size="7 4.5 0.05"/>
<geom name="platform" type="box" size="2.2 0.5 0.17" pos="0 3.2 0.17"/>
<geom name="platform_step" type="box" size="0.15 0.4 0.085" pos="-2.35 3.2 0.085"/>
<geom name="platform_ramp" type="box" size="1.773683 0.5 0.05" pos="3.960725 3.2 0.120230"
 euler="0 5.5 0"/>
<geom name="mat" type="box" size="0.6 0.35 0.0075" pos="0.6 3.2 0.3475"/>
<geom name="stepmat" type="box" size="0.45 0.5 0.0075" pos="{x:.4f} 3.2 0.0075"/>
<site name="stand_step" pos="{x - 0.3:.4f} 3.2 0"/>
<site name="stand_ramp" pos="6.6 3.2 0" euler="0 0 180"/>
<site name="p_mat" pos="0.6 3.2 0.355" euler="0 0 -90"/></worldbody></mujoco>""")
    return path


def _contacts(path, a: str, b: str, rng: int):
    """(the walk, its contacts) of ``a`` to ``b`` in the scene at ``path``."""
    walk = plan_walk(load_workplace(path, cache=False), a, b, default_model(progress=False),
                     rng=rng)  # fmt: skip
    return walk, check_collisions(walk, path)


@pytest.mark.parametrize(
    ("a", "b", "rng"),
    [
        ("stand_step", "p_mat", 0),
        ("stand_step", "p_mat", 2),
        ("stand_ramp", "stand_step", 1),
        ("p_mat", "stand_step", 0),
    ],
)
def test_walks_between_a_mat_short_of_a_step_and_the_platform_touch_nothing(tmp_path, a, b, rng):
    """A floor mat 5 cm short of the platform's step (issue 47): the walks up from it onto the
    platform's mat, down from there onto it, and along the floor from the ramp onto it plan
    and touch nothing. Before: up, a PlanningError (the pelvis lowered 0.069 m: the first
    riser step's feet on the mat were taken for a ramp's plane, no step edge, so the pelvis
    rose to the mean of the feet and fell back to the mat); along, a PlanningError at rngs
    1-2 (0.15-0.16 m: the foot on the mat stood on the level past the ramp's head, 5.7 m
    away in line with it, 0.34 m up); down, 38-41 contacts 15 mm deep (the riser step's
    landing on the mat stood at the floor's height). Up at rng 2 the heel strikes on the mat
    stand 0.4 mm above it (rampreach.heel_face_need), which lowtreads.low_treads took for no
    low top's height (0.069 m again, after the merge with the heel-face check)."""
    _, hits = _contacts(_stepmat(tmp_path, 0.05), a, b, rng)
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


@pytest.mark.parametrize("gap", [0.0, 0.3])
@pytest.mark.parametrize(("a", "b"), [("stand_step", "p_mat"), ("p_mat", "stand_step")])
def test_a_mat_against_or_well_short_of_a_step_touches_nothing(tmp_path, gap, a, b):
    """A floor mat right against the step (a level of its own, its riser 0.155 m to the
    tread) or 0.3 m short of it (the crossing's stance on the floor): 0 contacts up and
    down."""
    _, hits = _contacts(_stepmat(tmp_path, gap), a, b, 0)
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


def test_a_riser_step_off_a_mat_rises_from_the_mat_s_top(tmp_path):
    """The walk up from the mat 5 cm short of the step: the steps onto the step's tread and
    onto the platform leave feet standing on the mat's top (15 mm), a tread the risers are
    measured from (no ramp's plane): both are edged steps, the pelvis starting on the mat;
    the mat's footprints of the level steps before stay planes (not edged)."""
    walk, _ = _contacts(_stepmat(tmp_path, 0.05), "stand_step", "p_mat", 0)
    walk = with_low_tops(load_workplace(tmp_path / "stepmat.xml", cache=False), walk,
                         DEFAULT_STATURE)  # fmt: skip
    surfs = step_surfaces(walk)
    _, level = level_planes(walk, len(walk.steps))
    up = [k for k, sf in enumerate(surfs) if sf.land > sf.lift + 0.1 and sf.lift < 0.02]
    assert len(up) == 2
    first = surfs[up[0]]
    assert (first.lift, first.stance, first.land) == pytest.approx((0.015, 0.015, 0.17))
    assert first.edged and not (first.lift_ramp or first.stance_ramp)
    assert first.pelvis_level() == pytest.approx((0.015, 0.015))
    second = surfs[up[1]]  # step over step: the trailing foot leaves the mat for the platform
    assert (second.lift, second.land) == pytest.approx((0.015, 0.34)) and not second.lift_ramp
    assert second.edged
    before = [s for k, s in enumerate(surfs[: up[0]]) if level[k]]
    assert before and all(s.land_ramp and not s.edged for s in before)
