"""The stance leg of one step, compiled (paper §4.2.3, A8): the stance foot's pitch and ankle
(:func:`stance_foot`) and the stance knee with the pelvis height it gives (:func:`stance_knee`).

They were a few dozen NumPy operations per step on its few dozen samples, as
:func:`~mjwalk.body.legs.synthesis.legs_from_walk`'s loop over the steps, whose call overhead
cost more than their arithmetic. Here the same arithmetic runs in the same order in one
compiled call each (the same numbers, bit for bit: ``tests/timeline/test_kernels.py`` compares them
with that NumPy code on walks). The reference gait's values come in as arrays (any reference
table); the knee for a hip-to-ankle span (an arccos) and powers of NumPy scalars stay with the
caller, as compiled code rounds them differently from NumPy here.

Step phase ``phi`` in [0, 1] from lift-off of the swing foot's step to its landing; the stance
leg covers gait cycle 0-50 %. World frame, metres, radians; a foot's pitch + toes up.

numba caches this module's machine code by its own source, not by the compiled functions it
calls from other modules (``footpivot.heel_rise_rows``, ``footpivot.pivot_rows``,
``curves.clamped_cubic_rows`` and the one-value shapes such as ``curves.smoothstep1``): change a
comment here when those change.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit, njit_inline
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import (
    FLAT,
    clamped_cubic_rows,
    maximum1,
    minimum1,
    smoothstep1,
    soft_flat1,
    spread,
)
from mjwalk.body.legs.footpivot import ball_offset, heel_rise_rows, pivot_rows
from mjwalk.body.legs.ik import KNEE_MIN
from mjwalk.body.legs.ikcache import clip1
from mjwalk.body.legs.reference import ReferenceGait, ppoly_at
from mjwalk.body.legs.steps import FOOT_FLAT, STANCE_KEYS, StepFrames
from mjwalk.errors import PlanningError

#: The stance knee's upper bound (radians, 80 deg): the synthesis's clip of the stance spline.
KNEE_STANCE_MAX = float(np.deg2rad(80))
#: :func:`~mjwalk.body.legs.footpivot.heel_rise`'s default lowest pitch (radians).
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
    """The stance foot's pitch and ankle over a step: heel-strike roll-down, flat, heel rise
    after the reference, and the heel rising further (about the ball) towards the end where
    the leg with ``knee_end`` flexion would not reach the hip at the target posture.

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

    Returns:
        the pitch (n,), radians, + toes up, and the ankle (n, 3), metres, world frame.
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
        np.asarray(fr.stance, float).reshape(1, 3),
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
def _stance_foot(phi, p_ref, scaled, land_prev, hs_pitch, first, stance2, hip_end, span0, span1,
                 knee_end, ball, back, ah, p, ankle):  # fmt: skip
    """:func:`stance_foot` into ``p`` (n,) and ``ankle`` (n, 3); ``span0 + span1 cos knee`` the
    squared hip-to-ankle span (:meth:`LegGeometry.span`); ``stance2`` the footprint as a
    (1, 3) row (no reshape in compiled code: its error path compiles slowly)."""
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
    heel_rise_rows(stance2[0], hip_end, d, p[n - 1 : n].copy(), ball, back, ah, HEEL_RISE_LO, rise)
    last = p[n - 1]
    for i in range(n):
        p[i] = p[i] + (rise[0] - last) * smoothstep1((phi[i] - FOOT_FLAT) / (1.0 - FOOT_FLAT))
    pivot_rows(stance2, p, ball, back, ah, ankle)


@dataclass(frozen=True)
class KneeEnds:
    """The stance knee spline's boundary conditions (:func:`stance_knee`).

    Attributes:
        th0: the knee flexion at step phase 0 (the current posture), radians.
        v0: its velocity there, radians per unit step phase.
        th1: the knee flexion at step phase 1 (the target posture), radians.
        v1: its velocity there, radians per unit step phase.
    """

    th0: float
    v0: float
    th1: float
    v1: float


