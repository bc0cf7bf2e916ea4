"""The legs on steps, stairs and ramps (mjwalk.body.legs.legheights, issue 47 deliverable 4)."""

import functools
from dataclasses import replace

import numpy as np
import pytest

from mjwalk.anthropometry import ROM_DEG, leg_geometry
from mjwalk.body.legs import legs_from_walk, synthesis
from mjwalk.body.legs.analysis import sagittal_angles, swing_hip_peaks
from mjwalk.body.legs.edgeswing import STAIR_TOE_CLEARANCE
from mjwalk.body.legs.footcheck import foot_points, posed
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.legheights import (
    DESCENT_CONTACT_PITCH,
    HIP_PEAK_DOWN,
    HIP_PEAK_UP,
    KNEE_PEAK_DOWN,
    KNEE_PEAK_UP,
    StepSurfaces,
    heel_rise,
    step_surfaces,
    surface_pitch,
)
from mjwalk.body.legs.pelvistilt import STAIR_ASCENT_PELVIC_TILT
from mjwalk.body.legs.stance import REACH_DROP_MAX
from mjwalk.body.legs.steps import FootTracks
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import TREAD_RISER_GAP
from mjwalk.plan.synthetic import synthetic_ramp_walk, synthetic_stair_walk, synthetic_walk


def _peaks(walk, motion, joint):
    """The peak flexion (deg) of ``joint`` (a key with ``{}`` for the side) over the stair's
    steps (not the first or last)."""
    a, b = walk.steps[1].start, walk.steps[-2].end
    return float(np.rad2deg(max(motion.angles[joint.format(s)][a:b].max() for s in "lr")))


def test_step_surfaces_of_a_stair():
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    surfs = step_surfaces(walk)
    assert replace(surfs[1], risers=()) == StepSurfaces(0.0, 0.17, 0.34)
    assert len(surfs[1].risers) == 6  # the stair's riser edges, carried from the walk
    assert surfs[1].edged and surfs[1].pelvis_level() == (0.0, 0.17)
    assert all(surface_pitch(walk, np.asarray(s.foot)) == 0.0 for s in walk.steps)


def test_ramp_pitch_is_found():
    walk = synthetic_ramp_walk(np.deg2rad(5.5))
    p = surface_pitch(walk, np.asarray(walk.steps[3].foot))
    assert p == pytest.approx(np.deg2rad(5.5), abs=np.deg2rad(0.2))
    assert not step_surfaces(walk)[3].edged


def test_ramp_pitch_only_on_the_route_s_ramps():
    """With the level planner's route in the walk's meta, a footfall is pitched only in a ramp
    crossing's steps: the same ramp walk read as level parts gets no pitch (the walk's height
    eases over a stair's ends and read as a 7 deg slope on a level landing)."""
    walk = synthetic_ramp_walk(np.deg2rad(5.5))
    n = len(walk.steps)
    walk.meta["levels"] = {
        "route": [{"kind": "level", "steps": 3}, {"kind": "ramp", "steps": n - 3}]
    }
    surfs = step_surfaces(walk)
    assert all(sf.land_pitch == 0.0 for sf in surfs[:3])
    assert surfs[3].land_pitch == pytest.approx(np.deg2rad(5.5), abs=np.deg2rad(0.2))
    walk.meta["levels"]["route"] = [{"kind": "level", "steps": n}]
    assert all(sf.land_pitch == 0.0 and sf.stance_pitch == 0.0 for sf in step_surfaces(walk))


def test_flat_walk_takes_the_flat_path():
    motion = legs_from_walk(synthetic_walk())
    assert "edge_clearance" not in motion.meta


def test_stair_ascent_pelvis_and_knee():
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    motion = legs_from_walk(walk)
    # the pelvis ends one flight (1.02 m) above where it started
    assert motion.root[-1, 2] - motion.root[0, 2] == pytest.approx(1.02, abs=0.03)
    assert KNEE_PEAK_UP[0] <= _peaks(walk, motion, "knee_{}") <= KNEE_PEAK_UP[1]
    # the swing foot is pitched as its clipped ankle holds it (no more than its range asked)
    a, b = walk.steps[1].start, walk.steps[-2].end
    top = np.deg2rad(ROM_DEG["ankle_flex"][1])
    assert max(motion.angles[f"ankle_{s}_flex"][a:b].max() for s in "lr") <= top + 1e-9


