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
  its ball (toes flat). Then the swing ankle follows a cubic spline through key positions at
  ``phi`` = 0.2, 0.4, 0.6, 0.8, 0.9: the reference hip/knee angles of that gait-cycle instant
  placed at the current hip (forward progress and height), kept on the line from the lift-off
  to the landing footprint, lifted where the foot would touch the floor; zero velocity at the
  landing (``phi = 1``), heel first.
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

import itertools
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.ndimage import gaussian_filter1d, maximum_filter1d

from mjwalk.body.humanoid import ROM_DEG, LegGeometry, leg_geometry
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import CaptureError, PlanningError
from mjwalk.plan.walkpath import WalkPath

#: Literature reference gait (:data:`DEFAULT_REFERENCE`): sagittal angles in degrees
#: every 5 % of the gait cycle, 0 % = heel strike. ``hip``: thigh flexion, ``knee``: knee
#: flexion, after D. A. Winter, "The Biomechanics and Motor Control of Human Gait: Normal,
#: Elderly and Pathological", 2nd ed. (1991), natural cadence ensemble averages (read off the
#: figures, rounded to the degree): knee ~3 deg at heel strike, ~18 deg loading response,
#: ~60-63 deg peak swing; hip +30 to -10 deg. ``pitch``: foot angle to the floor (+ toes up),
#: after the foot-floor angles in J. Perry & J. M. Burnfield, "Gait Analysis: Normal and
#: Pathological Function", 2nd ed. (2010): ~20 deg at heel strike, foot flat ~8-40 %, toe-off
#: at ~60 % with ~35-40 deg, rounded.
WINTER_GAIT = {
    "cycle": np.arange(0, 101, 5) / 100.0,
    "hip": [30, 29, 27, 24, 20, 15, 10, 5, 0, -4, -8, -9, -5, 3, 12, 20, 26, 30, 32, 31, 30],
    "knee": [3, 10, 16, 19, 18, 15, 11, 7, 5, 6, 10, 20, 35, 50, 60, 63, 57, 42, 25, 10, 3],
    "pitch": [20, 8, 0, 0, 0, 0, 0, 0, 0, -3, -10, -22, -38, -50, -45, -30, -15, -3, 8, 17, 20],
}

#: Stance key-frame phases (paper §4.2.3) and swing key-frame phases (§4.2.4).
STANCE_KEYS = (0.4, 0.5, 0.6)
SWING_KEYS = (0.2, 0.4, 0.6, 0.8, 0.9)
#: Toe-off phase of the step: double support lasts phi in [0, TOE_OFF] (10 % of the cycle).
TOE_OFF = 0.2
#: Pitches smaller than this (degrees) count as a flat foot (no roll, so no drift).
FLAT_DEG = 2.0
#: Corrections of a leg whose clipped joints would put the foot below the floor, and the depth
#: (m) a foot may reach (a flat, slightly inverted sole dips a millimetre or two at its edge).
FLOOR_ITERATIONS = 10
FLOOR_TOLERANCE = 2e-3
#: Grounded legs keep their knee flexed at least as the reference's at that instant of the
#: gait cycle, up to this many degrees (the pelvis lowers where they would not).
KNEE_SOFT = 10.0
#: Step phase from which the swing knee eases into the landing (the last swing key frame).
LAND_EASE = 0.8
#: Smallest knee flexion the IK uses when a leg must stretch (radians): never lock the knee.
KNEE_MIN = np.deg2rad(2.0)
#: Spin turns (degrees): a grounded foot whose hip would rotate past its range less
#: ``SPIN_MARGIN`` turns about its ball by the excess (softly: from ``SPIN_SOFT`` before that),
#: its heel raised ``SPIN_HEEL`` over the last ``SPIN_RAMP`` of hip rotation before the turn.
SPIN_MARGIN, SPIN_SOFT, SPIN_HEEL, SPIN_RAMP = 2.0, 4.0, 4.0, 6.0

LEG_JOINTS = (
    "hip_{}_rot",
    "hip_{}_flex",
    "hip_{}_abd",
    "knee_{}",
    "ankle_{}_flex",
    "ankle_{}_inv",
    "toe_{}",
)


@dataclass(frozen=True)
class ReferenceGait:
    """One gait cycle of sagittal reference angles (the "gait DB" of the paper).

    Attributes:
        cycle: (M,) increasing cycle fractions from 0 (heel strike) to 1 (next heel strike).
        hip: (M,) thigh flexion from the vertical in the walking plane, radians (+ knee ahead).
        knee: (M,) knee flexion, radians.
        pitch: (M,) foot angle to the floor, radians, + toes up.
        source: where the numbers come from.
    """

    cycle: np.ndarray
    hip: np.ndarray
    knee: np.ndarray
    pitch: np.ndarray
    source: str = ""

    def __post_init__(self) -> None:
        sp = {}
        for k in ("hip", "knee", "pitch"):
            v = np.asarray(getattr(self, k), float).copy()
            v[-1] = v[0]  # periodic
            sp[k] = CubicSpline(np.asarray(self.cycle, float), v, bc_type="periodic")
        object.__setattr__(self, "_splines", sp)

    def __call__(self, name: str, cycle, derivative: bool = False) -> np.ndarray:
        """Angle ``name`` ("hip", "knee", "pitch") in radians at cycle fraction(s) (wrapped);
        ``derivative=True`` gives radians per unit cycle."""
        c = np.mod(cycle, 1.0)
        sp = self._splines[name]
        return sp(c, 1) if derivative else sp(c)


def winter_reference() -> ReferenceGait:
    """The default reference gait :data:`WINTER_GAIT` (literature values, radians)."""
    g = WINTER_GAIT
    return ReferenceGait(
        cycle=g["cycle"],
        hip=np.deg2rad(g["hip"]),
        knee=np.deg2rad(g["knee"]),
        pitch=np.deg2rad(g["pitch"]),
        source="Winter 1991 (hip, knee); Perry & Burnfield 2010 (foot-floor angle)",
    )


#: Landmarks of a straight-walk gait cycle calibrated on real capture, for :func:`warp_reference`:
#: per angle, pairs ((cycle %, deg) on :data:`WINTER_GAIT`, (cycle %, deg) in the calibrated gait)
#: at the gait events and extrema (heel strike, loading-response peak, mid-stance, push-off
#: minimum, toe-off, swing peak, late swing). Target figures: bandai-walk (Kobayashi et al.
#: 2023, CC BY-NC 4.0), ``dataset-2_walk_normal_001..003``, left leg, mean of 13 gait cycles
#: by :func:`gait_cycles` (heel strike = toes-up pitch peak), read off and rounded to the
#: percent and degree. This actor walks with more knee flexion in stance than Winter's
#: ensemble (34 vs 19 deg at the loading-response peak, 17 vs 5 deg at mid-stance).
BANDAI_LANDMARKS = {
    "hip": [
        ((0, 30), (0, 22)),
        ((5, 29), (11, 29)),
        ((30, 10), (30, 11)),
        ((55, -9), (57, -10)),
        ((90, 32), (85, 27)),
        ((100, 30), (100, 22)),
    ],
    "knee": [
        ((0, 3), (0, 1)),
        ((15, 19), (18, 34)),
        ((40, 5), (44, 17)),
        ((60, 35), (60, 35)),
        ((75, 63), (75, 70)),
        ((90, 25), (90, 29)),
        ((100, 3), (100, 1)),
    ],
    "pitch": [
        ((0, 20), (0, 28)),
        ((10, 0), (12, 0)),
        ((40, 0), (40, 0)),
        ((65, -50), (69, -69)),
        ((80, -15), (80, -42)),
        ((100, 20), (100, 28)),
    ],
}


