"""The step loop of the leg synthesis in one compiled call per walk (issue 50).

:func:`~mjwalk.body.legs.synthesis.legs_from_walk` builds a walk's tracks step by step: the
stance foot and knee (A8), the swing foot (A9) and the pelvis height, each step a dozen
compiled kernels joined by NumPy slicing and scalar arithmetic in Python. About 36 steps a
station cycle made that glue ~8 ms of its ~18 ms legs. :func:`synth_steps` runs the same loop
in one compiled call (``benchmarks/bench_synthloop.py``, 10 station cycles' 70 walks replayed:
the legs 20.1 -> 15.6 ms a cycle, CPU, median of 5 interleaved rounds): the steps' frames
packed into arrays once per walk, the reference tables as their piecewise-polynomial arrays,
the same kernels (``stance._stance_foot``, ``stance._stance_knee``, ``swing._swing``,
``stance._pelvis_height``) called in the same order on the same numbers, so the tracks are
bit for bit those of the step-by-step path (``tests/body/test_synthloop.py`` compares them
exactly, signed zeros included, on seeded walks).

What compiled code rounds differently from NumPy is kept NumPy's: the knee for a hip-to-ankle
span is NumPy's ``arccos`` (its SIMD loop differs from the C library's in the last bit for a
tenth of the arguments), called back in object mode, twice a step; a squared distance that the
step path takes as a NumPy scalar's ``** 2`` is the C library's ``pow`` (``math.pow`` with the
exponent an argument, so the compiler cannot turn it into a product); the landing ease's cubes
are NumPy's ``** 3`` on all the walk's steps at once, before the loop (element by element the
same numbers as per step). Only reference tables on the unit cycle (``ReferenceGait._unit``)
come here; others take the step path's scipy splines.

Step phase ``phi`` in [0, 1] from lift-off of the swing foot's step to its landing. World
frame, metres, radians; a foot's pitch + toes up. Sides are indices: 0 left, 1 right.

numba caches this module's machine code by its own source, not by the compiled functions it
calls from other modules (``stance``, ``swing``, ``footpivot``, ``reference``): change a comment
here when those change.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from mjwalk._jit import njit_gil
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import soft_flat
from mjwalk.body.legs.footpivot import ball_offset, pivot_rows
from mjwalk.body.legs.ik import KNEE_MIN
from mjwalk.body.legs.reference import ReferenceGait, ppoly_at, wrap01
from mjwalk.body.legs.stance import (
    STANCE_KNOTS,
    pelvis_height_rows,
    stance_foot_rows,
    stance_knee_rows,
)
from mjwalk.body.legs.steps import StepFrames
from mjwalk.body.legs.swing import ROLL_CONTINUE, ROLL_FIRST, swing_rows
from mjwalk.conventions import SAMPLE_RATE_HZ

#: Slots of the walk's scalars (:func:`synth_steps`' ``consts``).
(C_HS_PITCH, C_D_LAND, C_D_LAND_SQ, C_D_MAX_SQ, C_L1, C_L2, C_SPAN0, C_SPAN1, C_KL1SQ, C_KL2SQ,
 C_KDEN, C_BALL, C_BACK, C_FRONT, C_AH, C_R0, C_DR0, C_R1, C_DR1, C_KNEE_END, C_P0, C_TWO,
 N_CONSTS) = range(23)  # fmt: skip


@dataclass(frozen=True)
class SynthTracks:
    """The tracks the step loop writes (each a side's pair where per side: left, right), over
    a walk's n samples, world frame, metres, radians (:class:`~.steps.FootTracks`' arrays and
    the synthesis's ``cyc``, ``contact``, ``phase`` and pelvis height ``z``).

    Attributes:
        ankle: (n, 3) ankle targets per side.
        fyaw: (n,) foot headings per side.
        pitch: (n,) foot pitches per side, + toes up.
        toe: (n,) toe angles per side.
        ground: (n,) bool, foot on the floor, per side.
        prints: (n, 3) the footprint a grounded foot stands on, per side.
        cyc: (n,) gait-cycle fraction per side (0 = heel strike).
        contact: (n,) int, 0 left stance, 1 right stance, 2 double support.
        phase: (n,) step phase.
        z: (n,) pelvis height.
    """

    ankle: tuple[np.ndarray, np.ndarray]
    fyaw: tuple[np.ndarray, np.ndarray]
    pitch: tuple[np.ndarray, np.ndarray]
    toe: tuple[np.ndarray, np.ndarray]
    ground: tuple[np.ndarray, np.ndarray]
    prints: tuple[np.ndarray, np.ndarray]
    cyc: tuple[np.ndarray, np.ndarray]
    contact: np.ndarray
    phase: np.ndarray
    z: np.ndarray


def loop_consts(
    ref: ReferenceGait, geom: LegGeometry, hs_pitch: float, d_land: float, d_max_sq: float
) -> np.ndarray:
    """The walk's scalars :func:`synth_steps` takes, computed as the step path computes them.

    Args:
        ref: the reference gait.
        geom: the leg lengths.
        hs_pitch: the reference's heel-strike pitch, radians (>= 0).
        d_land: the landing leg's hip-to-ankle distance, metres.
        d_max_sq: the swing leg's longest hip-to-ankle distance, squared (m²).

    Returns:
        (:data:`N_CONSTS`,) the values in their ``C_*`` slots.
    """
    L1, L2 = float(geom.thigh), float(geom.shank)
    c = np.empty(N_CONSTS)
    c[C_HS_PITCH], c[C_D_LAND], c[C_D_LAND_SQ] = hs_pitch, d_land, d_land**2
    c[C_D_MAX_SQ], c[C_L1], c[C_L2] = d_max_sq, L1, L2
    c[C_SPAN0], c[C_SPAN1] = L1**2 + L2**2, 2 * L1 * L2  # (as stance's and swing's wrappers)
    # (as LegGeometry.knee_for_span: its squares are Python's, the C library's pow)
    c[C_KL1SQ], c[C_KL2SQ] = geom.thigh**2, geom.shank**2
    c[C_KDEN] = 2 * geom.thigh * geom.shank
    c[C_BALL], c[C_BACK] = ball_offset(geom), geom.foot_back
    c[C_FRONT], c[C_AH] = geom.foot_front, geom.ankle_height
    c[C_R0], c[C_DR0] = ref("knee", 0.0), ref("knee", 0.0, True)
    c[C_R1], c[C_DR1] = ref("knee", 0.5), ref("knee", 0.5, True)
    c[C_KNEE_END] = max(float(ref("knee", 0.5)), float(KNEE_MIN))
    c[C_P0] = soft_flat(np.minimum(ref("pitch", 0.5), 0.0))  # (swing.swing_foot's p0)
    c[C_TWO] = 2.0
    return c


def synth_steps(
    frames: list[StepFrames],
    hip_xy: tuple[np.ndarray, np.ndarray],
    ppoly: dict[str, tuple[np.ndarray, np.ndarray]],
    consts: np.ndarray,
    ease_from: float,
    out: SynthTracks,
) -> None:
    """Every step of ``frames`` into ``out`` (in place) and the steps' ``p_start`` /
    ``p_end``, as :func:`~mjwalk.body.legs.synthesis._synth_step` does them one by one.

    Args:
        frames: the walk's steps (``land_p`` set by :func:`~.steps.landing_pitches`).
        hip_xy: the left and right hips' (x, y) per sample, (n, 2) each, metres.
        ppoly: the reference's piecewise polynomials (``ReferenceGait._ppoly``: "hip", "knee",
            "pitch" -> coefficients (4, m - 1), knots (m,)) on the unit cycle.
        consts: (:data:`N_CONSTS`,) the walk's scalars in the ``C_*`` slots (see
            :func:`loop_consts`).
        ease_from: the step phase from which the landing eases (``synthesis.LAND_EASE``).
        out: the tracks, written where the steps cover them.
    """
    m = len(frames)
    side = np.array([0 if fr.side == "l" else 1 for fr in frames], dtype=np.int64)
    start = np.array([fr.start for fr in frames], dtype=np.int64)
    end = np.array([fr.end for fr in frames], dtype=np.int64)
    lift = np.array([fr.lift for fr in frames], dtype=float).reshape(m, 3)
    land = np.array([fr.land for fr in frames], dtype=float).reshape(m, 3)
    stance = np.array([fr.stance for fr in frames], dtype=float).reshape(m, 3)
    land_p = np.array([fr.land_p for fr in frames], dtype=float)
    dyaw, seg, seg_sq, nrm = step_chords(lift, land)
    ease_j, ease_at, base = _ease_bases(start, end, float(ease_from))
    u3 = base**3  # NumPy's power (see the module's docstring)
    p_end = np.empty(m)
    _synth_loop(
        side, start, end, lift, land, stance, land_p, dyaw, seg, seg_sq, nrm, ease_j, ease_at,
        u3, hip_xy, *ppoly["hip"], *ppoly["knee"], *ppoly["pitch"], STANCE_KNOTS, consts,
        out.ankle, out.fyaw, out.pitch, out.toe, out.ground, out.prints, out.cyc, out.contact,
        out.phase, out.z, p_end,
    )  # fmt: skip
    for k, fr in enumerate(frames):
        fr.p_start = frames[k - 1].p_end if k > 0 else None
        fr.p_end = float(p_end[k])


def step_chords(
    lift: np.ndarray, land: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`~mjwalk.body.legs.swing.step_chord` of every step at once, the same numbers
    (``tests/body/test_synthloop.py`` compares them bit for bit): NumPy's complex exponential
    and angle on the steps' turns, each chord's squared length by BLAS's dot as ``seg @ seg``
    (a stacked ``matmul``; the plain sum of squares differs in the last bit), its norm the
    square root of that dot, as ``np.linalg.norm`` takes it.

    Args:
        lift: (m, 3) the steps' lift-off footprints (x, y, yaw), metres, radians.
        land: (m, 3) their landing footprints.

    Returns:
        per step: the foot's turn, wrapped to [-pi, pi] (m,) (radians); the chord (m, 2)
        (metres); its squared length (m,) (m², at least 1e-9); its unit normal (m, 2), 90 deg
        CCW.
    """
    turn = np.exp(1j * (land[:, 2] - lift[:, 2]))
    dyaw = np.arctan2(turn.imag, turn.real)  # (np.angle's own arithmetic)
    seg = land[:, :2] - lift[:, :2]
    dot = np.matmul(seg[:, None, :], seg[:, :, None])[:, 0, 0]
    nrm = np.empty_like(seg)  # (np.column_stack([-seg[:, 1], seg[:, 0]]))
    nrm[:, 0], nrm[:, 1] = -seg[:, 1], seg[:, 0]
    nrm /= np.maximum(np.sqrt(dot), 1e-9)[:, None]
    return dyaw, seg, np.maximum(dot, 1e-9), nrm


