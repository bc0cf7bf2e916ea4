"""The swing leg from a foot that did not trail its hip (mjwalk.body.legs.swingthigh)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.body.legs.ik import KNEE_MIN
from mjwalk.body.legs.swingthigh import (
    PITCH_LO,
    SWING_DORSI,
    SWING_TOE_CLEARANCE,
    reference_rows,
    swing_pitch,
    thigh_kept,
)

L1, L2 = 0.43, 0.43
HF, KF = math.radians(15.0), math.radians(65.0)  # mid swing
FWD = L1 * math.sin(HF) + L2 * math.sin(HF - KF)  # the reference's ankle ahead of the hip


def test_behind_the_reference_ankle_the_leg_is_the_reference():
    drop, turn = thigh_kept(FWD - 0.05, HF, KF, L1, L2, float(KNEE_MIN), 1.0)
    assert drop == L1 * math.cos(HF) + L2 * math.cos(HF - KF) and turn == 0.0


def test_ahead_of_it_the_thigh_is_kept_and_the_ankle_hangs_lower():
    """A foot under its hip (f = 0): the shank turns forward until the ankle is there, the
    thigh keeps the reference's flexion; continuous where the foot meets the reference's
    ankle; weighted by ``kept``."""
    ref_drop = L1 * math.cos(HF) + L2 * math.cos(HF - KF)
    drop, turn = thigh_kept(0.0, HF, KF, L1, L2, float(KNEE_MIN), 1.0)
    sig = HF - KF + turn
    assert L1 * math.sin(HF) + L2 * math.sin(sig) == pytest.approx(0.0, abs=1e-12)
    assert drop == pytest.approx(L1 * math.cos(HF) + L2 * math.cos(sig)) and drop > ref_drop
    near = thigh_kept(FWD + 1e-9, HF, KF, L1, L2, float(KNEE_MIN), 1.0)
    assert near[0] == pytest.approx(ref_drop, abs=1e-6) and near[1] == pytest.approx(0, abs=1e-6)
    half = thigh_kept(0.0, HF, KF, L1, L2, float(KNEE_MIN), 0.5)
    assert half == pytest.approx((0.5 * (ref_drop + drop), 0.5 * turn))
    assert thigh_kept(0.0, HF, KF, L1, L2, float(KNEE_MIN), 0.0) == (ref_drop, 0.0)


def test_out_of_the_straight_legs_reach_the_thigh_flexes_only_as_far_as_needed():
    f = 0.6  # beyond L1 sin HF + L2 sin(HF - KNEE_MIN)
    drop, _ = thigh_kept(f, HF, KF, L1, L2, float(KNEE_MIN), 1.0)
    span = math.hypot(f, drop)
    straight = math.sqrt(L1**2 + L2**2 + 2 * L1 * L2 * math.cos(float(KNEE_MIN)))
    assert span == pytest.approx(straight, abs=1e-9)


def test_the_pitch_dorsiflexes_for_the_toes_up_to_neutral():
    """A foot hanging toes down 50 deg from an ankle 9 cm up: raised until the rigid toe tip
    clears the floor by SWING_TOE_CLEARANCE where the ankle at neutral allows, never lowered,
    and not at all with ``kept`` 0."""
    front, ah, z = 0.19, 0.068, 0.09
    pv, kf = math.radians(-50.0), math.radians(35.0)  # the shank 20 deg back from vertical
    p = swing_pitch(pv, 0.0, HF, kf, z, front, ah, 1.0)
    tip = z + front * math.sin(p) - ah * math.cos(p)
    top = HF - kf + SWING_DORSI
    assert p > pv and (tip == pytest.approx(SWING_TOE_CLEARANCE) or p == pytest.approx(top))
    assert p <= top + 1e-12
    assert swing_pitch(pv, 0.0, HF, kf, z, front, ah, 0.0) == pv
    assert swing_pitch(math.radians(-5.0), 0.0, HF, KF, 0.3, front, ah, 1.0) == math.radians(-5)
    assert swing_pitch(math.radians(-90.0), 0.0, HF, KF, 0.5, front, ah, 0.0) == PITCH_LO


def test_reference_rows_are_the_kernels_row_by_row():
    rng = np.random.default_rng(47)
    m = 9
    f, hf, kf, pv = (
        rng.uniform(-0.4, 0.2, m),
        rng.uniform(-0.2, 0.5, m),
        rng.uniform(0, 1.2, m),
        rng.uniform(-1, 0.4, m),
    )
    zh = rng.uniform(0.85, 0.95, m)
    z, pit = reference_rows(f, hf, kf, pv, zh, L1, L2, float(KNEE_MIN), 0.19, 0.068, 0.7)
    for i in range(m):
        drop, turn = thigh_kept(f[i], hf[i], kf[i], L1, L2, float(KNEE_MIN), 0.7)
        assert z[i] == zh[i] - drop
        assert pit[i] == swing_pitch(pv[i], turn, hf[i], kf[i], z[i], 0.19, 0.068, 0.7)