def stance_knee(
    ref: ReferenceGait,
    phi: np.ndarray,
    k_ref: np.ndarray,
    ends: KneeEnds,
    hip_xy: np.ndarray,
    ankle: np.ndarray,
    geom: LegGeometry,
) -> tuple[np.ndarray, np.ndarray]:
    """The stance knee over a step and the pelvis height it gives.

    The knee is :func:`~mjwalk.body.legs.steps.stance_angle`'s: the reference knee ``k_ref``
    at gait cycle ``0.5 phi`` plus a clamped cubic-spline displacement, zero at
    :data:`~mjwalk.body.legs.steps.STANCE_KEYS`, meeting ``ends`` at ``phi = 0`` and 1;
    clipped to [:data:`KNEE_MIN`, :data:`KNEE_STANCE_MAX`]. The pelvis height is
    :math:`z = a_z + \\sqrt{\\max(s(k)^2 - h^2, 10^{-6})}` with :math:`s(k)` the leg's
    hip-to-ankle span at knee :math:`k` and :math:`h` the horizontal hip-to-ankle distance.

    Args:
        ref: the reference gait (its knee curve and velocities).
        phi: (n,) step phases in [0, 1].
        k_ref: (n,) the reference knee at gait cycle ``0.5 phi``, radians.
        ends: the spline's boundary angles and velocities.
        hip_xy: (n, 2) the stance hip's (x, y), metres, world frame.
        ankle: (n, 3) the stance ankle, metres, world frame.
        geom: the leg lengths.

    Returns:
        the knee flexion (n,, radians) and the pelvis height (n,, metres).
    """
    th0, v0, th1, v1 = ends.th0, ends.v0, ends.th1, ends.v1
    r0, r1 = float(ref("knee", 0.0)), float(ref("knee", 0.5))
    d0 = v0 - 0.5 * float(ref("knee", 0.0, True))
    d1 = v1 - 0.5 * float(ref("knee", 0.5, True))
    values = np.array([[th0 - r0], [0.0], [0.0], [0.0], [th1 - r1]])
    L1, L2 = float(geom.thigh), float(geom.shank)
    n = len(phi)
    knee, z = np.empty(n), np.empty(n)
    _stance_knee(
        _KNOTS,
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
def _stance_knee(knots, phi, k_ref, values, d0, d1, hip_xy, ankle, span0, span1, knee, z):
    """:func:`stance_knee` into ``knee`` and ``z`` (n,); ``knots`` :data:`_KNOTS` (an argument:
    a global array is a read-only type, for which ``clamped_cubic_rows`` would compile again)."""
    disp = clamped_cubic_rows(knots, values, d0, d1, phi)
    for i in range(phi.shape[0]):
        k = min(max(k_ref[i] + disp[i, 0], KNEE_MIN), KNEE_STANCE_MAX)
        knee[i] = k
        dx, dy = hip_xy[i, 0] - ankle[i, 0], hip_xy[i, 1] - ankle[i, 1]
        h = math.sqrt(dx * dx + dy * dy)
        s = math.sqrt(span0 + span1 * math.cos(k))
        z[i] = ankle[i, 2] + math.sqrt(maximum1(s * s - h * h, 1e-6))


@dataclass(frozen=True)
class StanceLeg:
    """The stance leg over a step's n samples, as :func:`pelvis_height` needs it.

    Attributes:
        hip_xy: (n, 2) the stance hip's (x, y), metres, world frame.
        knee: (n,) the stance knee flexion, radians.
        pitch: (n,) the stance foot's pitch, radians, + toes up (:func:`pelvis_height` updates
            it in place).
    """

    hip_xy: np.ndarray
    knee: np.ndarray
    pitch: np.ndarray


@dataclass(frozen=True)
class LandingEase:
    """The swing leg's reach during a walk (:func:`pelvis_height`).

    Attributes:
        d_max_sq: the swing leg's longest hip-to-ankle distance, squared (m²).
        d_land: its hip-to-ankle distance at heel strike (m).
        ease_from: the step phase from which the leg eases into ``d_land``.
    """

    d_max_sq: float
    d_land: float
    ease_from: float


def pelvis_height(
    phi: np.ndarray,
    z_flat: np.ndarray,
    ankle_sw: np.ndarray,
    hip_sw: np.ndarray,
    stance: StanceLeg,
    fr: StepFrames,
    ease: LandingEase,
    geom: LegGeometry,
) -> tuple[np.ndarray, np.ndarray | None]:
    """The pelvis height over a step: the stance leg's ``z_flat``, capped where the swing leg
    could not reach its foot at its longest span (``ease.d_max_sq``); from step phase
    ``ease.ease_from`` (at least three samples, not the first) the swing leg's hip-to-ankle
    distance eases into its heel-strike length ``ease.d_land`` (zero velocity) along a cubic
    from its length and velocity there, and the pelvis height follows from it. Where the
    pelvis then rises, the trailing (stance) leg keeps its knee: its heel rises further about
    the ball of its footprint.

    Args:
        phi: (n,) step phases in [0, 1].
        z_flat: (n,) the pelvis height the stance leg gives (:func:`stance_knee`), metres.
        ankle_sw: (n, 3) the swing ankle, metres, world frame.
        hip_sw: (n, 2) the swing hip's (x, y), metres, world frame.
        stance: the stance leg; its ``pitch`` is updated in place where the heel rises.
        fr: the step (its stance footprint).
        ease: the swing leg's longest and landing spans and the ease's start phase.
        geom: the leg lengths.

    Returns:
        the pelvis height (n,, metres) and the stance ankle (n, 3, metres) for the new
        pitches where the landing eased, else None.
    """
    hip_st, knee_st, p_st = stance.hip_xy, stance.knee, stance.pitch
    d_max_sq, d_land, ease_from = ease.d_max_sq, ease.d_land, ease.ease_from
    lj = np.flatnonzero(phi >= ease_from)
    easing = len(lj) >= 3 and lj[0] > 0
    j = int(lj[0]) if easing else -1
    # u³ by NumPy (its power rounds unlike a compiled one)
    u3 = ((phi[lj] - phi[j]) / (1.0 - phi[j])) ** 3 if easing else np.empty(0)
    L1, L2 = float(geom.thigh), float(geom.shank)
    n = len(phi)
    z, ankle = np.empty(n), np.empty((n, 3))
    eased = _pelvis_height(
        np.ascontiguousarray(phi, dtype=float),
        np.ascontiguousarray(z_flat, dtype=float),
        np.ascontiguousarray(ankle_sw, dtype=float),
        np.ascontiguousarray(hip_sw, dtype=float),
        np.ascontiguousarray(hip_st, dtype=float),
        np.ascontiguousarray(knee_st, dtype=float),
        p_st,
        np.asarray(fr.stance, float).reshape(1, 3),
        float(d_max_sq),
        float(d_land),
        j,
        u3,
        L1**2 + L2**2,
        2 * L1 * L2,
        ball_offset(geom),
        float(geom.foot_back),
        float(geom.ankle_height),
        z,
        ankle,
    )
    return z, (ankle if eased else None)


@njit
def _pelvis_height(phi, z_flat, ankle_sw, hip_sw, hip_st, knee_st, p_st, stance2, d_max_sq,
                   d_land, j, u3, span0, span1, ball, back, ah, z, ankle):  # fmt: skip
    """:func:`pelvis_height` into ``z`` (n,), and ``p_st`` and ``ankle`` (n, 3) where the
    landing eases (samples ``j`` on, ``u3`` (n - j,) the cubed phase within the ease);
    returns whether it did (``j >= 1``). ``stance2``: the stance footprint as a (1, 3) row."""
    n = phi.shape[0]
    z_sw = np.empty(n)
    for i in range(n):
        dx, dy = hip_sw[i, 0] - ankle_sw[i, 0], hip_sw[i, 1] - ankle_sw[i, 1]
        h = math.sqrt(dx * dx + dy * dy)
        z_sw[i] = ankle_sw[i, 2] + math.sqrt(maximum1(d_max_sq - h * h, 1e-6))
        z[i] = minimum1(z_flat[i], z_sw[i])
    if j < 1:
        return False
    dj = np.empty(2)
    for r in range(2):
        i = j - 1 + r
        dx = hip_sw[i, 0] - ankle_sw[i, 0]
        dy = hip_sw[i, 1] - ankle_sw[i, 1]
        dz = z[i] - ankle_sw[i, 2]
        dj[r] = math.sqrt(dx * dx + dy * dy + dz * dz)
    span, gap = 1.0 - phi[j], d_land - dj[1]
    m0 = span * (dj[1] - dj[0]) / (phi[j] - phi[j - 1])
    g3 = 3 * gap
    lo = g3 if g3 < 0.0 else 0.0  # Python's min(0.0, 3 gap), max(0.0, 3 gap)
    hi = g3 if g3 > 0.0 else 0.0
    m0 = min(max(m0, lo), hi)
    m = n - j
    hip = np.empty((m, 3))
    d = np.empty(m)
    p0 = np.empty(m)
    for k in range(m):
        i = j + k
        u = (phi[i] - phi[j]) / span
        d_prof = dj[1] + (u3[k] - 2 * (u * u) + u) * m0 + (3 * (u * u) - 2 * u3[k]) * gap
        dx, dy = hip_sw[i, 0] - ankle_sw[i, 0], hip_sw[i, 1] - ankle_sw[i, 1]
        h = math.sqrt(dx * dx + dy * dy)
        z_prof = ankle_sw[i, 2] + math.sqrt(maximum1(d_prof * d_prof - h * h, 1e-6))
        z[i] = minimum1(z_prof, z_sw[i])
        hip[k, 0], hip[k, 1], hip[k, 2] = hip_st[i, 0], hip_st[i, 1], z[i]
        d[k] = math.sqrt(span0 + span1 * math.cos(knee_st[i]))
        p0[k] = minimum1(p_st[i], 0.0)
    p_up = np.empty(m)
    heel_rise_rows(stance2[0], hip, d, p0, ball, back, ah, HEEL_RISE_LO, p_up)
    for k in range(m):
        if p_st[j + k] <= 0:
            p_st[j + k] = p_up[k]
    pivot_rows(stance2, p_st, ball, back, ah, ankle)
    return True


def reach_deficit(
    root: np.ndarray,
    yaw: np.ndarray,
    ankle: dict[str, np.ndarray],
    ground: dict[str, np.ndarray],
    reach_sq: dict[str, np.ndarray],
    geom: LegGeometry,
) -> np.ndarray:
    """How far the pelvis stands above the height from which each grounded leg reaches its
    ankle with a given span: the larger of the legs' deficits, 0 where neither is grounded or
    the grounded legs reach.

    Args:
        root: (n, 3) pelvis positions, metres, world frame.
        yaw: (n,) pelvis yaw, radians from +x CCW.
        ankle: per side ("l"/"r") the (n, 3) ankle targets, metres.
        ground: per side the (n,) bool foot-on-the-floor flags.
        reach_sq: per side the (n,) squared hip-to-ankle spans, m².
        geom: the leg geometry (``hip_y``).

    Returns:
        (n,) the deficit, metres (>= 0).
    """
    out = np.zeros(len(yaw))
    for s_ in "lr":
        _reach_deficit(
            np.ascontiguousarray(root, dtype=float),
            np.ascontiguousarray(yaw, dtype=float),
            np.ascontiguousarray(ankle[s_], dtype=float),
            np.ascontiguousarray(ground[s_], dtype=np.bool_),
            np.ascontiguousarray(reach_sq[s_], dtype=float),
            (1.0 if s_ == "l" else -1.0) * float(geom.hip_y),
            out,
        )
    return out


#: The most (metres) the pelvis may be lowered below its level so that a grounded leg reaches
#: its foot: 5 cm, the whole vertical travel of the body's centre in a level stride (about 2 in,
#: Saunders, Inman & Eberhart 1953, J Bone Joint Surg 35-A: 543-558; quoted from memory, not
#: checked against the paper here). A walk that needs more asks a leg for what no walking step
#: does (the platform cycle's run 14: a 120 degree turn in one step onto a ramp, the pelvis
#: lowered 0.21 m, the feet through the floor): an error of its planning, raised rather than
#: animated.
REACH_DROP_MAX = 0.05


def bound_lowering(lowering: np.ndarray, root: np.ndarray) -> float:
    """The whole lowering of the pelvis below its gait's height over the stance surface,
    bounded: the one check of :data:`REACH_DROP_MAX` (the flat synthesis's ankle fit and the
    lift onto the levels add theirs; :func:`~mjwalk.body.legs.synthesis.legs_from_walk`).

    On a level the gait's height is the flat synthesis's pelvis over the stance foot's
    surface; on a stair it follows the stance tread, and down a stair its controlled lowering
    (the stance knee flexing a riser in late single support, McFadyen & Winter 1988) is the
    gait's own, not a lowering (:func:`~mjwalk.body.legs.legheights.level_tracks`).

    Args:
        lowering: (n,) how far the pelvis stands below that height, metres (>= 0 where
            lowered).
        root: (n, 3) the pelvis positions, metres, world frame (for the error's place).

    Returns:
        The largest lowering, metres (>= 0).

    Raises:
        PlanningError: the lowering exceeds :data:`REACH_DROP_MAX` (one line naming the walk
            point).
    """
    drop = float(lowering.max(initial=0.0))  # (np.max's reduction, without its wrapper)
    if drop > REACH_DROP_MAX:
        i = int(np.argmax(lowering))
        raise PlanningError(
            f"the legs reach their feet only with the pelvis {drop:.3f} m lowered at "
            f"({root[i, 0]:.2f}, {root[i, 1]:.2f}), more than {REACH_DROP_MAX} m: the walk's "
            "steps there are no walking steps"
        )
    return drop


def lower_to_reach(root, yaw: np.ndarray, ankle: dict, ground: dict, reach_sq: dict,
                   geom: LegGeometry, win: int,
                   before: np.ndarray | None = None) -> float:  # fmt: skip
    """Lower the pelvis (smoothly, in place) where a grounded leg cannot reach its ankle
    (:func:`reach_deficit`, up to 4 passes).

    Args:
        root: (n, 3) pelvis positions, metres, world frame (z lowered in place).
        yaw: (n,) pelvis yaw, radians from +x CCW.
        ankle: per side ("l"/"r") the (n, 3) ankle targets, metres.
        ground: per side the (n,) bool foot-on-the-floor flags.
        reach_sq: per side the (n,) squared hip-to-ankle spans, m².
        geom: the leg geometry.
        win: the smoothing window, samples (:func:`~mjwalk.body.legs.curves.spread`).
        before: (n,) the lowering ``root`` already has (metres; the flat synthesis's), this
            one added to it in place and the sum bounded; None: none.

    Returns:
        The largest whole lowering, metres (>= 0).

    Raises:
        PlanningError: the whole lowering exceeds :data:`REACH_DROP_MAX`
            (:func:`bound_lowering`).
    """
    z0 = root[:, 2].copy()
    for _ in range(4):
        deficit = reach_deficit(root, yaw, ankle, ground, reach_sq, geom)
        if deficit.max() <= 1e-3:
            break
        root[:, 2] -= spread(np.maximum(deficit, 0.0) + 2e-3, win)
    own = z0 - root[:, 2]
    if before is None:
        return bound_lowering(own, root)
    before += own
    return bound_lowering(before, root)


@njit
def _reach_deficit(root, yaw, ankle, ground, reach_sq, c, out):
    """One leg's part of :func:`reach_deficit`, folded into ``out`` (n,) by ``np.maximum``:
    the hip ``c`` metres to the pelvis's left (:func:`~.kinematics.hip_world`), the height
    above the ankle at which the leg spans ``reach_sq``, the pelvis height above that."""
    for i in range(yaw.shape[0]):
        _deficit_row(root, ankle, ground, reach_sq, c, i, math.cos(yaw[i]), math.sin(yaw[i]), out)


@njit
def _reach_deficit_kept(root, yaw, ankle, ground, reach_sq, c, key, vals, out):
    """:func:`_reach_deficit` with the pelvis yaw's cosine and sine read from an IK cache's
    kept ones (``ikcache.yaw_trig_row``'s ``key`` (n, 2), ``vals`` (n, 7)) where the row's
    yaw is the one kept (to the bit), else taken: the same numbers."""
    for i in range(yaw.shape[0]):
        y = yaw[i]
        if y == key[i, 0] and math.copysign(1.0, y) == math.copysign(1.0, key[i, 0]):
            cy, sy = vals[i, 0], vals[i, 1]
        else:
            cy, sy = math.cos(y), math.sin(y)
        _deficit_row(root, ankle, ground, reach_sq, c, i, cy, sy, out)


@njit_inline
def _deficit_row(root, ankle, ground, reach_sq, c, i, cy, sy, out):
    """Row ``i`` of :func:`_reach_deficit`, the pelvis yaw's cosine ``cy`` and sine ``sy``
    given."""
    dx = (root[i, 0] + c * -sy) - ankle[i, 0]
    dy = (root[i, 1] + c * cy) - ankle[i, 1]
    h = math.sqrt(dx * dx + dy * dy)
    cap = ankle[i, 2] + math.sqrt(maximum1(reach_sq[i] - h * h, 0.0))
    out[i] = maximum1(out[i], root[i, 2] - cap if ground[i] else 0.0)


def floor_reach_sq(ref: ReferenceGait, cyc: np.ndarray, knee_hi: float, geom: LegGeometry):
    """The squared hip-to-ankle spans (n,), m², of a leg whose knee is flexed as the
    reference's at the gait-cycle fractions ``cyc`` (n,), clipped to :data:`KNEE_MIN` ..
    ``knee_hi`` radians: ``geom.span(np.clip(ref("knee", cyc), KNEE_MIN, knee_hi)) ** 2``, its
    arithmetic in its order in one compiled call (reference tables on the unit cycle; others
    take that NumPy expression).

    Args:
        ref: the reference gait.
        cyc: (n,) gait-cycle fractions (wrapped onto [0, 1)).
        knee_hi: the knee's upper bound, radians.
        geom: the leg lengths.

    Returns:
        (n,) the squared spans, m².
    """
    if not ref._unit:
        return geom.span(np.clip(ref("knee", cyc), KNEE_MIN, knee_hi)) ** 2
    L1, L2 = geom.thigh, geom.shank
    coef, knots = ref._ppoly["knee"]
    out = np.empty(len(cyc))
    _floor_reach_sq(np.ascontiguousarray(cyc, dtype=float), coef, knots, float(KNEE_MIN),
                    float(knee_hi), float(L1**2 + L2**2), float(2 * L1 * L2), out)  # fmt: skip
    return out


@njit
def _floor_reach_sq(cyc, coef, knots, lo, hi, c0, c1, out):
    """:func:`floor_reach_sq` per row: the reference knee (``reference.ppoly_at`` at
    ``cyc % 1``, as ``np.mod``), clipped as ``np.clip`` clips, the span
    ``sqrt(c0 + c1 cos(knee))`` (``c0`` = L1² + L2², ``c1`` = 2 L1 L2) squared."""
    for i in range(cyc.shape[0]):
        k = clip1(ppoly_at(coef, knots, cyc[i] % 1.0, 0), lo, hi)
        d = np.sqrt(c0 + c1 * np.cos(k))
        out[i] = d * d


#: The compiled kernels of :func:`stance_foot`, :func:`stance_knee` and :func:`pelvis_height`
#: and the stance spline's knots, for callers that run a walk's steps in one compiled loop
#: (:mod:`~mjwalk.body.legs.synthloop`), and the reach-deficit kernel (the yaws' sines kept) for
#: the compiled ankle-fit passes (:func:`~mjwalk.body.legs.pitchfit.fit_ankle_passes`).
stance_foot_rows, stance_knee_rows, pelvis_height_rows = _stance_foot, _stance_knee, _pelvis_height
reach_deficit_kept = _reach_deficit_kept
STANCE_KNOTS = _KNOTS