@njit_gil
def _ease_bases(start, end, ease_from):
    """Per step (samples ``start``..``end``, phases ``(i - start) / (end - start)``): the
    first sample of the landing ease (:func:`~.stance.pelvis_height`: the phases from
    ``ease_from``, at least three, not the first sample; else -1), and the ease's phases as
    shares of it, ``(phi - phi_j) / (1 - phi_j)``, of all steps in one array (step k's from
    ``at[k]`` to ``at[k + 1]``)."""
    m = start.shape[0]
    j = np.full(m, -1, dtype=np.int64)
    at = np.zeros(m + 1, dtype=np.int64)
    for k in range(m):
        n = end[k] - start[k] + 1
        j0 = 0
        while j0 < n and j0 / (end[k] - start[k]) < ease_from:
            j0 += 1
        if n - j0 >= 3 and j0 > 0:
            j[k] = j0
            at[k + 1] = at[k] + (n - j0)
        else:
            at[k + 1] = at[k]
    out = np.empty(at[m])
    for k in range(m):
        if j[k] < 0:
            continue
        den = end[k] - start[k]
        pj = j[k] / den
        for r in range(at[k + 1] - at[k]):
            out[at[k] + r] = ((j[k] + r) / den - pj) / (1.0 - pj)
    return j, at, out


