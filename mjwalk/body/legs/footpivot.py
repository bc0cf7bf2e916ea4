"""The foot on the floor: where its ankle is when it pitches about its heel or ball on a
footprint (:func:`pivot_ankle`), its footprints when it spins about a point of its sole
(:func:`spin_print`), and how far its heel must rise for the leg to reach the hip
(:func:`heel_rise`) or as the shank leans forward (:func:`ankle_kept_rows`). World frame,
metres, radians; a footprint is (x, y, yaw) of the floor point under the ankle with the foot
flat; a pitch is + toes up.

numba caches the compiled functions of the modules that call :func:`pivot_rows`,
:func:`heel_rise_rows` and :func:`ankle_kept_rows` (stance, swing, steps, pitchfit) by their
own source: change a comment there when these change.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.anthropometry import ball_offset
from mjwalk.body.humanoid import LegGeometry


def sole_profile(pitch, toe, geom: LegGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The sole's heel, the point under the ankle, the ball and the toe tip relative to the
    ankle in the foot's vertical plane, for a foot pitched ``pitch`` with its toes turned by
    ``toe`` about the ball.

    Args:
        pitch: (m,) the foot's pitch, radians, + toes up.
        toe: (m,) the toe angle, radians, + toes up.
        geom: the foot's lengths and ankle height.

    Returns:
        (forward, up): (m, 4) each, metres (heel, under the ankle, ball, toe tip).
    """
    p, t = np.asarray(pitch, float)[:, None], np.asarray(toe, float)[:, None]
    d = np.array([-geom.foot_back, 0.0, ball_offset(geom)])[None, :]
    fwd = d * np.cos(p) + geom.ankle_height * np.sin(p)
    up = d * np.sin(p) - geom.ankle_height * np.cos(p)
    tip = geom.foot_front - ball_offset(geom)
    fwd = np.concatenate([fwd, fwd[:, 2:] + tip * np.cos(p + t)], axis=1)
    return fwd, np.concatenate([up, up[:, 2:] + tip * np.sin(p + t)], axis=1)


def pivot_ankle(foot: np.ndarray, pitch, geom: LegGeometry) -> np.ndarray:
    """Ankle positions of a foot on a footprint pitched by ``pitch``: negative (heel up)
    rolls about the ball, positive (toes up) about the heel; the pivot stays where it is on
    the floor when the foot is flat.

    Args:
        foot: footprint (x, y, yaw) in metres and radians, (3,) or per sample (n, 3).
        pitch: pitch(es) to the floor, radians, + toes up; scalar, (1,) or (n,).
        geom: the leg and foot lengths.

    Returns:
        (n, 3) ankle positions, metres, world frame.
    """
    pitch = np.atleast_1d(np.asarray(pitch, float))
    foot = np.atleast_2d(np.asarray(foot, float))
    n = 0 if 0 in (len(pitch), len(foot)) else max(len(pitch), len(foot))
    if len(pitch) not in (1, n) or len(foot) not in (1, n):
        raise ValueError(f"pivot_ankle: {len(foot)} footprints for {len(pitch)} pitches")
    out = np.empty((n, 3))
    pivot_rows(foot, pitch, ball_offset(geom), geom.foot_back, geom.ankle_height, out)
    return out