def warp_reference(
    landmarks: dict, base: ReferenceGait | None = None, source: str = "", n: int = 101
) -> ReferenceGait:
    """A reference gait generated from ``base`` (default :func:`winter_reference`) warped onto
    landmark figures, so a gait can be calibrated on a few numbers rather than copied.

    Args:
        landmarks: angle name ("hip", "knee", "pitch") -> increasing list of pairs
            ``((base cycle %, base deg), (cycle %, deg))``, the first at 0 % and the last at
            100 %. Time is warped piecewise linearly between the landmarks; between two
            landmarks the base curve is scaled affinely so its landmark values map onto the
            targets (the base's shape is kept on every segment).
        base: the gait whose shapes are warped.
        source: where the landmark figures come from.
        n: samples per cycle of the result.

    Returns:
        the warped :class:`ReferenceGait` (radians).
    """
    base = base or _WINTER
    x = np.linspace(0.0, 100.0, n)
    out = {}
    for name in ("hip", "knee", "pitch"):
        lm = np.asarray(landmarks[name], float)  # (K, 2, 2)
        src, dst = lm[:, 0], lm[:, 1]
        if not (np.all(np.diff(dst[:, 0]) > 0) and np.all(np.diff(src[:, 0]) > 0)):
            raise ValueError(f"warp_reference: {name} landmarks must increase in cycle")
        v = np.degrees(base(name, np.interp(x, dst[:, 0], src[:, 0]) / 100.0))
        k = np.clip(np.searchsorted(dst[:, 0], x, side="right") - 1, 0, len(dst) - 2)
        a0, a1, b0, b1 = src[k, 1], src[k + 1, 1], dst[k, 1], dst[k + 1, 1]
        same = np.isclose(a1, a0)
        lin = (x - dst[k, 0]) / (dst[k + 1, 0] - dst[k, 0])
        scaled = b0 + (v - a0) * (b1 - b0) / np.where(same, 1.0, a1 - a0)
        out[name] = np.radians(np.where(same, b0 + (v - a0) + (b1 - b0) * lin, scaled))
    return ReferenceGait(
        cycle=x / 100.0,
        hip=out["hip"],
        knee=out["knee"],
        pitch=out["pitch"],
        source=f"{base.source} warped onto {source or 'landmarks'}",
    )


def bandai_reference() -> ReferenceGait:
    """The Winter reference warped onto :data:`BANDAI_LANDMARKS` (a generated gait calibrated
    on the figures of the bandai-walk "normal" actor; no capture samples are used)."""
    return warp_reference(
        BANDAI_LANDMARKS, source="bandai-walk normal 001-003 landmarks (BANDAI_LANDMARKS)"
    )


def reference_angle(joint: str, cycle, derivative: bool = False):
    """Default-reference angle (radians) of ``joint`` ("hip", "knee", "pitch") at cycle(s)."""
    return DEFAULT_REFERENCE(joint, cycle, derivative)


_WINTER = winter_reference()
#: The reference gait :func:`legs_from_walk` uses by default: the generated
#: :func:`bandai_reference` (the Winter table warped onto the landmark figures
#: :data:`BANDAI_LANDMARKS`; no capture samples). Its maximum difference to held-out
#: bandai-walk clips is hip 4.8 / knee 6.9 deg, the plain Winter table's 12.4 / 16.1 deg
#: (tests/test_legs.py::test_knee_hip_curves_vs_bandai_capture).
DEFAULT_REFERENCE = bandai_reference()


def sagittal_angles(hip, knee, ankle, toe, yaw):
    """Hip (thigh) flexion, knee flexion and raw foot pitch (ankle -> toe vs floor), radians,
    of one leg in the walking plane, from (T, 3) joint positions and the (T,) heading yaw."""
    fwd = np.column_stack([np.cos(yaw), np.sin(yaw), np.zeros_like(yaw)])
    th, sh, ft = knee - hip, ankle - knee, toe - ankle
    hipf = np.arctan2((th * fwd).sum(1), -th[:, 2])
    kneef = hipf - np.arctan2((sh * fwd).sum(1), -sh[:, 2])
    pitch = np.arctan2(ft[:, 2], (ft * fwd).sum(1))
    return hipf, kneef, pitch


def heel_strikes(pitch: np.ndarray, fps: float) -> np.ndarray:
    """Sample indices of heel strikes: the foot's toes-up pitch peaks (radians, (T,)), at least
    0.6 s apart and 10 deg prominent. The foot lands heel first with the toes highest, then
    rolls down."""
    from scipy.signal import find_peaks

    peaks, _ = find_peaks(pitch, distance=max(1, int(0.6 * fps)), prominence=np.deg2rad(10))
    return peaks


def gait_cycles(
    take, side: str = "L", names: str = "UpperLeg_{},LowerLeg_{},Foot_{},Toes_{}", n: int = 101
) -> np.ndarray:
    """Time-normalised gait cycles of one leg of a capture :class:`~mjwalk.mocap.take.Take`.

    Args:
        take: a take with ``joints`` holding hip, knee, ankle and toe positions.
        side: side letter used in the joint names ("L"/"R").
        names: comma-separated joint-name patterns (hip, knee, ankle, toe), ``{}`` = side.
        n: samples per cycle.

    Returns:
        (C, 3, n) per complete cycle (heel strike to heel strike, the first and last dropped):
        thigh flexion, knee flexion and foot pitch (radians; pitch relative to the flat foot,
        the median over 20-40 % of the cycle).
    """
    keys = [k.format(side) for k in names.split(",")]
    missing = [k for k in keys if k not in take.joints]
    if missing:
        raise CaptureError(
            f"{take.name}: gait_cycles needs joints {missing} (have {sorted(take.joints)[:8]}...)"
        )
    h, k, a, t = (np.asarray(take.joints[j], float) for j in keys)
    hipf, kneef, pitch = sagittal_angles(h, k, a, t, np.asarray(take.pelvis_yaw, float))
    hs = heel_strikes(pitch, take.fps)
    x = np.linspace(0, 1, n)
    cycles = []
    for i0, i1 in itertools.pairwise(hs):
        s = np.linspace(0, 1, i1 - i0 + 1)
        cycles.append([np.interp(x, s, v[i0 : i1 + 1]) for v in (hipf, kneef, pitch)])
    cycles = np.array(cycles[1:-1]).reshape(-1, 3, n)
    if len(cycles):
        flat = np.median(cycles[:, 2, int(0.2 * (n - 1)) : int(0.4 * (n - 1)) + 1])
        cycles[:, 2] -= flat
    return cycles


def reference_from_takes(
    takes, side: str = "L", names: str = "UpperLeg_{},LowerLeg_{},Foot_{},Toes_{}"
) -> ReferenceGait:
    """A reference gait from captured straight walks: the mean of their gait cycles."""
    cyc = [c for t in takes for c in gait_cycles(t, side, names)]
    if not cyc:
        raise CaptureError("reference_from_takes: no complete gait cycle in the takes")
    m = np.mean(cyc, axis=0)
    return ReferenceGait(
        cycle=np.linspace(0, 1, m.shape[1]),
        hip=m[0],
        knee=m[1],
        pitch=m[2],
        source=f"{len(cyc)} captured cycles ({', '.join(t.name for t in takes)})",
    )


