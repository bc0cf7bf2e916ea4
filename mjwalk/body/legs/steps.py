"""A walk's steps as the leg synthesis sees them (:class:`StepFrames`: swing side, sample range,
lift-off, landing and stance footprints), and the per-step curves: the stance-leg angle
(paper §4.2.3, A8), the swing foot (§4.2.4, A9) and the landing pitch.

Step phase ``phi`` in [0, 1]: from lift-off of the swing foot's step to its landing; one step is
half a gait cycle. World frame, metres, radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import (
    clamped_cubic,
    maximum1,
    smoothstep,
    soft_clip01,
    soft_flat,
    soft_max,
)
from mjwalk.body.legs.footpivot import (
    ankle_kept_rows,
    ball_offset,
    heel_rise,
    pivot_ankle,
    pivot_rows,
)
from mjwalk.body.legs.ik import KNEE_MIN, ik_lengths, leg_ik_world_row
from mjwalk.body.legs.reference import ReferenceGait, heel_strike_ankle
from mjwalk.body.legs.swingthigh import reference_rows
from mjwalk.conventions import SAMPLE_RATE_HZ, side_prefix
from mjwalk.plan.walkpath import WalkPath

#: Stance key-frame phases (paper §4.2.3) and swing key-frame phases (§4.2.4).
STANCE_KEYS = (0.4, 0.5, 0.6)
SWING_KEYS = (0.2, 0.4, 0.6, 0.8, 0.9)
#: Toe-off phase of the step: double support lasts phi in [0, TOE_OFF] (10 % of the cycle).
TOE_OFF = 0.2
#: Step phase up to which the stance foot rolls down after heel strike (toes up or flat) and
#: from which its heel may rise (toes down): the first stance key frame, cycle 20 %, inside
#: the reference's foot-flat 8-40 % of the cycle.
FOOT_FLAT = STANCE_KEYS[0]
#: Step phase by which the swing foot has turned to its landing heading: the last swing key.
SWING_TURNED = SWING_KEYS[-1]
#: Share of the step after toe-off over which the swing foot's toes straighten (at least).
TOE_STRAIGHTEN = 0.25
#: Mean speed at which the swing foot's toes straighten (rad/s): the reference's 50 deg peak
#: heel rise (:mod:`~mjwalk.body.legs.reference`) undone over the initial swing, 60-73 % of
#: the cycle, at free-walking cadence 113 steps/min (Perry & Burnfield, "Gait Analysis",
#: 2nd ed., 2010): 50 deg in 0.138 s, ~362 deg/s. Toes bent further (up to
#: :data:`HEEL_RISE_MAX`) or a quicker step take longer than :data:`TOE_STRAIGHTEN`: no
#: faster (a 60 deg toe-off in a 0.48 s step straightened over 0.25 of it was 745 deg/s).
TOE_STRAIGHTEN_SPEED = np.deg2rad(50.0) / (0.13 * 120.0 / 113.0)
#: Half-width (share of the chord) of the rounded corner where the swing's chord progress
#: hands over from the toe-off ankle's going on to the reference's (:func:`soft_max`): the
#: larger of the two alone kinks the ankle's path there (a forward-speed jump of up to
#: 0.77 m/s within one 120 Hz sample in the gait-pose training walks, against 0.47 m/s at
#: most elsewhere after toe-off). The soft clamp's rounding of the chord's ends (0.1) halved;
#: a smoothing width, no measured figure.
PROGRESS_BLEND = 0.05
#: Highest heel rise of a foot rolling about its ball (radians, pitch toes down): 60 deg,
#: within the toes' 70 deg extension (ROM_DEG["toe"]); :func:`heel_rise`'s bound.
HEEL_RISE_MAX = np.deg2rad(60.0)


@dataclass
class StepFrames:
    """One step of a walk as the leg synthesis sees it (world frame, metres, radians).

    Attributes:
        side: the swing leg's joint-name letter ("l" / "r"); ``other`` the stance leg's.
        start, end: the walk's sample indices where the step begins and ends (inclusive).
        lift: (3,) the swing foot's lift-off footprint x, y, yaw.
        land: (3,) its landing footprint.
        stance: (3,) the stance foot's footprint.
        first, final: the walk's first / last step.
        land_p: the pitch the swing foot lands with (set by :func:`landing_pitches`).
        p_start: the stance pitch the previous step ended with (None on the first step).
        p_end: the stance pitch this step ends with (set by the synthesis).
    """

    side: str
    other: str
    start: int
    end: int
    lift: np.ndarray
    land: np.ndarray
    stance: np.ndarray
    first: bool
    final: bool
    land_p: float = 0.0
    p_start: float | None = None
    p_end: float | None = None


@dataclass(frozen=True)
class FootTracks:
    """Both feet's per-sample targets over a walk, as the leg synthesis builds them: each field
    maps a side's joint-name letter ("l"/"r") to an array over the walk's n samples (world
    frame, metres, radians). The dicts and arrays are shared with the caller: the functions
    that take a FootTracks update them in place where they say so.

    Attributes:
        ankle: (n, 3) ankle-joint targets.
        fyaw: (n,) foot headings, from +x CCW.
        pitch: (n,) foot pitch to the floor, + toes up.
        toe: (n,) toe-joint angle (+ flexion).
        ground: (n,) bool, the foot on the floor (pivoting on a footprint).
        prints: (n, 3) the footprint (x, y, yaw) it stands on where ``ground``.
    """

    ankle: dict[str, np.ndarray]
    fyaw: dict[str, np.ndarray]
    pitch: dict[str, np.ndarray]
    toe: dict[str, np.ndarray]
    ground: dict[str, np.ndarray]
    prints: dict[str, np.ndarray]


def step_frames(walk: WalkPath) -> list[StepFrames]:
    """Per step: swing side, lift-off and landing footprints, stance footprint. The first
    step lifts a foot mirrored beside the stance foot about the pelvis (standing start); the
    others lift the foot the previous step stood on.

    Args:
        walk: a WalkPath with steps.

    Returns:
        one :class:`StepFrames` per step, in order (``land_p`` not set yet).
    """
    steps = walk.steps
    frames = []
    for i, st in enumerate(steps):
        side = side_prefix(st.side)
        stance = np.asarray(st.stance, float)
        if i > 0:
            lift = np.asarray(steps[i - 1].stance, float)
        else:  # standing start: the swing foot beside the stance foot, mirrored about the pelvis
            y0 = walk.yaw[st.start]
            n = np.array([-np.sin(y0), np.cos(y0)])
            off = float((walk.xy[st.start] - stance[:2]) @ n)
            lift = np.array([*(stance[:2] + 2 * off * n), stance[2]])
        frames.append(
            StepFrames(
                side=side,
                other="r" if side == "l" else "l",
                start=st.start,
                end=st.end,
                lift=lift,
                land=np.asarray(st.foot, float),
                stance=stance,
                first=i == 0,
                final=i == len(steps) - 1,
            )
        )
    return frames


def landing_pitches(
    frames: list[StepFrames],
    xy,
    yaw,
    hs_pitch,
    d_land,
    dorsi_max,
    geom: LegGeometry,
    ref: ReferenceGait | None = None,
) -> None:
    """Per step (``frames``, in place: ``land_p``), the pitch the swing foot lands with: the
    reference's ``hs_pitch``, or flatter (down to 0) where the landing leg at its heel-strike
    length ``d_land`` under the pelvis of the landing sample would dorsiflex its ankle past
    ``dorsi_max`` (a foot landing under the hip), a walk's first step past ``ref``'s own
    heel-strike ankle if given (:func:`~.reference.heel_strike_ankle`: with the range's 19
    deg alone it landed at 16 deg against the steady 7.4, b3507ca). All steps at once; a few
    fixed-point rounds (compiled: :func:`_landing_rounds`).

    Args:
        frames: the walk's steps; their ``land_p`` is set.
        xy: (N, 2) the pelvis positions of the walk's samples, metres.
        yaw: (N,) the pelvis yaw, radians from +x CCW.
        hs_pitch: the reference's heel-strike pitch, radians, + toes up.
        d_land: the landing leg's hip-to-ankle distance, metres.
        dorsi_max: the highest ankle flexion, radians.
        geom: the leg lengths.
        ref: the reference gait whose heel-strike ankle bounds a first step's landing.
    """
    L1, L2, rmin, rmax = ik_lengths(geom)
    first = min(float(dorsi_max), heel_strike_ankle(ref)) if ref is not None else dorsi_max
    land_p = np.full(len(frames), float(hs_pitch))
    _landing_rounds(
        np.array([fr.end for fr in frames], dtype=np.int64),
        np.array([fr.land for fr in frames], dtype=float).reshape(-1, 3),
        np.array([1.0 if fr.side == "l" else -1.0 for fr in frames]),
        np.ascontiguousarray(xy, dtype=float),
        np.ascontiguousarray(yaw, dtype=float),
        float(d_land**2),
        np.array([first if fr.first else dorsi_max for fr in frames], dtype=float),
        float(geom.hip_y),
        L1,
        L2,
        rmin,
        rmax,
        ball_offset(geom),
        float(geom.foot_back),
        float(geom.ankle_height),
        land_p,
    )
    for fr, p in zip(frames, land_p, strict=True):
        fr.land_p = float(p)


@njit
def _landing_rounds(b, land, sgn, xy, yaw, d_land_sq, dorsi_max, hip_y, L1, L2, rmin, rmax,
                    ball, back, ah, land_p):  # fmt: skip
    """The rounds of :func:`landing_pitches` on ``land_p`` (m,), in place: per step (landing
    sample ``b``, footprint ``land`` (m, 3), ``sgn`` +1 left / -1 right) the landing ankle
    pivoted by its pitch, the pelvis height at which the leg spans ``d_land_sq`` (m²) to it
    from the hip of the upright pelvis (:func:`~.kinematics.hip_world` at height 0), and the
    leg IK's ankle flexion there (:func:`~.kinematics.leg_ik_world_row`); a foot whose
    ankle flexes past ``dorsi_max`` (m,) lands flatter by 1.2 times the excess (down to 0)."""
    m = b.shape[0]
    pos = np.empty((m, 3))
    root = np.empty((m, 3))
    yaw_b = np.empty(m)
    foot_yaw = land[:, 2].copy()
    out = np.empty((m, 6))
    for _ in range(4):
        pivot_rows(land, land_p, ball, back, ah, pos)
        for i in range(m):
            k = b[i]
            c = sgn[i] * hip_y
            dx = (xy[k, 0] + c * -math.sin(yaw[k])) - pos[i, 0]
            dy = (xy[k, 1] + c * math.cos(yaw[k])) - pos[i, 1]
            hz = math.sqrt(dx * dx + dy * dy)
            root[i, 0], root[i, 1] = xy[k, 0], xy[k, 1]
            root[i, 2] = pos[i, 2] + math.sqrt(maximum1(d_land_sq - hz * hz, 1e-6))
            yaw_b[i] = yaw[k]
            leg_ik_world_row(pos, foot_yaw, land_p, root, yaw_b, i, sgn[i], hip_y, L1, L2,
                              rmin, rmax, out)  # fmt: skip
        done = True
        for i in range(m):
            if out[i, 4] - dorsi_max[i] > 0 and land_p[i] > 0:
                done = False
        if done:
            break
        for i in range(m):
            over = out[i, 4] - dorsi_max[i]
            if over > 0:
                land_p[i] = maximum1(land_p[i] - 1.2 * over, 0.0)


def stance_angle(ref: ReferenceGait, name: str, phi, th0, v0, th1, v1) -> np.ndarray:
    """Stance-leg angle ``name`` at step phases ``phi``: the reference's own curve over cycle
    0-50 % plus a cubic-spline displacement that is zero at the key frames
    :data:`STANCE_KEYS` (so the angle coincides with the reference key-frame angles there)
    and meets the current posture's angle ``th0`` / velocity ``v0`` at ``phi = 0`` and the
    target posture's ``th1`` / ``v1`` at ``phi = 1``.

    Between the keys and the boundaries the result keeps the reference's shape (its loading
    response, say) instead of the bare cubic through five points, which cuts the reference's
    curves short (motion warping, Witkin & Popovic 1995, applied to the paper's spline).

    Args:
        ref: the reference gait.
        name: "hip", "knee" or "pitch".
        phi: step phases in [0, 1] (any shape).
        th0: the angle at ``phi = 0``, radians.
        v0: its velocity there, radians per unit phase.
        th1: the angle at ``phi = 1``, radians.
        v1: its velocity there, radians per unit phase.

    Returns:
        the angle, radians, the shape of ``phi``.
    """
    r0, r1 = float(ref(name, 0.0)), float(ref(name, 0.5))
    d0 = v0 - 0.5 * float(ref(name, 0.0, True))
    d1 = v1 - 0.5 * float(ref(name, 0.5, True))
    phi = np.asarray(phi, float)
    knots, values = [0.0, *STANCE_KEYS, 1.0], [th0 - r0, 0.0, 0.0, 0.0, th1 - r1]
    disp = clamped_cubic(knots, values, d0, d1, phi).reshape(phi.shape)
    return ref(name, 0.5 * phi) + disp


def _end_slopes(f: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The first and last rows of ``np.gradient(f, x, axis=0)`` (its first-order one-sided
    differences at the ends, the same arithmetic) for ``f`` (n, ...) sampled at ``x`` (n,),
    n >= 2, without the interior's central differences."""
    return np.stack([(f[1] - f[0]) / (x[1] - x[0]), (f[-1] - f[-2]) / (x[-1] - x[-2])])


@dataclass(frozen=True)
class _SwingStep:
    """The inputs of :func:`swing_foot` (its helpers share them)."""

    fr: StepFrames
    phi: np.ndarray
    idx: np.ndarray
    z_hip: np.ndarray
    hip_pos: Callable[..., np.ndarray]
    ref: ReferenceGait
    geom: LegGeometry
    land_p: float


def swing_foot(fr, phi, idx, z_hip, hip_pos, ref: ReferenceGait, geom: LegGeometry, land_p):
    """Swing foot over the step (A9) and the step phase of its toe-off: :data:`TOE_OFF`, or
    earlier where the pre-swing heel rise reaches :data:`HEEL_RISE_MAX` and the leg still
    cannot reach the foot with the reference knee (a trailing foot far behind its hip): the
    toes leave the floor there and the foot goes with the leg (held on the floor, the
    stretched leg's knee would straighten until toe-off, then flex to the swing's within a
    few samples).

    In the pre-swing the knee follows the reference and the heel rises as far as that needs
    (:func:`~.footpivot.heel_rise`), and at least as far as the reference's heel rise in
    proportion to how far the foot trails its hip (:func:`_trailing_rise`): the reference's
    foot-floor angle (Perry & Burnfield) is that of a foot the reference's distance behind the
    hip (0.25-0.36 m over the pre-swing at this stature), and from there on it applies whole
    (a normal stride, a stair: as before). A foot nearer under its hip (a short, closing or
    turning step) held to it whole flexes the knee past the reference's and swings the thigh
    forward: steady 0.25 m steps reached 35 deg hip flexion against the reference's 27 deg
    peak, and the last step of the station batch's run 307 (seed 0), from a foot under the
    hip, 39 deg, its knee 0.33 m out from the pelvis and into the car beside it. A foot under
    the hip keeps the pitch its step starts with. The share is linear in the distance: an
    ASSUMPTION, no measured figure; its direction is the literature's: joint excursions shrink
    at slow speeds and short steps, not grow (Fukuchi, Fukuchi & Duarte, "Effects of walking
    speed on gait biomechanics in healthy participants: a systematic review and
    meta-analysis", Syst. Rev. 8:153, 2019, abstract: the amplitude of joint kinematics
    decreases at slow speeds). A first step from standing rolls the same way (its roll faded
    in from flat, as far as the foot trails), and its heel rises further as far as the shank
    leans forward past its standing lean (:func:`~.footpivot.ankle_kept_rows`): in gait
    initiation the swing heel comes off the floor before the toes (the events "swing
    heel-off" and "swing toe-off" of gait-initiation studies). Lifted flat (879469c) the
    ankle dorsiflexed from its standing 5 deg to 12.3-12.6 at toe-off and 16 in early swing
    (synthetic first steps, ``benchmarks/bench_swing_ankle.py``); now 5.7 and 12.4.

    After toe-off the swing follows the reference from the current hip, and as far as the foot
    did not trail its hip at toe-off as the reference's (one minus that share) it hangs from
    the reference thigh, its knee and ankle following from where the foot is and the toe
    clearance it needs (:mod:`~.swingthigh`), and its progress along the step never falls
    further behind its hip than at toe-off. Before (e749e69) the reference ankle height and
    foot angle, measured from the hip, folded the leg of a foot from under its hip: every
    first step of the station's runs 0-19 reached 46.5 deg hip flexion median (50.4 max)
    against the reference's 27 deg peak; now 29.8 (31.2).

    Args:
        fr: the step (swing side, lift-off and landing footprints, first step, ``p_start``).
        phi: (n,) increasing step phases of the step's samples, 0 to 1.
        idx: (n,) the samples' indices into the walk (passed to ``hip_pos``).
        z_hip: (n,) the pelvis height, metres.
        hip_pos: ``hip_pos(idx, side, zz=None)``: the ``side`` hip's (x, y) (m, 2) at
            samples ``idx``, with the height ``zz`` as a third column if given, metres.
        ref: the reference gait.
        geom: the leg lengths.
        land_p: the pitch the foot lands with, radians, + toes up.

    Returns:
        ankle (n, 3, metres, world frame), pitch (n,), toe angle (n,), yaw (n,, from +x CCW),
        radians, and the toe-off step phase.
    """
    st = _SwingStep(fr, phi, idx, z_hip, hip_pos, ref, geom, land_p)
    lift, land = fr.lift, fr.land
    yaw = lift[2] + np.angle(np.exp(1j * (land[2] - lift[2]))) * smoothstep(
        (phi - TOE_OFF) / (SWING_TURNED - TOE_OFF)
    )
    pos = np.zeros((len(phi), 3))
    p = np.zeros(len(phi))
    early = phi <= TOE_OFF
    p[early] = _roll_pitch(fr, ref, phi[early])
    phi_to = TOE_OFF
    if fr.first:
        # from standing: the roll faded in, as far as the foot trails as the reference's
        je = np.flatnonzero(early)
        hip = hip_pos(idx[je], fr.side, z_hip[je])
        p[je], share = _trailing_rise(st, p[je], hip)
        p[je] = _ankle_kept(lift, hip, p[je], geom)
    else:
        # pre-swing: the knee follows the reference; the heel rises as far as that needs and
        # at least as the reference's does as far as the foot trails as its does (see above)
        je = np.flatnonzero(early)
        hip = hip_pos(idx[je], fr.side, z_hip[je])
        knee = np.maximum(ref("knee", 0.5 + 0.5 * phi[je]), float(KNEE_MIN))
        p0, share = _trailing_rise(st, p[je], hip)
        p[je] = heel_rise(lift, hip, knee, p0, geom, lo=-HEEL_RISE_MAX)
        held = np.flatnonzero(p[je] <= -HEEL_RISE_MAX + 1e-9)
        if len(held) and held[0] >= 1:  # (two samples on the floor give the lift-off velocity)
            phi_to = float(phi[je[held[0]]])
            early = phi <= phi_to
    pos[early] = pivot_ankle(lift, p[early], geom)
    late = ~early
    if late.any():
        # how far the swing departs from the reference's: as far as the foot did not trail
        # its hip as the reference's at toe-off (swingthigh.thigh_kept)
        _swing_path(st, pos, p, early, yaw, 1.0 - float(share[int(np.count_nonzero(early)) - 1]))
    # the toes stay flat during the roll-off, then straighten while the foot lifts
    p_end = p[early][-1] if early.any() else 0.0
    share = toe_straighten_share(p_end, (fr.end - fr.start) / SAMPLE_RATE_HZ, phi_to)
    toe = np.where(early, -p, -p_end * (1 - smoothstep((phi - phi_to) / share)))
    if late.any():
        _clear_floor(pos, p, toe, late, geom)
    return pos, p, toe, yaw, phi_to


@njit
def toe_straighten_share(p_end: float, duration: float, phi_to: float) -> float:
    """The share of the step over which the swing foot's toes straighten after toe-off:
    :data:`TOE_STRAIGHTEN`, or longer where that would straighten them faster than
    :data:`TOE_STRAIGHTEN_SPEED` on average; never past the landing.

    Args:
        p_end: the foot's pitch at toe-off, radians (toes down negative; the toes are bent
            by ``-p_end``).
        duration: the step's duration, seconds.
        phi_to: the step phase of the toe-off.

    Returns:
        the share of the step (step phase), positive.
    """
    need = abs(p_end) / (TOE_STRAIGHTEN_SPEED * max(duration, 1e-9))
    return max(min(max(TOE_STRAIGHTEN, need), 1.0 - phi_to), 1e-9)


def _ankle_kept(lift: np.ndarray, hip: np.ndarray, p: np.ndarray, geom: LegGeometry) -> np.ndarray:
    """The first step's pre-swing pitches ``p`` (m,) raised at the heel as far as the ankle
    would otherwise dorsiflex past its standing angle (:func:`~.footpivot.ankle_kept_rows`,
    ``hip`` (m, 3) the hip joint centres, metres)."""
    out = np.empty(len(p))
    ankle_kept_rows(np.asarray(lift, float), np.ascontiguousarray(hip, dtype=float),
                    np.ascontiguousarray(p, dtype=float), float(geom.thigh), float(geom.shank),
                    ball_offset(geom), float(geom.foot_back), float(geom.ankle_height),
                    -HEEL_RISE_MAX, out)  # fmt: skip
    return out


def _trailing_rise(st: _SwingStep, p: np.ndarray, hip: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pre-swing roll's pitches ``p`` (m,) (from :func:`_roll_pitch`) as far as the foot
    trails its hip ``hip`` (m, 3) as the reference's does: the reference's heel rise beyond
    the step's starting pitch in proportion to the foot's distance behind the hip along the
    step over the reference ankle's behind its hip at that instant, all of it from that
    distance on (see :func:`swing_foot`); and that share (m,), 0 to 1."""
    fr, ref, geom = st.fr, st.ref, st.geom
    lift, land = fr.lift, fr.land
    seg = land[:2] - lift[:2]
    seg_n = math.sqrt(max(float(seg @ seg), 1e-9))
    c = 0.5 + 0.5 * st.phi[: len(p)]
    hf, kf = ref("hip", c), ref("knee", c)
    behind = -(geom.thigh * np.sin(hf) + geom.shank * np.sin(hf - kf))
    trail = ((hip[:, 0] - lift[0]) * seg[0] + (hip[:, 1] - lift[1]) * seg[1]) / seg_n
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(behind > 0, np.minimum(np.maximum(trail / behind, 0.0), 1.0), 1.0)
    return np.where(share >= 1.0, p, p[0] + (p - p[0]) * share), share


def _roll_pitch(fr: StepFrames, ref: ReferenceGait, ph: np.ndarray) -> np.ndarray:
    """The swing foot's pitch (radians) rolling about its ball before toe-off, at step
    phases ``ph``: the reference's heel rise (toes down only, softly flat), faded in on a
    standing start, continuing the stance's extra heel rise otherwise (a later step takes
    only its start from it: :func:`swing_foot`)."""
    p = soft_flat(np.minimum(ref("pitch", 0.5 + 0.5 * ph), 0.0))
    if fr.first:
        p = p * smoothstep(ph / TOE_OFF)
    elif fr.p_start is not None:  # continue from the stance's extra heel rise
        p0 = soft_flat(np.minimum(ref("pitch", 0.5), 0.0))
        p = p + min(fr.p_start - p0, 0.0) * (1 - smoothstep(ph / TOE_OFF))
    return p


def _reference_swing(st: _SwingStep, jl: np.ndarray, yaw: np.ndarray, to: tuple):
    """The reference swing at samples ``jl`` after toe-off: the reference hip/knee angles of
    each gait-cycle instant placed at the current hip (forward progress and height), along
    the line from the lift-off to the landing footprint, never behind the toe-off ankle going
    on at its toe-off velocity nor further behind its hip than then (``to``: its phase,
    position (3,) and velocity (3,) per unit phase, the hip's (x, y) and the foot's yaw
    there); returns the ankle (m, 3) and the clipped reference pitch (m,)."""
    fr, phi, ref, geom = st.fr, st.phi, st.ref, st.geom
    L1, L2 = geom.thigh, geom.shank
    lift, land, sw = fr.lift, fr.land, fr.side
    c = 0.5 + 0.5 * phi[jl]
    hf, kf = ref("hip", c), ref("knee", c)
    fwd = L1 * np.sin(hf) + L2 * np.sin(hf - kf)
    heading = np.column_stack([np.cos(yaw[jl]), np.sin(yaw[jl])])
    hip = st.hip_pos(st.idx[jl], sw)
    target = hip + fwd[:, None] * heading
    seg = land[:2] - lift[:2]
    # progress along the chord, clamped to the footprints softly (C1): a hard clamp where
    # the reference passes the landing footprint (short steps) kinks the ankle's path; it
    # never decreases: on a step backward or across, the reference's forward reach along
    # the heading would carry the foot to the landing and back out towards its lift-off. Nor
    # is it ever behind the toe-off ankle's going on at its toe-off speed along the chord:
    # the heel rise of late stance has carried the ankle ahead of the lift-off footprint,
    # where the reference's own progress starts, and the foot would first swing back to it.
    # People's swing foot moves forward from toe-off to heel strike (Winter, "Foot trajectory
    # in human gait: a precise and multifactorial motor control task", Phys. Ther. 72(1),
    # 1992: its abstract gives a 0.87 m/s forward heel velocity even at heel contact; the
    # forward heel and toe trajectories through swing quoted from memory, not checked)
    seg_sq = max(float(seg @ seg), 1e-9)
    s = soft_clip01((target - lift[:2]) @ seg / seg_sq, 0.1)
    phi_to, a_to, v_to, hip_to, yaw_to, kept = to
    u_to = float((a_to[:2] - lift[:2]) @ seg) / seg_sq
    du_to = max(float(v_to[:2] @ seg) / seg_sq, 0.0)
    # nor does it fall further behind its hip than at toe-off: the reference's ankle comes
    # forward on its hip from toe-off to late swing (cycle 60-90 %), and a foot that started
    # under its hip (a first step, where the reference's own progress starts behind the
    # lift-off footprint) would otherwise hang there, its thigh flexing over it, and then
    # sweep the whole step at once
    f_to = (a_to[0] - hip_to[0]) * math.cos(yaw_to) + (a_to[1] - hip_to[1]) * math.sin(yaw_to)
    u_h = (
        (hip[:, 0] + f_to * heading[:, 0] - lift[0]) * seg[0]
        + (hip[:, 1] + f_to * heading[:, 1] - lift[1]) * seg[1]
    ) / seg_sq
    u_lin = u_to + du_to * (phi[jl] - phi_to)
    s_to = soft_clip01(np.maximum(u_lin, u_lin + kept * (u_h - u_lin)), 0.1)
    s = np.maximum.accumulate(soft_max(s, s_to, PROGRESS_BLEND))
    chord = lift[:2] + s[:, None] * seg
    # sideways, the foot swings under its hip: where the step turns, the hip's track bends
    # away from the chord (and from an inner corner the pelvis was planned clear of)
    nrm = np.array([-seg[1], seg[0]]) / max(float(np.linalg.norm(seg)), 1e-9)
    off = (hip - chord) @ nrm
    xy = chord + (off * np.sin(np.pi * s))[:, None] * nrm
    # the height: the reference leg's where the foot is at or behind the reference's ankle,
    # else the reference thigh with the shank turned forward to the foot (swingthigh.thigh_kept)
    f = (xy[:, 0] - hip[:, 0]) * heading[:, 0] + (xy[:, 1] - hip[:, 1]) * heading[:, 1]
    z, ref_pit = reference_rows(f, hf, kf, ref("pitch", c), st.z_hip[jl], L1, L2,
                                 float(KNEE_MIN), float(geom.foot_front),
                                 float(geom.ankle_height), kept)  # fmt: skip
    return np.column_stack([xy, z]), ref_pit


def _swing_path(st: _SwingStep, pos, p, early, yaw, kept: float) -> None:
    """The swing after toe-off into ``pos`` and ``p`` (in place, where not ``early``): the
    reference swing plus a clamped cubic-spline displacement through the key positions;
    ``kept`` (0 to 1) how far a foot ahead of the reference's ankle hangs from the reference
    thigh (:func:`~.swingthigh.thigh_kept`)."""
    phi, geom, late = st.phi, st.geom, ~early
    je = np.flatnonzero(early)[-2:]
    h = float(phi[je[1]] - phi[je[0]])
    p_to = p[je[::-1]]
    a0 = pos[je[::-1]]
    v0 = (a0[0] - a0[1]) / h
    jl = np.flatnonzero(late)
    hip_to = st.hip_pos(st.idx[je[1:]], st.fr.side)[0]
    to = (float(phi[je[1]]), a0[0], v0, hip_to, float(yaw[je[1]]), kept)
    ref_pos, ref_pit = _reference_swing(st, jl, yaw, to)
    # key positions at SWING_KEYS: the reference, lifted where the ankle would be lower
    # than standing height; the reference shape is kept between the keys and the
    # boundaries (lift-off state at toe-off, the landing pose with zero velocity) by a
    # cubic-spline displacement (as the stance angles, :func:`stance_angle`)
    knots, dpos, dpit = [float(phi[je[1]])], [a0[0]], [p_to[0]]
    for ph in SWING_KEYS[1:]:
        m = int(np.argmin(np.abs(phi[jl] - ph)))
        knots.append(float(phi[jl[m]]))
        key = ref_pos[m].copy()
        key[2] = max(key[2], geom.ankle_height)
        dpos.append(key)
        dpit.append(ref_pit[m])
    knots.append(1.0)
    dpos.append(pivot_ankle(st.fr.land, st.land_p, geom)[0])
    dpit.append(st.land_p)
    # the reference at the knots; the toe-off knot (the last pre-swing sample) lies before
    # the first swing sample: extrapolated linearly with the reference's velocity there (the
    # first sample's value would offset the whole reference by one sample's motion, and the
    # foot would move back by it right after toe-off)
    rk = np.column_stack([np.interp(knots, phi[jl], ref_pos[:, k]) for k in range(3)])
    rp = np.interp(knots, phi[jl], ref_pit)
    # (the reference's slopes at both ends: np.gradient's one-sided end differences)
    dr = _end_slopes(ref_pos, phi[jl]) if len(jl) > 1 else np.zeros((1, 3))
    dq = _end_slopes(ref_pit, phi[jl]) if len(jl) > 1 else np.zeros(1)
    lead = float(phi[jl[0]]) - knots[0]
    rk[0] -= lead * dr[0]
    rp[0] -= lead * dq[0]
    sp = clamped_cubic(knots, np.array(dpos) - rk, v0 - dr[0], -dr[-1], phi[late])
    dp0 = (p_to[0] - p_to[1]) / h
    spp = clamped_cubic(knots, np.array(dpit) - rp, dp0 - dq[0], -dq[-1], phi[late])
    pos[late], p[late] = ref_pos + sp, ref_pit + spp


def _clear_floor(pos, p, toe, late, geom: LegGeometry) -> None:
    """Keep heel, ball and toe tip off the floor after toe-off (lift the ankle ``pos`` where
    they would dip, in place)."""
    # the toe tip is on the toes, bent by the toe angle (flat on the floor at toe-off: a tip
    # rigid with the pitched foot would dip below it and jolt the ankle up)
    ah = geom.ankle_height
    pl, tl = p[late], toe[late]
    ball = ball_offset(geom)
    ball_z = ball * np.sin(pl) - ah * np.cos(pl)
    for tip in (
        -geom.foot_back * np.sin(pl) - ah * np.cos(pl),
        ball_z,
        ball_z + (geom.foot_front - ball) * np.sin(pl + tl),
    ):
        pos[late, 2] += np.maximum(0.0, -(pos[late, 2] + tip))