@njit
def pivot_rows(foot, pitch, ball, back, ah, out):
    """:func:`pivot_ankle` into ``out``:
    :math:`R_z(yaw) R_y(-pitch) (lever, 0, -ah)` from the pivot, written out; the pivot is
    ``lever`` ahead of the ankle when flat (the ball for pitch <= 0, the heel otherwise).

    Args:
        foot: (1 or n, 3) footprints (x, y, yaw), metres and radians.
        pitch: (1 or n,) pitches, radians, + toes up.
        ball: the ball's distance ahead of the ankle, metres (:func:`ball_offset`).
        back: the heel's distance behind the ankle, metres.
        ah: the ankle height above the sole, metres.
        out: (n, 3) the ankle positions, metres, written.
    """
    one_f, one_p = foot.shape[0] == 1, pitch.shape[0] == 1
    for i in range(out.shape[0]):
        f = 0 if one_f else i
        p = pitch[0 if one_p else i]
        lever = ball if p <= 0 else -back
        yaw = foot[f, 2]
        fx, fy = math.cos(yaw), math.sin(yaw)
        c, s = math.cos(p), math.sin(p)
        along = lever * (c - 1) + ah * s
        out[i, 0] = foot[f, 0] - along * fx
        out[i, 1] = foot[f, 1] - along * fy
        out[i, 2] = ah * c - lever * s


def spin_print(foot: np.ndarray, spin, geom: LegGeometry, lever: float | None = None):
    """Footprints of a foot turned about a point of its sole. That point stays on the floor
    where it is; the rest of the foot swings round.

    Args:
        foot: (3,) the footprint (x, y, yaw), metres and radians.
        spin: (n,) turns, radians (CCW).
        geom: the foot lengths.
        lever: the pivot's distance ahead of the ankle on the sole, metres (default the ball;
            ``-foot_back``: the heel).

    Returns:
        (n, 3) the turned footprints.
    """
    b = ball_offset(geom) if lever is None else lever
    spin = np.asarray(spin, float)
    piv = foot[:2] + b * np.array([np.cos(foot[2]), np.sin(foot[2])])
    yaw = foot[2] + spin
    return np.column_stack([piv[0] - b * np.cos(yaw), piv[1] - b * np.sin(yaw), yaw])


def heel_rise(foot, hip, knee, p0, geom: LegGeometry, lo: float = -1.0472):
    """Foot pitch <= ``p0`` (rolled about the ball) at which the leg with ``knee`` flexion
    reaches from the ankle to ``hip``; ``p0`` if it reaches already. Where it reaches at no
    pitch, the pitch in [``lo``, ``p0``] that brings the ankle closest to the hip: rolled
    about the ball the ankle moves on a circle, so past the point of the circle nearest the
    hip a higher heel takes it away again (a foot ahead of the hip gets there long before
    ``lo``, a trailing foot not before).

    Args:
        foot: (3,) the footprint (x, y, yaw), metres and radians.
        hip: (3,) or (n, 3) the hip joint centre, metres, world frame.
        knee: knee flexion(s), radians (scalar or (n,)).
        p0: the current pitch(es), radians, + toes up (scalar or (n,)).
        geom: the leg and foot lengths.
        lo: the lowest pitch (highest heel), radians.

    Returns:
        the pitch(es), radians: a float for scalar ``knee`` and ``p0`` with ``hip`` (3,),
        else (n,) (one bisection for all samples).
    """
    scalar = np.ndim(p0) == 0
    hip = np.atleast_2d(np.asarray(hip, float))
    p0 = np.atleast_1d(np.asarray(p0, float))
    knee = np.broadcast_to(np.asarray(knee, float), p0.shape)
    d = geom.span(knee)
    foot = np.asarray(foot, float)
    if foot.shape == (3,) and p0.ndim == 1 and hip.shape == (len(p0), 3):  # compiled
        p = np.empty(len(p0))
        heel_rise_rows(
            foot,
            np.ascontiguousarray(hip),
            np.ascontiguousarray(d, dtype=float),
            p0,
            ball_offset(geom),
            geom.foot_back,
            geom.ankle_height,
            float(lo),
            p,
        )
        return float(p[0]) if scalar else p

    def gap(h, p, dd=d):
        return np.linalg.norm(h - pivot_ankle(foot, p, geom), axis=-1) - dd

    p = p0.copy()
    j = np.flatnonzero(gap(hip, p0) > 0)  # the samples that do not reach at p0
    if not len(j):
        return float(p[0]) if scalar else p
    hj, dj = hip[j], d[j]
    # rolled about the ball B by p <= 0 the ankle is B + rho (-cos t f, sin t z), t = beta - p
    # (f the foot's heading): |hip - ankle| = d is closed-form in t, the first root as the
    # heel rises; without a root the clipped arcsin gives the t nearest the hip
    ball, ah = ball_offset(geom), geom.ankle_height
    rho, beta = np.hypot(ball, ah), np.arctan2(ah, ball)
    f = np.array([np.cos(foot[2]), np.sin(foot[2])])
    rel = hj - np.array([foot[0] + ball * f[0], foot[1] + ball * f[1], 0.0])
    a_, c_ = rel[:, :2] @ f, rel[:, 2]
    k_ = ((rel**2).sum(1) + rho**2 - dj**2) / (2 * rho)
    t = np.arctan2(a_, c_) + np.arcsin(np.clip(k_ / np.hypot(a_, c_), -1.0, 1.0))
    p[j] = np.clip(beta - t, lo, np.minimum(p0[j], 0.0))
    # toes up at p0 and reaching with the foot flat: bisect between flat and p0 (the roll
    # pivots on the heel there); not reaching flat, the ball roll above holds
    up = j[p0[j] > 0]
    up = up[gap(hip[up], np.zeros(len(up)), d[up]) <= 0]
    if len(up):
        hu, du = hip[up], d[up]
        a, b = np.zeros(len(up)), p0[up]  # gap(a) <= 0 < gap(b)
        for _ in range(40):
            m = 0.5 * (a + b)
            out = gap(hu, m, du) > 0
            b = np.where(out, m, b)
            a = np.where(out, a, m)
        p[up] = 0.5 * (a + b)
    return float(p[0]) if scalar else p


