"""The swing leg after toe-off from a foot that did not trail its hip as the reference's (issue
47, item 4; the gait on the flat): the reference thigh kept, the shank turned forward to the
foot (:func:`thigh_kept`), and the foot's pitch dorsiflexed as far as its toes then clear the
floor (:func:`swing_pitch`). One-sample kernels shared by both swing twins
(:func:`~mjwalk.body.legs.steps.swing_foot` and :func:`~mjwalk.body.legs.swing.swing_foot`,
which must stay bit-equal), and their per-row form for the NumPy twin (:func:`reference_rows`).

Why: the reference swing (Winter 1991; Perry & Burnfield 2010, :mod:`.reference`) places its
ankle by the reference's hip and knee angles measured from the hip. From a foot near or under
the hip (a first step from standing, a short or closing step) that ankle, kept on the step's
chord, sits ahead of the reference's and at its height, and the leg folds to reach it: every
first step of the station's runs 0-19 flexed the hip 46.5 deg median (50.4 max) against the
reference's 27 deg swing peak (e749e69). World frame, metres, radians; pitch + toes up.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit

#: The reference pitch's clamp in the swing after toe-off (radians).
PITCH_LO, PITCH_HI = float(np.deg2rad(-70)), float(np.deg2rad(30))
#: Toe clearance (m) the swing foot's pitch keeps over the floor after toe-off where its ankle
#: allows (:func:`swing_pitch`): the minimum toe clearance of able-bodied gait, 1.9 +- 0.5 cm
#: at about 51 % of the swing (Moosabhoy & Gard, "Methodology for determining the sensitivity
#: of swing leg toe clearance and leg length to swing leg joint angles during gait", Gait
#: Posture 24(4):493-501, 2006, abstract; its toe clearance is most sensitive to the ankle
#: angle, 17.1 cm/rad, then the hip's 9.5 and the knee's 2.5).
SWING_TOE_CLEARANCE = 0.019
#: Highest ankle dorsiflexion the swing foot's clearance pitch asks for (radians, from the
#: shank's perpendicular): neutral. In mid swing the ankle comes up to neutral to clear the toes
#: and stays there through terminal swing (Perry & Burnfield, "Gait Analysis", 2nd ed., 2010,
#: the ankle in swing; quoted from memory, not checked). Measured: allowing up to the range's
#: 19 deg instead, the ankle met its 20 deg limit after the spline and the floor lift had
#: flexed the knee further, and the toes dipped 1.2 mm into the floor (steady 0.25 m steps).
SWING_DORSI = 0.0


@njit
def thigh_kept(f, hf, kf, L1, L2, knee_min, kept):
    """The swing leg's hip-to-ankle drop and shank turn for an ankle ``f`` ahead of its hip
    at the reference's thigh and knee angles of that gait-cycle instant. At or behind the
    reference's own ankle: the reference leg (drop ``L1 cos hf +
    L2 cos(hf - kf)``, turn 0). Ahead of it (a foot starting near or under its hip: a first
    step, a short or closing step) the thigh keeps the reference's flexion and the shank
    turns forward to reach the ankle (the knee flexes less than the reference's, so the
    ankle hangs lower); where even the knee at ``min(kf, knee_min)`` cannot reach it, the
    thigh flexes further, only as far as that reach needs. Weighted by ``kept`` (0: the
    reference leg, 1: the kept thigh): how far the foot did not trail its hip at toe-off as
    the reference's (the pre-swing's trailing share), so a normal stride keeps the reference
    swing and a foot from under its hip the reference thigh. Used by both swing twins
    (``steps._reference_swing``, ``swing._swing_late``).

    Args:
        f: the ankle's distance ahead of the hip along the foot's heading, metres.
        hf: the reference's thigh flexion at that instant, radians.
        kf: the reference's knee flexion there, radians.
        L1: the thigh's length, metres.
        L2: the shank's length, metres.
        knee_min: the least knee flexion of a stretched leg, radians.
        kept: the weight of the kept thigh, 0 to 1.

    Returns:
        (drop, turn): the drop below the hip, metres; the shank's turn forward from the
        reference's, radians (>= 0), which the foot's pitch takes too (the reference's ankle
        angle kept).
    """
    sig_ref = hf - kf
    drop_ref = L1 * math.cos(hf) + L2 * math.cos(sig_ref)
    if not f > L1 * math.sin(hf) + L2 * math.sin(sig_ref):
        return drop_ref, 0.0
    k_lo = min(kf, knee_min)
    h = hf
    x = (f - L1 * math.sin(h)) / L2
    if x > math.sin(h - k_lo):  # the thigh flexes as far as the reach needs
        a, b = L1 + L2 * math.cos(k_lo), L2 * math.sin(k_lo)
        h = math.atan2(b, a) + math.asin(min(f / math.sqrt(a * a + b * b), 1.0))
        sig = h - k_lo
    else:
        sig = math.asin(max(x, -1.0))
    drop = L1 * math.cos(h) + L2 * math.cos(sig)
    return drop_ref + kept * (drop - drop_ref), kept * max(sig - sig_ref, 0.0)


@njit
def swing_pitch(pv, turn, hf, kf, z, front, ah, kept):
    """The swing foot's pitch after toe-off (radians, + toes up) at one sample: the reference's
    ``pv`` turned with the shank by ``turn`` (:func:`thigh_kept`; the reference's ankle angle
    kept) and clamped to :data:`PITCH_LO`-:data:`PITCH_HI`, raised (the ankle dorsiflexed) as
    far as the rigid foot's toe tip (``front`` ahead of the ankle, ``ah`` below it, metres)
    then clears the floor by :data:`SWING_TOE_CLEARANCE` with the ankle at height ``z`` (m),
    at most to :data:`SWING_DORSI` of dorsiflexion from the shank (``hf - kf + turn`` from the
    vertical): the ankle clears the toes before the hip and knee must lift the foot (Moosabhoy
    & Gard 2006; the floor lift after the spline, ``steps._clear_floor``, does the rest); that
    raise weighted by ``kept`` as :func:`thigh_kept`'s (the reference's pitch where 0).

    Args:
        pv: the reference's foot pitch at that instant, radians.
        turn: the shank's turn from :func:`thigh_kept`, radians.
        hf: the reference's thigh flexion, radians.
        kf: the reference's knee flexion, radians.
        z: the ankle's height over the floor, metres.
        front: the toe tip's distance ahead of the ankle along the sole, metres.
        ah: the ankle's height over the sole, metres.
        kept: the weight of the raise, 0 to 1.

    Returns:
        the pitch, radians.
    """
    p = min(max(pv + turn, PITCH_LO), PITCH_HI)
    r = math.sqrt(front * front + ah * ah)
    need = math.atan2(ah, front) + math.asin(min(max((SWING_TOE_CLEARANCE - z) / r, -1.0), 1.0))
    return p + kept * (max(p, min(need, hf - kf + turn + SWING_DORSI)) - p)


@njit
def reference_rows(f, hf, kf, pv, z_hip, L1, L2, knee_min, front, ah, kept):
    """:func:`thigh_kept` and :func:`swing_pitch` per row (the NumPy swing's form).

    Args:
        f: (m,) the ankles' distances ahead of the hip, metres.
        hf: (m,) the reference's thigh flexions, radians.
        kf: (m,) the reference's knee flexions, radians.
        pv: (m,) the reference's foot pitches, radians.
        z_hip: (m,) the pelvis heights, metres.
        L1: the thigh's length, metres.
        L2: the shank's length, metres.
        knee_min: the least knee flexion, radians.
        front: the toe tip ahead of the ankle, metres.
        ah: the ankle's height over the sole, metres.
        kept: the weight of the kept thigh, 0 to 1.

    Returns:
        (z, pitch): the ankle heights (m,), metres, and pitches (m,), radians.
    """
    m = f.shape[0]
    z, pit = np.empty(m), np.empty(m)
    for i in range(m):
        drop, turn = thigh_kept(f[i], hf[i], kf[i], L1, L2, knee_min, kept)
        z[i] = z_hip[i] - drop
        pit[i] = swing_pitch(pv[i], turn, hf[i], kf[i], z[i], front, ah, kept)
    return z, pit
