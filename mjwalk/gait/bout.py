"""A bout's step plan turned into a take: footsteps, contact timing and an inverted-pendulum
pelvis (the **Contact timing** and **Pelvis** paragraphs of :mod:`mjwalk.gait.corpus`'s module
docstring describe the model).

All outputs: 120 Hz by default, metres, z up, yaw radians CCW from +x (world frame).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_banded
from scipy.ndimage import gaussian_filter1d

from mjwalk.gait.subjects import SubjectParams
from mjwalk.mocap.take import TAKE_FPS, Take

#: Gravitational acceleration (m/s^2), the inverted pendulum's.
G = 9.81
#: Ankle and toe (ball of the foot) heights above the floor when the foot is planted, metres.
ANKLE_HEIGHT = 0.08
TOE_HEIGHT = 0.02


@dataclass
class BoutPlan:
    """Per-step arrays of one bout: forward/lateral advance of the walking line (m, in the
    mid-step heading frame), heading change (rad), duration (s)."""

    fwd: list[float]
    lat: list[float]
    dtheta: list[float]
    dur: list[float]


def _progress(u: np.ndarray) -> np.ndarray:
    """Swing progress 0->1 with a cycloid-like speed profile that leaves and lands with a
    quarter of the mean swing speed (a heel strike is an impact, not a soft landing)."""
    beta = 0.75
    return u - beta * np.sin(2 * np.pi * u) / (2 * np.pi)


def _lipm(p_ref: np.ndarray, z0: float, fps: float) -> np.ndarray:
    """Pelvis (N, 2) from the ZMP (N, 2) by the LIPM x'' = g/z0 (x - p) as a boundary-value
    problem, x = p at both ends, central differences on the frame grid (tridiagonal solve)."""
    n = p_ref.shape[0]
    w2 = G / z0 / fps**2
    ab = np.empty((3, n))
    ab[0, :] = 1.0
    ab[1, :] = -(2.0 + w2)
    ab[2, :] = 1.0
    ab[0, 1] = 0.0
    ab[1, 0] = ab[1, -1] = 1.0
    ab[2, -2] = 0.0
    rhs = -w2 * p_ref
    rhs[0], rhs[-1] = p_ref[0], p_ref[-1]
    return solve_banded((1, 1), ab, rhs)


@dataclass
class _Footsteps:
    """Where the feet of a bout land (world frame, metres, radians): per step ``k`` the swing
    foot ``side`` (0 left, 1 right) and ``sgn`` (-1 left, +1 right), the heading after the
    step ``theta``, the walking-line point ``centre`` (n, 2), the landing ``land`` (n, 2) and
    its yaw ``land_yaw``; ``init`` the initial stance pose (x, y, yaw) of each foot, ``r0``
    the right direction at the start; ``first`` the first swing foot."""

    start: np.ndarray
    theta0: float
    first: int
    side: np.ndarray
    sgn: np.ndarray
    theta: np.ndarray
    centre: np.ndarray
    land: np.ndarray
    land_yaw: np.ndarray
    init: dict[int, np.ndarray]
    r0: np.ndarray


@dataclass
class _Timing:
    """Contact timing of a bout in frames: step durations ``dur_f`` and double supports
    ``ds_f``, the end of the initial standing ``hs_start``, heel strikes ``hs`` and toe-offs
    ``to`` per step, the final double support ``end_ds``, and the take's ``n_frames``."""

    dur_f: np.ndarray
    ds_f: np.ndarray
    hs_start: int
    hs: np.ndarray
    to: np.ndarray
    end_ds: int
    n_frames: int