def test_stair_ascent_toe_clearance():
    """Up a 0.17/0.28 stair the swing sole clears every nosing by the cited 3 cm (Hamel et al.
    2005) with the knee peak in its cited range: the foot moves forward once its toes clear
    the lower nosing and rises on to the upper one (edgeswing._swing_path). The hip peak:
    test_stair_ascent_hip_peak_within_cited_range below."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    motion = legs_from_walk(walk)
    assert KNEE_PEAK_UP[0] <= _peaks(walk, motion, "knee_{}") <= KNEE_PEAK_UP[1]
    assert motion.meta["edge_clearance"] >= STAIR_TOE_CLEARANCE - 1e-3


def test_stair_hip_angle_is_the_thigh_to_the_tilted_pelvis():
    """Published stair hip flexion is the thigh relative to the PELVIS, which tilts in step
    ascent (Bohannon & Smutnick, J Appl Biomech 26:290 (2010), abstract verified here;
    backward, the pelvifemoral rhythm: pelvistilt): up the stair's inner steps the humanoid's
    pelvis is tilted by pelvistilt.STAIR_ASCENT_PELVIC_TILT (-2.6 deg; by MuJoCo forward
    kinematics, its z axis leaning against the heading), and ``hip_*_flex`` is the thigh's
    angle from the vertical in the walking plane (the hip-to-knee line,
    analysis.sagittal_angles) plus that tilt (2.6 deg less), within 0.5 deg (the hip's small
    abduction and rotation). Before the tilt (571cdb1) the pelvis stayed upright and the hip
    was the thigh from the vertical: this test failed there."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    motion = legs_from_walk(walk)
    a, b = walk.steps[1].start, walk.steps[-2].end
    frames = range(a, b, 3)
    pos = {k: np.zeros((len(frames), 3)) for k in ("hl", "kl", "hr", "kr")}
    lean = np.zeros(len(frames))
    poses = ((i, model, data) for i, model, data in posed(motion) if i in frames)
    for j, (i, model, data) in enumerate(poses):
        up = data.xmat[model.body("pelvis").id].reshape(3, 3)[:, 2]
        lean[j] = np.arctan2(up[0] * np.cos(motion.yaw[i]) + up[1] * np.sin(motion.yaw[i]), up[2])
        for s in "lr":
            pos[f"h{s}"][j] = data.xpos[model.body(f"thigh_{s}").id]
            pos[f"k{s}"][j] = data.xpos[model.body(f"shin_{s}").id]
    assert np.allclose(lean, STAIR_ASCENT_PELVIC_TILT, atol=1e-9)
    yaw = motion.yaw[list(frames)]
    for s in "lr":
        ang, _, _ = sagittal_angles(pos[f"h{s}"], pos[f"k{s}"], pos[f"k{s}"], pos[f"k{s}"], yaw)
        hip = motion.angles[f"hip_{s}_flex"][list(frames)]
        assert np.abs(np.rad2deg(ang + STAIR_ASCENT_PELVIC_TILT - hip)).max() < 0.5


def test_stair_ascent_hip_peaks_over_the_nosing():
    """Where the 1.75 m walker's ascent hip peak lies (0.17/0.28 stair): in mid swing, as
    the foot passes over the lower nosing at its highest (0.55-0.62 of the swing), and the
    hip extends by 8-12 deg before the foot lands, lowered onto its tread while the pelvis
    goes on forward; measured 54.1-55.3 deg peak, 43.4 at landing (the thigh to the pelvis
    tilted 2.6 deg backward), at 0.56-0.58 of the swing, with the pelvis midway between the
    feet at each contact as the level planner puts it (hip47d; 51.1-51.8 and 41.8 with it
    midway between the treads' centres, 6.65 cm further on). The published
    ascent hip flexion rises through swing to its peak in late swing and is held into foot
    contact (McFadyen & Winter 1988, Riener et al. 2002: read from their figures as usually
    reproduced, NOT verified here): the xfail below."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    for peak, land, at in swing_hip_peaks(walk, legs_from_walk(walk)):
        assert 0.5 <= at <= 0.65
        assert 5.0 <= peak - land <= 15.0


@pytest.mark.parametrize("stature", [1.55, 2.02])
def test_stair_ascent_hip_peak_scales_with_the_riser_to_leg_ratio(stature):
    """The ascent hip peak's fall with stature (58.3 deg at 1.55 m, 54.4 at 1.75, 49.4 at 2.02
    on the 0.17/0.28 stair) is the riser's share of the leg: on a stair scaled to the
    walker's stature (riser and tread times stature / 1.75) the peak is the 1.75 m
    walker's on the 0.17/0.28 stair within 1.5 deg (measured 54.6-55.4 at 1.55 m, 53.8-53.9
    at 2.02 m against 53.7-54.4) and its value at landing within 0.5 deg (44.4 at all three)
    (from the vertical, before hip47d; since, the thigh to the tilted pelvis with the pelvis
    placed as the planner places it: 54.7-55.8 and 53.5-54.7 against 54.1-55.3, landing
    43.3-43.4).
    Published hip flexion grows with the step's height (lead hip 66.3 deg up a 20.3 cm step,
    92.5 up 40.6 cm: "Hip and knee flexion of lead and trail limbs during ascent of a step of
    different heights by normal adults", abstract verified here), so the same stair asks a
    longer leg for less: the trend's direction is the published one."""
    f = stature / DEFAULT_STATURE
    ref = synthetic_stair_walk(0.17, 0.28, 6, "up")
    base = swing_hip_peaks(ref, legs_from_walk(ref))
    walk = synthetic_stair_walk(0.17 * f, 0.28 * f, 6, "up", stature=stature)
    scaled = swing_hip_peaks(walk, legs_from_walk(walk, stature))
    assert max(p for p, _, _ in scaled) == pytest.approx(max(p for p, _, _ in base), abs=1.5)
    for (_, land, _), (_, land_ref, _) in zip(scaled, base, strict=True):
        assert land == pytest.approx(land_ref, abs=0.5)
    # and on the same stair the shorter leg flexes more, the longer less
    same = synthetic_stair_walk(0.17, 0.28, 6, "up", stature=stature)
    peak = max(p for p, _, _ in swing_hip_peaks(same, legs_from_walk(same, stature)))
    assert (peak - max(p for p, _, _ in base)) * (DEFAULT_STATURE - stature) > 0