@dataclass
class LegMotion:
    """Per-sample leg motion for a WalkPath (same samples, 120 Hz), world frame.

    Attributes:
        t: (N,) sample times in seconds.
        root: (N, 3) pelvis (root) position, metres; z is the pelvis height above the floor.
        yaw: (N,) pelvis yaw, radians from +x CCW.
        angles: joint name (e.g. ``"knee_l"``) -> (N,) angle in radians, anatomical signs.
        ankle: side ("l"/"r") -> (N, 3) ankle target position, metres.
        pitch: side -> (N,) foot pitch to the floor, radians, + toes up.
        contact: (N,) contact state: 0 = left stance, 1 = right stance, 2 = double support.
        phase: (N,) step phase in [0, 1] (0 before the first / after the last step).
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
    clip: bool = True,
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
    # the hip-to-ankle vector in the foot frame R_f = R_z(yaw) R_y(-pitch) (sole level
    # sideways); the chain hip R_z R_y R_x, knee R_y, ankle R_y R_x gives
    # u = R_x(s inv) R_y(dorsi) w(knee) with w(knee) the hip-to-ankle vector in the shin frame
    # (knee and ankle flexion axes parallel): knee from |u|, ankle inversion and flexion from
    # the direction of u, then the hip's three angles from the remaining rotation, so the
    # foot's position and all three orientation angles are met exactly (6 joints, 6 dof)
    Rf = _rz(np.asarray(foot_yaw, float)) @ _ry(-np.asarray(foot_pitch, float))
    u = (np.swapaxes(Rf, -1, -2) @ np.asarray(ankle_rel, float)[..., None])[..., 0]
    r = np.linalg.norm(u, axis=-1)
    rmax = geom.span(KNEE_MIN)
    rmin = geom.span(np.deg2rad(ROM_DEG["knee"][1]))
    rc = np.clip(r, rmin, rmax)
    knee = geom.knee_for_span(rc)
    phi = np.arctan2(u[:, 1], -u[:, 2])  # rotation about the foot's x axis (s * inversion)
    m = np.hypot(u[:, 1], u[:, 2])
    a = np.arctan2(L1 * np.sin(knee), L1 * np.cos(knee) + L2) - np.arctan2(u[:, 0], m)
    a = np.mod(a + np.pi, 2 * np.pi) - np.pi  # ankle dorsiflexion
    H = Rf @ _rx(phi) @ _ry(a - knee)  # = R_z(-s rot) R_y(-flex) R_x(s abd)
    out = {
        f"hip_{side}_rot": -s * np.arctan2(H[:, 1, 0], H[:, 0, 0]),
        f"hip_{side}_flex": np.arcsin(np.clip(H[:, 2, 0], -1, 1)),
        f"hip_{side}_abd": s * np.arctan2(H[:, 2, 1], H[:, 2, 2]),
        f"knee_{side}": knee,
        f"ankle_{side}_flex": a,
        f"ankle_{side}_inv": s * phi,
    }
    if clip:
        for name, v in out.items():
            lo, hi = np.deg2rad(ROM_DEG[_generic(name)])
            out[name] = np.clip(v, lo, hi)
    return out


def leg_fk(angles: dict[str, np.ndarray], side: str, geom: LegGeometry):
    """Forward kinematics of one leg in the pelvis frame (x forward, y left, z up; pelvis
    upright), the humanoid's joint axes (:func:`~mjwalk.body.humanoid.build_humanoid`).

    Args:
        angles: joint name -> (N,) angles in radians (hip rotation/flexion/abduction, knee,
            ankle flexion/inversion of ``side``).
        side: "l" or "r".
        geom: the leg lengths.

    Returns:
        (ankle (N, 3) relative to the hip joint centre in metres, foot rotation (N, 3, 3)).
    """
    s = 1.0 if side == "l" else -1.0
    a = {k: np.asarray(angles[k.format(side)], float) for k in LEG_JOINTS[:-1]}
    R = _rz(-s * a["hip_{}_rot"]) @ _ry(-a["hip_{}_flex"]) @ _rx(s * a["hip_{}_abd"])
    knee = R[..., 2] * -geom.thigh
    R = R @ _ry(a["knee_{}"])
    ankle = knee + R[..., 2] * -geom.shank
    R = R @ _ry(-a["ankle_{}_flex"]) @ _rx(-s * a["ankle_{}_inv"])
    return ankle, R


def foot_lowest(angles: dict[str, np.ndarray], side: str, geom: LegGeometry) -> np.ndarray:
    """(N,) height (m) of the lowest point of the foot's collision boxes (sole and toes, as
    built by :func:`~mjwalk.body.humanoid.build_humanoid`) above the hip joint centre, from the
    leg angles (``toe_{side}`` included); add the hip height for the height above the floor."""
    ankle, R = leg_fk(angles, side, geom)
    ah, ball, hw = geom.ankle_height, _ball(geom), geom.foot_width / 2
    corners = np.array(list(itertools.product((0.0, 1.0), (-hw, hw), (0.0, 1.0))))
    # sole box: x from the heel to the ball, 0.8 ankle heights tall from the sole
    foot = corners * [ball + geom.foot_back, 1.0, 0.8 * ah] + [-geom.foot_back, 0.0, -ah]
    # toes box in the toes frame (origin at the ball on the sole, rotated by the toe angle)
    toes = corners * [geom.foot_front - ball, 1.0, 0.4 * ah]
    toe = np.asarray(angles[f"toe_{side}"], float)
    toes_foot = (_ry(-toe)[:, None] @ toes[None, :, :, None])[..., 0] + [ball, 0.0, -ah]
    z_foot = (R[:, 2, None, :] * foot[None]).sum(-1)
    z_toes = (R[:, 2, None, :] * toes_foot).sum(-1)
    return ankle[:, 2] + np.minimum(z_foot.min(1), z_toes.min(1))


def _generic(name: str) -> str:
    return "_".join(p for p in name.split("_") if p not in ("l", "r"))


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def _spread(need: np.ndarray, win: int) -> np.ndarray:
    """A smooth (n,) envelope of the non-negative per-sample amounts ``need`` (n,): their
    running maximum over +-``win`` samples, Gaussian-smoothed (sigma ``win / 3``), so a
    correction needed at some samples fades in and out over the samples around instead of
    acting on them alone (a jump)."""
    return gaussian_filter1d(maximum_filter1d(need, 2 * win + 1), win / 3)


def _soft_clip01(x: np.ndarray, w: float) -> np.ndarray:
    """``x`` clamped to [0, 1] with rounded corners (C1): unchanged in [w, 1 - w], quadratic
    blends over ``w`` either side of 0 and 1, constant beyond (``w`` <= 0.5)."""
    x = np.asarray(x, float)
    lo = np.where(x < -w, 0.0, np.where(x < w, (x + w) ** 2 / (4 * w), x))
    return np.where(lo > 1 + w, 1.0, np.where(lo > 1 - w, 1 - (1 + w - lo) ** 2 / (4 * w), lo))


def _ball(geom: LegGeometry) -> float:
    """Distance of the ball of the foot (toe joint) ahead of the ankle, metres."""
    return geom.foot_front - 0.2 * (geom.foot_front + geom.foot_back)


def _pivot(foot: np.ndarray, pitch, geom: LegGeometry) -> np.ndarray:
    """(n, 3) ankle positions of a foot on footprint ``foot`` ((3,) or per sample (n, 3))
    pitched by ``pitch`` (radians): negative (heel up) rolls about the ball, positive (toes up)
    about the heel; the pivot stays where it is on the floor when the foot is flat."""
    ah = geom.ankle_height
    pitch = np.atleast_1d(np.asarray(pitch, float))
    foot = np.asarray(foot, float)
    lever = np.where(pitch <= 0, _ball(geom), -geom.foot_back)
    fx, fy = np.cos(foot[..., 2]), np.sin(foot[..., 2])
    # R_z(yaw) R_y(-pitch) (lever, 0, -ah) from the pivot, written out (inner loops)
    c, s = np.cos(pitch), np.sin(pitch)
    along = lever * (c - 1) + ah * s  # the pivot is lever ahead of the ankle when flat
    return np.column_stack(
        [
            foot[..., 0] - along * fx,
            foot[..., 1] - along * fy,
            ah * c - lever * s,
        ]
    )


def _spin_print(foot: np.ndarray, spin, geom: LegGeometry, lever: float | None = None):
    """(n, 3) footprints of a foot on ``foot`` (3,) turned by ``spin`` (n,) radians about the
    point ``lever`` metres ahead of the ankle on its sole (default the ball; ``-foot_back``:
    the heel). That point stays on the floor where it is; the rest of the foot swings round."""
    b = _ball(geom) if lever is None else lever
    spin = np.asarray(spin, float)
    piv = foot[:2] + b * np.array([np.cos(foot[2]), np.sin(foot[2])])
    yaw = foot[2] + spin
    return np.column_stack([piv[0] - b * np.cos(yaw), piv[1] - b * np.sin(yaw), yaw])


def _soft_flat(p: np.ndarray) -> np.ndarray:
    """Pitches within +-FLAT_DEG become exactly 0 (flat foot), continuously."""
    t = np.deg2rad(FLAT_DEG)
    return np.sign(p) * np.maximum(np.abs(p) - t, 0.0)


def _heel_rise(foot, hip, knee, p0, geom: LegGeometry, lo: float = -1.0472):
    """Foot pitch <= ``p0`` (radians, rolled about the ball) at which the leg with ``knee``
    flexion reaches from the ankle to ``hip`` (3,); ``p0`` if it reaches already. Where it
    reaches at no pitch, the pitch in [``lo``, ``p0``] that brings the ankle closest to the
    hip: rolled about the ball the ankle moves on a circle, so past the point of the circle
    nearest the hip a higher heel takes it away again (a foot ahead of the hip gets there
    long before ``lo``, a trailing foot not before).

    Vectorized: ``hip`` (n, 3), ``knee`` (n,) and ``p0`` (n,) give (n,) pitches (one bisection
    for all samples); scalar ``knee`` and ``p0`` with ``hip`` (3,) give a float."""
    scalar = np.ndim(p0) == 0
    hip = np.atleast_2d(np.asarray(hip, float))
    p0 = np.atleast_1d(np.asarray(p0, float))
    knee = np.broadcast_to(np.asarray(knee, float), p0.shape)
    d = geom.span(knee)

    def gap(h, p, dd=d):
        return np.linalg.norm(h - _pivot(foot, p, geom), axis=-1) - dd

    p = p0.copy()
    j = np.flatnonzero(gap(hip, p0) > 0)  # the samples that do not reach at p0
    if not len(j):
        return float(p[0]) if scalar else p
    hj, dj = hip[j], d[j]
    # rolled about the ball B by p <= 0 the ankle is B + rho (-cos t f, sin t z), t = beta - p
    # (f the foot's heading): |hip - ankle| = d is closed-form in t, the first root as the
    # heel rises; without a root the clipped arcsin gives the t nearest the hip
    ball, ah = _ball(geom), geom.ankle_height
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


def _foot_frames(walk: WalkPath) -> list[dict]:
    """Per step: swing side, lift-off and landing footprints, stance footprint."""
    steps = walk.steps
    frames = []
    for i, st in enumerate(steps):
        side = "l" if st.side == "left" else "r"
        stance = np.asarray(st.stance, float)
        if i > 0:
            lift = np.asarray(steps[i - 1].stance, float)
        else:  # standing start: the swing foot beside the stance foot, mirrored about the pelvis
            y0 = walk.yaw[st.start]
            n = np.array([-np.sin(y0), np.cos(y0)])
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
                "stance": stance,
                "first": i == 0,
                "final": i == len(steps) - 1,
            }
        )
    return frames


def _landing_pitches(frames, xy, yaw, hs_pitch, d_land, dorsi_max, geom: LegGeometry) -> None:
    """Per step (``frames``, in place: ``"land_p"``), the pitch (radians, + toes up) the swing
    foot lands with: the reference's ``hs_pitch``, or flatter (down to 0) where the landing
    leg at its heel-strike length ``d_land`` (m) under the pelvis at ``xy``, ``yaw`` of the
    landing sample would dorsiflex its ankle past ``dorsi_max`` (a foot landing under the
    hip). All steps at once; a few fixed-point rounds."""
    b = np.array([fr["end"] for fr in frames])
    land = np.array([fr["land"] for fr in frames])
    left = np.array([fr["side"] == "l" for fr in frames])
    land_p = np.full(len(frames), hs_pitch)
    for _ in range(4):
        pos = _pivot(land, land_p, geom)
        z = np.zeros(len(b))
        flex = np.zeros(len(b))
        for side, sel in (("l", left), ("r", ~left)):
            if not sel.any():
                continue
            bs = b[sel]
            hip = _hip_world(np.column_stack([xy[bs], z[sel]]), yaw[bs], side, geom)
            hz = np.linalg.norm(hip[:, :2] - pos[sel, :2], axis=-1)
            z[sel] = pos[sel, 2] + np.sqrt(np.maximum(d_land**2 - hz**2, 1e-6))
            root = np.column_stack([xy[bs], z[sel]])
            raw = _leg_raw(pos[sel], land[sel, 2], land_p[sel], root, yaw[bs], side, geom)
            flex[sel] = raw[f"ankle_{side}_flex"]
        over = flex - dorsi_max
        if not np.any((over > 0) & (land_p > 0)):
            break
        land_p = np.where(over > 0, np.maximum(land_p - 1.2 * over, 0.0), land_p)
    for fr, p in zip(frames, land_p, strict=True):
        fr["land_p"] = float(p)


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
    geom = leg_geometry(stature)
    n = len(walk.t)
    xy = np.asarray(walk.xy, float)
    yaw = np.asarray(walk.yaw, float)
    frames = _foot_frames(walk)
    for k, fr in enumerate(frames):
        if not (0 <= fr["start"] < fr["end"] < n):
            raise PlanningError(
                f"legs_from_walk: step {k} has sample range {fr['start']}..{fr['end']} outside "
                f"the path's {n} samples"
            )
    ah = geom.ankle_height
    ankle = {s: np.zeros((n, 3)) for s in "lr"}
    fyaw = {s: np.zeros(n) for s in "lr"}
    pitch = {s: np.zeros(n) for s in "lr"}
    toe = {s: np.zeros(n) for s in "lr"}
    contact = np.full(n, 2, dtype=int)
    phase = np.zeros(n)
    z = np.full(n, np.nan)
    ground = {s: np.zeros(n, bool) for s in "lr"}  # foot on the floor (pivoting on a print)
    print_ = {s: np.zeros((n, 3)) for s in "lr"}  # ... on this footprint
    cyc = {s: np.zeros(n) for s in "lr"}  # the leg's gait-cycle fraction (0 = heel strike)

    def hip_pos(idx, side, zz=None):
        sgn = 1.0 if side == "l" else -1.0
        h = xy[idx] + sgn * geom.hip_y * np.stack([-np.sin(yaw[idx]), np.cos(yaw[idx])], -1)
        return h if zz is None else np.column_stack([h, zz])

    def height_for_knee(idx, side, foot_pos, knee):
        h = np.linalg.norm(hip_pos(idx, side) - foot_pos[:, :2], axis=-1)
        return foot_pos[:, 2] + np.sqrt(np.maximum(geom.span(knee) ** 2 - h**2, 1e-6))

    def knee_for(idx, side, foot_pos, zz):
        d = np.linalg.norm(hip_pos(idx, side, zz) - foot_pos, axis=-1)
        return geom.knee_for_span(d)

    hs_pitch = max(0.0, float(ref("pitch", 0.0)))
    dorsi_max = np.deg2rad(ROM_DEG["ankle_flex"][1] - 1.0)
    plantar_min = np.deg2rad(ROM_DEG["ankle_flex"][0] + 1.0)
    knee_prev = None  # (angle, velocity per unit phase) of the next stance leg at its landing
    d_land = geom.span(max(ref("knee", 0.0), KNEE_MIN))
    _landing_pitches(frames, xy, yaw, hs_pitch, d_land, dorsi_max, geom)
    for k, fr in enumerate(frames):
        fr["p_start"] = frames[k - 1].get("p_end") if k > 0 else None
        a, b = fr["start"], fr["end"]
        idx = np.arange(a, b + 1)
        phi = (idx - a) / (b - a)
        phase[idx] = phi
        cyc[fr["other"]][idx], cyc[fr["side"]][idx] = 0.5 * phi, 0.5 + 0.5 * phi
        sw, st = fr["side"], fr["other"]
        contact[idx] = np.where(phi <= TOE_OFF, 2, 0 if st == "l" else 1)
        # --- stance foot: heel strike roll-down, flat, heel rise (reference pitch)
        c_st = 0.5 * phi
        p_ref = ref("pitch", c_st)
        p_st = np.where(phi < 0.4, np.maximum(p_ref, 0), np.minimum(p_ref, 0))
        if k > 0 and hs_pitch > 0:  # the roll-down starts from the pitch it landed with
            p_st = np.where(phi < 0.4, p_st * frames[k - 1]["land_p"] / hs_pitch, p_st)
        p_st = _soft_flat(p_st)
        if fr["first"]:  # standing start: already flat
            p_st = np.minimum(p_st, 0.0)
        # --- target posture at phi = 1 (A7): the landing leg at the reference heel-strike knee
        # sets the pelvis height; the trailing (stance) leg takes the reference knee of
        # cycle 50 %, its heel rising further (about the ball) if it cannot reach otherwise.
        # The foot lands toes up as the reference's, or flatter where the ankle's range
        # does not allow that pitch (a foot landing under the hip): rolled down on the floor
        # after landing instead, it would drop the ankle and jolt the knee
        land_p = fr["land_p"]  # the last step too: the final pose is held as it lands
        land_pos = _pivot(fr["land"], land_p, geom)
        hz = np.linalg.norm(hip_pos(np.array([b]), sw) - land_pos[:, :2], axis=-1)[0]
        z_end = land_pos[0, 2] + np.sqrt(max(d_land**2 - hz**2, 1e-6))
        th1 = max(float(ref("knee", 0.5)), float(KNEE_MIN))
        hip_end = hip_pos(np.array([b]), st, np.array([z_end]))[0]
        p1 = _heel_rise(fr["stance"], hip_end, th1, float(p_st[-1]), geom)
        extra = (p1 - p_st[-1]) * _smoothstep((phi - 0.4) / 0.6)
        p_st = p_st + extra
        fr["p_end"] = float(p_st[-1])
        ankle[st][idx] = _pivot(fr["stance"], p_st, geom)
        ground[st][idx], print_[st][idx] = True, fr["stance"]
        pitch[st][idx], toe[st][idx], fyaw[st][idx] = p_st, -np.minimum(p_st, 0), fr["stance"][2]
        th1 = float(knee_for(np.array([b]), st, ankle[st][b][None], np.array([z_end]))[0])
        if knee_prev is None:
            th0, v0 = float(ref("knee", 0.0)), 0.5 * float(ref("knee", 0.0, True))
        else:
            th0, v0 = knee_prev
        v1 = 0.5 * float(ref("knee", 0.5, True))
        knee_st = np.clip(_displaced(ref, "knee", phi, th0, v0, th1, v1), KNEE_MIN, np.deg2rad(80))
        z_flat = height_for_knee(idx, st, ankle[st][idx], knee_st)
        # --- swing foot (A9)
        pos, p_sw, toe_sw, yw = _swing(fr, phi, idx, z_flat, hip_pos, ref, geom, land_p)
        ankle[sw][idx], pitch[sw][idx], toe[sw][idx], fyaw[sw][idx] = pos, p_sw, toe_sw, yw
        pre_swing = idx[phi <= TOE_OFF]
        ground[sw][pre_swing], print_[sw][pre_swing] = True, fr["lift"]
        d_max = geom.span(KNEE_MIN)
        hsw = np.linalg.norm(hip_pos(idx, sw) - pos[:, :2], axis=-1)
        z_sw = pos[:, 2] + np.sqrt(np.maximum(d_max**2 - hsw**2, 1e-6))
        z[idx] = np.minimum(z_flat, z_sw)
        # landing approach: from LAND_EASE the swing leg's hip-to-ankle distance eases into
        # its heel-strike length (zero velocity) along a cubic from its length and velocity
        # there, and the pelvis height follows from it. Capping the pelvis only where the
        # swing leg is fully stretched would snap the knee straight (near full extension a
        # millimetre of leg length is several degrees of knee)
        lj = np.flatnonzero(phi >= LAND_EASE)
        if len(lj) >= 3 and lj[0] > 0:
            j = lj[0]
            hj = hip_pos(idx[j - 1 : j + 1], sw, z[idx[j - 1 : j + 1]])
            dj = np.linalg.norm(hj - pos[j - 1 : j + 1], axis=-1)
            span, gap = 1.0 - phi[j], d_land - dj[1]
            m0 = span * (dj[1] - dj[0]) / (phi[j] - phi[j - 1])
            m0 = float(np.clip(m0, min(0.0, 3 * gap), max(0.0, 3 * gap)))
            u = (phi[lj] - phi[j]) / span
            d_prof = dj[1] + (u**3 - 2 * u**2 + u) * m0 + (3 * u**2 - 2 * u**3) * gap
            h_prof = np.linalg.norm(hip_pos(idx[lj], sw) - pos[lj, :2], axis=-1)
            z_prof = pos[lj, 2] + np.sqrt(np.maximum(d_prof**2 - h_prof**2, 1e-6))
            z[idx[lj]] = np.minimum(z_prof, z_sw[lj])
            # the trailing leg keeps its planned knee where the pelvis now rises faster: its
            # heel rises further (about the ball) instead of the leg stretching straight
            hip_st = hip_pos(idx[lj], st, z[idx[lj]])
            p_up = _heel_rise(fr["stance"], hip_st, knee_st[lj], np.minimum(p_st[lj], 0), geom)
            p_st[lj] = np.where(p_st[lj] <= 0, p_up, p_st[lj])
            fr["p_end"] = float(p_st[-1])
            ankle[st][idx] = _pivot(fr["stance"], p_st, geom)
            pitch[st][idx], toe[st][idx] = p_st, -np.minimum(p_st, 0)
        # the swing leg's knee at landing starts the next stance spline
        # the swing leg's knee at landing starts the next stance spline; its velocity is the
        # reference's (loading response: the knee flexes right after heel strike)
        k_land = knee_for(idx[-1:], sw, pos[-1:], z[idx[-1:]])
        knee_prev = (float(k_land[-1]), 0.5 * float(ref("knee", 0.0, True)))
    # where the pelvis turns further than a grounded foot's hip can rotate, the foot spins
    # about its ball; its next swing starts from the turned footprint
    _spin_turns(ankle, fyaw, pitch, toe, ground, print_, np.column_stack([xy, z]), yaw, geom)
    # before the first step: stand on both feet; after the last: hold the final pose
    first, last = frames[0], frames[-1]
    pre = np.arange(0, first["start"])
    if len(pre):
        for s_, f in ((first["side"], first["lift"]), (first["other"], first["stance"])):
            ankle[s_][pre] = [f[0], f[1], ah]
            fyaw[s_][pre] = f[2]
        z[pre] = z[first["start"]]
    post = np.arange(last["end"] + 1, n)
    if len(post):
        e = last["end"]
        for arr in (*ankle.values(), *fyaw.values(), *pitch.values(), *toe.values(), z):
            arr[post] = arr[e]
        contact[post] = 2
    win = max(3, round(0.05 * n / max(float(walk.t[-1] - walk.t[0]), 1e-9)))  # 50 ms

    def repitch(s_: str, dp: np.ndarray) -> None:
        # lower the ``s_`` foot's pitch by dp (n,) radians about its heel (toes up) or ball:
        # on the floor about its footprint's pivot, in the air about the same point of the
        # foot; the toes keep their angle to the floor while the heel is up
        p0, p1 = pitch[s_], pitch[s_] - dp
        lever = np.where(p0 <= 0, _ball(geom), -geom.foot_back)
        off = []
        for q in (p0, p1):
            c, si = np.cos(q), np.sin(q)
            off.append((-(lever * c + ah * si), ah * c - lever * si))
        g = ground[s_]
        head = np.column_stack([np.cos(fyaw[s_]), np.sin(fyaw[s_])])
        moved = ankle[s_].copy()
        moved[:, :2] += (off[1][0] - off[0][0])[:, None] * head
        moved[:, 2] += off[1][1] - off[0][1]
        moved[g] = _pivot(print_[s_][g], p1[g], geom)
        toe[s_] += np.minimum(p0, 0.0) - np.minimum(p1, 0.0)
        ankle[s_], pitch[s_] = moved, p1

    angles: dict[str, np.ndarray] = {}
    k_floor = {s_: np.clip(ref("knee", cyc[s_]), KNEE_MIN, np.deg2rad(KNEE_SOFT)) for s_ in "lr"}
    for _ in range(4):
        root = np.column_stack([xy, z])
        for s_ in "lr":
            # a grounded foot whose ankle would dorsiflex past its range pitches down
            # instead: a toes-up foot rolls down about its heel, a flat one onto its ball
            # (heel rise), so the sole keeps its place on the floor (clipping the ankle would
            # sink the toes). Likewise a heel-up foot whose ankle would plantarflex past its
            # range lowers its heel about the ball, down to flat (a stance foot ahead of the
            # hip: clipped, the foot would turn about the ankle and its ball slide), and the
            # pelvis lowers below. The roll is spread over the samples around (in the air
            # too, about the same point), so a landing or lift-off does not jolt the leg
            for _ in range(8):
                raw = _leg_raw(ankle[s_], fyaw[s_], pitch[s_], root, yaw, s_, geom)
                flex = raw[f"ankle_{s_}_flex"]
                excess = np.where(ground[s_], flex - dorsi_max, 0.0)
                short = np.where(ground[s_] & (pitch[s_] < 0), plantar_min - flex, 0.0)
                if excess.max() <= 0 and short.max() <= 0:
                    break
                down = _spread(1.2 * np.maximum(excess, 0.0), win)
                up = _spread(1.2 * np.maximum(short, 0.0), win)
                repitch(s_, down - np.minimum(up, np.maximum(-pitch[s_], 0.0)))
        # rolling a heel-strike foot down (or turning it about the ball) lowers its ankle:
        # where a grounded leg then cannot reach its foot with the knee flexed at least as
        # the reference's (up to KNEE_SOFT), the pelvis lowers (smoothly). Near full
        # extension a millimetre of leg length is several degrees of knee: a leg stretched
        # straight by the pelvis would flick its knee
        deficit = np.zeros(n)
        for s_ in "lr":
            h = np.linalg.norm(_hip_world(root, yaw, s_, geom)[:, :2] - ankle[s_][:, :2], axis=1)
            reach = geom.span(k_floor[s_])
            cap = ankle[s_][:, 2] + np.sqrt(np.maximum(reach**2 - h**2, 0.0))
            deficit = np.maximum(deficit, np.where(ground[s_], z - cap, 0.0))
        if deficit.max() <= 1e-3:
            break
        z = z - _spread(np.maximum(deficit, 0.0), win)
    root = np.column_stack([xy, z])
    for s_ in "lr":
        hip = _hip_world(root, yaw, s_, geom)
        # where the joint ranges still keep the foot from its target (a trailing foot too far
        # behind for the hip's extension, say), the clipped leg would put the sole below the
        # floor: lift the ankle target by the depth (or, where the ankle is at its
        # dorsiflexion limit and lifting would tilt the toes down further, pitch the foot
        # down) and solve again, so the foot stays above -FLOOR_TOLERANCE by construction
        for _ in range(FLOOR_ITERATIONS):
            raw = _leg_raw(ankle[s_], fyaw[s_], pitch[s_], root, yaw, s_, geom)
            ang = {k: np.clip(v, *np.deg2rad(ROM_DEG[_generic(k)])) for k, v in raw.items()}
            ang[f"toe_{s_}"] = np.clip(toe[s_], *np.deg2rad(ROM_DEG["toe"]))
            low = hip[:, 2] + foot_lowest(ang, s_, geom)
            bad = low < -FLOOR_TOLERANCE
            if not bad.any():
                break
            # (both spread over the samples around, as above)
            excess = raw[f"ankle_{s_}_flex"] - dorsi_max
            tilt = bad & (excess > 0)
            if tilt.any():
                repitch(s_, _spread(np.where(tilt, 1.2 * excess, 0.0), win))
            lift = bad & ~tilt
            ankle[s_][:, 2] += _spread(np.where(lift, -low, 0.0), win)
        angles.update(ang)
    return LegMotion(
        t=np.asarray(walk.t, float),
        root=root,
        yaw=yaw,
        angles=angles,
        ankle=ankle,
        pitch=pitch,
        contact=contact,
        phase=phase,
        meta={"stature": stature, "reference": ref.source},
    )


def _hip_world(root: np.ndarray, yaw: np.ndarray, side: str, geom: LegGeometry) -> np.ndarray:
    """(n, 3) world position of the ``side`` hip joint centre of an upright pelvis at
    ``root`` (n, 3) with heading ``yaw`` (n,), metres."""
    sgn = 1.0 if side == "l" else -1.0
    lat = np.column_stack([-np.sin(yaw), np.cos(yaw), np.zeros_like(yaw)])
    return root + sgn * geom.hip_y * lat


def _leg_raw(ankle, foot_yaw, pitch, root, yaw, side: str, geom: LegGeometry) -> dict:
    """Unclipped :func:`leg_ik` angles of the ``side`` leg for world ankle targets (n, 3), foot
    headings (n,) and pitches (n,) under the pelvis ``root`` (n, 3), ``yaw`` (n,)."""
    hip = _hip_world(root, yaw, side, geom)
    rel = (_rz(-yaw) @ (ankle - hip)[..., None])[..., 0]
    yrel = np.angle(np.exp(1j * (foot_yaw - yaw)))
    return leg_ik(rel, yrel, pitch, side, geom, clip=False)


def _soft_excess(x: np.ndarray, w: float) -> np.ndarray:
    """max(x, 0) rounded over ``[0, 2 w]`` (C1): 0 for x <= 0, x - w for x >= 2 w."""
    x = np.maximum(x, 0.0)
    return np.where(x < 2 * w, x * x / (4 * w), x - w)


def _spin_turns(ankle, fyaw, pitch, toe, ground, print_, root, yaw, geom: LegGeometry) -> dict:
    """Spin turns, in place: a grounded foot (stance, then pre-swing on the same footprint)
    whose hip rotation would pass its range as the pelvis turns (a sharp turning step) turns
    by the excess about the point it stands on, so that point stays put and the hip stays
    in range, instead of the clipped hip dragging the foot round:

    * flat or heel up: about the ball, the heel raised a little (:data:`SPIN_HEEL`, in
      smoothly before the turn starts, kept up until lift-off);
    * toes up after heel strike (the foot landed turned further than the hip allows): about
      the heel, the toes kept up a little until the turn is undone.

    The turned footprint carries into the swings before and after: the ankle, yaw and pitch
    offsets at toe-off fade out over the next swing (gone at 90 % of it, where the swing foot
    takes its landing heading), those at heel strike fade in over the second half of the
    swing before.

    Arrays are per side ("l"/"r") over the walk's samples: ankle (n, 3) m, fyaw (n,) rad, pitch
    and toe (n,) rad, ground (n,) bool, print_ (n, 3) footprints; root (n, 3) pelvis
    position, yaw (n,) pelvis yaw. Returns per side the largest turn (radians) and the number
    of contacts that turned."""
    n = len(yaw)
    lo, hi = np.deg2rad(ROM_DEG["hip_rot"])
    margin, soft, ramp = np.deg2rad([SPIN_MARGIN, SPIN_SOFT, SPIN_RAMP])
    heel = np.deg2rad(SPIN_HEEL)
    ball, back = _ball(geom), -geom.foot_back
    stats = {}
    for s_ in "lr":
        sgn = 1.0 if s_ == "l" else -1.0
        g = ground[s_]
        new_print = np.r_[True, np.any(print_[s_][1:] != print_[s_][:-1], axis=1)]
        starts = np.flatnonzero(g & (new_print | ~np.r_[False, g[:-1]]))
        ends = [
            j0 + int(np.argmax(np.r_[~g[j0 + 1 :] | new_print[j0 + 1 :], True])) for j0 in starts
        ]
        worst, count = 0.0, 0
        for i, (j0, j1) in enumerate(zip(starts, ends, strict=True)):
            run = np.arange(j0, j1 + 1)
            foot = print_[s_][j0].copy()

            def rot(a_, y_, p_, run=run, side=s_):
                return _leg_raw(a_, y_, p_, root[run], yaw[run], side, geom)[f"hip_{side}_rot"]

            p0 = pitch[s_][run].copy()
            r0 = rot(ankle[s_][run], fyaw[s_][run], p0)
            up = _soft_excess(r0 - (hi - margin - soft), soft / 2)
            down = _soft_excess((lo + margin + soft) - r0, soft / 2)
            need = (up > 0) | (down > 0)
            if not need.any():
                continue
            target = r0 - (up - down)
            rise = np.maximum(
                _smoothstep((r0 - (hi - margin - soft - ramp)) / ramp),
                _smoothstep(((lo + margin + soft + ramp) - r0) / ramp),
            )
            # heel phase: from heel strike while the toes are up or, turned, kept up; then
            # the ball phase (the heel rises at the latest where the reference raises it)
            free = (p0 <= 0) & (rise == 0)
            k_h = 0
            if p0[0] > 0:
                k_h = min(int(np.argmax(np.r_[free, True])), int(np.argmax(np.r_[p0 < 0, True])))
            heel_ph = np.arange(len(run)) < k_h
            lift = np.maximum.accumulate(np.where(heel_ph, 0.0, rise))
            p = np.where(
                heel_ph,
                np.maximum(p0, heel * rise),
                np.where(lift > 0, np.minimum(p0, -heel * lift), p0),
            )
            spin = np.zeros(len(run))

            def prints(spin, foot=foot, heel_ph=heel_ph, k_h=k_h):
                fp = np.empty((len(spin), 3))
                fp[heel_ph] = _spin_print(foot, spin[heel_ph], geom, back)
                base = fp[k_h - 1] if k_h else foot
                rest = spin[~heel_ph] - (spin[k_h - 1] if k_h else 0.0)
                fp[~heel_ph] = _spin_print(base, rest, geom, ball)
                return fp

            for _ in range(6):  # the hip rotation follows the foot's yaw one to one (-s)
                fp = prints(spin)
                err = rot(_pivot(fp, p, geom), fp[:, 2], p) - target
                spin = spin + np.where(need, sgn * err, 0.0)
                # without need the foot keeps its turn (relative to its phase's pivot)
                spin = np.where(need, spin, 0.0)
            fp = prints(spin)
            a_ = _pivot(fp, p, geom)
            worst, count = max(worst, float(np.abs(fp[:, 2] - foot[2]).max())), count + 1
            offsets = [
                (a_[k] - ankle[s_][j], fp[k, 2] - foot[2], p[k] - p0[k])
                for k, j in ((0, j0), (-1, j1))
            ]
            ankle[s_][run], fyaw[s_][run], print_[s_][run] = a_, fp[:, 2], fp
            pitch[s_][run], toe[s_][run] = p, -np.minimum(p, 0.0)
            # the swings around start from / land on the turned foot; the offsets fade
            j_prev = ends[i - 1] if i else None
            j_next = starts[i + 1] if i + 1 < len(starts) else n
            for (d_a, d_y, d_p), sw, fade in (
                (offsets[1], np.arange(j1 + 1, j_next), lambda x: 1 - _smoothstep(x / 0.9)),
                (
                    offsets[0],
                    np.arange((j_prev if j_prev is not None else j0) + 1, j0),
                    lambda x: _smoothstep(2 * x - 1),
                ),
            ):
                if not len(sw):
                    continue
                x = (sw - sw[0] + 1) / (len(sw) + 1)
                w = fade(x)
                ankle[s_][sw] += w[:, None] * d_a
                fyaw[s_][sw] += w * d_y
                pitch[s_][sw] += w * d_p
                toe[s_][sw] -= w * d_p
        stats[s_] = (worst, count)
    return stats


def _displaced(ref: ReferenceGait, name: str, phi, th0, v0, th1, v1) -> np.ndarray:
    """Stance-leg angle ``name`` (radians) at step phases ``phi``: the reference's own curve
    over cycle 0-50 % plus a cubic-spline displacement that is zero at the key frames
    :data:`STANCE_KEYS` (so the angle coincides with the reference key-frame angles there) and
    meets the current posture's angle ``th0`` / velocity ``v0`` at ``phi = 0`` and the target
    posture's ``th1`` / ``v1`` at ``phi = 1`` (velocities per unit phase).

    Between the keys and the boundaries the result keeps the reference's shape (its loading
    response, say) instead of the bare cubic through five points, which cuts the reference's
    curves short (motion warping, Witkin & Popovic 1995, applied to the paper's spline)."""
    r0, r1 = float(ref(name, 0.0)), float(ref(name, 0.5))
    d0 = v0 - 0.5 * float(ref(name, 0.0, True))
    d1 = v1 - 0.5 * float(ref(name, 0.5, True))
    sp = CubicSpline(
        [0.0, *STANCE_KEYS, 1.0], [th0 - r0, 0.0, 0.0, 0.0, th1 - r1], bc_type=((1, d0), (1, d1))
    )
    return ref(name, 0.5 * np.asarray(phi, float)) + sp(phi)


def _swing(fr, phi, idx, z_hip, hip_pos, ref: ReferenceGait, geom: LegGeometry, land_p):
    """Swing foot: ankle (n, 3), pitch (n,), toe angle (n,), yaw (n,) over the step."""
    ah, L1, L2 = geom.ankle_height, geom.thigh, geom.shank
    lift, land = fr["lift"], fr["land"]
    sw = fr["side"]
    yaw = lift[2] + np.angle(np.exp(1j * (land[2] - lift[2]))) * _smoothstep(
        (phi - TOE_OFF) / (0.9 - TOE_OFF)
    )

    def roll_pitch(ph):
        p = _soft_flat(np.minimum(ref("pitch", 0.5 + 0.5 * ph), 0.0))
        if fr["first"]:
            p = p * _smoothstep(ph / TOE_OFF)
        elif fr["p_start"] is not None:  # continue from the stance's extra heel rise
            p0 = _soft_flat(np.minimum(ref("pitch", 0.5), 0.0))
            p = p + min(fr["p_start"] - p0, 0.0) * (1 - _smoothstep(ph / TOE_OFF))
        return p

    pos = np.zeros((len(phi), 3))
    p = np.zeros(len(phi))
    early = phi <= TOE_OFF
    p[early] = roll_pitch(phi[early])
    if not fr["first"]:
        # pre-swing: the knee follows the reference; the heel rises as far as that needs
        je = np.flatnonzero(early)
        hip = hip_pos(idx[je], sw, z_hip[je])
        knee = np.maximum(ref("knee", 0.5 + 0.5 * phi[je]), float(KNEE_MIN))
        p[je] = _heel_rise(lift, hip, knee, p[je], geom)
    pos[early] = _pivot(lift, p[early], geom)
    late = ~early
    if late.any():
        je = np.flatnonzero(early)[-2:]
        h = float(phi[je[1]] - phi[je[0]])
        p_to = p[je[::-1]]
        a0 = pos[je[::-1]]
        v0 = (a0[0] - a0[1]) / h
        # the reference swing: the reference hip/knee angles of each gait-cycle instant placed
        # at the current hip (forward progress and height), along the line from the lift-off
        # to the landing footprint
        jl = np.flatnonzero(late)
        c = 0.5 + 0.5 * phi[jl]
        hf, kf = ref("hip", c), ref("knee", c)
        fwd = L1 * np.sin(hf) + L2 * np.sin(hf - kf)
        down = L1 * np.cos(hf) + L2 * np.cos(hf - kf)
        heading = np.column_stack([np.cos(yaw[jl]), np.sin(yaw[jl])])
        target = hip_pos(idx[jl], sw) + fwd[:, None] * heading
        seg = land[:2] - lift[:2]
        # progress along the chord, clamped to the footprints softly (C1): a hard clamp where
        # the reference passes the landing footprint (short steps) kinks the ankle's path
        s = _soft_clip01((target - lift[:2]) @ seg / max(float(seg @ seg), 1e-9), 0.1)
        chord = lift[:2] + s[:, None] * seg
        # sideways, the foot swings under its hip: where the step turns, the hip's track bends
        # away from the chord (and from an inner corner the pelvis was planned clear of)
        nrm = np.array([-seg[1], seg[0]]) / max(float(np.linalg.norm(seg)), 1e-9)
        off = (hip_pos(idx[jl], sw) - chord) @ nrm
        xy = chord + (off * np.sin(np.pi * s))[:, None] * nrm
        ref_pos = np.column_stack([xy, z_hip[jl] - down])
        ref_pit = np.clip(ref("pitch", c), np.deg2rad(-70), np.deg2rad(30))
        # key positions at SWING_KEYS: the reference, lifted where the ankle would be lower
        # than standing height; the reference shape is kept between the keys and the
        # boundaries (lift-off state at toe-off, the landing pose with zero velocity) by a
        # cubic-spline displacement (as the stance angles, :func:`_displaced`)
        knots, dpos, dpit = [float(phi[je[1]])], [a0[0]], [p_to[0]]
        for ph in SWING_KEYS[1:]:
            m = int(np.argmin(np.abs(phi[jl] - ph)))
            knots.append(float(phi[jl[m]]))
            key = ref_pos[m].copy()
            key[2] = max(key[2], ah)
            dpos.append(key)
            dpit.append(ref_pit[m])
        knots.append(1.0)
        dpos.append(_pivot(land, land_p, geom)[0])
        dpit.append(land_p)
        # the reference at the knots (toe-off and landing extrapolate the first/last sample)
        rk = np.column_stack([np.interp(knots, phi[jl], ref_pos[:, k]) for k in range(3)])
        rp = np.interp(knots, phi[jl], ref_pit)
        dr = np.gradient(ref_pos, phi[jl], axis=0) if len(jl) > 1 else np.zeros((1, 3))
        dq = np.gradient(ref_pit, phi[jl]) if len(jl) > 1 else np.zeros(1)
        sp = CubicSpline(knots, np.array(dpos) - rk, bc_type=((1, v0 - dr[0]), (1, -dr[-1])))
        dp0 = (p_to[0] - p_to[1]) / h
        spp = CubicSpline(knots, np.array(dpit) - rp, bc_type=((1, dp0 - dq[0]), (1, -dq[-1])))
        pos[late], p[late] = ref_pos + sp(phi[late]), ref_pit + spp(phi[late])
    # the toes stay flat during the roll-off, then straighten while the foot lifts
    p_end = p[early][-1] if early.any() else 0.0
    toe = np.where(early, -p, -p_end * (1 - _smoothstep((phi - TOE_OFF) / 0.25)))
    if late.any():
        # keep heel, ball and toe tip off the floor (lift the ankle where they would dip); the
        # toe tip is on the toes, bent by the toe angle (flat on the floor at toe-off: a tip
        # rigid with the pitched foot would dip below it and jolt the ankle up)
        pl, tl = p[late], toe[late]
        ball = _ball(geom)
        ball_z = ball * np.sin(pl) - ah * np.cos(pl)
        for tip in (
            -geom.foot_back * np.sin(pl) - ah * np.cos(pl),
            ball_z,
            ball_z + (geom.foot_front - ball) * np.sin(pl + tl),
        ):
            pos[late, 2] += np.maximum(0.0, -(pos[late, 2] + tip))
    return pos, p, toe, yaw