def render_bout(
    plan: BoutPlan,
    p: SubjectParams,
    rng: np.random.Generator,
    name: str,
    start: np.ndarray,
    theta0: float,
    meta: dict,
    fps: float = TAKE_FPS,
) -> Take:
    """Turn a step plan into a take (feet, contact timing, LIPM pelvis).

    Draws from ``rng``, in order: the first swing foot, the step-width noise, the initiation's
    weight shift, the initial and the final standing times, the pelvic-rotation noise.

    Args:
        plan: the bout's steps.
        p: the subject walking it.
        rng: random generator.
        name: the take's name.
        start: (2,) start of the walking line, metres (world frame).
        theta0: initial heading, radians CCW from +x.
        meta: the take's ``meta``; the true ``heel_strikes`` / ``toe_offs`` (side -> frames),
            ``n_steps`` and ``first_side`` are added.
        fps: frames per second.

    Returns:
        The :class:`~mjwalk.mocap.take.Take` (metres, z up).
    """
    fs = _footsteps(plan, p, rng, start, theta0)
    tm = _timing(plan, p, rng, fps)
    feet, truth_hs, truth_to = _feet(fs, tm, p)
    frames = np.arange(tm.n_frames)
    pelvis_xy = _pelvis_xy(fs, tm, p, fps)
    # Pelvis height: low in double support, high in single support.
    n, hs, to, hs_start = len(fs.side), tm.hs, tm.to, tm.hs_start
    zt, zv = [0, hs_start], [0.0, 0.0]
    for k in range(n):
        zt += [int(hs[k - 1] if k else hs_start) + int(tm.ds_f[k]) // 2, int((to[k] + hs[k]) // 2)]
        zv += [-p.bob, p.bob]
    zt += [int(hs[-1] + tm.end_ds), tm.n_frames - 1]
    zv += [0.0, 0.0]
    z = p.pelvis_height + gaussian_filter1d(np.interp(frames, zt, zv), 0.04 * fps, mode="nearest")
    # Pelvis yaw: heading at heel strikes + transverse rotation (extreme at heel strikes).
    yt = np.concatenate([[0, hs_start], hs, [hs[-1] + tm.end_ds, tm.n_frames - 1]]).astype(float)
    rot = fs.sgn * p.pelvis_rotation * (1 + 0.1 * rng.standard_normal(n))
    rot[-1] *= 0.5
    theta = fs.theta
    yv = np.concatenate([[theta0, theta0], theta + rot, [theta[-1], theta[-1]]])
    yaw = gaussian_filter1d(np.interp(frames, yt, yv), 0.05 * fps, mode="nearest")

    meta = dict(meta)
    meta.update(heel_strikes=truth_hs, toe_offs=truth_to, n_steps=n, first_side=int(fs.first))
    return Take(
        name=name,
        fps=fps,
        pelvis=np.column_stack([pelvis_xy, z]),
        pelvis_yaw=yaw,
        ankle_l=feet[0][0],
        ankle_r=feet[1][0],
        toe_l=feet[0][1],
        toe_r=feet[1][1],
        meta=meta,
    )


def _footsteps(
    plan: BoutPlan, p: SubjectParams, rng: np.random.Generator, start: np.ndarray, theta0: float
) -> _Footsteps:
    """The landings of ``plan`` from ``start`` (m) heading ``theta0`` (rad); draws the first
    swing foot and the step-width noise from ``rng``."""
    n = len(plan.fwd)
    fwd, lat = np.asarray(plan.fwd), np.asarray(plan.lat)
    dth = np.asarray(plan.dtheta)
    theta = theta0 + np.cumsum(dth)  # heading after each step
    th_mid = theta - 0.5 * dth
    adv = fwd[:, None] * np.stack([np.cos(th_mid), np.sin(th_mid)], 1) + lat[:, None] * np.stack(
        [np.sin(th_mid), -np.cos(th_mid)], 1
    )
    centre = start + np.cumsum(adv, axis=0)  # walking-line point of each step's landing
    first = int(rng.integers(2))  # 0: left foot swings first
    side = (first + np.arange(n)) % 2  # 0 left, 1 right
    sgn = np.where(side == 0, -1.0, 1.0)  # left foot is on the left (-right direction)
    right = np.stack([np.sin(theta), -np.cos(theta)], 1)
    width = np.where(np.abs(lat) > 1e-9, np.maximum(p.step_width, np.abs(lat) + 0.1), p.step_width)
    width = np.maximum(width + 0.02 * rng.standard_normal(n), 0.02)
    land = centre + (sgn * 0.5 * width)[:, None] * right
    land_yaw = theta - sgn * p.toe_out
    # Closing step: land beside the other foot, same heading.
    land[-1] = centre[-2] + sgn[-1] * 0.5 * p.step_width * right[-2]
    land_yaw[-1] = theta[-2] - sgn[-1] * p.toe_out
    theta[-1] = theta[-2]
    # Initial stance: feet side by side around start, heading theta0.
    r0 = np.array([math.sin(theta0), -math.cos(theta0)])
    init = {
        0: np.array([*(start - 0.5 * p.step_width * r0), theta0 + p.toe_out]),
        1: np.array([*(start + 0.5 * p.step_width * r0), theta0 - p.toe_out]),
    }
    return _Footsteps(start, theta0, first, side, sgn, theta, centre, land, land_yaw, init, r0)


def _timing(plan: BoutPlan, p: SubjectParams, rng: np.random.Generator, fps: float) -> _Timing:
    """Contact timing in frames: HS[-1] = end of the initial standing, HS[k] = HS[k-1] + T_k;
    draws the initiation's weight shift, the initial and the final standing from ``rng``."""
    dur_f = np.maximum(np.round(np.asarray(plan.dur) * fps).astype(int), 20)
    ds_f = np.maximum(np.round(p.double_support * dur_f).astype(int), 6)
    # Gait initiation: a longer weight shift before the first swing, then a normal swing.
    ds_f[0] = max(round(rng.uniform(0.3, 0.4) * fps), 6)
    dur_f[0] = ds_f[0] + round((1.0 - p.double_support) * dur_f[0])
    hs_start = round(rng.uniform(0.5, 0.9) * fps)
    hs = hs_start + np.cumsum(dur_f)
    to = np.concatenate([[hs_start], hs[:-1]]) + ds_f
    end_ds = int(ds_f[-1])
    n_frames = int(hs[-1] + end_ds + round(rng.uniform(0.8, 1.1) * fps))
    return _Timing(dur_f, ds_f, hs_start, hs, to, end_ds, n_frames)


def _feet(
    fs: _Footsteps, tm: _Timing, p: SubjectParams
) -> tuple[dict[int, tuple[np.ndarray, np.ndarray]], dict, dict]:
    """Ankle and toe paths (T, 3) of each foot (0 left, 1 right) and the true heel strikes and
    toe-offs per side: swing k moves foot side[k] from its previous pose to land[k]."""
    n_frames = tm.n_frames
    frames = np.arange(n_frames)
    poses = np.concatenate([fs.land, fs.land_yaw[:, None]], 1)
    feet = {}
    truth_hs, truth_to = {}, {}
    for j in (0, 1):
        init = fs.init[j]
        ks = np.flatnonzero(fs.side == j)
        prev = np.vstack([init, poses[ks[:-1]]]) if ks.size else init[None]
        nxt = poses[ks]
        t_off, t_hs = tm.to[ks], tm.hs[ks]
        idx = np.searchsorted(t_off, frames, side="right") - 1
        out = np.repeat(init[None], n_frames, 0)
        lift = np.zeros(n_frames)
        m = idx >= 0
        if m.any():
            i = idx[m]
            u = np.clip((frames[m] - t_off[i] + 1) / (t_hs[i] - t_off[i] + 1), 0.0, 1.0)
            s = _progress(u)
            d = nxt[i] - prev[i]
            d[:, 2] = (d[:, 2] + np.pi) % (2 * np.pi) - np.pi
            out[m] = prev[i] + s[:, None] * d
            lift[m] = (p.clearance * np.sin(np.pi * u)) * ((u > 0) & (u < 1))
        ankle = np.column_stack([out[:, 0], out[:, 1], ANKLE_HEIGHT + lift])
        toe = ankle + np.column_stack(
            [
                p.foot_length * np.cos(out[:, 2]),
                p.foot_length * np.sin(out[:, 2]),
                np.full(n_frames, TOE_HEIGHT - ANKLE_HEIGHT),
            ]
        )
        feet[j] = (ankle, toe)
        key = "left" if j == 0 else "right"
        truth_hs[key], truth_to[key] = t_hs.astype(int), t_off.astype(int)
    return feet, truth_hs, truth_to


def _pelvis_xy(fs: _Footsteps, tm: _Timing, p: SubjectParams, fps: float) -> np.ndarray:
    """(T, 2) horizontal pelvis: the LIPM over piecewise-linear ZMP knots, standing midpoint
    -> stance foot (heel to forefoot in single support) -> ... -> standing midpoint."""
    start, theta0, theta, centre, sgn = fs.start, fs.theta0, fs.theta, fs.centre, fs.sgn

    def zmp(k: int, along: float) -> np.ndarray:
        """ZMP under the stance foot of step k (the foot that landed at step k-1)."""
        if k == 0:
            c, th = start, theta0
        else:
            c, th = centre[k - 1], theta[k - 1]
        s_ = -sgn[k]  # the stance foot is the other one
        return (
            c
            + s_ * p.zmp_offset * np.array([math.sin(th), -math.cos(th)])
            + along * np.array([math.cos(th), math.sin(th)])
        )

    # Gait initiation: anticipatory postural adjustment, the ZMP first moves backwards and
    # towards the swing foot, which launches the pelvis forwards onto the stance foot.
    h0 = np.array([math.cos(theta0), math.sin(theta0)])
    apa = start - p.apa * h0 + sgn[0] * 0.3 * p.step_width * fs.r0
    hs_start, land, n = tm.hs_start, fs.land, len(fs.side)
    kt, kp = [0, hs_start, hs_start + int(tm.ds_f[0]) // 2], [start, start, apa]
    for k in range(n):
        kt += [int(tm.to[k]), int(tm.hs[k])]
        kp += [zmp(k, -0.02), zmp(k, 0.10)]
    end_mid = 0.5 * (land[-1] + land[-2]) if n > 1 else land[-1]
    kt += [int(tm.hs[-1] + tm.end_ds), tm.n_frames - 1]
    kp += [end_mid, end_mid]
    kt_a, kp_a = np.asarray(kt, float), np.asarray(kp)
    frames = np.arange(tm.n_frames)
    p_ref = np.column_stack(
        [np.interp(frames, kt_a, kp_a[:, 0]), np.interp(frames, kt_a, kp_a[:, 1])]
    )
    # Solve on a grid padded by 2 s of standing at both ends (about 7 pendulum time constants)
    # so that the boundary conditions do not pull the pelvis: it settles over the feet.
    pad = round(2.0 * fps)
    p_pad = np.pad(p_ref, ((pad, pad), (0, 0)), mode="edge")
    return _lipm(p_pad, p.pelvis_height, fps)[pad:-pad]