@pytest.mark.xfail(
    strict=True, reason="ascent hip peaks mid swing, 10.7-11.9 deg over its landing (issue 47)"
)
def test_stair_ascent_hip_held_into_foot_contact():
    """Published stair ascent hip flexion peaks in late swing and is held into foot contact
    (McFadyen & Winter 1988; Riener et al. 2002; NOT verified beyond the abstracts): the
    hip at the swing foot's landing within 5 deg of the swing's peak (ASSUMPTION: 5 deg,
    "held", not a published figure). The synthesis's hip extends 10.7-11.9 deg in foot
    placement (test_stair_ascent_hip_peaks_over_the_nosing; 9.3-10.0 with the pelvis midway
    between the treads' centres before hip47d: the pelvis placed as the planner places it
    raised the peak 3.5 deg and the landing 1.6)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    for peak, land, _ in swing_hip_peaks(walk, legs_from_walk(walk)):
        assert peak - land <= 5.0


def test_stair_ascent_hip_peak_within_cited_range():
    """Up the 0.17/0.28 stair the 1.75 m walker's hip (the thigh to the pelvis, which tilts
    2.6 deg backward in ascent: pelvistilt.STAIR_ASCENT_PELVIC_TILT, Bohannon & Smutnick
    2010's least mean tilt, posterior as the pelvifemoral rhythm of Bohannon & Bass 2017)
    peaks within HIP_PEAK_UP's 55-75 (ranges NOT verified beyond the abstracts): 55.3 deg
    (54.1-55.3 over the inner steps), 0.3 deg inside its low end. The synthetic walk's pelvis
    now stands at each foot contact midway between the feet (the points under the ankles), as
    the level planner's walks put it (plan.footfallwalk; the station's stair, planned: 55.2
    deg on the inner steps): it stood midway between the treads' centres, the setback (6.65
    cm) further on, and peaked at 51.8 deg (a strict xfail until hip47d; 57.0 while the tilt
    was taken forward, hip47b). Against a figure where a static tilt cancels, ascent minus
    descent hip peak is 18.3 deg (55.3 - 37.0; descent has no tilt) against 28.1 (SD 4.1) on
    an 18/28.5 cm stair (Protopapadaki et al. 2007, abstract verified): still 2.4 SD short.
    What-ifs measured at 1.75 m (branch hip47, not adopted, no cited figure for either): the
    flight's pelvis 4 / 8 cm behind the treads' midway at each double support, peak 56.4 /
    58.1 from the vertical; ascent landed forefoot first at the descent's -20 deg, peak 56.1,
    at contact 48.4 (knee 105.7 at 1.55 m)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    motion = legs_from_walk(walk)
    assert HIP_PEAK_UP[0] <= _peaks(walk, motion, "hip_{}_flex") <= HIP_PEAK_UP[1]


def test_stair_descent_knee_hip_and_forefoot_landing():
    """Down a 0.17/0.28 stair the hip peak lies in the cited range, and every step onto a
    lower tread lands on the forefoot (toes down) and ends flat."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down")
    motion = legs_from_walk(walk)
    assert HIP_PEAK_DOWN[0] <= _peaks(walk, motion, "hip_{}_flex") <= HIP_PEAK_DOWN[1]
    for st, nxt in zip(walk.steps[1:-1], walk.steps[2:], strict=True):
        assert motion.pitch[st.side][st.end] == pytest.approx(DESCENT_CONTACT_PITCH)
        # the heel lowered onto the tread while the other foot is still down
        assert np.abs(motion.pitch[st.side][nxt.start : nxt.end]).min() < 1e-3


def test_stair_descent_knee_peak():
    """Down a 0.17/0.28 stair the knee flexion peak over the flight's steps from one tread to
    the next (steps 2-5) lies in the cited range: 99.2 deg at 1.75 m (99.2, 99.2, 99.2, 98.7),
    as on the planner's own walk down the station's stair (next test). The peak is the SWING
    knee in leg pull-through, not the stance leg lowering the body. Before descent47 the
    synthetic walk's pelvis stood midway between the treads' centres at each contact, 6.65 cm
    further on than the planner's, and the swing knee peaked 95.5-95.7 deg there. The first
    step off the top landing from standing (step 1) is the strict xfail below. The 80-100 deg
    band itself is not verified beyond the abstracts (KNEE_PEAK_DOWN); a 101-person stair
    descent dataset's abstract gives knee flexion up to 85 deg."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down")
    motion = legs_from_walk(walk)
    a, b = walk.steps[2].start, walk.steps[-2].end
    peak = float(np.rad2deg(max(motion.angles[f"knee_{s}"][a:b].max() for s in "lr")))
    assert KNEE_PEAK_DOWN[0] <= peak <= KNEE_PEAK_DOWN[1]


@functools.cache
def _planned_descent(scene: str, stature: float | None = None):
    """The level planner's walk down the station's stair (mezzanine rack to rack 1, seed 1),
    its legs, and its steps from the top landing onto the first tread to the trailing foot's
    step off the bottom tread (7 steps). ``stature`` None: the default model's walk (1.75 m);
    else the walk planned for a walker of that stature (the model conditioned on it, as a
    cycle plans each operator's walks: the planner places the feet on the treads for that
    walker's foot, ``mjwalk.plan.levelcross.flight_setback``) and played at that stature."""
    from mjwalk.gait.default import default_model  # deferred: only these tests plan
    from mjwalk.plan.walks import plan_walk  # deferred: only these tests plan
    from mjwalk.world import load_workplace  # deferred: only these tests load a scene

    wp = load_workplace(scene)
    model = default_model(progress=False)
    if stature is not None:
        model = model.for_walker(Walker(stature=stature))
    walk = plan_walk(wp, "stand_mezz_rack", "stand_rack1", model, rng=1)
    top = max(max(s.stance_z, s.foot_z) for s in walk.steps)
    on_tread = [k for k, s in enumerate(walk.steps) if 0.01 < s.stance_z < top - 0.01]
    stair = walk.steps[on_tread[0] - 1 : on_tread[-1] + 2]
    assert len(stair) == 7 and stair[0].stance_z == top and stair[-1].stance_z == 0.0
    legs = legs_from_walk(walk) if stature is None else legs_from_walk(walk, stature)
    return walk, legs, stair


