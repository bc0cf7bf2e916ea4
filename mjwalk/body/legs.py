"""Legs from footprints (mocap-based DHM walking, §4.2 A8-A9): stance splines, swing splines, IK.

For every step of a :class:`~mjwalk.plan.walkpath.WalkPath` (one foot swings from its previous
footprint to ``step.foot`` while the other stands on ``step.stance``):

* **Stance leg (A8).** The stance knee follows a cubic spline in the step phase ``phi`` in [0, 1]
  through the reference key-frame angles at ``phi`` = 0.4, 0.5, 0.6 (they "change less against
  strides"), with the current posture's angle and angular velocity at ``phi = 0`` and the target
  posture's angle and the reference angular velocity at ``phi = 1`` as boundary conditions. The
  pelvis height follows from the stance leg (knee angle + footprint + pelvis x, y), which gives
  the pelvis height oscillation; it is capped where the swing leg could not reach its foot.
* **Swing leg (A9).** During ``phi`` < 0.2 (double support) the swing foot rolls about its ball
  (heel rise, toes flat). After toe-off the swing ankle follows a cubic spline through key
  positions at ``phi`` = 0.2, 0.4, 0.6, 0.8, 0.9 between the lift-off and the landing footprint
  (with ground clearance), zero velocity at landing (``phi = 1``).
* **IK.** Hip (rotation, flexion, abduction), knee and ankle (flexion, inversion) come from an
  analytic two-bone solution for the ankle position plus the foot orientation (yaw from the
  footprint, pitch from the roll-off / swing keys, sole level). Turning is taken by hip
  rotation: its angle is the foot yaw minus the pelvis yaw. All angles are clipped to the joint
  ranges.

Footprint convention: a footprint ``(x, y, yaw)`` is the point of the floor under the ankle joint
(the ``sole_*`` site of the humanoid) and the foot's heading. World frame, metres, radians.

The reference gait is :data:`REFERENCE_GAIT`, a table of normative sagittal angles over one gait
cycle (heel strike to heel strike of the same foot), read from D. A. Winter, "The Biomechanics and
Motor Control of Human Gait: Normal, Elderly and Pathological", 2nd ed. (1991), natural cadence
ensemble averages (Figs. 4.x, rounded to the degree). One step of our walks is half a cycle: the
stance leg covers cycle 0-50 %, the swing leg cycle 50-100 %.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline

from mjwalk.body.humanoid import ROM_DEG, LegGeometry, leg_geometry
from mjwalk.errors import PlanningError
from mjwalk.plan.walkpath import WalkPath

#: Normative sagittal joint angles (degrees) every 5 % of the gait cycle, 0 % = heel strike.
#: hip: + flexion; knee: + flexion; ankle: + dorsiflexion. After Winter (1991), natural cadence.
REFERENCE_GAIT = {
    "cycle": np.arange(0, 101, 5) / 100.0,
    "hip": np.array(
        [30, 29, 27, 24, 20, 15, 10, 5, 0, -4, -8, -9, -5, 3, 12, 20, 26, 30, 32, 31, 30],
        dtype=float,
    ),
    "knee": np.array(
        [3, 10, 16, 19, 18, 15, 11, 7, 5, 6, 10, 20, 35, 50, 60, 63, 57, 42, 25, 10, 3], dtype=float
    ),
    "ankle": np.array(
        [0, -4, -3, 1, 4, 6, 8, 9, 10, 9, 5, -3, -15, -18, -12, -5, 0, 1, 1, 0, 0], dtype=float
    ),
}

#: Stance key-frame phases (paper §4.2.3) and swing key-frame phases (§4.2.4).
STANCE_KEYS = (0.4, 0.5, 0.6)
SWING_KEYS = (0.2, 0.4, 0.6, 0.8, 0.9)
#: Toe-off phase of the step: double support lasts phi in [0, TOE_OFF] (10 % of the cycle).
TOE_OFF = 0.2
#: Swing-ankle key positions: (fraction of the way from the lift-off to the landing footprint,
#: ankle height above its standing height in metres, foot pitch in degrees, + toes up), for a
#: 1.75 m adult; heights scale with stature. Phase 0.2 is the end of the roll-off (computed).
SWING_PROFILE = {
    0.4: (0.30, 0.150, -20.0),
    0.6: (0.60, 0.100, -5.0),
    0.8: (0.88, 0.045, 5.0),
    0.9: (0.965, 0.020, 10.0),
}
#: Foot pitch at toe-off (degrees, toes down), rolled about the ball during double support.
TOE_OFF_PITCH = -30.0
#: Terminal stance heel rise: the stance foot rolls about its ball from phase HEEL_OFF to the
#: pitch HEEL_OFF_PITCH (degrees) at the end of the step (Winter: heel-off at ~35-40 % of the
#: cycle); the roll continues in the next step down to TOE_OFF_PITCH.
HEEL_OFF = 0.5
HEEL_OFF_PITCH = -25.0
#: Heel strike: the swing foot lands on its heel with the toes up by HEEL_STRIKE_PITCH degrees
#: and rolls down about the heel to flat at phase FOOT_FLAT of the next step (loading response,
#: foot flat at ~8 % of the cycle).
HEEL_STRIKE_PITCH = 15.0
FOOT_FLAT = 0.16
#: Smallest knee flexion the IK uses when a leg must stretch (radians): never lock the knee.
KNEE_MIN = np.deg2rad(2.0)

LEG_JOINTS = (
    "hip_{}_rot",
    "hip_{}_flex",
    "hip_{}_abd",
    "knee_{}",
    "ankle_{}_flex",
    "ankle_{}_inv",
    "toe_{}",
)


def reference_angle(joint: str, cycle: np.ndarray | float, derivative: bool = False):
    """Reference angle (radians) of ``joint`` in {"hip", "knee", "ankle"} at gait-cycle fraction(s).

    A periodic cubic spline through :data:`REFERENCE_GAIT`; ``derivative=True`` gives rad per
    unit cycle.
    """
    sp = _REF_SPLINES[joint]
    c = np.mod(cycle, 1.0)
    return np.deg2rad(sp(c, 1) if derivative else sp(c))


_REF_SPLINES = {
    k: CubicSpline(REFERENCE_GAIT["cycle"], REFERENCE_GAIT[k], bc_type="periodic")
    for k in ("hip", "knee", "ankle")
}


@dataclass
class LegMotion:
    """Per-sample leg motion for a WalkPath (same samples, 120 Hz), world frame.

    Attributes:
        t: (N,) sample times in seconds.
        root: (N, 3) pelvis (root) position, metres; z is the pelvis height above the floor.
        yaw: (N,) pelvis yaw, radians from +x CCW.
        angles: joint name (e.g. ``"knee_l"``) -> (N,) angle in radians, anatomical signs.
        ankle: side ("l"/"r") -> (N, 3) ankle target position, metres.
        contact: (N,) contact state: 0 = left stance, 1 = right stance, 2 = double support.
        phase: (N,) step phase in [0, 1] (0 before the first / after the last step).
    """

    t: np.ndarray
    root: np.ndarray
    yaw: np.ndarray
    angles: dict[str, np.ndarray]
    ankle: dict[str, np.ndarray]
    contact: np.ndarray
    phase: np.ndarray
    meta: dict = field(default_factory=dict)


def _rz(a: np.ndarray) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2
    )


def _ry(a: np.ndarray) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2
    )


def _rx(a: np.ndarray) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2
    )


def leg_ik(
    ankle_rel: np.ndarray,
    foot_yaw: np.ndarray,
    foot_pitch: np.ndarray,
    side: str,
    geom: LegGeometry,
) -> dict[str, np.ndarray]:
    """Analytic leg IK in the pelvis frame (x forward, y left, z up; pelvis upright).

    Args:
        ankle_rel: (N, 3) ankle position relative to the hip joint centre, metres.
        foot_yaw: (N,) foot heading relative to the pelvis heading, radians (CCW).
        foot_pitch: (N,) foot pitch relative to the floor, radians, + toes up.
        side: "l" or "r".
        geom: the leg lengths.

    Returns:
        joint name -> (N,) angle in radians (hip rotation/flexion/abduction, knee, ankle
        flexion/inversion), anatomical signs, clipped to the humanoid's ranges. Unreachable
        targets are met as closely as the leg allows (stretched to :data:`KNEE_MIN`).
    """
    s = 1.0 if side == "l" else -1.0
    L1, L2 = geom.thigh, geom.shank
    d = _rz(-foot_yaw) @ ankle_rel[..., None]
    d = d[..., 0]
    r = np.linalg.norm(d, axis=-1)
    rmax = np.sqrt(L1**2 + L2**2 + 2 * L1 * L2 * np.cos(KNEE_MIN))
    rmin = np.sqrt(L1**2 + L2**2 + 2 * L1 * L2 * np.cos(np.deg2rad(ROM_DEG["knee"][1])))
    rc = np.clip(r, rmin, rmax)
    knee = np.arccos(np.clip((rc**2 - L1**2 - L2**2) / (2 * L1 * L2), -1, 1))
    ax = -L2 * np.sin(knee)
    az = -L1 - L2 * np.cos(knee)
    beta = np.arcsin(np.clip(d[:, 1] / np.maximum(-az, 1e-9), -1, 1))  # rotation about +x
    c = az * np.cos(beta)
    flex = np.arctan2(d[:, 2], d[:, 0]) - np.arctan2(c, ax)
    flex = np.mod(flex + np.pi, 2 * np.pi) - np.pi
    # foot orientation: R_y(-flex) R_x(beta) R_y(knee) R_y(-dorsi) R_x(b) = R_y(-pitch)
    M = _ry(-flex) @ _rx(beta) @ _ry(knee)
    T = np.swapaxes(M, -1, -2) @ _ry(-foot_pitch)
    a = np.arctan2(-T[:, 2, 0], T[:, 0, 0])
    b = np.arctan2(-T[:, 1, 2], T[:, 1, 1])
    out = {
        f"hip_{side}_rot": -s * foot_yaw,
        f"hip_{side}_flex": flex,
        f"hip_{side}_abd": s * beta,
        f"knee_{side}": knee,
        f"ankle_{side}_flex": -a,
        f"ankle_{side}_inv": -s * b,
    }
    for name, v in out.items():
        lo, hi = np.deg2rad(ROM_DEG[_generic(name)])
        out[name] = np.clip(v, lo, hi)
    return out


def _generic(name: str) -> str:
    return "_".join(p for p in name.split("_") if p not in ("l", "r"))


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def _foot_frames(walk: WalkPath, geom: LegGeometry) -> list[dict]:
    """Per step: swing side, lift-off and landing footprints, stance footprint."""
    steps = walk.steps
    frames = []
    for i, st in enumerate(steps):
        side = "l" if st.side == "left" else "r"
        if i > 0:
            lift = np.asarray(steps[i - 1].stance, float)
        else:  # standing start: the swing foot beside the stance foot, mirrored about the pelvis
            y0 = walk.yaw[st.start]
            n = np.array([-np.sin(y0), np.cos(y0)])
            stance = np.asarray(st.stance, float)
            off = float((walk.xy[st.start] - stance[:2]) @ n)
            lift = np.array([*(stance[:2] + 2 * off * n), stance[2]])
        frames.append(
            {
                "side": side,
                "other": "r" if side == "l" else "l",
                "start": st.start,
                "end": st.end,
                "lift": lift,
                "land": np.asarray(st.foot, float),
                "stance": np.asarray(st.stance, float),
                "walking": i > 0,
                "final": i == len(steps) - 1,
            }
        )
    return frames


def _ball_pivot(foot: np.ndarray, pitch: np.ndarray, geom: LegGeometry) -> np.ndarray:
    """(n, 3) ankle positions of a foot on footprint ``foot`` pitched by ``pitch`` (radians):
    negative (heel up) rolls about the ball, positive (toes up) about the heel; the pivot stays
    on the floor where it is when the foot is flat."""
    ah = geom.ankle_height
    pitch = np.atleast_1d(np.asarray(pitch, float))
    lever = np.where(pitch <= 0, _ball(geom), -geom.foot_back)[:, None]
    yl = np.full_like(pitch, foot[2])
    fwd = np.array([np.cos(foot[2]), np.sin(foot[2]), 0.0])
    pivot = np.array([foot[0], foot[1], 0.0]) + lever * fwd
    local = np.column_stack([lever[:, 0], np.zeros_like(pitch), np.full_like(pitch, -ah)])
    return pivot - ((_rz(yl) @ _ry(-pitch)) @ local[..., None])[..., 0]


def _ball(geom: LegGeometry) -> float:
    """Distance of the ball of the foot (toe joint) ahead of the ankle, metres."""
    return geom.foot_front - 0.2 * (geom.foot_front + geom.foot_back)


def _swing_track(fr: dict, phi: np.ndarray, geom: LegGeometry, scale: float):
    """Swing ankle position (n, 3), foot yaw (n,), foot pitch (n,), toe angle (n,) for phases."""
    ah = geom.ankle_height
    lift, land = fr["lift"], fr["land"]
    yaw = lift[2] + (np.angle(np.exp(1j * (land[2] - lift[2])))) * _smoothstep(
        (phi - TOE_OFF) / (0.9 - TOE_OFF)
    )
    # roll-off about the ball during double support
    p_to = np.deg2rad(TOE_OFF_PITCH)

    p_ho = np.deg2rad(HEEL_OFF_PITCH) if fr["walking"] else 0.0

    def roll(ph):
        p = p_ho + (p_to - p_ho) * _smoothstep(ph / TOE_OFF)
        return _ball_pivot(lift, p, geom), p

    pos = np.zeros((len(phi), 3))
    pitch = np.zeros(len(phi))
    early = phi <= TOE_OFF
    pos[early], pitch[early] = roll(phi[early])
    late = ~early
    if late.any():
        # spline knots: toe-off (from the roll), keys, landing (zero velocity)
        p0, _ = roll(np.array([TOE_OFF]))
        h = 1e-4
        pa, _ = roll(np.array([TOE_OFF - h]))
        v0 = (p0[0] - pa[0]) / h
        knots = [TOE_OFF]
        pts = [p0[0]]
        pit = [p_to]
        for ph, (frac, hgt, pt) in SWING_PROFILE.items():
            xy = lift[:2] + frac * (land[:2] - lift[:2])
            knots.append(ph)
            pts.append(np.array([xy[0], xy[1], ah + hgt * scale]))
            pit.append(np.deg2rad(pt))
        hs = 0.0 if fr["final"] else np.deg2rad(HEEL_STRIKE_PITCH)  # the last step lands flat
        knots.append(1.0)
        pts.append(_ball_pivot(land, hs, geom)[0])
        pit.append(hs)
        sp = CubicSpline(knots, np.array(pts), bc_type=((1, v0), (1, np.zeros(3))))
        spp = CubicSpline(knots, np.array(pit), bc_type=((1, 0.0), (1, 0.0)))
        pos[late] = sp(phi[late])
        pitch[late] = spp(phi[late])
    # the toes stay flat during the roll-off, then straighten while the foot lifts
    toe = np.where(early, -pitch, -p_to * (1 - _smoothstep((phi - TOE_OFF) / 0.25)))
    return pos, yaw, pitch, toe


def legs_from_walk(walk: WalkPath, stature: float = 1.75) -> LegMotion:
    """Leg joint angles and root height for every sample of ``walk`` (paper §4.2 A8-A9).

    Args:
        walk: a WalkPath with steps (each with side, start/end sample, landing and stance foot).
        stature: the humanoid's stature in metres.

    Returns:
        a :class:`LegMotion` on the walk's samples.
    """
    if not walk.steps:
        raise PlanningError(
            "legs_from_walk: the walk path has no steps (grid-A* paths have no "
            "gait; plan with the hybrid A* or add footprints)"
        )
    geom = leg_geometry(stature)
    scale = stature / 1.75
    n = len(walk.t)
    xy = np.asarray(walk.xy, float)
    yaw = np.asarray(walk.yaw, float)
    frames = _foot_frames(walk, geom)
    for k, fr in enumerate(frames):
        if not (0 <= fr["start"] < fr["end"] < n):
            raise PlanningError(
                f"legs_from_walk: step {k} has sample range {fr['start']}..."
                f"{fr['end']} outside the path's {n} samples"
            )
    ah = geom.ankle_height
    L1, L2 = geom.thigh, geom.shank
    ankle = {s: np.zeros((n, 3)) for s in "lr"}
    fyaw = {s: np.zeros(n) for s in "lr"}
    pitch = {s: np.zeros(n) for s in "lr"}
    toe = {s: np.zeros(n) for s in "lr"}
    contact = np.full(n, 2, dtype=int)
    phase = np.zeros(n)
    z = np.full(n, np.nan)

    def hip_xy(idx, side):
        sgn = 1.0 if side == "l" else -1.0
        return xy[idx] + sgn * geom.hip_y * np.stack([-np.sin(yaw[idx]), np.cos(yaw[idx])], -1)

    def height_for_knee(idx, side, foot_pos, knee):
        h = np.linalg.norm(hip_xy(idx, side) - foot_pos[:, :2], axis=-1)
        d2 = L1**2 + L2**2 + 2 * L1 * L2 * np.cos(knee)
        return foot_pos[:, 2] + np.sqrt(np.maximum(d2 - h**2, 1e-6))

    def reach_height(idx, side, foot_pos):
        h = np.linalg.norm(hip_xy(idx, side) - foot_pos[:, :2], axis=-1)
        d2 = L1**2 + L2**2 + 2 * L1 * L2 * np.cos(KNEE_MIN)
        return foot_pos[:, 2] + np.sqrt(np.maximum(d2 - h**2, 1e-6))

    knee_prev = None  # (angle, velocity per unit phase) of the next stance leg at its landing
    for k, fr in enumerate(frames):
        a, b = fr["start"], fr["end"]
        idx = np.arange(a, b + 1)
        phi = (idx - a) / (b - a)
        phase[idx] = phi
        sw, st = fr["side"], fr["other"]
        contact[idx] = np.where(phi <= TOE_OFF, 2, 0 if st == "l" else 1)
        # swing leg
        pos, yw, pt, tq = _swing_track(fr, phi, geom, scale)
        ankle[sw][idx], fyaw[sw][idx], pitch[sw][idx], toe[sw][idx] = pos, yw, pt, tq
        # stance leg: foot fixed on its footprint
        stp = fr["stance"]
        p_st = np.deg2rad(HEEL_OFF_PITCH) * _smoothstep((phi - HEEL_OFF) / (1 - HEEL_OFF))
        if k > 0:  # loading response: roll down from the heel strike
            p_st = p_st + np.deg2rad(HEEL_STRIKE_PITCH) * (1 - _smoothstep(phi / FOOT_FLAT))
        ankle[st][idx] = _ball_pivot(stp, p_st, geom)
        pitch[st][idx] = p_st
        toe[st][idx] = -p_st
        fyaw[st][idx] = stp[2]
        # stance knee spline (A8): boundary at phi=0 from the current posture, at phi=1 the
        # target posture (both feet down, swing knee at the reference heel-strike angle)
        land_pos = _ball_pivot(
            fr["land"], 0.0 if fr["final"] else np.deg2rad(HEEL_STRIKE_PITCH), geom
        )
        z_end = reach_height(np.array([b]), sw, land_pos)[0]
        hk_end = L1**2 + L2**2 + 2 * L1 * L2 * np.cos(reference_angle("knee", 0.0))
        hz = np.linalg.norm(hip_xy(np.array([b]), sw) - land_pos[:, :2], axis=-1)[0]
        z_end = min(z_end, ah + np.sqrt(max(hk_end - hz**2, 1e-6)))
        st_end = ankle[st][b]
        h_st_end = np.linalg.norm(hip_xy(np.array([b]), st) - st_end[:2], axis=-1)[0]
        d_end = np.hypot(h_st_end, z_end - st_end[2])
        th1 = np.arccos(np.clip((d_end**2 - L1**2 - L2**2) / (2 * L1 * L2), -1, 1))
        if knee_prev is None:
            th0, v0 = reference_angle("knee", 0.0), 0.5 * reference_angle("knee", 0.0, True)
        else:
            th0, v0 = knee_prev
        v1 = 0.5 * reference_angle("knee", 0.5, True)
        kp = [0.0, *STANCE_KEYS, 1.0]
        kv = [th0, *(reference_angle("knee", 0.5 * p) for p in STANCE_KEYS), th1]
        knee_sp = CubicSpline(kp, kv, bc_type=((1, v0), (1, v1)))
        knee_st = np.clip(knee_sp(phi), KNEE_MIN, np.pi / 2)
        z_st = height_for_knee(idx, st, ankle[st][idx], knee_st)
        z_sw = reach_height(idx, sw, pos)
        z[idx] = np.minimum(z_st, z_sw)
        # the swing leg's knee at landing becomes the next stance leg's start posture
        dl = np.hypot(hz, z[b] - ah)
        th_next = np.arccos(np.clip((dl**2 - L1**2 - L2**2) / (2 * L1 * L2), -1, 1))
        knee_prev = (th_next, 0.5 * reference_angle("knee", 0.0, True))
    # before the first step: stand on both feet; after the last: hold the final pose
    first, last = frames[0], frames[-1]
    pre = np.arange(0, first["start"])
    if len(pre):
        for s_, f in ((first["side"], first["lift"]), (first["other"], first["stance"])):
            ankle[s_][pre] = [f[0], f[1], ah]
            fyaw[s_][pre] = f[2]
        z[pre] = np.minimum(
            reach_height(pre, "l", ankle["l"][pre]), reach_height(pre, "r", ankle["r"][pre])
        )
    post = np.arange(last["end"] + 1, n)
    if len(post):
        e = last["end"]
        for arr in (*ankle.values(), *fyaw.values(), *pitch.values(), *toe.values(), z):
            arr[post] = arr[e]
        contact[post] = 2
    root = np.column_stack([xy, z])
    angles: dict[str, np.ndarray] = {}
    for s_ in "lr":
        sgn = 1.0 if s_ == "l" else -1.0
        hip = root + sgn * geom.hip_y * np.column_stack([-np.sin(yaw), np.cos(yaw), np.zeros(n)])
        rel = (_rz(-yaw) @ (ankle[s_] - hip)[..., None])[..., 0]
        yrel = np.angle(np.exp(1j * (fyaw[s_] - yaw)))
        angles.update(leg_ik(rel, yrel, pitch[s_], s_, geom))
        lo, hi = np.deg2rad(ROM_DEG["toe"])
        angles[f"toe_{s_}"] = np.clip(toe[s_], lo, hi)
    return LegMotion(
        t=np.asarray(walk.t, float),
        root=root,
        yaw=yaw,
        angles=angles,
        ankle=ankle,
        contact=contact,
        phase=phase,
        meta={"stature": stature},
    )
