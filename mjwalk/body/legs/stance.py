"""The stance leg of one step, compiled (paper §4.2.3, A8): the stance foot's pitch and ankle
(:func:`stance_foot`) and the stance knee with the pelvis height it gives (:func:`stance_knee`).

They were a few dozen NumPy operations per step on its few dozen samples, as
:func:`~mjwalk.body.legs.synthesis.legs_from_walk`'s loop over the steps, whose call overhead
cost more than their arithmetic. Here the same arithmetic runs in the same order in one
compiled call each (the same numbers, bit for bit: ``tests/test_fast_anim.py`` compares them
with that NumPy code on walks). The reference gait's values come in as arrays (any reference
table); the knee for a hip-to-ankle span (an arccos) and powers of NumPy scalars stay with the
caller, as compiled code rounds them differently from NumPy here.

Step phase ``phi`` in [0, 1] from lift-off of the swing foot's step to its landing; the stance
leg covers gait cycle 0-50 %. World frame, metres, radians; a foot's pitch + toes up.

numba caches this module's machine code by its own source, not by the compiled functions it
calls from other modules (``kinematics._heel_rise_rows``, ``kinematics._pivot_rows``,
``curves._clamped_cubic`` and the one-value shapes such as ``curves.smoothstep1``): change a
comment here when those change.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import (
    FLAT,
    _clamped_cubic,
    maximum1,
    minimum1,
    smoothstep1,
    soft_flat1,
)
from mjwalk.body.legs.kinematics import KNEE_MIN, _heel_rise_rows, _pivot_rows, ball_offset
from mjwalk.body.legs.reference import ReferenceGait
from mjwalk.body.legs.steps import FOOT_FLAT, STANCE_KEYS, StepFrames

#: The stance knee's upper bound (radians, 80 deg): the synthesis's clip of the stance spline.
KNEE_STANCE_MAX = float(np.deg2rad(80))
#: :func:`~mjwalk.body.legs.kinematics.heel_rise`'s default lowest pitch (radians).
HEEL_RISE_LO = -1.0472


def stance_foot(
    fr: StepFrames,
    phi: np.ndarray,
    p_ref: np.ndarray,
    land_prev: float | None,
    hs_pitch: float,
    hip_end: np.ndarray,
    knee_end: float,
    geom: LegGeometry,
) -> tuple[np.ndarray, np.ndarray]:
    """The stance foot's pitch (n,) and ankle (n, 3) over a step: heel-strike roll-down, flat,
    heel rise after the reference, and the heel rising further (about the ball) towards the
    end where the leg with ``knee_end`` flexion would not reach the hip at the target posture.

    Args:
        fr: the step (stance footprint, ``first``).
        phi: (n,) increasing step phases of the step's samples, 0 to 1.
        p_ref: (n,) the reference foot pitch at gait cycle ``0.5 phi`` (radians).
        land_prev: the pitch the foot landed with (the previous step's ``land_p``), or None
            (the walk's first step, or a reference without toes-up heel strike).
        hs_pitch: the reference's heel-strike pitch (radians, > 0 where ``land_prev`` is set).
        hip_end: (3,) the stance hip joint centre at the step's end (target posture), metres.
        knee_end: the stance knee flexion there (radians).
        geom: the leg lengths.
    """
    L1, L2 = float(geom.thigh), float(geom.shank)
    n = len(phi)
    p, ankle = np.empty(n), np.empty((n, 3))
    _stance_foot(
        np.ascontiguousarray(phi, dtype=float),
        np.ascontiguousarray(p_ref, dtype=float),
        land_prev is not None,
        0.0 if land_prev is None else float(land_prev),
        float(hs_pitch),
        bool(fr.first),
        np.asarray(fr.stance, float),
        np.asarray(hip_end, float).reshape(1, 3),
        L1**2 + L2**2,
        2 * L1 * L2,
        float(knee_end),
        ball_offset(geom),
        float(geom.foot_back),
        float(geom.ankle_height),
        p,
        ankle,
    )
    return p, ankle


@njit
def _stance_foot(phi, p_ref, scaled, land_prev, hs_pitch, first, stance, hip_end, span0, span1,
                 knee_end, ball, back, ah, p, ankle):  # fmt: skip
    """:func:`stance_foot` into ``p`` (n,) and ``ankle`` (n, 3); ``span0 + span1 cos knee`` the
    squared hip-to-ankle span (:meth:`LegGeometry.span`)."""
    n = phi.shape[0]
    for i in range(n):
        q = maximum1(p_ref[i], 0.0) if phi[i] < FOOT_FLAT else minimum1(p_ref[i], 0.0)
        if scaled and phi[i] < FOOT_FLAT:  # the roll-down starts from the landing pitch
            q = q * land_prev / hs_pitch
        q = soft_flat1(q, FLAT)
        if first:  # standing start: already flat
            q = minimum1(q, 0.0)
        p[i] = q
    rise = np.empty(1)
    d = np.empty(1)
    d[0] = math.sqrt(span0 + span1 * math.cos(knee_end))
    _heel_rise_rows(stance, hip_end, d, p[n - 1 : n].copy(), ball, back, ah, HEEL_RISE_LO, rise)
    last = p[n - 1]
    for i in range(n):
        p[i] = p[i] + (rise[0] - last) * smoothstep1((phi[i] - FOOT_FLAT) / (1.0 - FOOT_FLAT))
    _pivot_rows(stance.reshape(1, 3), p, ball, back, ah, ankle)


def stance_knee(
    ref: ReferenceGait,
    phi: np.ndarray,
    k_ref: np.ndarray,
    th0: float,
    v0: float,
    th1: float,
    v1: float,
    hip_xy: np.ndarray,
    ankle: np.ndarray,
    geom: LegGeometry,
) -> tuple[np.ndarray, np.ndarray]:
    """The stance knee (n,) over a step (:func:`~mjwalk.body.legs.steps.stance_angle`: the
    reference knee ``k_ref`` (n,) at gait cycle ``0.5 phi`` plus a clamped cubic-spline
    displacement meeting ``th0``, ``v0`` at ``phi = 0`` and ``th1``, ``v1`` at ``phi = 1``,
    velocities per unit phase; clipped to [:data:`KNEE_MIN`, :data:`KNEE_STANCE_MAX`]) and the
    pelvis height (n,) at which that leg reaches its ankle (n, 3) from the hip at ``hip_xy``
    (n, 2), metres."""
    r0, r1 = float(ref("knee", 0.0)), float(ref("knee", 0.5))
    d0 = v0 - 0.5 * float(ref("knee", 0.0, True))
    d1 = v1 - 0.5 * float(ref("knee", 0.5, True))
    values = np.array([[th0 - r0], [0.0], [0.0], [0.0], [th1 - r1]])
    L1, L2 = float(geom.thigh), float(geom.shank)
    n = len(phi)
    knee, z = np.empty(n), np.empty(n)
    _stance_knee(
        np.ascontiguousarray(phi, dtype=float),
        np.ascontiguousarray(k_ref, dtype=float),
        values,
        np.array([d0]),
        np.array([d1]),
        np.ascontiguousarray(hip_xy, dtype=float),
        np.ascontiguousarray(ankle, dtype=float),
        L1**2 + L2**2,
        2 * L1 * L2,
        knee,
        z,
    )
    return knee, z


#: The stance spline's knots (step phases): the ends and the key frames.
_KNOTS = np.array([0.0, *STANCE_KEYS, 1.0])


@njit
def _stance_knee(phi, k_ref, values, d0, d1, hip_xy, ankle, span0, span1, knee, z):
    """:func:`stance_knee` into ``knee`` and ``z`` (n,)."""
    disp = _clamped_cubic(_KNOTS, values, d0, d1, phi)
    for i in range(phi.shape[0]):
        k = min(max(k_ref[i] + disp[i, 0], KNEE_MIN), KNEE_STANCE_MAX)
        knee[i] = k
        dx, dy = hip_xy[i, 0] - ankle[i, 0], hip_xy[i, 1] - ankle[i, 1]
        h = math.sqrt(dx * dx + dy * dy)
        s = math.sqrt(span0 + span1 * math.cos(k))
        z[i] = ankle[i, 2] + math.sqrt(maximum1(s * s - h * h, 1e-6))