def _step_peaks(motion, steps) -> tuple[float, float]:
    """Knee and hip flexion peaks (deg) of either leg over ``steps`` (consecutive)."""
    a, b = steps[0].start, steps[-1].end + 1
    knee, hip = (
        float(np.rad2deg(max(motion.angles[j.format(s)][a:b].max() for s in "lr")))
        for j in ("knee_{}", "hip_{}_flex")
    )
    return knee, hip


def test_the_planners_descent_knee_and_hip_peaks_within_cited_ranges(scenes_dir):
    """The level planner's own walk down the station's stair (mezzanine rack to rack 1, the
    walker arriving at the top landing walking) flexes the knee and the hip within the cited
    ranges on every step onto a lower tread or the floor, the trailing foot's step off the
    top landing included: measured 99.2 deg knee (the step onto the first tread 88.7), hip
    42.1 (1.75 m; seeds 1-3 alike: the flight's footfalls and pace do not depend on the draw;
    1.55 / 1.85 / 2.02 m walkers: knee 102.8 / 95.8 / 92.8, hip 43.6 / 40.0 / 38.0)."""
    _, motion, stair = _planned_descent(str(scenes_dir / "multilevel_station.xml"))
    knee, hip = _step_peaks(motion, stair[:-1])
    assert KNEE_PEAK_DOWN[0] <= knee <= KNEE_PEAK_DOWN[1]
    assert HIP_PEAK_DOWN[0] <= hip <= HIP_PEAK_DOWN[1]


@pytest.mark.xfail(
    strict=True,
    reason="hip 50.3 deg (cited descent 20-45) on the planner's trailing step off the bottom "
    "tread, a 0.52 m step onto the floor (issue 47)",
)
def test_the_planners_step_off_the_bottom_tread_within_descent_ranges(scenes_dir):
    """On the planner's walk down the station's stair, the trailing foot's step from the
    bottom tread onto the floor, 0.52 m past the stance foot as the walk goes on to rack 1
    (the synthetic walk's brings it beside the stance foot), peaks at 97.8 deg knee (inside
    80-100) and 50.3 deg hip, over the cited descent range (measured 1.75 m, descent47; not
    investigated: the cited ranges are the flight's steps, no figure for the step from the
    last tread onto the floor was found in mjwalk's norms nor in the stored corpora,
    docs/decisions/115). Other statures, each walker's own planned walk (hip202): hip 54.4 /
    52.2 / 51.3 / 47.6 / 44.7 deg at 1.55 / 1.65 / 1.70 / 1.85 / 2.02 m."""
    _, motion, stair = _planned_descent(str(scenes_dir / "multilevel_station.xml"))
    knee, hip = _step_peaks(motion, stair[-1:])
    assert KNEE_PEAK_DOWN[0] <= knee <= KNEE_PEAK_DOWN[1]
    assert HIP_PEAK_DOWN[0] <= hip <= HIP_PEAK_DOWN[1]


_SHORT_KNEE = pytest.mark.xfail(
    strict=True,
    reason="descent knee peak over the cited 100 deg on the planner's walk (1.55 / 1.65 / 1.70 m: "
    "102.8 / 101.0 / 100.1): the 0.17 m riser's larger share of a shorter leg; no cited "
    "stature-dependent range (docs/decisions/115)",
)


@pytest.mark.parametrize(
    "stature",
    [
        pytest.param(1.55, marks=_SHORT_KNEE),
        pytest.param(1.65, marks=_SHORT_KNEE),
        pytest.param(1.70, marks=_SHORT_KNEE),
        1.85,
        2.02,
    ],
)
def test_the_planners_descent_peaks_by_stature(scenes_dir, stature):
    """The level planner's walk down the station's stair, planned for a walker of ``stature``
    (as a cycle plans each operator's walks) and played at it (as in
    test_the_planners_descent_knee_and_hip_peaks_within_cited_ranges: the landing's step onto
    the first tread to the last step onto a tread), keeps the knee and hip peaks within the
    fixed cited descent ranges. Measured (knee / hip, deg; hip202): 1.55 m 102.8 / 43.6,
    1.65 m 101.0 / 43.0, 1.70 m 100.1 / 42.5, 1.75 m 99.2 / 42.1, 1.85 m 95.8 / 40.0, 2.02 m
    92.8 / 38.0 (its step from the top landing onto the first tread 83.4 / 33.8). The knee
    peak falls as the leg lengthens, as the stature / step-height ratio governs the hip and
    knee's range on stairs (J Hum Kinet 26:45, children to young adults in six stature groups,
    abstract only); the ranges stay the adults' of ordinary stature since no cited figure for
    other ratios was found (docs/decisions/115).

    Each walker's landing heel on the first tread stands off the top landing's riser: the
    1.75 m walk played by a 2.02 m walker (stair47's measurement) put its 7.7 cm heel 3.3 mm
    into that riser, so the swing foot was held at the landing's height to the last sample
    (hip 46.9, knee 72.5 deg at phase 0.98) and dropped 20 cm in one frame (knee 72.5 -> 7.5
    deg); planned for the walker, its foot (longer than the tread) keeps its heel 3 cm off the
    riser (``levelcross.RISER_GAP``)."""
    walk, motion, stair = _planned_descent(str(scenes_dir / "multilevel_station.xml"), stature)
    top = stair[0].stance_z
    (riser,) = [e for e in walk.meta["edges"] if abs(e["high"] - top) < 1e-6]
    behind = -np.asarray(riser["normal"], dtype=float)  # the walk's way down, off the riser
    heel = float((stair[0].foot[:2] - np.asarray(riser["xy"])) @ behind)
    assert heel - leg_geometry(stature).foot_back >= TREAD_RISER_GAP - 1e-6
    knee, hip = _step_peaks(motion, stair[:-1])
    assert KNEE_PEAK_DOWN[0] <= knee <= KNEE_PEAK_DOWN[1]
    assert HIP_PEAK_DOWN[0] <= hip <= HIP_PEAK_DOWN[1]


