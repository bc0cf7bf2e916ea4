"""Compiled pitch corrections of the leg synthesis (:func:`~.synthesis.legs_from_walk`).

Where a grounded foot's ankle would leave its range, the synthesis lowers or raises the foot's
pitch about its pivot on the floor, spread over the samples around, and solves the leg again,
up to eight times per leg and pass (four passes), until no grounded ankle is more than a
tolerance past its bound (``AnkleFit.tol``; the synthesis's ``ANKLE_TOL``). Each round is a
few dozen NumPy operations on a walk's few hundred samples: in NumPy their call overhead cost
about as much as the arithmetic. :func:`repitch_foot` and :func:`fit_ankle_range` do the same
arithmetic, in the same order, in one compiled call (the same numbers, bit for bit:
tests/timeline/test_kernels.py compares them with the NumPy code they replace). World frame,
metres, radians; a foot's pitch + toes up.

The compiled rounds solve the leg IK's ankle flexion (:func:`_ankle_flex_row`: the arithmetic of
``ik.leg_ik_world_row`` up to it) and call the spread (``curves.spread_rows``): numba caches this
module's machine code by its own source, so change a comment here when those change (else a cached
copy keeps the old callees).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import gauss_kernel, maximum1, spread_rows
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.ik import hip_rel, ik_lengths
from mjwalk.body.legs.ikcache import LegIKCache, yaw_trig_row
from mjwalk.body.legs.stance import reach_deficit_kept
from mjwalk.body.legs.steps import FootTracks


def repitch_foot(
    ankle: np.ndarray,
    pitch: np.ndarray,
    toe: np.ndarray,
    fyaw: np.ndarray,
    ground: np.ndarray,
    prints: np.ndarray,
    dp: np.ndarray,
    geom: LegGeometry,
) -> tuple[np.ndarray, np.ndarray]:
    """A foot's ankle targets and pitches with the pitch lowered by ``dp``: on the floor
    (``ground``) about the pivot of its footprint (the heel while toes up, the ball while heel
    up, :func:`~mjwalk.body.legs.footpivot.pivot_ankle`), in the air by the same motion of the
    ankle relative to the foot, as if it stood on a footprint under it. New arrays; the
    inputs are not changed except ``toe``.

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        pitch: (n,) pitches, radians, + toes up.
        toe: (n,) toe angles, radians; updated in place (the toes keep their angle to the floor
            while the heel is up).
        fyaw: (n,) foot headings, radians from +x CCW.
        ground: (n,) bool, the foot on the floor.
        prints: (n, 3) the footprints it stands on.
        dp: (n,) the pitch decrease, radians.
        geom: the leg and foot lengths.

    Returns:
        the new ankle targets (n, 3) and pitches (n,).
    """
    ankle = np.array(ankle, dtype=float, order="C")
    pitch = np.array(pitch, dtype=float)
    _repitch_rows(
        ankle,
        pitch,
        toe,
        np.ascontiguousarray(fyaw, dtype=float),
        np.ascontiguousarray(ground, dtype=np.bool_),
        np.ascontiguousarray(prints, dtype=float),
        np.ascontiguousarray(dp, dtype=float),
        ball_offset(geom),
        geom.foot_back,
        geom.ankle_height,
    )
    return ankle, pitch


@njit
def _pivot_cs(x, y, fx, fy, c, s, p, ball, back, ah):
    """One row of :func:`~mjwalk.body.legs.footpivot.pivot_rows` (the same arithmetic) on
    the footprint at ``x``, ``y`` heading (``fx``, ``fy``) = (cos, sin) yaw, pitched by ``p``
    with (``c``, ``s``) = (cos, sin) p."""
    lever = ball if p <= 0 else -back
    along = lever * (c - 1) + ah * s
    return x - along * fx, y - along * fy, ah * c - lever * s


@njit
def _repitch_row(ankle, pitch, toe, i, grounded, px, py, cg, sg, cf, sf, c0, s0, p1, cp, sp,
                 ball, back, ah):  # fmt: skip
    """Row ``i`` of a repitch to ``p1`` (its cos ``cp`` and sin ``sp``; ``c0``, ``s0`` those of
    the pitch before) in place: a ``grounded`` foot about the pivot of its footprint at ``px``,
    ``py`` heading (``cg``, ``sg``), an airborne one by the pivot's motion on a footprint at
    the origin heading (``cf``, ``sf``) = the foot's heading, as NumPy's order; the toes keep
    their angle to the floor while the heel is up."""
    p0 = pitch[i]
    if grounded:
        a0, a1, a2 = _pivot_cs(px, py, cg, sg, cp, sp, p1, ball, back, ah)
        ankle[i, 0], ankle[i, 1], ankle[i, 2] = a0, a1, a2
    else:  # ankle + pivot(p1) - pivot(p0) on a footprint at the origin
        n0, n1, n2 = _pivot_cs(0.0, 0.0, cf, sf, cp, sp, p1, ball, back, ah)
        o0, o1, o2 = _pivot_cs(0.0, 0.0, cf, sf, c0, s0, p0, ball, back, ah)
        ankle[i, 0] = (ankle[i, 0] + n0) - o0
        ankle[i, 1] = (ankle[i, 1] + n1) - o1
        ankle[i, 2] = (ankle[i, 2] + n2) - o2
    toe[i] += min(p0, 0.0) - min(p1, 0.0)
    pitch[i] = p1


@njit
def _repitch_rows(ankle, pitch, toe, fyaw, ground, prints, dp, ball, back, ah):
    """:func:`repitch_foot` in place: ``ankle`` (n, 3), ``pitch`` and ``toe`` (n,)."""
    for i in range(ankle.shape[0]):
        p0 = pitch[i]
        p1 = p0 - dp[i]
        yaw = prints[i, 2]
        _repitch_row(
            ankle, pitch, toe, i, ground[i], prints[i, 0], prints[i, 1], math.cos(yaw),
            math.sin(yaw), math.cos(fyaw[i]), math.sin(fyaw[i]), math.cos(p0), math.sin(p0),
            p1, math.cos(p1), math.sin(p1), ball, back, ah,
        )  # fmt: skip


@dataclass(frozen=True)
class AnkleFit:
    """The bounds of the synthesis's ankle-range fit (:func:`fit_ankle_range`).

    Attributes:
        dorsi_max: the highest ankle flexion (dorsiflexion) of a grounded foot, radians.
        plantar_min: the lowest ankle flexion of a heel-up grounded foot, radians.
        win: half-width of the spread of a correction over the samples around (samples).
        rounds: the most rounds of corrections.
        tol: radians; the rounds stop once no grounded ankle is more than this past
            ``dorsi_max`` or short of ``plantar_min`` (0: until none is past them at all).
    """

    dorsi_max: float
    plantar_min: float
    win: int
    rounds: int
    tol: float = 0.0


def fit_ankle_range(
    ik: LegIKCache,
    feet: FootTracks,
    root: np.ndarray,
    yaw: np.ndarray,
    fit: AnkleFit,
) -> tuple[np.ndarray, np.ndarray] | None:
    """Up to ``fit.rounds`` rounds of the synthesis's ankle-range fit of one leg (its ``ik``
    cache): solve the leg (:meth:`LegIKCache.__call__`); a grounded foot whose ankle flexes
    past ``dorsi_max`` pitches down by 1.2 times the excess, one heel-up foot whose ankle
    extends past ``plantar_min`` lowers its heel by 1.2 times the shortfall (down to flat),
    both spread over +-``win`` samples (:func:`~mjwalk.body.legs.curves.spread`), by
    :func:`repitch_foot`; stop when no grounded ankle is more than ``fit.tol`` out of range.

    Args:
        ik: the leg's IK cache (its ``side`` selects the foot of ``feet``).
        feet: the feet's tracks over n samples; the ``ik.side`` foot's ``toe`` is updated in
            place, its ``ankle`` and ``pitch`` are not changed.
        root: (n, 3) pelvis position, metres, world frame.
        yaw: (n,) pelvis yaw, radians from +x CCW.
        fit: the ankle bounds (radians), spread window and rounds.

    Returns:
        the new ankle targets (n, 3, metres) and pitches (n,, radians), or None for walks
        shorter than the compiled spread handles (2 ``win`` + 2 samples): the caller runs the
        NumPy rounds.
    """
    s_, win = ik.side, fit.win
    n = len(feet.ankle[s_])
    if n < 2 * win + 2:
        return None
    inputs, out = ik.buffers(n)
    f_inputs, flex = ik.flex_buffers(n)
    key, vals = ik.trig_buffers(n)
    ankle = np.array(feet.ankle[s_], dtype=float, order="C")
    pitch = np.array(feet.pitch[s_], dtype=float)
    geom = ik.geom
    _fit_rounds(
        ankle,
        np.ascontiguousarray(feet.fyaw[s_], dtype=float),
        pitch,
        feet.toe[s_],
        np.ascontiguousarray(feet.ground[s_], dtype=np.bool_),
        np.ascontiguousarray(feet.prints[s_], dtype=float),
        np.ascontiguousarray(root, dtype=float),
        np.ascontiguousarray(yaw, dtype=float),
        1.0 if s_ == "l" else -1.0,
        float(geom.hip_y),
        *ik_lengths(geom),
        (inputs, out, f_inputs, flex, key, vals),
        float(fit.dorsi_max),
        float(fit.plantar_min),
        int(win),
        gauss_kernel(int(win)),
        ball_offset(geom),
        float(geom.foot_back),
        float(geom.ankle_height),
        int(fit.rounds),
        float(fit.tol),
    )
    return ankle, pitch


def fit_ankle_passes(
    ik: dict[str, LegIKCache],
    feet: FootTracks,
    xy: np.ndarray,
    z: np.ndarray,
    yaw: np.ndarray,
    reach_sq: dict[str, np.ndarray],
    fit: AnkleFit,
    passes: int,
) -> np.ndarray | None:
    """The synthesis's ankle fit of both legs with the pelvis lowered after each pass, in one
    compiled call: up to ``passes`` passes of :func:`fit_ankle_range` on the left leg, then
    the right, the pelvis at (``xy``, ``z``); then each grounded leg's reach deficit
    (``stance.reach_deficit``, the larger of the legs'); done when no deficit exceeds 1 mm,
    else the pelvis lowered by its spread (``curves.spread``) and another pass -- the numbers
    of that loop in Python (``synthesis._fit_ankles``), bit for bit.

    Args:
        ik: per side ("l"/"r") the leg's IK cache over the n samples (updated).
        feet: the feet's tracks; both feet's ``ankle`` and ``pitch`` are replaced by the
            fitted ones, their ``toe`` updated in place.
        xy: (n, 2) pelvis (x, y), metres, world frame.
        z: (n,) pelvis heights, metres (not changed).
        yaw: (n,) pelvis yaw, radians from +x CCW.
        reach_sq: per side the (n,) squared hip-to-ankle spans a grounded leg reaches, m².
        fit: the ankle bounds (radians), spread window and rounds per leg and pass.
        passes: the most passes.

    Returns:
        the lowered pelvis heights (n,), metres, or None for walks shorter than the compiled
        spread handles (2 ``win`` + 2 samples; nothing changed: the caller runs the loop).
    """
    n, win = len(z), fit.win
    if n < 2 * win + 2:
        return None
    geom = ik["l"].geom
    arr = lambda a: np.ascontiguousarray(a, dtype=float)  # noqa: E731
    ankle = {s_: np.array(feet.ankle[s_], dtype=float, order="C") for s_ in "lr"}
    pitch = {s_: np.array(feet.pitch[s_], dtype=float) for s_ in "lr"}
    legs = [
        (ankle[s_], arr(feet.fyaw[s_]), pitch[s_], feet.toe[s_],
         np.ascontiguousarray(feet.ground[s_], dtype=np.bool_), arr(feet.prints[s_]),
         arr(reach_sq[s_]), (*ik[s_].buffers(n), *ik[s_].flex_buffers(n), *ik[s_].trig_buffers(n)))
        for s_ in "lr"
    ]  # fmt: skip
    z = np.array(z, dtype=float)
    bounds = (float(fit.dorsi_max), float(fit.plantar_min), float(fit.tol))
    sole = (ball_offset(geom), float(geom.foot_back), float(geom.ankle_height))
    _fit_passes(
        legs[0], legs[1], arr(xy), z, arr(yaw), float(geom.hip_y), ik_lengths(geom), bounds,
        (int(win), int(fit.rounds)), gauss_kernel(int(win)), sole, int(passes),
    )  # fmt: skip
    for s_ in "lr":
        feet.ankle[s_], feet.pitch[s_] = ankle[s_], pitch[s_]
    return z


@njit
def _fit_leg(leg, root, yaw, sgn, hip_y, lengths, bounds, counts, kernel, sole):
    """One leg's :func:`_fit_rounds` (``leg``: ankle, foot yaw, pitch, toe, ground, prints,
    reach, IK caches) with the pelvis at ``root`` (n, 3)."""
    ankle, fyaw, pitch, toe, ground, prints, _, caches = leg
    L1, L2, rmin, rmax = lengths
    dorsi_max, plantar_min, tol = bounds
    win, rounds = counts
    ball, back, ah = sole
    _fit_rounds(ankle, fyaw, pitch, toe, ground, prints, root, yaw, sgn, hip_y, L1, L2, rmin, rmax,
                caches, dorsi_max, plantar_min, win, kernel, ball, back, ah, rounds,
                tol)  # fmt: skip


@njit
def _fit_passes(left, right, xy, z, yaw, hip_y, lengths, bounds, counts, kernel, sole, passes):
    """:func:`fit_ankle_passes` in place (the legs' ankles, pitches, toes and IK caches, the
    pelvis heights ``z``)."""
    n = z.shape[0]
    root = np.empty((n, 3))
    deficit = np.empty(n)
    need = np.empty(n)
    for _ in range(passes):
        for i in range(n):  # (np.column_stack([xy, z]))
            root[i, 0], root[i, 1], root[i, 2] = xy[i, 0], xy[i, 1], z[i]
        _fit_leg(left, root, yaw, 1.0, hip_y, lengths, bounds, counts, kernel, sole)
        _fit_leg(right, root, yaw, -1.0, hip_y, lengths, bounds, counts, kernel, sole)
        deficit[:] = 0.0
        # (the pelvis yaw's cosines and sines those the legs' IK caches keep)
        reach_deficit_kept(root, yaw, left[0], left[4], left[6], 1.0 * hip_y, left[7][4],
                           left[7][5], deficit)  # fmt: skip
        reach_deficit_kept(root, yaw, right[0], right[4], right[6], -1.0 * hip_y, right[7][4],
                           right[7][5], deficit)  # fmt: skip
        top, nan = -np.inf, False  # (NumPy's max: NaN if any)
        for i in range(n):
            if deficit[i] != deficit[i]:
                nan = True
            elif deficit[i] > top:
                top = deficit[i]
        if not nan and top <= 1e-3:
            break
        for i in range(n):
            need[i] = maximum1(deficit[i], 0.0)
        env = spread_rows(need, counts[0], kernel)
        for i in range(n):
            z[i] = z[i] - env[i]


@njit
def _fit_rounds(
    ankle,
    fyaw,
    pitch,
    toe,
    ground,
    prints,
    root,
    yaw,
    sgn,
    hip_y,
    L1,
    L2,
    rmin,
    rmax,
    caches,
    dorsi_max,
    plantar_min,
    win,
    kernel,
    ball,
    back,
    ah,
    rounds,
    tol,
):
    """The rounds of :func:`fit_ankle_range` in place (``ankle``, ``pitch``, ``toe``, the IK
    cache's ``caches``: its inputs and angles, its flexion-only inputs and flexions, its
    yaws' sines and cosines). Returns the number of rounds that corrected the pitches."""
    n = ankle.shape[0]
    inputs, out, f_inputs, flex_c, key, vals = caches
    need_down = np.empty(n)
    need_up = np.empty(n)
    # sines and cosines: of the foot headings, the footprints' headings (constant here) and
    # the pitches (c0, s0: before a round's repitch; cp, sp: after), taken at the first round
    # that corrects (nearly half the fits correct nothing: issue 50)
    cf = sf = cg = sg = c0 = s0 = cp = sp = need_down[:0]
    done = 0
    for _ in range(rounds):
        # (the grounded rows' ankle flexions only: the rounds read no other angle)
        _grounded_flex(ground, ankle, fyaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax,
                       inputs, out, f_inputs, flex_c, key, vals)  # fmt: skip
        e_max = -np.inf
        s_max = -np.inf
        for i in range(n):
            flex = flex_c[i]
            excess = flex - dorsi_max if ground[i] else 0.0
            short = plantar_min - flex if ground[i] and pitch[i] < 0 else 0.0
            e_max = max(e_max, excess)
            s_max = max(s_max, short)
            need_down[i] = 1.2 * max(excess, 0.0)
            need_up[i] = 1.2 * max(short, 0.0)
        if e_max <= tol and s_max <= tol:
            break
        if done == 0:  # (no pitch has changed yet: those of the walk's start)
            cf, sf = np.cos(fyaw), np.sin(fyaw)
            cg, sg = np.cos(prints[:, 2]), np.sin(prints[:, 2])
            c0, s0 = np.cos(pitch), np.sin(pitch)
            cp, sp = c0.copy(), s0.copy()
        done += 1
        down = spread_rows(need_down, win, kernel)
        up = spread_rows(need_up, win, kernel)
        for i in range(n):
            p0 = pitch[i]
            p1 = p0 - (down[i] - min(up[i], max(-p0, 0.0)))
            if p1 != p0:  # (the sines and cosines of unchanged pitches are kept)
                cp[i], sp[i] = math.cos(p1), math.sin(p1)
            _repitch_row(
                ankle, pitch, toe, i, ground[i], prints[i, 0], prints[i, 1], cg[i], sg[i],
                cf[i], sf[i], c0[i], s0[i], p1, cp[i], sp[i], ball, back, ah,
            )  # fmt: skip
            c0[i], s0[i] = cp[i], sp[i]
    return done


@njit
def _grounded_flex(ground, ankle, fyaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax, inputs,
                   out, f_inputs, flex, key, vals):  # fmt: skip
    """The ankle flexion ``flex`` (n,) of every grounded row (``ground``): from the IK cache
    (``inputs`` (n, 9), angles ``out`` (n, 6)) where a row's inputs are its, else from the
    flexion cache (``f_inputs`` (n, 9)) where they are that's, else solved
    (:func:`_ankle_flex_row`, with the yaws' sines and cosines ``key``, ``vals`` of
    :func:`~mjwalk.body.legs.ik.yaw_trig_row`); ``f_inputs`` and ``flex`` are updated, the IK
    cache's inputs and angles are not."""
    for i in range(ankle.shape[0]):
        if not ground[i]:
            continue
        row = (ankle[i, 0], ankle[i, 1], ankle[i, 2], fyaw[i], pitch[i], root[i, 0], root[i, 1],
               root[i, 2], yaw[i])  # fmt: skip
        in_ik, in_flex = True, True
        for k in range(9):
            if row[k] != inputs[i, k]:
                in_ik = False
            if row[k] != f_inputs[i, k]:
                in_flex = False
        if in_flex:
            continue
        for k in range(9):
            f_inputs[i, k] = row[k]
        if in_ik:
            flex[i] = out[i, 4]
        else:
            flex[i] = _ankle_flex_row(ankle, fyaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin,
                                      rmax, key, vals)  # fmt: skip


@njit
def _ankle_flex_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, key,
                    vals):  # fmt: skip
    """Row ``i``'s ankle flexion (radians) of ``ik.leg_ik_world_row``: its arithmetic, in its
    order, up to that angle (the rotation products of ``ik._mat3`` written out, zero terms
    kept, so the bits are the same), the yaws' sines and cosines kept per row
    (``ik.yaw_trig_row``'s ``key`` (n, 2) and ``vals`` (n, 7))."""
    cy, sy, c, sn, _, cz, sz = yaw_trig_row(foot_yaw, yaw, i, key, vals)
    u0, u1, u2 = hip_rel(ankle, root, i, sgn * hip_y, cy, sy, c, sn)
    pitch_f = pitch[i]
    cp, sp = math.cos(-pitch_f), math.sin(-pitch_f)
    # rf = R_z(yaw_f) R_y(-pitch_f), row-major: a = (cz, -sz, 0, sz, cz, 0, 0, 0, 1),
    # b = (cp, 0, sp, 0, 1, 0, -sp, 0, cp)
    msz = -sz
    msp = -sp
    rf0 = cz * cp + msz * 0.0 + 0.0 * msp
    rf1 = cz * 0.0 + msz * 1.0 + 0.0 * 0.0
    rf2 = cz * sp + msz * 0.0 + 0.0 * cp
    rf3 = sz * cp + cz * 0.0 + 0.0 * msp
    rf4 = sz * 0.0 + cz * 1.0 + 0.0 * 0.0
    rf5 = sz * sp + cz * 0.0 + 0.0 * cp
    rf6 = 0.0 * cp + 0.0 * 0.0 + 1.0 * msp
    rf7 = 0.0 * 0.0 + 0.0 * 1.0 + 1.0 * 0.0
    rf8 = 0.0 * sp + 0.0 * 0.0 + 1.0 * cp
    v0 = rf0 * u0 + rf3 * u1 + rf6 * u2  # R_f^T (ankle - hip)
    v1 = rf1 * u0 + rf4 * u1 + rf7 * u2
    v2 = rf2 * u0 + rf5 * u1 + rf8 * u2
    r = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    rc = min(max(r, rmin), rmax)
    ck = (rc**2 - L1**2 - L2**2) / (2 * L1 * L2)
    knee = math.acos(min(max(ck, -1.0), 1.0))
    m = math.hypot(v1, v2)
    a = math.atan2(L1 * math.sin(knee), L1 * math.cos(knee) + L2) - math.atan2(v0, m)
    w = np.fmod(a + math.pi, 2 * math.pi)  # np.mod(a + pi, 2 pi) - pi: into [-pi, pi)
    if w < 0.0:
        w += 2 * math.pi
    return w - math.pi