@njit
def _pivot_gap(foot, fx, fy, h, p, d, ball, back, ah):
    """|hip ``h`` - ankle of the foot pitched by ``p``| - ``d`` (:func:`pivot_ankle`)."""
    lever = ball if p <= 0 else -back
    c, s = math.cos(p), math.sin(p)
    along = lever * (c - 1) + ah * s
    dx = h[0] - (foot[0] - along * fx)
    dy = h[1] - (foot[1] - along * fy)
    dz = h[2] - (ah * c - lever * s)
    return math.sqrt(dx * dx + dy * dy + dz * dz) - d


@njit
def heel_rise_rows(foot, hip, d, p0, ball, back, ah, lo, out):
    """:func:`heel_rise` per sample (the same steps: reach test at ``p0``, the closed-form
    roll about the ball, the 40-step bisection of a toes-up foot) into ``out``.

    Args:
        foot: (3,) the footprint (x, y, yaw), metres and radians.
        hip: (n, 3) hip joint centres, metres.
        d: (n,) the leg's hip-to-ankle spans, metres.
        p0: (n,) current pitches, radians.
        ball: the ball's distance ahead of the ankle, metres.
        back: the heel's distance behind the ankle, metres.
        ah: the ankle height, metres.
        lo: the lowest pitch, radians.
        out: (n,) the pitches, radians, written.
    """
    fx, fy = math.cos(foot[2]), math.sin(foot[2])
    rho, beta = math.hypot(ball, ah), math.atan2(ah, ball)
    bx, by = foot[0] + ball * fx, foot[1] + ball * fy
    for i in range(len(p0)):
        h = hip[i]
        q0 = p0[i]
        if not _pivot_gap(foot, fx, fy, h, q0, d[i], ball, back, ah) > 0:
            out[i] = q0
            continue
        r0, r1, r2 = h[0] - bx, h[1] - by, h[2] - 0.0
        a_, c_ = r0 * fx + r1 * fy, r2
        k_ = ((r0**2 + r1**2 + r2**2) + rho**2 - d[i] ** 2) / (2 * rho)
        t = math.atan2(a_, c_) + math.asin(min(max(k_ / math.hypot(a_, c_), -1.0), 1.0))
        q = min(max(beta - t, lo), min(q0, 0.0))
        if q0 > 0 and _pivot_gap(foot, fx, fy, h, 0.0, d[i], ball, back, ah) <= 0:
            a, b = 0.0, q0  # gap(a) <= 0 < gap(b)
            for _ in range(40):
                m = 0.5 * (a + b)
                if _pivot_gap(foot, fx, fy, h, m, d[i], ball, back, ah) > 0:
                    b = m
                else:
                    a = m
            q = 0.5 * (a + b)
        out[i] = q