@pytest.mark.xfail(
    strict=True,
    reason="knee peak 100.2 deg (cited 80-100) on the synthetic walk's first step off the top "
    "landing from standing, its pelvis still accelerating (issue 47); the planner's walk 99.2",
)
def test_the_first_step_off_a_landing_from_standing_knee_peak():
    """Down a 0.17/0.28 stair from standing on the top landing, the trailing foot's step off
    the landing (step 1: from the landing to the second tread) peaks at 100.2 deg knee at 1.75
    m, 1.0 deg over the flight's 99.2 and over the cited 100. The feet and the pelvis at every
    contact stand as on the planner's walk (99.2 on that step there); what differs is the
    pelvis's speed: the synthetic walk starts from rest and its pelvis (a PCHIP through the
    contacts) moves at 0.41 m/s as step 1 starts against the steady 0.61 (0.28 m per 0.46 s),
    1.4 cm behind the planner's at 30 % of the swing, when the swing foot is held over the
    landing until its toes clear the top nosing and the knee peaks (98.6 against 97.5 deg at
    that sample). How fast a walker starting from standing reaches its steady speed is
    reported differently (within the first step: Breniere & Do; over about three steps: Mann
    et al. 1979, J Bone Joint Surg 61-A; neither checked here), so the synthetic start is not
    changed to either."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down")
    motion = legs_from_walk(walk)
    st = walk.steps[1]
    peak = float(np.rad2deg(motion.angles[f"knee_{st.side[0]}"][st.start : st.end + 1].max()))
    assert KNEE_PEAK_DOWN[0] <= peak <= KNEE_PEAK_DOWN[1]


def test_stair_descent_swing_lowers_smoothly():
    """Down a 0.17/0.28 stair the swing ankle lowers onto its tread over the swing, not at
    landing (e2808db dropped it 0.24 m in one sample): no drop of more than 5 cm between two
    samples (120 Hz), and its sole never dips into a tread."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down")
    motion = legs_from_walk(walk)
    for st in walk.steps[1:-1]:
        z = motion.ankle[st.side][st.start : st.end + 1, 2]
        assert np.diff(z).min() > -0.05
    assert motion.meta["edge_clearance"] > -1e-3


@pytest.mark.parametrize(
    "direction",
    [
        "up",
        "down",
    ],
)
def test_feet_on_treads(direction):
    """By forward kinematics of the clipped joint angles: a stance foot's lowest sole point
    (heel or ball) lies within 1 cm of its tread and never below it, and the whole foot (heel
    to toe tip) stands within the tread's depth (0.17/0.28 stair, the interior treads)."""
    riser, tread, n = 0.17, 0.28, 6
    walk = synthetic_stair_walk(riser, tread, n, direction)
    motion = legs_from_walk(walk)
    pts, _, _ = foot_points(motion)
    g = leg_geometry(DEFAULT_STATURE)
    toe_len = g.foot_back + g.foot_front - np.linalg.norm(pts[0, 0, 1, :2] - pts[0, 0, 0, :2])
    for st in walk.steps[1:-1]:
        k = 1 if st.side == "left" else 0  # the stance foot
        sl = slice(st.start, st.end + 1)
        low = pts[sl, k, :, 2].min(axis=1)
        assert low.min() >= st.stance_z - 0.01  # never below its tread
        assert np.abs(low - st.stance_z).max() <= 0.01
        i = round(st.stance[0] / tread + 0.25)  # the tread's index along +x
        if 1 <= i <= n - 1:
            heel_x, ball_x = pts[sl, k, 0, 0], pts[sl, k, 1, 0]
            assert heel_x.min() >= (i - 0.5) * tread - 0.005
            assert (ball_x + toe_len).max() <= (i + 0.5) * tread + 0.005


def test_foot_flat_on_a_ramp():
    """On a 5.5 deg ramp the stance foot lies on the slope (FK, 0.5 deg) over its foot-flat,
    30-38 % of the step from its landing (15-19 % of the gait cycle)."""
    angle = np.deg2rad(5.5)
    walk = synthetic_ramp_walk(angle)
    motion = legs_from_walk(walk)
    _, pitch, _ = foot_points(motion)
    for st in walk.steps[2:-1]:
        k = 1 if st.side == "left" else 0
        n = st.end - st.start
        sl = slice(st.start + round(0.30 * n), st.start + round(0.38 * n) + 1)
        assert np.abs(pitch[sl, k] - angle).max() < np.deg2rad(0.5)


def test_foot_pitch_on_a_ramp():
    """On a 5.5 deg ramp a stance foot in mid-stance is pitched to the slope (FK, 1 deg). The
    level synthesis's stance ankle is at 15.1 deg dorsiflexion there; carried onto the slope
    it needed 21.4 deg against the AAOS 20 deg limit and the heel rose (2.7-4.2 deg pitch).
    Uphill the stance ankle now gains only Kwon & Shin's (2022) share of the slope, the stance
    knee extending instead (mjwalk.body.legs.rampstance)."""
    angle = np.deg2rad(5.5)
    walk = synthetic_ramp_walk(angle)
    motion = legs_from_walk(walk)
    _, pitch, _ = foot_points(motion)
    for st in walk.steps[2:-1]:
        k = 1 if st.side == "left" else 0
        mid = (st.start + st.end) // 2
        assert pitch[mid, k] == pytest.approx(angle, abs=np.deg2rad(1.0))


