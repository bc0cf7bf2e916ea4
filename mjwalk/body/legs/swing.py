"""The swing foot of one step, compiled (:func:`swing_foot`, paper §4.2.4, A9).

:func:`~mjwalk.body.legs.steps.swing_foot` is a few dozen NumPy operations on a step's few
dozen samples, thousands of steps per station cycle: their call overhead cost several times
their arithmetic. :func:`swing_foot` does the same arithmetic in the same order in one compiled
call (the same numbers, bit for bit: ``tests/timeline/test_kernels.py`` compares the two on walks).
It needs a reference gait tabulated on the unit cycle (:attr:`ReferenceGait._unit`, as the
default and the warped references are); others take the NumPy code.

Step phase ``phi`` in [0, 1] from lift-off of the swing foot's step to its landing. World
frame, metres, radians; a foot's pitch + toes up.

numba caches this module's machine code by its own source, not by the compiled functions it
calls from other modules (``footpivot.heel_rise_rows``, ``footpivot.pivot_rows``,
``footpivot.ankle_kept_rows``,
``curves.clamped_cubic_rows`` and the one-value shapes such as ``curves.smoothstep1``,
``reference.ppoly_at``, ``swingthigh.thigh_kept`` and ``swingthigh.swing_pitch``): change a
comment here when those change.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import fma, njit
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import (
    FLAT,
    clamped_cubic_rows,
    maximum1,
    minimum1,
    smoothstep1,
    soft_clip01_1,
    soft_flat,
    soft_flat1,
    soft_max1,
)
from mjwalk.body.legs.footpivot import ankle_kept_rows, ball_offset, heel_rise_rows, pivot_rows
from mjwalk.body.legs.ik import KNEE_MIN
from mjwalk.body.legs.reference import ReferenceGait, ppoly_at, wrap01
from mjwalk.body.legs.steps import (
    HEEL_RISE_MAX,
    PROGRESS_BLEND,
    SWING_KEYS,
    SWING_TURNED,
    TOE_OFF,
    StepFrames,
    toe_straighten_share,
)
from mjwalk.body.legs.swingthigh import swing_pitch, thigh_kept
from mjwalk.conventions import SAMPLE_RATE_HZ

#: How the pre-swing roll starts (:func:`~.steps.swing_foot`'s ``roll_pitch``): the walk's
#: first step (from standing, flat), a step after one whose stance raised the heel further
#: (``p_start`` known), or neither.
ROLL_FIRST, ROLL_CONTINUE, ROLL_PLAIN = 0, 1, 2


def swing_foot(
    fr: StepFrames,
    phi: np.ndarray,
    hip_xy: np.ndarray,
    z_hip: np.ndarray,
    ref: ReferenceGait,
    geom: LegGeometry,
    land_p: float,
):
    """:func:`~mjwalk.body.legs.steps.swing_foot` compiled: the swing foot's ankle (n, 3),
    pitch (n,), toe angle (n,) and yaw (n,) over the step's phases ``phi`` (n,), and the step
    phase of its toe-off.

    Args:
        fr: the step (lift-off and landing footprints, ``first``, ``p_start``).
        phi: (n,) increasing step phases of the step's samples, 0 to 1.
        hip_xy: (n, 2) the swing leg's hip joint centre (x, y) at those samples, metres.
        z_hip: (n,) the pelvis height there, metres.
        ref: the reference gait (``ref._unit``).
        geom: the leg lengths.
        land_p: the pitch the foot lands with, radians.
    """
    lift, land = np.asarray(fr.lift, float), np.asarray(fr.land, float)
    dyaw, seg, seg_sq, nrm = step_chord(fr)
    if fr.first:
        mode, p_pre = ROLL_FIRST, 0.0
    elif fr.p_start is not None:  # continue from the stance's extra heel rise
        p0 = soft_flat(np.minimum(ref("pitch", 0.5), 0.0))
        mode, p_pre = ROLL_CONTINUE, min(float(fr.p_start - p0), 0.0)
    else:
        mode, p_pre = ROLL_PLAIN, 0.0
    L1, L2 = float(geom.thigh), float(geom.shank)
    n = len(phi)
    pos, p, toe, yaw = np.zeros((n, 3)), np.zeros(n), np.empty(n), np.empty(n)
    phi_to = _swing(
        np.ascontiguousarray(phi, dtype=float),
        np.ascontiguousarray(hip_xy, dtype=float),
        np.ascontiguousarray(z_hip, dtype=float),
        lift.reshape(1, 3),
        land.reshape(1, 3),
        dyaw,
        mode,
        float(p_pre),
        seg,
        seg_sq,
        nrm,
        *ref._ppoly["hip"],
        *ref._ppoly["knee"],
        *ref._ppoly["pitch"],
        L1,
        L2,
        L1**2 + L2**2,
        2 * L1 * L2,
        float(KNEE_MIN),
        ball_offset(geom),
        float(geom.foot_back),
        float(geom.foot_front),
        float(geom.ankle_height),
        float(land_p),
        (fr.end - fr.start) / SAMPLE_RATE_HZ,
        pos,
        p,
        toe,
        yaw,
    )
    return pos, p, toe, yaw, phi_to


def step_chord(fr: StepFrames) -> tuple[float, np.ndarray, float, np.ndarray]:
    """The swing's turn and chord of step ``fr``, as :func:`swing_foot` gives them to its
    kernel (NumPy's arithmetic: the turn through the complex exponential, the chord's squared
    length and norm by BLAS).

    Args:
        fr: the step (lift-off and landing footprints).

    Returns:
        the foot's turn from lift-off to landing heading, wrapped to [-pi, pi] (radians); the
        chord from the lift-off to the landing footprint (2,) (metres); its squared length
        (m², at least 1e-9); its unit normal (2,), 90 deg CCW.
    """
    lift, land = np.asarray(fr.lift, float), np.asarray(fr.land, float)
    dyaw = float(np.angle(np.exp(1j * (land[2] - lift[2]))))
    seg = land[:2] - lift[:2]
    seg_sq = max(float(seg @ seg), 1e-9)
    nrm = np.array([-seg[1], seg[0]]) / max(float(np.linalg.norm(seg)), 1e-9)
    return dyaw, seg, seg_sq, nrm


@njit
def _swing(phi, hip_xy, z_hip, lift2, land2, dyaw, mode, p_pre, seg, seg_sq, nrm,
           hip_c, hip_k, knee_c, knee_k, pitch_c, pitch_k, L1, L2, span0, span1, knee_min,
           ball, back, front, ah, land_p, duration, pos, p, toe, yaw):  # fmt: skip
    """The arithmetic of :func:`swing_foot` into ``pos`` (n, 3, zeros), ``p`` (n, zeros),
    ``toe`` and ``yaw`` (n,); returns the toe-off phase. ``hip_c``, ``hip_k`` (and knee,
    pitch): the reference's piecewise-polynomial coefficients and knots; ``span0 + span1 cos
    knee`` the squared hip-to-ankle span (:meth:`LegGeometry.span`); ``lift2``, ``land2``
    the footprints as (1, 3) rows (no reshape in compiled code: its error path compiles
    slowly); ``duration`` the step's, seconds (how fast the toes straighten)."""
    lift = lift2[0]
    n = phi.shape[0]
    for i in range(n):
        yaw[i] = lift[2] + dyaw * smoothstep1((phi[i] - TOE_OFF) / (SWING_TURNED - TOE_OFF))
    # pre-swing roll (the samples up to TOE_OFF: a prefix, phi increasing)
    ne = 0
    while ne < n and phi[ne] <= TOE_OFF:
        ne += 1
    for i in range(ne):
        ph = phi[i]
        q = soft_flat1(minimum1(ppoly_at(pitch_c, pitch_k, wrap01(0.5 + 0.5 * ph), 0), 0.0), FLAT)
        if mode == ROLL_FIRST:
            q = q * smoothstep1(ph / TOE_OFF)
        elif mode == ROLL_CONTINUE:
            q = q + p_pre * (1 - smoothstep1(ph / TOE_OFF))
        p[i] = q
    phi_to = TOE_OFF
    p0 = np.empty(ne)
    shares = np.empty(ne)
    # the reference's heel rise as far as the foot trails its hip as the reference's
    # (steps._trailing_rise); from standing that is the whole roll
    seg_n = math.sqrt(seg_sq)
    for i in range(ne):
        c = wrap01(0.5 + 0.5 * phi[i])
        hf = ppoly_at(hip_c, hip_k, c, 0)
        kf = ppoly_at(knee_c, knee_k, c, 0)
        behind = -(L1 * math.sin(hf) + L2 * math.sin(hf - kf))
        trail = ((hip_xy[i, 0] - lift[0]) * seg[0] + (hip_xy[i, 1] - lift[1]) * seg[1]) / seg_n
        share = min(max(trail / behind, 0.0), 1.0) if behind > 0 else 1.0
        shares[i] = share
        p0[i] = p[i] if share >= 1.0 else p[0] + (p[i] - p[0]) * share
    if mode == ROLL_FIRST:
        # the heel rises as far as the ankle would dorsiflex past its standing angle
        hip1 = np.empty((ne, 3))
        for i in range(ne):
            hip1[i, 0], hip1[i, 1], hip1[i, 2] = hip_xy[i, 0], hip_xy[i, 1], z_hip[i]
        ankle_kept_rows(lift, hip1, p0, L1, L2, ball, back, ah, -HEEL_RISE_MAX, p[:ne])
    elif ne > 0:
        # the knee follows the reference; the heel rises as far as that needs
        hip = np.empty((ne, 3))
        d = np.empty(ne)
        for i in range(ne):
            hip[i, 0], hip[i, 1], hip[i, 2] = hip_xy[i, 0], hip_xy[i, 1], z_hip[i]
            kv = maximum1(ppoly_at(knee_c, knee_k, wrap01(0.5 + 0.5 * phi[i]), 0), knee_min)
            d[i] = math.sqrt(span0 + span1 * math.cos(kv))
        rise = np.empty(ne)
        heel_rise_rows(lift, hip, d, p0, ball, back, ah, -HEEL_RISE_MAX, rise)
        for i in range(ne):  # (element loops: no shape checks to compile)
            p[i] = rise[i]
        held = -1
        for i in range(ne):
            if p[i] <= -HEEL_RISE_MAX + 1e-9:
                held = i
                break
        if held >= 1:  # (two samples on the floor give the lift-off velocity)
            phi_to = phi[held]
            ne = 0
            while ne < n and phi[ne] <= phi_to:
                ne += 1
    pivot_rows(lift2, p[:ne], ball, back, ah, pos[:ne])
    if ne < n:
        kept = 1.0 - shares[ne - 1] if ne > 0 else 0.0  # (steps.swing_foot's)
        _swing_late(phi, hip_xy, z_hip, lift, land2, seg, seg_sq, nrm, hip_c, hip_k, knee_c,
                    knee_k, pitch_c, pitch_k, L1, L2, knee_min, ball, back, front, ah, land_p,
                    ne, yaw, pos, p, kept)  # fmt: skip
    # the toes stay flat during the roll-off, then straighten while the foot lifts
    p_end = p[ne - 1] if ne > 0 else 0.0
    share = toe_straighten_share(p_end, duration, phi_to)
    for i in range(n):
        if i < ne:
            toe[i] = -p[i]
        else:
            toe[i] = -p_end * (1 - smoothstep1((phi[i] - phi_to) / share))
    # keep heel, ball and toe tip off the floor (lift the ankle where they would dip)
    for i in range(ne, n):
        sp, cp = math.sin(p[i]), math.cos(p[i])
        ball_z = ball * sp - ah * cp
        z = pos[i, 2]
        z += maximum1(0.0, -(z + (-back * sp - ah * cp)))
        z += maximum1(0.0, -(z + ball_z))
        z += maximum1(0.0, -(z + (ball_z + (front - ball) * math.sin(p[i] + toe[i]))))
        pos[i, 2] = z
    return phi_to


