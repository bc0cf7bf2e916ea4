"""The pelvis tilted backward in stair ascent (mjwalk.body.legs.pelvistilt, issue 47)."""

import mujoco
import numpy as np
import pytest

from mjwalk.body.legs import legs_from_walk, synthesis
from mjwalk.body.legs.footcheck import posed
from mjwalk.body.legs.pelvistilt import (
    STAIR_ASCENT_PELVIC_TILT,
    ascent_tilt,
    pelvis_quat,
    thigh_rotation,
    tilt_pelvis,
)
from mjwalk.plan.synthetic import synthetic_stair_walk
from mjwalk.timeline.frames import yaw_quat


def test_ascent_tilt_over_a_flight_up():
    """Up a six-riser flight: no tilt before the first step, the full tilt from the end of
    the first step to the end of the last riser's step, eased out over the trailing foot's
    step onto the landing (zero at its end), never beyond the held figure."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    tilt = ascent_tilt(walk, len(walk.t))
    share = tilt / STAIR_ASCENT_PELVIC_TILT
    first, last, off = walk.steps[0], walk.steps[-2], walk.steps[-1]
    assert tilt[first.start] == 0.0
    assert np.all(np.diff(share[first.start : first.end + 1]) >= 0)
    assert np.allclose(tilt[first.end : last.end + 1], STAIR_ASCENT_PELVIC_TILT)
    assert np.all(np.diff(share[off.start : off.end + 1]) <= 0)
    assert np.abs(tilt[off.end :]).max() == 0.0
    assert share.min() >= 0.0
    assert share.max() == pytest.approx(1.0)


def test_the_ascent_tilt_is_backward_and_takes_off_hip_flexion():
    """The pelvifemoral rhythm of step ascent (Bohannon & Smutnick 2010; posterior, Bohannon &
    Bass 2017): the pelvis tilts backward, so up the stair each hip's flexion to the pelvis is
    the thigh's angle from the vertical LESS the tilt's 2.6 deg. With no hip rotation or
    abduction exactly; on the synthetic stair walk every inner-step sample's hip flexion lies
    below the untilted synthesis's, by the tilt within 0.5 deg. On the base tree the tilt was
    forward and added to the flexion: this test failed there."""
    assert STAIR_ASCENT_PELVIC_TILT == pytest.approx(-np.radians(2.6))
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    tilt = ascent_tilt(walk, len(walk.t))
    assert tilt.max() == 0.0 and tilt.min() == pytest.approx(-np.radians(2.6))
    a, b = walk.steps[1].start, walk.steps[-2].end
    tilted = legs_from_walk(walk)
    for s in "lr":
        flex = tilted.angles[f"hip_{s}_flex"][a:b]
        plain = {k: v[a:b] for k, v in tilted.angles.items()}
        # the thigh from the vertical: the tilted hip angles re-solved in an upright pelvis
        upright = tilt_pelvis(plain, -tilt[a:b])[f"hip_{s}_flex"]
        assert np.all(flex < upright)
        assert np.abs(np.rad2deg(upright - flex) - 2.6).max() < 0.5


def test_no_tilt_off_a_stair_ascent(off_ascent_walk):
    """Down a stair, on the floor and up a ramp (no step rises a riser) the pelvis stays
    upright, and the legs carry no tilt."""
    assert not ascent_tilt(off_ascent_walk, len(off_ascent_walk.t)).any()
    assert "pelvis_tilt" not in legs_from_walk(off_ascent_walk).meta


def test_tilt_pelvis_keeps_the_thighs_world_rotation():
    """The hip angles re-solved in a pelvis tilted by t give the same thigh rotation in the
    world: Ry(t) R_new = R_old (seeded random hip angles within the joints' ranges); with no
    hip rotation or abduction the flexion grows by t exactly."""
    rng = np.random.default_rng(47)
    n = 200
    angles = {}
    for s in "lr":
        angles[f"hip_{s}_rot"] = rng.uniform(-0.6, 0.6, n)
        angles[f"hip_{s}_flex"] = rng.uniform(-0.4, 1.5, n)
        angles[f"hip_{s}_abd"] = rng.uniform(-0.4, 0.6, n)
    tilt = rng.uniform(0.0, 0.2, n)
    new = tilt_pelvis(angles, tilt)
    c, s_ = np.cos(tilt), np.sin(tilt)
    ry = np.zeros((n, 3, 3))
    ry[:, 0, 0], ry[:, 0, 2], ry[:, 1, 1], ry[:, 2, 0], ry[:, 2, 2] = c, s_, 1.0, -s_, c
    for s in "lr":
        old = thigh_rotation(s, *(angles[f"hip_{s}_{j}"] for j in ("rot", "flex", "abd")))
        got = ry @ thigh_rotation(s, *(new[f"hip_{s}_{j}"] for j in ("rot", "flex", "abd")))
        assert np.abs(got - old).max() < 1e-12
    zero = {k: np.zeros(n) for k in angles}
    zero["hip_l_flex"] = angles["hip_l_flex"]
    assert np.allclose(tilt_pelvis(zero, tilt)["hip_l_flex"], angles["hip_l_flex"] + tilt)


def test_pelvis_quat():
    """Rz(yaw) Ry(tilt) as MuJoCo reads the quaternion; the yaw-only quaternion at no tilt."""
    rng = np.random.default_rng(3)
    yaw, tilt = rng.uniform(-4, 4, 20), rng.uniform(-0.3, 0.3, 20)
    q = pelvis_quat(yaw, tilt)
    assert np.array_equal(pelvis_quat(yaw, np.zeros(20)), yaw_quat(yaw))
    for k in range(20):
        m = np.zeros(9)
        mujoco.mju_quat2Mat(m, q[k])
        cz, sz, cy, sy = np.cos(yaw[k]), np.sin(yaw[k]), np.cos(tilt[k]), np.sin(tilt[k])
        rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
        ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
        assert np.allclose(m.reshape(3, 3), rz @ ry, atol=1e-12)


def test_tilt_leaves_the_legs_in_place(monkeypatch):
    """Up the stair, the tilted pelvis's legs by MuJoCo forward kinematics: knees, ankles and
    toes where the untilted synthesis put them (within 0.1 mm); posed from the legs alone (no
    lumbar counter-flexion, which the timeline adds: tests/timeline/test_frames.py), the
    trunk's top (the head) moves along the heading by about the tilt's sine times its height
    over the hips (backward, the tilt being backward)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    tilted = legs_from_walk(walk)
    monkeypatch.setattr(synthesis, "ascent_tilt", lambda w, n: np.zeros(n))
    upright = legs_from_walk(walk)
    assert "pelvis_tilt" not in upright.meta
    frames = set(range(0, len(walk.t), 7))
    bodies = [f"{b}_{s}" for b in ("shin", "foot", "toes") for s in "lr"]

    def where(motion):
        out = {}
        for i, model, data in posed(motion):
            if i in frames:
                out[i] = np.array([data.xpos[model.body(b).id] for b in bodies])
                out[i, "head"] = data.xpos[model.body("neck").id].copy()
        return out

    a, b = where(tilted), where(upright)
    for i in frames:
        assert np.abs(a[i] - b[i]).max() < 1e-4
    mid = walk.steps[3].start
    i = min(f for f in frames if f >= mid)
    fwd = np.array([np.cos(walk.yaw[i]), np.sin(walk.yaw[i]), 0.0])
    lead = float((a[i, "head"] - b[i, "head"]) @ fwd)
    height = float(b[i, "head"][2] - upright.root[i, 2])
    assert lead == pytest.approx(height * np.sin(STAIR_ASCENT_PELVIC_TILT), rel=0.05)