def test_a_heel_rise_on_the_heel_stops_lowering_the_toes_at_the_surface():
    """A foot on its heel after heel strike on a 5.5 deg ramp (toes up 1 deg from it) whose
    ankle would dorsiflex 3 deg past its range turns toes down about its heel only until its
    sole is on the ramp, and about its ball by the other 2 deg (its heel rises, its toes stay
    on the ramp): turned the whole 3 deg about its heel, its toe tip went 1 cm into the ramp
    (the multi-level platform cycle's run 1, its first ramp step)."""
    geom = leg_geometry()
    slope, pitch = np.deg2rad(5.5), np.deg2rad(6.5)
    back = np.array([np.cos(pitch), np.sin(pitch)])  # the sole's direction, heel to toe (x, z)
    heel = np.array([0.0, 0.05])
    ankle = heel + geom.foot_back * back + geom.ankle_height * np.array([-back[1], back[0]])
    one = lambda v: {"l": np.array([v])}  # noqa: E731
    feet = FootTracks(
        {"l": np.array([[ankle[0], 0.0, ankle[1]]])}, one(0.0), one(pitch), one(0.0),
        one(True), {"l": np.zeros((1, 3))},
    )  # fmt: skip
    dorsi = np.array([np.deg2rad(ROM_DEG["ankle_flex"][1] + 3.0)])
    assert heel_rise(feet, "l", dorsi, np.array([True]), geom, np.array([slope]))
    p = float(feet.pitch["l"][0])
    assert p == pytest.approx(slope - np.deg2rad(2.0), abs=1e-9)
    assert float(feet.toe["l"][0]) == pytest.approx(np.deg2rad(2.0), abs=1e-9)
    # the ball (turned about) is where the sole met the ramp at the slope's pitch
    sole = np.array([np.cos(slope), np.sin(slope)])
    ball_on_ramp = heel + (geom.foot_back + ball_offset(geom)) * sole
    a = feet.ankle["l"][0][[0, 2]]
    ball = (
        a
        + ball_offset(geom) * np.array([np.cos(p), np.sin(p)])
        - geom.ankle_height * np.array([-np.sin(p), np.cos(p)])
    )
    assert ball == pytest.approx(ball_on_ramp, abs=1e-9)


