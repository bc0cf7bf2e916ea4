"""Gait-cycle analysis of captures (mjwalk.body.legs.analysis): sagittal angles, heel strikes,
gait cycles and a reference gait from takes, checked against the model's own legs."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from mjwalk.body.legs.analysis import (
    gait_cycles,
    heel_strikes,
    reference_from_takes,
    sagittal_angles,
    swing_hip_peaks,
)
from mjwalk.body.legs.footcheck import posed
from mjwalk.body.legs.reference import winter_reference
from mjwalk.body.legs.synthesis import legs_from_walk
from mjwalk.errors import CaptureError, InputError
from mjwalk.mocap.take import Take
from mjwalk.plan.synthetic import synthetic_walk

DATA = Path(os.environ.get("MJWALK_SHARED_DATA", Path(__file__).parents[3] / "shared" / "data"))

make_walk = synthetic_walk


def test_sagittal_angles_of_a_straight_leg_are_zero():
    """A vertical leg with a foot pointing forward has no thigh or knee flexion and a flat
    foot; a thigh swung forward by 30 deg (knee straight) flexes the hip by 30 deg."""
    n = 5
    hip = np.tile([0.0, 0.0, 0.9], (n, 1))
    knee = np.tile([0.0, 0.0, 0.5], (n, 1))
    ankle = np.tile([0.0, 0.0, 0.1], (n, 1))
    toe = np.tile([0.15, 0.0, 0.1], (n, 1))
    hipf, kneef, pitch = sagittal_angles(hip, knee, ankle, toe, np.zeros(n))
    assert np.allclose([hipf, kneef, pitch], 0.0, atol=1e-12)
    a = np.deg2rad(30)
    knee2 = hip + 0.4 * np.array([np.sin(a), 0, -np.cos(a)])
    ankle2 = hip + 0.8 * np.array([np.sin(a), 0, -np.cos(a)])
    hipf, kneef, _ = sagittal_angles(hip, knee2, ankle2, ankle2 + [0.15, 0, 0], np.zeros(n))
    assert np.allclose(hipf, a) and np.allclose(kneef, 0.0, atol=1e-12)


def test_heel_strikes_are_prominent_pitch_peaks():
    """One toes-up peak per second is found at each peak; small wiggles are not."""
    fps = 100.0
    t = np.arange(0, 5, 1 / fps)
    pitch = np.deg2rad(20) * np.maximum(np.sin(2 * np.pi * t), 0) ** 4
    pitch += np.deg2rad(2) * np.sin(2 * np.pi * 7 * t)
    hs = heel_strikes(pitch, fps)
    assert len(hs) == 5
    assert np.all(np.abs(t[hs] % 1.0 - 0.25) < 0.05)


def test_reference_from_takes_needs_cycles():
    """Takes without a complete gait cycle give no reference."""
    with pytest.raises(CaptureError, match="no complete gait cycle"):
        reference_from_takes([])


def _model_cycles(walk, stature, reference=None):
    """Gait cycles (C, 3, 101) of the model's left leg, through MuJoCo FK and the same
    :func:`gait_cycles` used on the capture (like-for-like)."""
    legs = legs_from_walk(walk, stature, reference=reference)
    bodies = ("thigh_l", "shin_l", "foot_l", "toes_l")
    pos = np.zeros((len(legs.t), 4, 3))
    for i, model, data in posed(legs, stature):
        pos[i] = [data.xpos[model.body(b).id] for b in bodies]
    joints = dict(
        zip(("UpperLeg_L", "LowerLeg_L", "Foot_L", "Toes_L"), pos.swapaxes(0, 1), strict=True)
    )
    take = Take(
        "model",
        120.0,
        legs.root,
        legs.yaw,
        pos[:, 2],
        pos[:, 2],
        pos[:, 3],
        pos[:, 3],
        joints=joints,
    )
    return gait_cycles(take)


def test_knee_hip_curves_vs_bandai_capture():
    """Mean knee/hip flexion over a straight-walk cycle vs bandai-walk (normal style).

    Reference gait from clips 1-3 (the paper's gait DB), compared with held-out clips 4-6 of
    the same style; the walk (step length, cadence) and the leg length match those clips."""
    files = sorted((DATA / "bandai-walk").glob("dataset-2_walk_normal_*.bvh"))[:6]
    if len(files) < 6:
        pytest.skip("../shared/data/bandai-walk not available")
    mocap = pytest.importorskip("mjwalk.mocap")
    takes = [mocap.load_bvh(f, skeleton="bandai") for f in files]
    train, test = takes[:3], takes[3:]
    cap = np.concatenate([gait_cycles(t) for t in test])
    assert len(cap) >= 6
    cap = cap.mean(0)
    j = test[0].joints
    leg = np.median(np.linalg.norm(j["UpperLeg_L"] - j["LowerLeg_L"], axis=1)) + np.median(
        np.linalg.norm(j["LowerLeg_L"] - j["Foot_L"], axis=1)
    )
    stature = leg / 0.491  # thigh + shank = 0.491 stature (Winter)
    speed = np.mean(
        [np.linalg.norm(np.diff(t.pelvis[:, :2], axis=0), axis=1).sum() / t.duration for t in test]
    )
    period = []
    for t in test:
        _, _, pitch = sagittal_angles(
            *(t.joints[k] for k in ("UpperLeg_L", "LowerLeg_L", "Foot_L", "Toes_L")), t.pelvis_yaw
        )
        period.extend(np.diff(heel_strikes(pitch, t.fps)) / t.fps)
    T = float(np.median(period))
    walk = make_walk(n_steps=14, step_len=speed * T / 2, step_time=T / 2)
    figures = {}
    refs = (
        ("default (generated, Bandai landmarks)", None),
        ("Winter table", winter_reference()),
        ("capture clips 1-3", reference_from_takes(train)),
    )
    for name, ref in refs:
        mod = _model_cycles(walk, stature, ref).mean(0)
        d = np.degrees(np.abs(mod - cap)).max(1)
        figures[name] = d
        print(
            f"\nvs bandai-walk normal 4-6, reference {name}: max diff hip {d[0]:.1f} deg "
            f"(target 5), knee {d[1]:.1f} deg (target 10), foot pitch {d[2]:.1f} deg"
        )
    # measured: generated (BANDAI_LANDMARKS, calibrated on clips 1-3) hip 4.8, knee 6.9 deg;
    # capture reference hip 4.2, knee 7.2 deg; Winter table hip 12.4, knee 16.1 deg (the
    # literature gait, not this actor's). Targets: the paper's 5 / 10 deg.
    for name in ("default (generated, Bandai landmarks)", "capture clips 1-3"):
        hip, knee, _ = figures[name]
        assert hip <= 5.0 and knee <= 10.0, name


def test_swing_hip_peaks_of_a_level_walk():
    """On a level walk each inner step's swing hip peaks about 0.6 of the way through its
    swing, as the Winter reference's does (32 deg at 85 % of the cycle, the swing 60-100 %),
    and is lower when the foot lands (measured 27.4-28.0 deg peak, 20.6 at landing: the
    synthesis lands with less hip flexion than the reference's 30 deg); a walk whose step has
    no swing samples is refused."""
    walk = synthetic_walk()
    legs = legs_from_walk(walk)
    peaks = swing_hip_peaks(walk, legs)
    assert len(peaks) == len(walk.steps) - 2
    for peak, land, at in peaks:
        assert 0.5 <= at <= 0.75
        assert peak >= land
    legs.contact[:] = 2  # double support throughout: no swing
    with pytest.raises(InputError, match="no swing"):
        swing_hip_peaks(walk, legs)