@njit
def ankle_kept_rows(foot, hip, p0, L1, L2, ball, back, ah, lo, out):
    """The pitches <= ``p0`` (rolled about the ball) of a foot whose heel rises as far as the
    shank leans forward past its lean at the first sample: a first step from standing, whose
    swing heel comes off the floor before its toes (:func:`~.swing.swing_foot`) instead of
    the ankle dorsiflexing under the forward-leaning shank with the foot flat. The shank's
    lean is taken once, at the foot as it is (pitch ``p0``), in the foot's sagittal plane:
    the knee from the hip-to-ankle span (``L1``, ``L2``: thigh and shank, metres), the thigh
    flexed past the hip-to-ankle line by the triangle's hip angle, the lean ``thigh - knee``.
    Once, not solved for the raised foot: with the hip where it is, a higher heel brings the
    ankle nearer the hip, flexes the knee and leans the shank further, and the fixed point of
    that loop (tried: eight rounds) jumped the knee from 10 to 33 deg within one sample of a
    synthetic first step. So the ankle still dorsiflexes a little (synthetic first steps,
    ``benchmarks/bench_swing_ankle.py``: 5.0 deg standing, 5.7 at toe-off; 12.3-12.6 with
    the foot lifted flat, 879469c).

    Args:
        foot: (3,) the footprint (x, y, yaw), metres and radians.
        hip: (n, 3) hip joint centres, metres.
        p0: (n,) current pitches, radians, + toes up (``p0[0]`` the standing foot's).
        L1: the thigh's length, metres.
        L2: the shank's length, metres.
        ball: the ball's distance ahead of the ankle, metres.
        back: the heel's distance behind the ankle, metres.
        ah: the ankle height, metres.
        lo: the lowest pitch, radians.
        out: (n,) the pitches, radians, written.
    """
    n = p0.shape[0]
    if n == 0:
        return
    fx, fy = math.cos(foot[2]), math.sin(foot[2])
    lean0 = _shank_lean(foot, fx, fy, hip[0], p0[0], L1, L2, ball, back, ah)
    for i in range(n):
        lean = _shank_lean(foot, fx, fy, hip[i], p0[i], L1, L2, ball, back, ah)
        out[i] = min(max(p0[i] + min(lean - lean0, 0.0), lo), p0[i])


@njit
def _shank_lean(foot, fx, fy, h, p, L1, L2, ball, back, ah):
    """The shank's lean from the vertical (radians, + ankle ahead of the knee) of the leg
    from hip ``h`` to the ankle of the foot pitched by ``p`` (:func:`ankle_kept_rows`)."""
    lever = ball if p <= 0 else -back
    c, s = math.cos(p), math.sin(p)
    along = lever * (c - 1) + ah * s
    dx = foot[0] - along * fx - h[0]
    dy = foot[1] - along * fy - h[1]
    down = h[2] - (ah * c - lever * s)
    d = math.sqrt(dx * dx + dy * dy + down * down)
    knee = math.acos(min(max((d * d - L1 * L1 - L2 * L2) / (2 * L1 * L2), -1.0), 1.0))
    hip_in = math.acos(min(max((L1 * L1 + d * d - L2 * L2) / (2 * L1 * d), -1.0), 1.0))
    return math.atan2(dx * fx + dy * fy, down) + hip_in - knee
