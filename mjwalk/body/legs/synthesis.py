"""Legs from footprints (mocap-based DHM walking, §4.2 A8-A9): stance splines, swing splines, IK.

For every step of a :class:`~mjwalk.plan.walkpath.WalkPath` (one foot swings from its previous
footprint to ``step.foot`` while the other stands on ``step.stance``), with the step phase
``phi`` in [0, 1] from lift-off of the swing foot's step to its landing:

* **Stance leg (A8).** The stance knee follows a cubic spline through the reference key-frame
  angles at ``phi`` = 0.4, 0.5, 0.6 (they "change less against strides"), with the current
  posture's angle and velocity at ``phi = 0`` and the target posture's angle (both feet down at
  the next heel strike) and the reference velocity at ``phi = 1`` as boundary conditions. The
  pelvis height follows from the stance leg (knee angle, footprint, pelvis x, y): this is the
  pelvis height oscillation. It is capped where the swing leg could not reach its foot;
  over the last 20 % of the step the swing leg's length eases into its heel-strike length
  (zero velocity), so the knee does not snap straight at landing.
* **Swing leg (A9).** Until toe-off (``phi`` = 0.2, double support) the swing foot rolls about
  its ball (toes flat), its heel rising as far as the reference knee needs and as the
  reference's as far as the foot trails its hip as the reference's (a foot under the hip
  does not fold the leg forward: :func:`~.steps.swing_foot`); a trailing
  foot whose heel rise reaches its bound (60 deg) before that lifts off there (the leg could
  not reach it on the floor). Then the swing ankle follows a
  cubic spline through key positions at ``phi`` = 0.2, 0.4, 0.6, 0.8, 0.9: the reference
  hip/knee angles of that gait-cycle instant placed at the current hip (forward progress and
  height), kept on the line from the lift-off to the landing footprint, lifted where the foot
  would touch the floor; zero velocity at the landing (``phi = 1``), heel first. A foot that
  did not trail its hip as the reference's at toe-off (a first step, a short step) hangs from
  the reference thigh instead, as far as it did not (:mod:`~.swingthigh`).
* **Feet.** The foot pitch (toes up +) follows the reference: heel strike and roll-down about
  the heel, flat, heel rise and roll-off about the ball. Pivots stay put on the floor.
* **IK.** Hip (rotation, flexion, abduction), knee, ankle (flexion, inversion) from an analytic
  two-bone solution for the ankle position plus the foot orientation (yaw from the footprints,
  pitch as above, sole level sideways). Turning is taken by hip rotation: foot yaw minus pelvis
  yaw. All angles are clipped to the joint ranges.

Footprint convention: a footprint ``(x, y, yaw)`` is the point of the floor under the ankle joint
(the ``sole_*`` site of the humanoid) with the foot flat, and the foot's heading. World frame,
metres, radians. One step is half a gait cycle: the stance leg covers cycle 0-50 %, the swing
leg cycle 50-100 % (cycle 0 = heel strike of that leg).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mjwalk.body.humanoid import ROM_DEG, LegGeometry, leg_geometry
from mjwalk.body.legs.curves import spread
from mjwalk.body.legs.footpivot import pivot_ankle
from mjwalk.body.legs.ik import KNEE_MIN, LEG_JOINTS
from mjwalk.body.legs.ikcache import LegIKCache
from mjwalk.body.legs.legheights import lift_to_levels
from mjwalk.body.legs.pelvistilt import ascent_tilt, tilt_pelvis
from mjwalk.body.legs.pitchfit import AnkleFit, fit_ankle_passes, fit_ankle_range, repitch_foot
from mjwalk.body.legs.rampreach import BESIDE_KEY
from mjwalk.body.legs.reference import DEFAULT_REFERENCE, ReferenceGait
from mjwalk.body.legs.spin import spin_turns
from mjwalk.body.legs.stance import (
    KneeEnds,
    LandingEase,
    StanceLeg,
    bound_lowering,
    floor_reach_sq,
    pelvis_height,
    reach_deficit,
    stance_foot,
    stance_knee,
)
from mjwalk.body.legs.steps import (
    FootTracks,
    StepFrames,
    landing_pitches,
    step_frames,
    swing_foot,
)
from mjwalk.body.legs.swing import swing_foot as swing_foot_compiled
from mjwalk.body.legs.synthloop import SynthTracks, loop_consts, synth_steps
from mjwalk.body.legs.trunklean import ascent_lean
from mjwalk.boundedmemo import Memo
from mjwalk.conventions import DEFAULT_STATURE, side_of_prefix
from mjwalk.errors import PlanningError
from mjwalk.plan.walkpath import WalkPath

#: Corrections of a leg whose clipped joints would put the foot below the floor, and the depth
#: (m) a foot may reach (a flat, slightly inverted sole dips a millimetre or two at its edge).
FLOOR_ITERATIONS = 10
FLOOR_TOLERANCE = 2e-3

#: Grounded legs keep their knee flexed at least as the reference's at that instant of the
#: gait cycle, up to this many degrees (the pelvis lowers where they would not).
KNEE_SOFT = 10.0
KNEE_SOFT_RAD = float(np.deg2rad(KNEE_SOFT))  # (the same, radians)

#: The leg geometry per stature (a Python number, keyed by its type and value: the same lengths,
#: the same object, whose reference-derived numbers the reference keeps by geometry), at most
#: 64 statures; other statures get theirs made each time.
_GEOMS: Memo = Memo(limit=64)

#: Step phase from which the swing knee eases into the landing (the last swing key frame).
LAND_EASE = 0.8

#: Rounds of the ankle-range fit (pitch corrections and IK) per leg and pass.
ANKLE_ROUNDS = 8

#: Degrees a grounded ankle may stay past its fit bound when the ankle-range rounds stop. The
#: bounds sit 1 degree inside the joint's range, so an ankle left 0.01 degree past one is still
#: 0.99 degree inside it; and 0.01 degree is far below the precision joint angles are measured
#: with (McGinley et al. 2009, Gait & Posture 29:360-369, "The reliability of
#: three-dimensional kinematic gait measurements: a systematic review": errors of about 2
#: degrees or less judged acceptable -- that threshold quoted from memory). On 20 recorded
#: station walks the worst excess fell 0.085 -> 0.010 degree (median) by the fourth round and
#: the four rounds after moved it by less than that (issue 50, ankletol50).
ANKLE_TOL = 0.01

#: Whether a walk with a reference tabulated on the unit cycle has its steps synthesised in one
#: compiled call (:func:`~mjwalk.body.legs.synthloop.synth_steps`, bit for bit the numbers of
#: :func:`_synth_step`'s loop, which other references take); False: step by step (the tests
#: that pin the per-step kernels set it).
COMPILED_STEPS = True

#: Passes of the ankle fit of both legs, each followed by the pelvis lowered where a grounded
#: leg cannot reach its foot (:func:`_fit_ankles`).
FIT_PASSES = 4

#: Whether walks long enough for the compiled spread run :func:`_fit_ankles`' passes in one
#: compiled call (:func:`~mjwalk.body.legs.pitchfit.fit_ankle_passes`, bit for bit the numbers
#: of the loop); False: pass by pass in Python (the tests that compare the two set it).
COMPILED_FIT = True
#: Per side the leg's joint names in :data:`~mjwalk.body.legs.ik.LEG_JOINTS` order.
_LEG_NAMES = {s_: [k.format(s_) for k in LEG_JOINTS] for s_ in "lr"}


@dataclass
class LegMotion:
    """Per-sample leg motion for a WalkPath (same samples, 120 Hz), world frame.

    Attributes:
        t: (N,) sample times in seconds.
        root: (N, 3) pelvis (root) position, metres; z is the pelvis height above the floor.
        yaw: (N,) pelvis yaw, radians from +x CCW.
        angles: joint name (e.g. ``"knee_l"``) -> (N,) angle in radians, anatomical signs.
        ankle: side ("left"/"right") -> (N, 3) ankle target position, metres.
        pitch: side -> (N,) foot pitch to the floor, radians, + toes up.
        contact: (N,) contact state: 0 = left stance, 1 = right stance, 2 = double support.
        phase: (N,) step phase in [0, 1] (0 before the first / after the last step).
        meta: the stature, the reference's source, ``pelvis_lowering`` ((N,) metres: how far
            the pelvis stands below its gait's height over the stance surface, at most
            :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX`) and, for a walk lifted onto
            levels, ``edge_clearance`` (metres); up a stair ``pelvis_tilt`` and
            ``trunk_lean`` ((N,) radians, + forward: :mod:`~mjwalk.body.legs.pelvistilt`,
            :mod:`~mjwalk.body.legs.trunklean`).
    """

    t: np.ndarray
    root: np.ndarray
    yaw: np.ndarray
    angles: dict[str, np.ndarray]
    ankle: dict[str, np.ndarray]
    pitch: dict[str, np.ndarray]
    contact: np.ndarray
    phase: np.ndarray
    meta: dict = field(default_factory=dict)


def legs_from_walk(
    walk: WalkPath, stature: float = DEFAULT_STATURE, reference: ReferenceGait | None = None
) -> LegMotion:
    """Leg joint angles and root height for every sample of ``walk`` (paper §4.2 A8-A9).

    Args:
        walk: a WalkPath with steps (each with side, start/end sample, landing and stance foot).
        stature: the humanoid's stature in metres.
        reference: the reference gait (key frames); default :data:`DEFAULT_REFERENCE`.

    Returns:
        a :class:`LegMotion` on the walk's samples.
    """
    if not walk.steps:
        raise PlanningError(
            "legs_from_walk: the walk path has no steps (grid-A* paths have no gait; plan with "
            "the hybrid A* or add footprints)"
        )
    ref = reference or DEFAULT_REFERENCE
    geom = (
        _GEOMS.get((type(stature), stature), lambda: leg_geometry(stature))
        if isinstance(stature, float | int)
        else leg_geometry(stature)
    )
    n = len(walk.t)
    frames = step_frames(walk)
    for k, fr in enumerate(frames):
        if not (0 <= fr.start < fr.end < n):
            raise PlanningError(
                f"legs_from_walk: step {k} has sample range {fr.start}..{fr.end} outside "
                f"the path's {n} samples"
            )
    sy = _start(walk, ref, geom)
    landing_pitches(frames, sy.xy, sy.yaw, sy.hs_pitch, sy.d_land, sy.dorsi_max, geom, ref)
    if ref._unit and COMPILED_STEPS:  # all steps in one compiled call (the same numbers)
        _synth_compiled(sy, frames)
    else:
        knee_prev = None  # (angle, velocity per unit phase) of the next stance leg at landing
        for k in range(len(frames)):
            knee_prev = _synth_step(sy, frames, k, knee_prev)
    # where the pelvis turns further than a grounded foot's hip can rotate, the foot spins
    # about its ball; its next swing starts from the turned footprint
    # (the loops below re-solve only the samples changed since: the spin turns' grounded
    # samples are solved already)
    ik = {s_: LegIKCache(s_, geom) for s_ in "lr"}
    ik["l"].share_trig(ik["r"], sy.feet.fyaw["l"], sy.feet.fyaw["r"], sy.yaw)
    spin_turns(sy.feet, np.column_stack([sy.xy, sy.z]), sy.yaw, geom, ik)
    _hold_ends(sy, frames[0], frames[-1])
    win = max(3, round(0.05 * n / max(float(walk.t[-1] - walk.t[0]), 1e-9)))  # 50 ms
    z_gait = sy.z.copy()  # the gait's pelvis height over the stance surface
    _fit_ankles(sy, ik, win)
    root = np.column_stack([sy.xy, sy.z])
    angles = _clear_floor(sy, ik, root, win)
    feet = sy.feet
    # the whole lowering below it, bounded in one place (the lift onto levels adds its own)
    lowered = z_gait - sy.z
    meta = {"stature": stature, "reference": ref.source, "pelvis_lowering": lowered}
    # platforms, steps, stairs, ramps, a ramp's low end beside a floor walk (issue 47): the flat
    # legs lifted
    if not walk.is_flat or (walk.meta or {}).get(BESIDE_KEY):
        root, angles, meta["edge_clearance"] = lift_to_levels(
            walk, frames, feet, root, sy.yaw, geom, lowered
        )
        tilt = ascent_tilt(walk, n)  # the pelvis tilted back up a stair, the legs kept
        if tilt.any():
            angles, meta["pelvis_tilt"] = tilt_pelvis(angles, tilt), tilt
        lean = ascent_lean(walk, n)  # the trunk forward, in the spine (the timeline)
        if lean.any():
            meta["trunk_lean"] = lean
    else:
        bound_lowering(lowered, root)  # or raises
    return LegMotion(
        t=np.asarray(walk.t, float),
        root=root,
        yaw=sy.yaw,
        angles=angles,
        ankle={side_of_prefix(s_): v for s_, v in feet.ankle.items()},
        pitch={side_of_prefix(s_): v for s_, v in feet.pitch.items()},
        contact=sy.contact,
        phase=sy.phase,
        meta=meta,
    )


@dataclass
class _Synth:
    """The leg synthesis's state over a walk's n samples (world frame, metres, radians):
    the reference and leg geometry, the pelvis track (``xy`` (n, 2), ``yaw``, ``z`` (n,)),
    each hip's (x, y) per side, the feet's tracks, each leg's gait-cycle fraction ``cyc``
    (0 = heel strike), the contact state and step phase, and the ankle bounds and leg spans
    every step shares, and the compiled step loop's scalars (:func:`~.synthloop.loop_consts`;
    None for a reference not on the unit cycle)."""

    ref: ReferenceGait
    geom: LegGeometry
    xy: np.ndarray
    yaw: np.ndarray
    z: np.ndarray
    hip_xy: dict[str, np.ndarray]
    feet: FootTracks
    cyc: dict[str, np.ndarray]
    contact: np.ndarray
    phase: np.ndarray
    hs_pitch: float
    dorsi_max: float
    plantar_min: float
    d_land: float
    d_max_sq: float
    loop: np.ndarray | None

    def hip_pos(self, idx, side, zz=None):
        """The ``side`` hip's (x, y) at samples ``idx`` (indices or a slice: a view of
        ``hip_xy``, the same numbers), with the height ``zz`` as a third column if given."""
        h = self.hip_xy[side][idx]
        return h if zz is None else np.column_stack([h, zz])

    def knee_for(self, i: int, side: str, foot_pos, zz) -> float:
        """The knee flexion that puts the ankle ``foot_pos`` (3,) at the hip of sample ``i``
        with the pelvis at height ``zz``."""
        # |hip - ankle| as np.linalg.norm sums it, in Python floats (the same IEEE arithmetic
        # without array calls), the arccos NumPy's
        dx = float(self.hip_xy[side][i, 0]) - float(foot_pos[0])
        dy = float(self.hip_xy[side][i, 1]) - float(foot_pos[1])
        dz = float(zz) - float(foot_pos[2])
        span = np.array([math.sqrt(dx * dx + dy * dy + dz * dz)])
        return float(self.geom.knee_for_span(span)[0])

    def repitch(self, s_: str, dp: np.ndarray) -> None:
        """Lower the ``s_`` foot's pitch by ``dp`` (n,) radians, in place."""
        # on the floor about its footprint's pivot (the heel while toes up, the ball while heel
        # up), in the air by the same motion of the ankle relative to the foot, as if it stood
        # on a footprint under it (pivot_ankle is continuous through the flat foot: a pivot
        # switched by the pitch's sign would move an airborne ankle by centimetres where the
        # pitch crosses zero); the toes keep their angle to the floor while the heel is up
        # (compiled: pitchfit.repitch_foot)
        f = self.feet
        f.ankle[s_], f.pitch[s_] = repitch_foot(
            f.ankle[s_], f.pitch[s_], f.toe[s_], f.fyaw[s_], f.ground[s_], f.prints[s_], dp,
            self.geom,
        )  # fmt: skip


@dataclass(frozen=True)
class _WalkerConsts:
    """What the synthesis derives from the reference for one leg geometry (kept per
    reference and geometry: the same numbers for every walk of a walker): the heel-strike
    pitch (radians, >= 0), the landing leg's hip-to-ankle distance (m), the swing leg's
    longest one squared (m²) and the compiled step loop's scalars (None for a reference not
    on the unit cycle)."""

    hs_pitch: float
    d_land: float
    d_max_sq: float
    loop: np.ndarray | None


def _walker_consts(ref: ReferenceGait, geom: LegGeometry) -> _WalkerConsts:
    """:class:`_WalkerConsts` of ``ref`` for ``geom``, computed once per pair."""
    c = ref.per_geom.get(geom)
    if c is None:
        hs_pitch = max(0.0, float(ref("pitch", 0.0)))
        d_land = geom.span(max(ref("knee", 0.0), KNEE_MIN))
        d_max_sq = geom.span(KNEE_MIN) ** 2  # the swing leg's longest hip-to-ankle distance²
        loop = loop_consts(ref, geom, hs_pitch, d_land, d_max_sq) if ref._unit else None
        c = _WalkerConsts(hs_pitch, d_land, d_max_sq, loop)
        if len(ref.per_geom) < 64:
            ref.per_geom[geom] = c
    return c


def _start(walk: WalkPath, ref: ReferenceGait, geom: LegGeometry) -> _Synth:
    """The synthesis's state before the first step: empty tracks, the hips' (x, y), the
    ankle's range less a degree each way and the legs' landing and longest spans."""
    wc = _walker_consts(ref, geom)
    n = len(walk.t)
    xy = np.asarray(walk.xy, float)
    yaw = np.asarray(walk.yaw, float)
    # the sides' zeroed tracks as disjoint rows of a few blocks (fewer allocations, the same
    # zeros; "l" row 0, "r" row 1): ankle and prints, fyaw/pitch/toe/cyc, ground
    vec, flat, on = np.zeros((2, 2, n, 3)), np.zeros((4, 2, n)), np.zeros((2, n), bool)
    feet = FootTracks(
        ankle={"l": vec[0, 0], "r": vec[0, 1]},
        fyaw={"l": flat[0, 0], "r": flat[0, 1]},
        pitch={"l": flat[1, 0], "r": flat[1, 1]},
        toe={"l": flat[2, 0], "r": flat[2, 1]},
        ground={"l": on[0], "r": on[1]},  # foot on the floor (pivoting on a print)
        prints={"l": vec[1, 0], "r": vec[1, 1]},  # ... on this footprint
    )
    # each hip's offset from the pelvis centre (m) at every sample: (-sin, cos) of the yaw
    side_dir = np.empty((n, 2))
    side_dir[:, 0], side_dir[:, 1] = -np.sin(yaw), np.cos(yaw)
    z, contact = np.empty(n), np.empty(n, dtype=int)
    z.fill(np.nan)
    contact.fill(2)
    return _Synth(
        ref=ref,
        geom=geom,
        xy=xy,
        yaw=yaw,
        z=z,
        hip_xy={"l": xy + (1.0 * geom.hip_y) * side_dir, "r": xy + (-1.0 * geom.hip_y) * side_dir},
        feet=feet,
        cyc={"l": flat[3, 0], "r": flat[3, 1]},
        contact=contact,
        phase=np.zeros(n),
        hs_pitch=wc.hs_pitch,
        dorsi_max=np.deg2rad(ROM_DEG["ankle_flex"][1] - 1.0),
        plantar_min=np.deg2rad(ROM_DEG["ankle_flex"][0] + 1.0),
        d_land=wc.d_land,
        d_max_sq=wc.d_max_sq,
        loop=wc.loop,
    )


def _stance_leg(sy: _Synth, fr: StepFrames, phi: np.ndarray, land_prev: float | None):
    """The stance foot of step ``fr`` (A8): its pitch and ankle into the tracks; returns the
    pitch (n,), the ankle (n, 3) and the pelvis height at the target posture (m)."""
    # heel strike roll-down, flat, heel rise (reference pitch); the roll-down starts from the
    # pitch it landed with; a standing start is flat already.
    # Target posture at phi = 1 (A7): the landing leg at the reference heel-strike knee sets
    # the pelvis height; the trailing (stance) leg takes the reference knee of cycle 50 %,
    # its heel rising further (about the ball) if it cannot reach otherwise. The foot lands
    # toes up as the reference's, or flatter where the ankle's range does not allow that
    # pitch (a foot landing under the hip): rolled down on the floor after landing instead,
    # it would drop the ankle and jolt the knee
    ref, geom, f = sy.ref, sy.geom, sy.feet
    sw, st, b, ids = fr.side, fr.other, fr.end, slice(fr.start, fr.end + 1)
    c_st = 0.5 * phi
    land_pos = pivot_ankle(fr.land, fr.land_p, geom)  # the last step too: its pose is held
    # (|hip - landing ankle| in (x, y) as np.linalg.norm sums it, without array calls)
    dx, dy = sy.hip_xy[sw][b] - land_pos[0, :2]
    hz = np.sqrt(dx * dx + dy * dy)
    z_end = land_pos[0, 2] + np.sqrt(max(sy.d_land**2 - hz**2, 1e-6))
    hip_end = np.array([*sy.hip_xy[st][b], z_end])
    th1 = max(float(ref("knee", 0.5)), float(KNEE_MIN))
    p_st, ankle_st = stance_foot(
        fr, phi, ref("pitch", c_st), land_prev, sy.hs_pitch, hip_end, th1, geom
    )  # (compiled: stance.stance_foot)
    fr.p_end = float(p_st[-1])
    f.ankle[st][ids] = ankle_st
    f.ground[st][ids], f.prints[st][ids] = True, fr.stance
    f.pitch[st][ids], f.toe[st][ids], f.fyaw[st][ids] = p_st, -np.minimum(p_st, 0), fr.stance[2]
    return p_st, ankle_st, z_end


def _synth_step(sy: _Synth, frames: list[StepFrames], k: int, knee_prev):
    """Step ``k`` of ``frames`` into the tracks: stance foot and knee (A8), swing foot (A9),
    pelvis height; returns the landing knee's (angle, velocity per unit phase), which starts
    the next stance spline."""
    ref, geom, f, fr = sy.ref, sy.geom, sy.feet, frames[k]
    fr.p_start = frames[k - 1].p_end if k > 0 else None
    a, b = fr.start, fr.end
    idx = np.arange(a, b + 1)
    ids = slice(a, b + 1)  # the same samples, indexed without a copy
    phi = (idx - a) / (b - a)
    sy.phase[ids] = phi
    sy.cyc[fr.other][ids], sy.cyc[fr.side][ids] = 0.5 * phi, 0.5 + 0.5 * phi
    sw, st = fr.side, fr.other
    land_prev = frames[k - 1].land_p if k > 0 and sy.hs_pitch > 0 else None
    p_st, ankle_st, z_end = _stance_leg(sy, fr, phi, land_prev)
    th1 = sy.knee_for(b, st, ankle_st[-1], z_end)
    if knee_prev is None:
        th0, v0 = float(ref("knee", 0.0)), 0.5 * float(ref("knee", 0.0, True))
    else:
        th0, v0 = knee_prev
    v1 = 0.5 * float(ref("knee", 0.5, True))
    # the stance knee (steps.stance_angle, clipped) and the pelvis height it gives
    knee_st, z_flat = stance_knee(
        ref, phi, ref("knee", 0.5 * phi), KneeEnds(th0, v0, th1, v1), sy.hip_xy[st][ids],
        ankle_st, geom,
    )  # (compiled: stance.stance_knee)  # fmt: skip
    # --- swing foot (A9)
    if ref._unit:  # compiled (the same numbers); other tables through scipy's splines
        swing = swing_foot_compiled(fr, phi, sy.hip_xy[sw][ids], z_flat, ref, geom, fr.land_p)
    else:
        swing = swing_foot(fr, phi, idx, z_flat, sy.hip_pos, ref, geom, fr.land_p)
    pos, p_sw, toe_sw, yw, phi_to = swing
    sy.contact[ids] = np.where(phi <= phi_to, 2, 0 if st == "l" else 1)
    f.ankle[sw][ids], f.pitch[sw][ids], f.toe[sw][ids], f.fyaw[sw][ids] = pos, p_sw, toe_sw, yw
    pre_swing = idx[phi <= phi_to]
    f.ground[sw][pre_swing], f.prints[sw][pre_swing] = True, fr.lift
    # the pelvis height: capped where the swing leg could not reach its foot; landing
    # approach: from LAND_EASE the swing leg's hip-to-ankle distance eases into its
    # heel-strike length (zero velocity) along a cubic from its length and velocity
    # there, and the pelvis height follows from it. Capping the pelvis only where the
    # swing leg is fully stretched would snap the knee straight (near full extension a
    # millimetre of leg length is several degrees of knee). The trailing leg keeps its
    # planned knee where the pelvis now rises faster: its heel rises further (about the
    # ball) instead of the leg stretching straight (compiled: stance.pelvis_height)
    sy.z[ids], ankle_up = pelvis_height(
        phi, z_flat, pos, sy.hip_xy[sw][ids], StanceLeg(sy.hip_xy[st][ids], knee_st, p_st), fr,
        LandingEase(sy.d_max_sq, sy.d_land, LAND_EASE), geom,
    )  # fmt: skip
    if ankle_up is not None:
        fr.p_end = float(p_st[-1])
        f.ankle[st][ids] = ankle_up
        f.pitch[st][ids], f.toe[st][ids] = p_st, -np.minimum(p_st, 0)
    # the swing leg's knee at landing starts the next stance spline; its velocity is the
    # reference's (loading response: the knee flexes right after heel strike)
    return (sy.knee_for(b, sw, pos[-1], sy.z[b]), 0.5 * float(ref("knee", 0.0, True)))


def _synth_compiled(sy: _Synth, frames: list[StepFrames]) -> None:
    """Every step of ``frames`` into the tracks of ``sy`` as :func:`_synth_step`'s loop does,
    in one compiled call (:func:`~mjwalk.body.legs.synthloop.synth_steps`; ``sy.ref._unit``)."""
    f = sy.feet
    c = sy.loop  # (loop_consts, kept per reference and geometry)
    assert c is not None
    pair = lambda d: (d["l"], d["r"])  # noqa: E731
    out = SynthTracks(
        ankle=pair(f.ankle), fyaw=pair(f.fyaw), pitch=pair(f.pitch), toe=pair(f.toe),
        ground=pair(f.ground), prints=pair(f.prints), cyc=pair(sy.cyc), contact=sy.contact,
        phase=sy.phase, z=sy.z,
    )  # fmt: skip
    synth_steps(frames, pair(sy.hip_xy), sy.ref._ppoly, c, LAND_EASE, out)


def _hold_ends(sy: _Synth, first: StepFrames, last: StepFrames) -> None:
    """Before the first step: stand on both feet; after the last: hold the final pose."""
    f, n = sy.feet, len(sy.z)
    pre = np.arange(0, first.start)
    if len(pre):
        for s_, fp in ((first.side, first.lift), (first.other, first.stance)):
            f.ankle[s_][pre] = [fp[0], fp[1], sy.geom.ankle_height]
            f.fyaw[s_][pre] = fp[2]
        sy.z[pre] = sy.z[first.start]
    post = np.arange(last.end + 1, n)
    if len(post):
        e = last.end
        for arr in (*f.ankle.values(), *f.fyaw.values(), *f.pitch.values(), *f.toe.values(), sy.z):
            arr[post] = arr[e]
        sy.contact[post] = 2


def _fit_ankles(sy: _Synth, ik: dict[str, LegIKCache], win: int) -> None:
    """Keep the grounded ankles in their range by pitching the feet, and lower the pelvis
    where a grounded leg then cannot reach its foot (up to :data:`FIT_PASSES` passes), in
    place."""
    ref, geom, f = sy.ref, sy.geom, sy.feet
    # (m²) with the reference's knees, at least KNEE_MIN, at most KNEE_SOFT (compiled)
    reach_sq = {s_: floor_reach_sq(ref, sy.cyc[s_], KNEE_SOFT_RAD, geom) for s_ in "lr"}
    bounds = AnkleFit(sy.dorsi_max, sy.plantar_min, win, ANKLE_ROUNDS, np.deg2rad(ANKLE_TOL))
    if COMPILED_FIT:  # the passes below in one compiled call (the same numbers)
        z = fit_ankle_passes(ik, f, sy.xy, sy.z, sy.yaw, reach_sq, bounds, FIT_PASSES)
        if z is not None:
            sy.z = z
            return
    for _ in range(FIT_PASSES):
        root = np.column_stack([sy.xy, sy.z])
        for s_ in "lr":
            # a grounded foot whose ankle would dorsiflex past its range pitches down
            # instead: a toes-up foot rolls down about its heel, a flat one onto its ball
            # (heel rise), so the sole keeps its place on the floor (clipping the ankle would
            # sink the toes). Likewise a heel-up foot whose ankle would plantarflex past its
            # range lowers its heel about the ball, down to flat (a stance foot ahead of the
            # hip: clipped, the foot would turn about the ankle and its ball slide), and the
            # pelvis lowers below. The roll is spread over the samples around (in the air
            # too, about the same point), so a landing or lift-off does not jolt the leg
            # (compiled: pitchfit.fit_ankle_range; the rounds below for very short walks)
            fit = fit_ankle_range(ik[s_], f, root, sy.yaw, bounds)
            if fit is not None:
                f.ankle[s_], f.pitch[s_] = fit
                continue
            _fit_ankle_rounds(sy, ik[s_], root, win)
        # rolling a heel-strike foot down (or turning it about the ball) lowers its ankle:
        # where a grounded leg then cannot reach its foot with the knee flexed at least as
        # the reference's (up to KNEE_SOFT), the pelvis lowers (smoothly). Near full
        # extension a millimetre of leg length is several degrees of knee: a leg stretched
        # straight by the pelvis would flick its knee
        # (compiled: stance.reach_deficit)
        deficit = reach_deficit(root, sy.yaw, f.ankle, f.ground, reach_sq, geom)
        if deficit.max() <= 1e-3:
            break
        sy.z = sy.z - spread(np.maximum(deficit, 0.0), win)


def _fit_ankle_rounds(sy: _Synth, ik: LegIKCache, root: np.ndarray, win: int) -> None:
    """:func:`~mjwalk.body.legs.pitchfit.fit_ankle_range`'s rounds in NumPy, for walks too
    short for the compiled spread (in place)."""
    f, s_ = sy.feet, ik.side
    tol = np.deg2rad(ANKLE_TOL)
    for _ in range(ANKLE_ROUNDS):
        raw = ik(f.ankle[s_], f.fyaw[s_], f.pitch[s_], root, sy.yaw)
        flex = raw[f"ankle_{s_}_flex"]
        excess = np.where(f.ground[s_], flex - sy.dorsi_max, 0.0)
        short = np.where(f.ground[s_] & (f.pitch[s_] < 0), sy.plantar_min - flex, 0.0)
        if excess.max() <= tol and short.max() <= tol:
            break
        down = spread(1.2 * np.maximum(excess, 0.0), win)
        up = spread(1.2 * np.maximum(short, 0.0), win)
        sy.repitch(s_, down - np.minimum(up, np.maximum(-f.pitch[s_], 0.0)))


def _clear_floor(
    sy: _Synth, ik: dict[str, LegIKCache], root: np.ndarray, win: int
) -> dict[str, np.ndarray]:
    """The legs' joint angles, clipped to their ranges, with each foot kept above
    -:data:`FLOOR_TOLERANCE` (ankle targets lifted or feet pitched down, in place)."""
    f = sy.feet
    angles: dict[str, np.ndarray] = {}
    for s_ in "lr":
        names = _LEG_NAMES[s_]
        # where the joint ranges still keep the foot from its target (a trailing foot too far
        # behind for the hip's extension, say), the clipped leg would put the sole below the
        # floor: lift the ankle target by the depth (or, where the ankle is at its
        # dorsiflexion limit and lifting would tilt the toes down further, pitch the foot
        # down) and solve again, so the foot stays above -FLOOR_TOLERANCE by construction
        # (compiled: the IK, the clipped angles and the foot's lowest point in one call,
        # LegIKCache.floor_round)
        for _ in range(FLOOR_ITERATIONS):
            q, low = ik[s_].floor_round(
                f.ankle[s_], f.fyaw[s_], f.pitch[s_], f.toe[s_], root, sy.yaw
            )
            ang = dict(zip(names, q, strict=True))
            bad = low < -FLOOR_TOLERANCE
            if not bad.any():
                break
            # (both spread over the samples around, as above)
            raw = ik[s_].out  # the round's unclipped angles
            assert raw is not None
            excess = raw[:, 4] - sy.dorsi_max  # (the ankle flexion)
            tilt = bad & (excess > 0)
            if tilt.any():
                sy.repitch(s_, spread(np.where(tilt, 1.2 * excess, 0.0), win))
            lift = bad & ~tilt
            f.ankle[s_][:, 2] += spread(np.where(lift, -low, 0.0), win)
        angles.update(ang)
    return angles
