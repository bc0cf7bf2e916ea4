"""The swing foot of one step, compiled (mjwalk.body.legs.swing)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import leg_geometry, pelvis_height
from mjwalk.body.legs import steps
from mjwalk.body.legs.footpivot import pivot_ankle
from mjwalk.body.legs.reference import DEFAULT_REFERENCE
from mjwalk.body.legs.steps import TOE_OFF, StepFrames, step_frames
from mjwalk.body.legs.swing import swing_foot
from mjwalk.plan.synthetic import synthetic_walk


def test_swing_lands_on_its_footprint_as_the_numpy_swing():
    """The second step of a straight walk: the foot leaves its lift-off footprint flat-toed,
    lands on its landing footprint with the landing pitch and heading, toes straight, toe-off
    no later than TOE_OFF; the same numbers as steps.swing_foot (to 1e-12)."""
    g = leg_geometry(1.75)
    walk = synthetic_walk(n_steps=4)
    fr = step_frames(walk)[1]
    fr.land_p = 0.1
    idx = np.arange(fr.start, fr.end + 1)
    phi = (idx - fr.start) / (fr.end - fr.start)
    s = 1.0 if fr.side == "l" else -1.0
    yaw = walk.yaw[idx]
    hip_xy = walk.xy[idx] + s * g.hip_y * np.column_stack([-np.sin(yaw), np.cos(yaw)])
    z_hip = np.full(len(idx), pelvis_height(1.75) - 0.03)
    pos, p, toe, fyaw, phi_to = swing_foot(fr, phi, hip_xy, z_hip, DEFAULT_REFERENCE, g, 0.1)
    assert pos.shape == (len(idx), 3) and p.shape == toe.shape == fyaw.shape == (len(idx),)
    assert 0 < phi_to <= TOE_OFF
    assert np.allclose(pos[0], pivot_ankle(fr.lift, np.array([p[0]]), g)[0])
    assert np.allclose(pos[-1], pivot_ankle(fr.land, np.array([0.1]), g)[0])
    assert p[-1] == pytest.approx(0.1) and fyaw[-1] == pytest.approx(fr.land[2])
    assert toe[-1] == pytest.approx(0.0, abs=1e-9)
    assert pos[:, 2].min() >= g.ankle_height * 0.99
    want = steps.swing_foot(
        fr, phi, np.arange(len(phi)), z_hip,
        lambda i, side, zz=None: hip_xy[i] if zz is None else np.column_stack([hip_xy[i], zz]),
        DEFAULT_REFERENCE, g, 0.1,
    )  # fmt: skip
    for x, y in zip(want, (pos, p, toe, fyaw, phi_to), strict=True):
        assert np.allclose(x, y, rtol=0, atol=1e-12)


def test_a_step_back_and_across_does_not_swing_back_out():
    """A walk's last step backward and across the stance foot (run 2100 of the station at
    scale, seed 0: the left foot lifts at (0.372, -1.822) facing -101 deg and lands 0.34 m
    back-left, crossed 11 cm over the right stance foot; 1.70 m operator). The reference
    foot reaches forward along the heading, away from this landing: its progress along the
    chord rose and fell, and the ankle went back out 0.33 m towards the lift-off and a rack's
    frame after nearly landing. The progress never decreases now: after toe-off the ankle
    goes back along the chord by less than 6 cm (the spline's overshoot past the reference,
    4.9 cm here); compiled and NumPy swings agree."""
    g = leg_geometry(1.70)
    fr = StepFrames(
        side="l", other="r", start=0, end=82,
        lift=np.array([0.372, -1.822, -1.765]), land=np.array([0.126, -1.591, -1.551]),
        stance=np.array([0.241, -1.579, -1.714]), first=False, final=True,
        land_p=0.042, p_start=-0.148, p_end=-0.148,
    )  # fmt: skip
    phi = np.arange(83) / 82
    hip_xy = np.array([0.383, -1.706]) + phi[:, None] * np.array([-0.126, -0.014])
    z_hip = np.full(83, 0.87)
    pos, _, _, _, phi_to = swing_foot(fr, phi, hip_xy, z_hip, DEFAULT_REFERENCE, g, 0.042)
    want = steps.swing_foot(
        fr, phi, np.arange(83), z_hip,
        lambda i, side, zz=None: hip_xy[i] if zz is None else np.column_stack([hip_xy[i], zz]),
        DEFAULT_REFERENCE, g, 0.042,
    )  # fmt: skip
    assert np.allclose(want[0], pos, rtol=0, atol=1e-12)
    seg = fr.land[:2] - fr.lift[:2]
    u = (pos[phi > phi_to, :2] - fr.lift[:2]) @ (seg / np.linalg.norm(seg))
    assert u[-1] > 0.3  # the landing ankle, 0.34 m along the chord
    assert (np.maximum.accumulate(u) - u).max() < 0.06  # before: 0.32 m (0.27 m, then -0.04)


def test_station_run_2100_has_no_contacts(scenes_dir):
    """Station run 2100 of 10 000 (seed 0, main at 64ea5f7): the 1.70 m operator's left toes
    swung back out 7.2 mm into rack 2's frame on walk T4's last step (the step above); the
    whole cycle, with its contact check, has none now (about 4 s)."""
    from mjwalk.cycle.context import prepare  # deferred: the cycle stage, for this test only
    from mjwalk.cycle.seeding import run_generator  # deferred: as above
    from mjwalk.cycle.simulate import simulate_cycle  # deferred: as above
    from mjwalk.cycle.spec import load_cycle_spec  # deferred: as above

    ctx = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    r = simulate_cycle(ctx, run_generator(0, 2100), run=2100, ergonomics=False)
    assert r.operator.stature == pytest.approx(1.70)
    assert r.walks[-2].direction == "stand_car3->stand_rack2"
    assert list(r.collisions) == []


@pytest.mark.parametrize("first", [True, False])
def test_the_swing_ankle_never_goes_back_from_toe_off(first):
    """The first (standing start) and a middle step of a straight walk and of a turning one:
    from toe-off to mid-swing the ankle's progress along the step's ankle chord never
    decreases, and it is never behind its toe-off position (people's swing foot moves forward
    from toe-off to heel strike: Winter 1992). Before the fix the heel rise's lead over the
    lift-off footprint was given back: 7.8 cm median in the station's first steps
    (benchmarks/bench_swing_back.py)."""
    from mjwalk.body.legs import legs_from_walk

    for walk in (synthetic_walk(n_steps=6), synthetic_walk(n_steps=6, radius=1.2)):
        legs = legs_from_walk(walk)
        st = walk.steps[0 if first else 2]
        a, b = st.start, st.end
        ankle = legs.ankle[st.side][a : b + 1, :2]
        chord = (ankle[-1] - ankle[0]) / np.linalg.norm(ankle[-1] - ankle[0])
        ito = int(np.argmin(legs.contact[a : b + 1] == 2)) - 1
        d = (ankle[ito : round(0.6 * (b - a)) + 1] - ankle[0]) @ chord
        assert d.min() >= d[0] - 1e-9
        assert np.diff(d).min() >= -1e-9


@pytest.mark.slow
def test_the_station_batchs_run_307_arrives_at_the_car_without_contact():
    """Seeded: run 307 of ``mjwalk simulate scenes/assembly_station.toml --runs 2000`` (seed 0),
    replayed alone as ``--only-run 307`` does, has 0 contacts. Its left thigh grazed the car
    0.7 mm at t = 31.0 s (6.5 mm clear at a196e73): the carry's last step lifts a foot standing
    under the hip, and the reference's pre-swing heel rise held whole folded that leg to 39 deg
    hip flexion, the knee 0.33 m out from the pelvis towards the car (the heel rise now follows
    the foot's trail behind the hip: legs.steps.swing_foot; 16 mm clear at 120 Hz)."""
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.shipped import cycle_file

    spec = load_cycle_spec(cycle_file("assembly_station"))
    r = simulate_cycle(spec, run_generator(0, 307), run=307, ergonomics=False)
    assert r.operator.stature == pytest.approx(1.78, abs=0.005)
    assert r.collisions == []


def test_the_early_swing_foot_is_the_shank_plus_a_plantarflexed_ankle():
    """A straight walk's middle steps (1.55 and 1.95 m walkers): after toe-off the swing foot
    points toes down to -69 +- 3 deg at 67-72 % of the gait cycle, the reference's own
    (bandai-walk normal capture, 224 cycles: median -69.7, p10-p90 -73.4 to -66.0,
    benchmarks/bench_swing_pitch.py), with the swing ankle plantarflexed 8-20 deg there
    (Winter 1991: 15-20 deg at toe-off, dorsiflexing in initial swing): the toes-down foot is
    the knee's flexion, not an ankle past its range."""
    from mjwalk.body.legs import legs_from_walk

    for stature in (1.55, 1.95):
        walk = synthetic_walk(n_steps=8, step_len=0.65 * stature / 1.75)
        legs = legs_from_walk(walk, stature)
        for st in walk.steps[2:-2]:
            a, b = st.start, st.end
            p = np.rad2deg(legs.pitch[st.side][a : b + 1])
            ank = np.rad2deg(legs.angles[f"ankle_{st.side[0]}_flex"][a : b + 1])
            j = int(np.argmin(p))
            assert p[j] == pytest.approx(-69.0, abs=3.0)
            assert 67.0 <= 50 + 50 * legs.phase[a + j] <= 72.0
            assert -20.0 <= ank[j] <= -8.0