def _arccos1(x: float) -> float:
    """NumPy's arccos of one value, as ``LegGeometry.knee_for_span`` takes it (a one-element
    array: NumPy's SIMD loop, not the C library's ``acos``)."""
    return float(np.arccos(np.array([x]))[0])


@njit_gil
def _knee_for(span, l1sq, l2sq, den):
    """``LegGeometry.knee_for_span`` of one span (m): the knee flexion (radians) whose leg
    spans it, clipped to straight and folded; ``l1sq``, ``l2sq``, ``den`` its ``L1**2``,
    ``L2**2`` and ``2 L1 L2`` as Python computed them."""
    x = (span * span - l1sq - l2sq) / den
    if x < -1.0:
        x = -1.0
    elif x > 1.0:
        x = 1.0
    with numba.objmode(r="float64"):
        r = _arccos1(x)
    return r


@njit_gil
def _toe1(p):
    """``-np.minimum(p, 0)`` of one pitch: NumPy's minimum takes the second value on a tie
    (``np.minimum(-0.0, 0)`` is +0.0) and NaN from either."""
    return -(p if p < 0.0 or p != p else 0.0)


@njit_gil
def _synth_loop(side, start, end, lift, land, stance, land_p, dyaw, seg, seg_sq, nrm, ease_j,
                ease_at, u3, hip_xy, hip_c, hip_k, knee_c, knee_k, pitch_c, pitch_k, knots, c,
                ankle, fyaw, pitch, toe, ground, prints, cyc, contact, phase, z,
                p_end):  # fmt: skip
    """:func:`synth_steps`' loop over the steps (``synthesis._synth_step``'s arithmetic in
    its order): per step the stance foot (``_stance_leg``), the stance knee, the swing foot,
    the pelvis height and the landing knee that starts the next stance spline. Per-side
    tracks come as (left, right) pairs; ``c`` the walk's scalars (``C_*`` slots)."""
    hs_pitch, d_land, d_land_sq, d_max_sq = (
        c[C_HS_PITCH],
        c[C_D_LAND],
        c[C_D_LAND_SQ],
        c[C_D_MAX_SQ],
    )
    L1, L2, span0, span1 = c[C_L1], c[C_L2], c[C_SPAN0], c[C_SPAN1]
    kl1sq, kl2sq, kden = c[C_KL1SQ], c[C_KL2SQ], c[C_KDEN]
    ball, back, front, ah = c[C_BALL], c[C_BACK], c[C_FRONT], c[C_AH]
    r0, dr0, r1, dr1, two = c[C_R0], c[C_DR0], c[C_R1], c[C_DR1], c[C_TWO]
    land_pos = np.empty((1, 3))
    lp1 = np.empty(1)
    hip_end = np.empty((1, 3))
    values = np.zeros((5, 1))
    d0, d1 = np.empty(1), np.empty(1)
    th0, v0 = r0, 0.5 * dr0  # the first step's stance knee starts as the reference's
    for k in range(side.shape[0]):
        sw = side[k]
        st = 1 - sw
        a, b = start[k], end[k]
        n = b - a + 1
        hip_sw, hip_st = hip_xy[sw][a : b + 1], hip_xy[st][a : b + 1]
        phi = np.empty(n)
        for i in range(n):
            phi[i] = i / (b - a)
            phase[a + i] = phi[i]
            cyc[st][a + i] = 0.5 * phi[i]
            cyc[sw][a + i] = 0.5 + 0.5 * phi[i]
        # --- the stance foot (synthesis._stance_leg)
        lp1[0] = land_p[k]
        pivot_rows(land[k : k + 1], lp1, ball, back, ah, land_pos)
        dx = hip_xy[sw][b, 0] - land_pos[0, 0]
        dy = hip_xy[sw][b, 1] - land_pos[0, 1]
        hz = math.sqrt(dx * dx + dy * dy)
        v = d_land_sq - math.pow(hz, two)
        z_end = land_pos[0, 2] + math.sqrt(1e-6 if 1e-6 > v else v)  # Python's max(v, 1e-6)
        hip_end[0, 0], hip_end[0, 1], hip_end[0, 2] = hip_st[n - 1, 0], hip_st[n - 1, 1], z_end
        p_ref = np.empty(n)
        k_ref = np.empty(n)
        for i in range(n):
            p_ref[i] = ppoly_at(pitch_c, pitch_k, wrap01(0.5 * phi[i]), 0)
            k_ref[i] = ppoly_at(knee_c, knee_k, wrap01(0.5 * phi[i]), 0)
        scaled = k > 0 and hs_pitch > 0
        p_st = np.empty(n)
        ankle_st = np.empty((n, 3))
        stance_foot_rows(phi, p_ref, scaled, land_p[k - 1] if scaled else 0.0, hs_pitch,
                         k == 0, stance[k : k + 1], hip_end, span0, span1, c[C_KNEE_END], ball,
                         back, ah, p_st, ankle_st)  # fmt: skip
        p_end[k] = p_st[n - 1]
        an_st, pi_st, to_st = ankle[st], pitch[st], toe[st]
        for i in range(n):
            for q in range(3):
                an_st[a + i, q] = ankle_st[i, q]
                prints[st][a + i, q] = stance[k, q]
            ground[st][a + i] = True
            pi_st[a + i] = p_st[i]
            to_st[a + i] = _toe1(p_st[i])
            fyaw[st][a + i] = stance[k, 2]
        # --- the stance knee and the pelvis height it gives
        dx = hip_st[n - 1, 0] - ankle_st[n - 1, 0]
        dy = hip_st[n - 1, 1] - ankle_st[n - 1, 1]
        dz = z_end - ankle_st[n - 1, 2]
        th1 = _knee_for(math.sqrt(dx * dx + dy * dy + dz * dz), kl1sq, kl2sq, kden)
        values[0, 0], values[4, 0] = th0 - r0, th1 - r1
        d0[0], d1[0] = v0 - 0.5 * dr0, 0.5 * dr1 - 0.5 * dr1
        knee_st = np.empty(n)
        z_flat = np.empty(n)
        stance_knee_rows(knots, phi, k_ref, values, d0, d1, hip_st, ankle_st, span0, span1,
                         knee_st, z_flat)  # fmt: skip
        # --- the swing foot (A9)
        if k == 0:
            mode, p_pre = ROLL_FIRST, 0.0
        else:
            dp = p_end[k - 1] - c[C_P0]
            mode, p_pre = ROLL_CONTINUE, (0.0 if 0.0 < dp else dp)  # Python's min(dp, 0.0)
        pos, p_sw = np.zeros((n, 3)), np.zeros(n)
        toe_sw, yaw_sw = np.empty(n), np.empty(n)
        phi_to = swing_rows(phi, hip_sw, z_flat, lift[k : k + 1], land[k : k + 1], dyaw[k],
                            mode, p_pre, seg[k], seg_sq[k], nrm[k], hip_c, hip_k, knee_c, knee_k,
                            pitch_c, pitch_k, L1, L2, span0, span1, KNEE_MIN, ball, back, front,
                            ah, land_p[k], (b - a) / SAMPLE_RATE_HZ, pos, p_sw, toe_sw,
                            yaw_sw)  # fmt: skip
        for i in range(n):
            on = phi[i] <= phi_to
            contact[a + i] = 2 if on else st
            for q in range(3):
                ankle[sw][a + i, q] = pos[i, q]
            pitch[sw][a + i] = p_sw[i]
            toe[sw][a + i] = toe_sw[i]
            fyaw[sw][a + i] = yaw_sw[i]
            if on:
                ground[sw][a + i] = True
                for q in range(3):
                    prints[sw][a + i, q] = lift[k, q]
        # --- the pelvis height, capped by the swing leg's reach, easing into the landing
        z_st = np.empty(n)
        ankle_up = np.empty((n, 3))
        eased = pelvis_height_rows(phi, z_flat, pos, hip_sw, hip_st, knee_st, p_st,
                                   stance[k : k + 1], d_max_sq, d_land, ease_j[k],
                                   u3[ease_at[k] : ease_at[k + 1]], span0, span1, ball, back,
                                   ah, z_st, ankle_up)  # fmt: skip
        for i in range(n):
            z[a + i] = z_st[i]
        if eased:
            p_end[k] = p_st[n - 1]
            for i in range(n):
                for q in range(3):
                    an_st[a + i, q] = ankle_up[i, q]
                pi_st[a + i] = p_st[i]
                to_st[a + i] = _toe1(p_st[i])
        # the landing knee starts the next stance spline, at the reference's velocity
        dx = hip_sw[n - 1, 0] - pos[n - 1, 0]
        dy = hip_sw[n - 1, 1] - pos[n - 1, 1]
        dz = z[b] - pos[n - 1, 2]
        th0, v0 = _knee_for(math.sqrt(dx * dx + dy * dy + dz * dz), kl1sq, kl2sq, kden), 0.5 * dr0