def _tall_stair_peaks(stature: float, direction: str) -> tuple[float, float]:
    """Knee and hip flexion peaks (deg) of a walker of ``stature`` up or down the shipped
    stair (0.17/0.28 m), its feet placed as the level planner places them
    (:func:`mjwalk.plan.levelcross.flight_setback`: from 1.78 m the foot is longer than the
    going and hangs over the nosing)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, direction, stature=stature)
    motion = legs_from_walk(walk, stature)
    return _peaks(walk, motion, "knee_{}"), _peaks(walk, motion, "hip_{}_flex")


@pytest.mark.parametrize("stature", [1.85, 2.02])
def test_tall_walkers_knee_peaks_and_descent_hip_within_cited_ranges(stature):
    """Tall walkers on the stair with the overhanging foot (issue 47, stair47): the knee peaks
    up and down and the hip peak down lie in the cited ranges (measured: knee 99.9 / 95.8 deg
    up; down, with the pelvis at each contact as the planner's, descent47, knee 96.5 / 93.5,
    hip 40.8 / 39.0 at 1.85 / 2.02 m; the planner's own walk down the station's stair 95.8 /
    92.8 and 40.0 / 38.0)."""
    knee, _ = _tall_stair_peaks(stature, "up")
    assert KNEE_PEAK_UP[0] <= knee <= KNEE_PEAK_UP[1]
    knee, hip = _tall_stair_peaks(stature, "down")
    assert KNEE_PEAK_DOWN[0] <= knee <= KNEE_PEAK_DOWN[1]
    assert HIP_PEAK_DOWN[0] <= hip <= HIP_PEAK_DOWN[1]


@pytest.mark.xfail(strict=True, reason="hip ascent peak 52.5 / 48.9 deg < cited 55 (issue 47)")
@pytest.mark.parametrize("stature", [1.85, 2.02])
def test_tall_walkers_ascent_hip_peak_within_cited_range(stature):
    """Up the 0.17 m risers the hip peak falls with stature: the thigh to the pelvis (tilted
    2.6 deg backward, pelvistilt) 59.5 deg at 1.55 m, 55.3 at 1.75, 52.5 at 1.85, 48.9 at 2.02
    m with the pelvis midway between the feet at each contact as the planner puts it (hip47d;
    55.8, 51.8, 49.7, 46.8 midway between the treads' centres before), under HIP_PEAK_UP's
    55-75 at 1.85 and 2.02 m. The ranges come from studies of adults of
    ordinary height on 17-18 cm risers; a longer leg climbs the same riser with less hip
    flexion. No jump where the foot starts to overhang (1.77 / 1.78 / 1.79 m: 53.9 / 53.6 /
    53.4 deg from the vertical, before hip47d): the leg's length, not the overhanging foot.
    That the stature / step-height ratio sets the hip and knee's range on stairs is published
    (J Hum Kinet 26:45, abstract only, no figures in it); no cited range for a ratio other
    than the cited studies' was found in the stored corpora (stair47, docs/decisions/115:
    Livingston et al. 1991's statures not found there), so the range stays fixed. (Before
    edgeswing.REACHED one step's swing rose higher on a float knife edge: 60.2 at 1.55, 55.6
    at 1.75, 51.0 at 2.02.)"""
    _, hip = _tall_stair_peaks(stature, "up")
    assert HIP_PEAK_UP[0] <= hip <= HIP_PEAK_UP[1]


def _descent_knee_peak(stature: float, riser: float = 0.17, tread: float = 0.28) -> float:
    """The knee flexion peak (deg) of a walker of ``stature`` down a six-riser stair, its feet
    placed as the level planner places them (the first and last steps left out)."""
    walk = synthetic_stair_walk(riser, tread, 6, "down", stature=stature)
    return _peaks(walk, legs_from_walk(walk, stature), "knee_{}")


def test_a_short_walkers_descent_knee_peak_is_the_risers_share_of_its_leg():
    """Down a stair scaled to its stature (riser and tread times 1.55 / 1.75) a 1.55 m walker
    flexes its knee as the 1.75 m walker does down the 0.17/0.28 stair (measured 99.0 and 98.4
    deg at fed66aa; 100.3 and 99.7 since the pre-swing heel rise follows the foot's trail,
    run307, which puts the scaled walker 0.3 deg over the cited 100, so only the equality is
    asserted here and the 1.75 m walker's range in its own test): its 103.0 deg down the
    0.17 m stair (the strict xfail below) is the same riser's larger share of a shorter leg,
    as a higher step takes more knee flexion (lead knee 90.5 deg up a 20.3 cm step, 119.9 up
    a 40.6 cm one: "Hip and knee flexion of lead and trail limbs during ascent of a step of
    different heights by normal adults", abstract verified here). The riser, not the tread or
    the foot's place on it: on a 0.32 m tread the 1.55 m walker's peak stays 103.4 deg, on a
    0.15 m riser it is 98.7."""
    scale = 1.55 / DEFAULT_STATURE
    short = _descent_knee_peak(1.55, 0.17 * scale, 0.28 * scale)
    assert short == pytest.approx(_descent_knee_peak(DEFAULT_STATURE), abs=1.5)


@pytest.mark.xfail(
    strict=True,
    reason="knee peak down 104.0 deg at 1.55 m > cited 100 (issue 47): steps 1-5 104.0, 102.9, "
    "102.9, 102.8, 102.2 deg, the swing knee in pull-through; the planner's walk 102.8; the "
    "riser's share of a shorter leg",
)
def test_a_short_walkers_descent_knee_peak_within_cited_range():
    """Down the 0.17/0.28 stair a 1.55 m walker's knee peaks at 104.0 deg (steps 1-5 of the
    synthetic walk: 104.0, 102.9, 102.9, 102.8, 102.2, the swing knee in pull-through each
    time; the planner's own walk down the station's stair: 102.8 deg on every step from a
    tread, 94.3 onto the first, descent47). With the pelvis midway between the treads' centres
    at each contact, 6.65 cm further on than the planner's (before descent47): 100.2, 99.7,
    99.6, 99.6, 99.3; 104.5 on step 1 before the walk's pelvis started midway between the
    feet, descent47i. The suspects below were measured at those. Measured with
    each suspect taken out (stair47c): the descent sole's 5 mm (DESCENT_LOW_CLEARANCE) lift
    -0.4 deg, the pelvis lowered to reach (stance.lower_to_reach) -0.8, the soles' lift
    altogether -0.4, the descent swing planned 5 mm instead of 3 cm over the nosings -1.7:
    none brings it within 100. The cited 80-100 deg come from adults of ordinary height;
    the stature / step-height ratio sets the stair range (J Hum Kinet 26:45, abstract only),
    but no cited figure for a 1.55 m adult's ratio (riser / leg 0.223 against 0.198 at
    1.75 m) was found, nor a cited short-stature stair strategy (docs/decisions/115)."""
    assert KNEE_PEAK_DOWN[0] <= _descent_knee_peak(1.55) <= KNEE_PEAK_DOWN[1]


@pytest.mark.parametrize("stature", [1.55, DEFAULT_STATURE])
def test_the_last_step_off_a_stair_flexes_the_knee_as_the_flight_does(stature):
    """The trailing foot's step from the bottom tread onto the floor beside the stance foot is
    swung as a descent (StepSurfaces.descends): its knee peak stays within 1 deg of the
    flight's highest (measured 101.0 / 96.1 deg at 1.55 / 1.75 m against 103.0 / 98.4). Swung
    as a step up, held behind the nosing it leaves, it peaked at 104.5 / 101.3."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down", stature=stature)
    motion = legs_from_walk(walk, stature)
    peaks = [
        float(np.rad2deg(motion.angles[f"knee_{st.side[0]}"][st.start : st.end + 1].max()))
        for st in walk.steps
    ]
    assert peaks[-1] <= max(peaks[1:-1]) + 1.0


_FROM_REST = pytest.mark.xfail(
    strict=True,
    reason="104.0 deg against the flight's 102.9 at 1.55 m (1.1 deg over) since the synthetic "
    "walk's pelvis stands as the planner's (descent47): its pelvis still accelerating",
)