@njit
def _swing_late(phi, hip_xy, z_hip, lift, land2, seg, seg_sq, nrm, hip_c, hip_k, knee_c, knee_k,
                pitch_c, pitch_k, L1, L2, knee_min, ball, back, front, ah, land_p, ne, yaw,
                pos, p, kept):  # fmt: skip
    """The swing after toe-off (samples ``ne`` on) into ``pos`` and ``p``: the reference
    swing (the reference hip/knee angles of each gait-cycle instant at the current hip, along
    the chord from the lift-off to the landing footprint, under the hip sideways; a foot
    ahead of the reference's ankle hangs from the reference thigh as far as ``kept``,
    :func:`~.swingthigh.thigh_kept`) plus
    clamped cubic-spline displacements to the key positions at :data:`SWING_KEYS` (``land2``
    the landing footprint as a (1, 3) row)."""
    n = phi.shape[0]
    if ne < 2:
        raise IndexError("swing_foot: fewer than two samples before toe-off")
    h = phi[ne - 1] - phi[ne - 2]
    v0 = np.empty(3)
    for k in range(3):
        v0[k] = (pos[ne - 1, k] - pos[ne - 2, k]) / h
    m = n - ne
    ref_pos = np.empty((m, 3))
    ref_pit = np.empty(m)
    # the progress never falls behind the toe-off ankle's going on at its toe-off speed
    # along the chord (see steps._reference_swing)
    u_to = fma(pos[ne - 1, 0] - lift[0], seg[0], (pos[ne - 1, 1] - lift[1]) * seg[1]) / seg_sq
    du_to = max(fma(v0[0], seg[0], v0[1] * seg[1]) / seg_sq, 0.0)
    # nor further behind its hip than at toe-off (see steps._reference_swing)
    k0 = ne - 1
    f_to = (pos[k0, 0] - hip_xy[k0, 0]) * math.cos(yaw[k0]) + (
        pos[k0, 1] - hip_xy[k0, 1]
    ) * math.sin(yaw[k0])
    s_run = 0.0  # the progress so far (soft_clip01_1 is never below 0)
    for j in range(m):
        i = ne + j
        c = 0.5 + 0.5 * phi[i]
        hf = ppoly_at(hip_c, hip_k, wrap01(c), 0)
        kf = ppoly_at(knee_c, knee_k, wrap01(c), 0)
        fwd = L1 * math.sin(hf) + L2 * math.sin(hf - kf)
        cy, sy = math.cos(yaw[i]), math.sin(yaw[i])
        t0 = hip_xy[i, 0] + fwd * cy
        t1 = hip_xy[i, 1] + fwd * sy
        # progress along the chord, clamped softly (C1), never decreasing and never behind
        # the toe-off ankle's going on (see steps._reference_swing); numpy's (m, 2) @ (2,) is
        # OpenBLAS's
        s = soft_clip01_1(fma(t0 - lift[0], seg[0], (t1 - lift[1]) * seg[1]) / seg_sq, 0.1)
        u_h = (
            (hip_xy[i, 0] + f_to * cy - lift[0]) * seg[0]
            + (hip_xy[i, 1] + f_to * sy - lift[1]) * seg[1]
        ) / seg_sq
        u_lin = u_to + du_to * (phi[i] - phi[ne - 1])
        s_to = soft_clip01_1(max(u_lin, u_lin + kept * (u_h - u_lin)), 0.1)
        s = max(soft_max1(s, s_to, PROGRESS_BLEND), s_run)
        s_run = s
        ch0 = lift[0] + s * seg[0]
        ch1 = lift[1] + s * seg[1]
        off = fma(hip_xy[i, 0] - ch0, nrm[0], (hip_xy[i, 1] - ch1) * nrm[1])
        w = off * math.sin(np.pi * s)
        ref_pos[j, 0] = ch0 + w * nrm[0]
        ref_pos[j, 1] = ch1 + w * nrm[1]
        # the reference leg, or the reference thigh over a foot ahead of its ankle
        f = (ref_pos[j, 0] - hip_xy[i, 0]) * cy + (ref_pos[j, 1] - hip_xy[i, 1]) * sy
        down, turn = thigh_kept(f, hf, kf, L1, L2, knee_min, kept)
        ref_pos[j, 2] = z_hip[i] - down
        pv = ppoly_at(pitch_c, pitch_k, wrap01(c), 0)
        ref_pit[j] = swing_pitch(pv, turn, hf, kf, ref_pos[j, 2], front, ah, kept)
    # knots: the toe-off sample, the swing samples nearest the keys, the landing
    nk = len(SWING_KEYS) + 1
    knots = np.empty(nk)
    rows = np.empty(nk, dtype=np.int64)  # the reference row at each knot
    knots[0], rows[0] = phi[ne - 1], 0
    for kk in range(1, nk - 1):
        best = 0
        for j in range(1, m):
            if abs(phi[ne + j] - SWING_KEYS[kk]) < abs(phi[ne + best] - SWING_KEYS[kk]):
                best = j
        knots[kk], rows[kk] = phi[ne + best], best
    knots[nk - 1], rows[nk - 1] = 1.0, m - 1
    # key values less the reference at the knots (np.interp: the knots are swing samples,
    # the toe-off knot before them takes the first one's value)
    dpos = np.empty((nk, 3))
    dpit = np.empty((nk, 1))  # (one column, as the spline takes it)
    for k in range(3):
        dpos[0, k] = pos[ne - 1, k]
    dpit[0, 0] = p[ne - 1]
    for kk in range(1, nk - 1):
        for k in range(3):
            dpos[kk, k] = ref_pos[rows[kk], k]
        dpos[kk, 2] = ah if ah > dpos[kk, 2] else dpos[kk, 2]
        dpit[kk, 0] = ref_pit[rows[kk]]
    land_pos = np.empty((1, 3))
    pivot_rows(land2, np.array([land_p]), ball, back, ah, land_pos)
    for k in range(3):
        dpos[nk - 1, k] = land_pos[0, k]
    dpit[nk - 1, 0] = land_p
    # the reference's slopes at both ends (np.gradient's one-sided end differences); the
    # toe-off knot extrapolated linearly with the first one
    dr0, dr1 = np.zeros(3), np.zeros(3)
    dq0, dq1 = 0.0, 0.0
    if m > 1:
        for k in range(3):
            dr0[k] = (ref_pos[1, k] - ref_pos[0, k]) / (phi[ne + 1] - phi[ne])
            dr1[k] = (ref_pos[m - 1, k] - ref_pos[m - 2, k]) / (phi[n - 1] - phi[n - 2])
        dq0 = (ref_pit[1] - ref_pit[0]) / (phi[ne + 1] - phi[ne])
        dq1 = (ref_pit[m - 1] - ref_pit[m - 2]) / (phi[n - 1] - phi[n - 2])
    lead = phi[ne] - knots[0]
    for kk in range(nk):
        for k in range(3):
            rk = ref_pos[rows[kk], k]
            if kk == 0:
                rk -= lead * dr0[k]
            dpos[kk, k] = dpos[kk, k] - rk
        rp = ref_pit[rows[kk]]
        if kk == 0:
            rp -= lead * dq0
        dpit[kk, 0] = dpit[kk, 0] - rp
    xq = phi[ne:]
    d0, d1 = np.empty(3), np.empty(3)
    for k in range(3):
        d0[k], d1[k] = v0[k] - dr0[k], -dr1[k]
    sp = clamped_cubic_rows(knots, dpos, d0, d1, xq)
    dp0 = (p[ne - 1] - p[ne - 2]) / h
    spp = clamped_cubic_rows(knots, dpit, np.array([dp0 - dq0]), np.array([-dq1]), xq)
    for j in range(m):
        for k in range(3):
            pos[ne + j, k] = ref_pos[j, k] + sp[j, k]
        p[ne + j] = ref_pit[j] + spp[j, 0]


#: :func:`swing_foot`'s compiled kernel, for callers that run a walk's steps in one compiled
#: loop (:mod:`~mjwalk.body.legs.synthloop`).
swing_rows = _swing