@pytest.mark.parametrize("stature", [pytest.param(1.55, marks=_FROM_REST), DEFAULT_STATURE])
def test_the_first_step_off_a_landing_flexes_the_knee_as_the_flight_does(stature):
    """Down the 0.17/0.28 stair the first step off the top landing (step 1: the trailing foot
    from the landing to the second tread) peaks within 1 deg of the flight's steps 2-5: it
    starts with the pelvis midway between the feet, as they do (measured 104.0 / 100.2 deg
    against 102.9 / 99.2 at 1.55 / 1.75 m since the pelvis stands at each contact as the
    planner's, descent47, the 1.75 m walker 1.0 deg over, at the bound: the pelvis starting
    from rest, test_the_first_step_off_a_landing_from_standing_knee_peak; 100.2 / 96.4
    against 99.7 / 95.7 midway between the treads' centres; before that, a quarter tread on:
    104.5 / 100.1)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "down", stature=stature)
    motion = legs_from_walk(walk, stature)
    peaks = [
        float(np.rad2deg(motion.angles[f"knee_{st.side[0]}"][st.start : st.end + 1].max()))
        for st in walk.steps
    ]
    assert peaks[1] <= max(peaks[2:-1]) + 1.0


def _one_riser_walk(riser: float, step_len: float, first: int = 3):
    """A straight 8-step walk whose step ``first`` lands one riser up (``riser`` > 0) or down
    and whose next step brings the trailing foot onto that level, the ground height jumping at
    the riser (a step as the level planner's crossings give it, not a ramp)."""
    walk = synthetic_walk(n_steps=8, step_len=step_len, step_time=0.55)
    lo, hi = (0.0, riser) if riser > 0 else (-riser, 0.0)
    walk.steps[:] = [
        replace(s, foot_z=hi if k >= first else lo, stance_z=hi if k > first else lo)
        for k, s in enumerate(walk.steps)
    ]
    z = np.full(len(walk.t), lo)
    z[walk.steps[first].end :] = hi
    walk.z = z
    return walk


@pytest.mark.parametrize("riser", [0.17, -0.17])
def test_a_step_onto_the_stance_foot_s_level_lands_on_its_heel(riser):
    """Off a riser (up or down) the next step brings the trailing foot onto the level the
    stance foot already stands on: it lands on its heel as on the level (its riser is behind
    the stance foot), and the pelvis is not lowered for it. Landed flat (before), its ankle 4 cm
    ahead and 2 cm below the heel strike, the leg reached it only with the pelvis 3.4 cm
    lowered (0.49 m steps; 3.5 cm in generated halls 201 and 510). The step down onto the
    lower level itself is landed flat (a riser below the stance foot) and lowers the pelvis
    3.4 cm: within the bound."""
    walk = _one_riser_walk(riser, 0.49)
    flat = legs_from_walk(synthetic_walk(n_steps=8, step_len=0.49, step_time=0.55))
    motion = legs_from_walk(walk)
    onto = walk.steps[4]  # lift one riser from the stance foot's level, lands on it
    assert motion.pitch[onto.side][onto.end] == pytest.approx(flat.pitch[onto.side][onto.end])
    low = motion.meta["pelvis_lowering"]
    assert low[onto.end - 10 :].max() < 5e-3
    for st in walk.steps:  # every step's lowering within the bound
        assert low[st.start : st.end + 1].max() <= REACH_DROP_MAX


def test_stair_walks_pelvis_lowering_within_the_bound():
    """Up and down a 0.17/0.28 stair (the level planner's footfalls) the pelvis's whole
    lowering below its gait's height over the stance tread (flat synthesis and lift onto the
    treads together; down a stair the gait's own lowering of a riser per step is not counted)
    stays under 1 cm on every step but the first two down, and under half REACH_DROP_MAX on
    those (measured: 2.0 mm on the flight; 11.8 mm on the steps onto the first tread and off
    the landing since the pelvis stands at each contact as the planner's, descent47, 6.65 cm
    further back than midway between the treads' centres, where it was 5.1 / 4.8 mm: the
    leading leg reaches further down and forward to the first tread. The planner's own walk
    down the station's stair lowers it 26.4 mm there, arriving walking)."""
    for direction in ("up", "down"):
        walk = synthetic_stair_walk(0.17, 0.28, 6, direction)
        low = legs_from_walk(walk).meta["pelvis_lowering"]
        assert len(low) == len(walk.t)
        for k, st in enumerate(walk.steps):
            bound = 0.5 * REACH_DROP_MAX if direction == "down" and k < 2 else 0.01
            assert 0.0 <= low[st.start : st.end + 1].max() < bound


@pytest.mark.parametrize("flat_drop", [0.0, 0.03, 0.06])
def test_the_whole_lowering_is_bounded_once(monkeypatch, flat_drop):
    """The flat synthesis's lowering and the lift's are one lowering of the pelvis below its
    gait's height, bounded once. With ``flat_drop`` lowered by the flat synthesis (its ankle
    fit, stood in for here) the step down a riser (3.4 cm to reach its flat landing) is
    lowered only what is still missing (the lift measures from the lowered pelvis): the whole
    is the larger of the two, and past the bound the walk is refused in one line naming
    where, a flat walk too (before, the flat synthesis's lowering had no bound, and the lift
    counted only its own part)."""
    fit = synthesis._fit_ankles

    def lowered_fit(sy, ik, win):
        fit(sy, ik, win)
        sy.z = sy.z - flat_drop

    monkeypatch.setattr(synthesis, "_fit_ankles", lowered_fit)
    for walk, need in ((synthetic_walk(n_steps=6), 0.0), (_one_riser_walk(-0.17, 0.49), 0.034)):
        if flat_drop <= REACH_DROP_MAX:
            low = legs_from_walk(walk).meta["pelvis_lowering"]
            assert low.max() == pytest.approx(max(flat_drop, need), abs=5e-3)
            continue
        with pytest.raises(PlanningError, match=r"m lowered at \(") as err:
            legs_from_walk(walk)
        assert "\n" not in str(err.value)
