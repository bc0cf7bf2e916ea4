"""A cycle's reaches: an arm reach from the standing pose to a pick/place/fasten target (the
PCA + DCS reach model, alzubi-sommer; the right arm mirrors it), two-handed reaches, the
pre-grasp approach, and the step back that keeps the arm clear of the scene
(:mod:`mjwalk.cycle.standoff`). World frame: metres, z up; frames at ``fps`` per second."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from mjwalk.anthropometry import knee_height
from mjwalk.conventions import Side, side_prefix
from mjwalk.cycle.crouch import bend_trunk, crouch_frames, crouch_pose, trunk_bend, trunk_room
from mjwalk.cycle.handling import RETURN_CASE, body_motion_duration, reach_duration
from mjwalk.cycle.standoff import REACH_TOLERANCE, STEP_BACK, ArmClearance, step_back_offsets

if TYPE_CHECKING:
    from mjwalk.arms.reach import ReachResult

from mjwalk.cycle.context import CycleContext
from mjwalk.cycle.poses import _turn_frames

#: Lateral offset of the shoulder from the pelvis centre (m, stature 1.75 m; Winter: 0.1·H).
SHOULDER_OFFSET = 0.18


#: The hand stops this far above a pick/place site (m) and this far in front of a fasten site.
PICK_CLEARANCE = 0.06


FASTEN_STANDOFF = 0.13


#: The pre-grasp point: this far back towards the operator and (shelf work) up from the target.
APPROACH_BACK = 0.15


APPROACH_UP = 0.10
#: Visual-only geoms a ray passes through at most while measuring a target's headroom.
HEADROOM_HITS = 8


def _default_timing(dist: float) -> tuple[float, float]:
    """The reference adult's reach (MTM-1 case B) and return (case E) times, seconds, for a
    hand movement of ``dist`` metres."""
    return reach_duration(dist, None, "B"), reach_duration(dist, None, RETURN_CASE)


def _time_factor(timing) -> float:
    """The operator's time factor of a ``timing(distance)`` (None: the reference adult): the
    return time over the reference adult's (factor / pace), which times the body's bend and
    arise."""
    return 1.0 if timing is None else timing(1.0)[1] / _default_timing(1.0)[1]


def _reach_frames(
    ctx,
    q0: np.ndarray,
    target_w: np.ndarray,
    approach_w: np.ndarray,
    hold: float,
    fps: float,
    side: Side = "left",
    timing=None,
    face: np.ndarray | None = None,
    lean: bool = False,
    drop: float = 0.0,
):
    """Frames of reaching from pose ``q0`` to ``target_w`` (world, m), holding, returning.

    ``timing(distance)`` gives the (reach, return) durations in seconds of a hand movement of
    ``distance`` metres (the hand's true path at the index knuckle, as MTM-1 measures a reach:
    from where the hand is in ``q0`` along the planned movement to the target); default: the
    reference adult's MTM-1 case B reach and case E return (:mod:`mjwalk.cycle.handling`).

    The reach model (PCA + DCS) brings the hand from rest to the pre-grasp point
    ``target_w + approach_w``; the hand then moves straight onto the target along
    ``-approach_w`` with a minimum-jerk profile (two-link IK, hand direction kept), so it comes
    over a shelf's front edge instead of through it. The return retraces the motion. ``face``
    (world unit vector, the normal of a grip face such as a box's side): during the approach
    the hand also turns to lie flat on that face (the approach's direction less its component
    along the normal), so the palm, not only the hand's end, comes onto the face.

    Returns (frames, hand error in metres, ReachResult of the model part)."""
    from mjwalk.arms.kinematics import (
        arm_frames,
        arm_joint_angles,
        min_jerk,
        two_link_ik_rows,
    )
    from mjwalk.arms.reach import humanoid_arm, reach_for_side
    from mjwalk.body.humanoid import PALM_SHARE

    m, jm, model = ctx.model, ctx.jointmap, ctx.reach_model_for(side)
    # the reach is solved at the reach model's arm lengths; an operator of another stature has
    # the same arm shape scaled (Winter's shares), so the targets are scaled into the model's
    # size (directions, hence joint angles, do not change with the scale)
    scale, lengths = humanoid_arm(model, ctx.spec.stature)
    # ``base``: q0, or q0 bent forward at the trunk (the lean comes in with the ready phase and
    # goes with the return; the arm's poses are solved from the leaning shoulder)
    base = q0
    if drop > 0.0:  # crouched: the pelvis lower, the trunk bent for balance (mjwalk.cycle.crouch)
        base = crouch_pose(ctx, q0, drop)
    if lean:
        base = _leaning(ctx, base, [(side, target_w)], float(lengths.sum()) / scale - LEAN_SPARE)
    data = ctx.scratch()
    data.qpos[:] = base
    mujoco.mj_kinematics(m, data)
    ua = m.body(f"{jm.prefix}upper_arm_{side_prefix(side)}").id
    shoulder = data.xpos[ua].copy()
    frame = data.xmat[ua].reshape(3, 3).copy()
    end = frame.T @ (target_w - shoulder) * scale
    pre = frame.T @ (target_w + approach_w - shoulder) * scale
    start = model.rest_hand  # where the model's reaches start (the ready posture)
    # a right arm mirrors the left-arm model; the fit puts the humanoid's own hand on the
    # points (the model's clips may have had arms of other proportions)
    res = reach_for_side(model, pre, side, start, arm_lengths=lengths)
    u_last = res.directions[-1]
    n_app = max(4, len(res.directions) // 2)
    app = np.repeat(u_last[None], n_app, axis=0)
    taus = min_jerk(np.linspace(0.0, 1.0, n_app + 1)[1:])
    hands = pre + taus[:, None] * (end - pre)
    # the hand's direction on the target: along its approach (the hand, and the forearm behind
    # it as far as the wrist follows, stay on the approach's line, which comes in from the free
    # side of the target: out of a shelf's opening, from the operator at the car), or in the
    # grip face's plane; as far as the humanoid's wrist can turn it there, the elbow swivelled
    # as it needs (_wrist_feasible). Before, the wrist was clipped after the fact and the
    # fingers ended up to 14 cm off a fastening target
    u_app = frame.T @ -np.asarray(approach_w, dtype=float)
    u_app /= max(float(np.linalg.norm(u_app)), 1e-9)
    if face is not None:
        # in the face's plane: the approach's direction there. The model's last direction
        # (up, for a part above the shoulder) put the wrists below the grips and the forearms
        # through a shelf board's front edge (benchmarks/bench_heights.py, both hands, 1.55 m)
        # (the model's, when the approach runs along the normal: grips one behind the other)
        n_s = frame.T @ np.asarray(face, dtype=float)
        u_face = u_app - (u_app @ n_s) * n_s
        if np.linalg.norm(u_face) < 0.1:
            u_face = u_last[2] - (u_last[2] @ n_s) * n_s
        u_face /= max(float(np.linalg.norm(u_face)), 1e-9)
    u_end, elbow_end = _wrist_feasible(
        ctx, base, side, end, u_face if face is not None else u_app, u_last, lengths
    )
    model_dirs = res.directions
    if face is not None:
        # a grip face: the hand turns to it during the last third of the movement to the
        # pre-grasp point and comes onto the face along the approach without turning, so the
        # part held between the palms moves straight along that line as it is lifted off (or
        # set down), instead of tilting in the hands
        model_dirs = _turn_hand(model_dirs, u_end, lengths)
        u_last = model_dirs[-1]
        app[:] = u_last
    elif not np.allclose(u_end, u_last[2]):
        app[:, 2] = [_blend_dir(u_last[2], u_end, tau) for tau in taus]
    wrists = hands - lengths[2] * app[:, 2]
    # the elbow swivels from where the model left it to where the hand's end pose needs it
    hints = np.array([_blend_dir(u_last[0], elbow_end, tau) for tau in taus]) * lengths[0]
    app[:, 0], app[:, 1] = two_link_ik_rows(wrists, lengths[0], lengths[1], hints)  # (row-wise)
    directions = np.concatenate([model_dirs, app])
    q = arm_joint_angles(directions, side)
    if timing is None:
        timing = _default_timing
    # MTM-1 times a reach by the true path of the hand, not the straight line from start to
    # end (MTM-1 data card, Reach: "distance moved ... is the true path"; Freivalds & Niebel
    # 2014, ch. 12): the humanoid's index knuckle from where it is in q0 (the ready phase bends
    # the arm into the model's start), along the model's trajectory and the approach
    knuckle = PALM_SHARE * lengths[2] / scale
    ready_len, model_len = _hand_path(ctx, q0, q, side, knuckle, base)
    reach_out, reach_back = timing(ready_len + model_len)
    n_out = max(2, round(reach_out * fps))
    # The reach model's trajectories start at its ready posture (ReachModel.rest_hand; the
    # default model's REST_HAND: elbow bent, hand in front of the thigh), the standing arm
    # hangs straight: the first frames bend the arm into the ready posture (joint-space, the
    # hand stays by the body), their share of the reach time the share of the hand's path they
    # cover (one pace along the path: a fixed quarter of the time moved the hand up to 3.5 m/s
    # there), the rest follows the model's trajectory; the return ends the same way. Without
    # it the arm snapped between the two in one frame (elbow 0 <-> 87 deg).
    share = ready_len / max(ready_len + model_len, 1e-9)
    n_ready = min(n_out - 2, max(1, round(max(share * n_out, READY_MIN * fps))))
    n_arm_ready = n_rise = n_ready
    if drop > 0.0 or (lean and target_w[2] < knee_height(ctx.spec.stature)):
        # the crouch (or a stoop for a target below the knee: MTM-1's bend) comes with the
        # ready phase and the rise with the return's, each taking at least MTM-1's bend /
        # arise at the operator's time factor (its return time over the reference adult's:
        # factor / pace); the reach lasts longer by what they add
        factor = _time_factor(timing)
        n_down = round(body_motion_duration("B") * factor * fps)
        n_ready = max(n_ready, n_down)
        n_out += n_ready - n_arm_ready
        n_rise = max(n_arm_ready, round(body_motion_duration("AB") * factor * fps))
    ready_pose = arm_frames(base, jm, q[:1], side, np.ones(1))[0][0]
    w = _smooth(np.arange(1, n_ready + 1) / (n_ready + 1))
    # the feet stay planted while the pelvis lowers (the legs solved at every pose)
    ready = crouch_frames(ctx, q0, ready_pose, w)
    n_out -= n_ready
    out, _ = arm_frames(base, jm, q, side, np.linspace(0.0, 1.0, n_out + 1)[1:])
    data.qpos[:] = out[-1]
    mujoco.mj_kinematics(m, data)
    # the hand's end as the humanoid holds it (its hand body's -z axis, after the joint ranges)
    error = float(np.linalg.norm(_hand_tip(data, m, jm, side, lengths[2] / scale) - target_w))
    n_hold = max(0, round(hold * fps))
    n_back = max(1, round(reach_back * fps))
    n_back = max(2, n_back - n_arm_ready)
    # the reach retraced in the return's time: poses interpolated between the reach's frames
    # (hinge angles; the root does not move during a reach). Rounding to the nearest frame
    # skipped one or two frames in turn and the hand jumped (19 cm in one frame, 5.6 m/s)
    src = np.linspace(0.0, n_out - 1.0, n_back)
    i0 = np.minimum(np.floor(src).astype(int), n_out - 1)
    i1 = np.minimum(i0 + 1, n_out - 1)
    w = (src - i0)[:, None]
    rev = out[::-1]
    back = (1.0 - w) * rev[i0] + w * rev[i1]
    rise = ready[::-1]  # ... the ready posture, hanging (standing up from a crouch)
    if n_rise != n_ready:
        w = _smooth(np.arange(1, n_rise + 1) / (n_rise + 1))[::-1]
        rise = crouch_frames(ctx, q0, ready_pose, w)
    back = np.vstack([back[1:], rise, q0[None]])
    frames = np.vstack([ready, out, np.repeat(out[-1:], n_hold, axis=0), back])
    if lean or drop > 0.0:  # the other arm hangs plumb from the bending trunk
        other: Side = "right" if side == "left" else "left"
        frames = _plumb_arms(ctx, frames, q0, np.ones(len(frames)), (other,))
    return frames, error, res


#: Steps (radians) of the trunk's forward lean for a target out of the arm's reach, and the
#: reach (m) the lean leaves to spare: the smallest lean, 5 deg at a time, that brings the target
#: within the arm's length less 2 cm of the shoulder (a choice: a reach short of locking the
#: elbow). The lean goes into the lumbar and thoracic flexion in proportion to their ranges
#: (:data:`mjwalk.anthropometry.ROM_DEG`: 60 and 45 deg).
LEAN_STEP = np.radians(5.0)
LEAN_SPARE = 0.02
#: How deep (share of stature: the pelvis 9, 17 and 26 cm lower at 1.72 m) a one-handed reach
#: that touches the scene from every spot standing or stooping crouches, tried in this order:
#: a semi-squat to a squat with the knees at about 50, 70 and 90 deg (mjwalk.cycle.crouch).
#: People reaching into low storage bend the knees as well as the back (the "semi-squat" and
#: "squat" of lifting studies: Straker 2003, "Evidence to support using squat, semi-squat
#: and stoop techniques to lift low-lying objects", Int. J. Ind. Ergon. 31:149-160).
CROUCH_DROPS = (0.05, 0.10, 0.15)


def _leaning(ctx, q0: np.ndarray, targets, reach: float) -> np.ndarray:
    """``q0`` with the trunk bent forward just far enough that every ``(side, target)`` of
    ``targets`` (the target in world coordinates, m) lies within ``reach`` metres of that side's
    shoulder (lumbar and thoracic flexion, within their ranges, :data:`LEAN_STEP` at a time:
    :func:`~mjwalk.cycle.crouch.bend_trunk`); bent as far as they go when that is not enough."""
    prefix = ctx.jointmap.prefix
    arms = [
        (ctx.model.body(f"{prefix}upper_arm_{side_prefix(side)}").id, np.asarray(t, dtype=float))
        for side, t in targets
    ]
    return bend_trunk(
        ctx,
        q0,
        LEAN_STEP,
        lambda data: all(np.linalg.norm(t - data.xpos[ua]) <= reach for ua, t in arms),
    )


def _hand_tip(data, m, jm, side, hand_length: float) -> np.ndarray:
    """World position of the end of ``side``'s hand in the pose ``data`` holds (kinematics
    done): the hand body's origin (the wrist) plus ``hand_length`` m along its -z axis, the
    direction the humanoid's hand points (:mod:`mjwalk.body.humanoid`)."""
    b = m.body(f"{jm.prefix}hand_{side_prefix(side)}").id
    return data.xpos[b] - hand_length * data.xmat[b].reshape(3, 3)[:, 2]


#: Iterations of :func:`_wrist_feasible` (each re-solves the arm for the last hand direction;
#: the direction moves by well under a degree after the second).
WRIST_ITERATIONS = 4
#: Elbow swivels (radians about the shoulder-wrist axis, nearest first) that
#: :func:`_wrist_feasible` tries when the model's elbow leaves the hand's direction beyond the
#: wrist's range: a search grid of 5 deg steps up to 60 deg either way, the nearest in-range
#: swivel kept (people orient the hand partly by the elbow's swivel, which varies with the hand's
#: position and orientation: Kim, Miller, Byl, Abrams & Rosen 2012, "Redundancy resolution of
#: the human arm and an upper limb exoskeleton", IEEE Trans. Biomed. Eng. 59:1770-1779).
SWIVELS = np.radians(np.array([0.0] + [s * k for k in range(5, 65, 5) for s in (1, -1)]))


def _turn_hand(directions: np.ndarray, u_end: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """``directions`` (n, 3, 3: upper arm, forearm, hand; shoulder frame) with the hand turned
    to ``u_end`` over the last third of the samples (a smooth blend reaching ``u_end`` at the
    last), the hand's end kept where it was (the upper arm and forearm re-solved for the
    moved wrist, the elbow swivelled as little as it can)."""
    from mjwalk.arms.kinematics import end_effector, two_link_ik_rows

    out = np.array(directions, dtype=float)
    n_turn = max(2, len(out) // 3)
    tail = out[-n_turn:]
    taus = _smooth(np.arange(1, n_turn + 1) / n_turn)
    ends = end_effector(tail, lengths)
    hands = np.array(
        [_blend_dir(u, u_end, float(t)) for u, t in zip(tail[:, 2], taus, strict=True)]
    )
    wrists = ends - lengths[2] * hands
    u1, u2 = two_link_ik_rows(wrists, lengths[0], lengths[1], tail[:, 0] * lengths[0])
    out[-n_turn:] = np.stack([u1, u2, hands], axis=1)
    return out


def _wrist_feasible(ctx, q0, side, end, u_hand, u_last, lengths) -> tuple[np.ndarray, np.ndarray]:
    """A hand direction (unit, shoulder frame) the humanoid's wrist can hold with the hand's
    end on ``end`` (model size), and the upper arm's direction for it: ``u_hand`` (turned
    towards ``end`` as far as the arm needs to reach it: :func:`_within_reach`) with the elbow
    where the model's last pose has it (``u_last``) when the arm's joint angles are within their
    ranges there; else ``u_hand`` with the elbow swivelled about the shoulder-wrist axis (the
    nearest of :data:`SWIVELS` that keeps every joint in range: people turn the elbow out or in
    to orient the hand); else the hand turned only as far as the humanoid's wrist ranges allow,
    the arm re-solved for that hand (:func:`~mjwalk.arms.kinematics.wrist_in_range`)."""
    from scipy.spatial.transform import Rotation

    from mjwalk.arms.kinematics import (
        arm_frames,
        arm_joint_angles,
        two_link_ik_rows,
        wrist_in_range,
    )

    u = _within_reach(np.asarray(u_hand, dtype=float), end, lengths)
    hint = u_last[0] * lengths[0]
    wrist = end - lengths[2] * u
    axis = wrist / max(float(np.linalg.norm(wrist)), 1e-9)
    # the elbow hint turned by each swivel about the shoulder-wrist axis
    for h in Rotation.from_rotvec(SWIVELS[:, None] * axis).apply(hint):
        u1, u2 = two_link_ik_rows(wrist[None], lengths[0], lengths[1], h[None])
        q = arm_joint_angles(np.stack([u1[0], u2[0], u])[None], side)
        if not arm_frames(q0, ctx.jointmap, q, side, np.ones(1))[1]:
            return u, u1[0]
    # no swivel will do: the wrist at the humanoid's range limits, the arm re-solved for it
    limits = np.array(
        [ctx.jointmap.limits(f"wrist_{side_prefix(side)}_{dof}") for dof in ("flex", "dev")]
    )
    arm = wrist_in_range(end[None], u[None], lengths, hint[None], limits, side, WRIST_ITERATIONS)
    return arm[0, 2], arm[0, 0]


#: Poses of the ready phase, and poses per interval between two of the trajectory's samples,
#: along which :func:`_hand_path` measures the knuckle's path (the frames interpolate the joint
#: angles between the samples; a finer split changes the length by well under 1 %).
PATH_POSES = 16
PATH_SUBSTEPS = 4


def _within_reach(u: np.ndarray, end: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Hand direction ``u`` (unit) turned towards ``end``'s direction from the shoulder (the
    hand pointing away from the shoulder reaches farthest) just far enough that the wrist,
    the hand's length back from ``end``, is within the upper arm and forearm's reach (a 5 %
    grid of blends; the radial direction when even it is not: ``end`` beyond the arm)."""
    reach = (lengths[0] + lengths[1]) * (1.0 - 1e-6)
    if np.linalg.norm(end - lengths[2] * u) <= reach:
        return u
    radial = end / max(float(np.linalg.norm(end)), 1e-9)
    for b in np.linspace(0.05, 1.0, 20):
        v = _blend_dir(u, radial, float(b))
        if np.linalg.norm(end - lengths[2] * v) <= reach:
            return v
    return radial


def _hand_path(ctx, q0, q, side, knuckle: float, base=None) -> tuple[float, float]:
    """Lengths (m) of the path of the humanoid's index knuckle in a reach, where MTM-1 measures
    a hand's reach (Freivalds & Niebel 2014, *Niebel's Methods, Standards, and Work Design*,
    13th ed., ch. 12): ``(ready, movement)``, through the ready phase's poses (the joint angles
    from ``q0`` into the trajectory's first pose) and the trajectory's poses (joint angles ``q``,
    (n, 7), each interval split as the frames interpolate it), after the joint ranges.
    ``knuckle``: its distance (m) from the wrist along the hand (the operator's size).
    ``base``: the pose the arm's angles are set in (q0 bent forward, for a leaning reach).
    Computes in the context's scratch data."""
    from mjwalk.arms.kinematics import arm_frames

    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    base = q0 if base is None else base
    first = arm_frames(base, jm, q[:1], side, np.ones(1))[0][0]
    w = np.linspace(0.0, 1.0, PATH_POSES)[:, None]
    ready = q0[None] + w * (first - q0)[None]
    steps = np.linspace(0.0, 1.0, PATH_SUBSTEPS * (len(q) - 1) + 1)
    move, _ = arm_frames(base, jm, q, side, steps)

    def length(poses: np.ndarray) -> float:
        points = np.empty((len(poses), 3))
        for k, pose in enumerate(poses):
            data.qpos[:] = pose
            mujoco.mj_kinematics(m, data)
            points[k] = _hand_tip(data, m, jm, side, knuckle)  # ``knuckle`` m along the hand
        return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())

    return length(ready), length(move)


#: The ready phase (bending the hanging arm into the reach model's ready posture, or back)
#: lasts at least this long (s): the elbow bends by about 85 deg into the ready posture, at
#: most about 600 deg/s (peak elbow speeds of quick human reaches are of that order).
READY_MIN = 0.15


def _smooth(u: np.ndarray) -> np.ndarray:
    """Smoothstep 3u^2 - 2u^3 of ``u`` in [0, 1]."""
    return u * u * (3.0 - 2.0 * u)


#: Largest shift (radians) of both shoulder abductions that :func:`_holding_frames` tries to keep
#: the palms' distance while the hands move a held part (the abduction's range is about 1.2 rad).
HOLD_SHIFT = 0.5


def _holding_frames(ctx, qa: np.ndarray, qb: np.ndarray, n: int) -> np.ndarray:
    """``n`` frames (n, nq) that move both hands, holding a part, from pose ``qa`` to ``qb``
    (``qa`` excluded, ``qb`` included; same root): every joint on a minimum-jerk profile, and
    both shoulder abductions shifted together in each frame (:func:`_palms_apart`) so the palms'
    distance (m) follows the same profile from ``qa``'s to ``qb``'s: the hands keep the grips
    of the part they carry between the bench and the carrying posture."""
    from mjwalk.arms.kinematics import min_jerk

    ga, gb = _palm_gap(ctx, qa), _palm_gap(ctx, qb)
    prof = min_jerk(np.arange(1, n + 1) / n)
    frames = qa[None] + prof[:, None] * (qb - qa)[None]
    for f, p in enumerate(prof[:-1]):  # the last frame is qb itself
        frames[f] = _palms_apart(ctx, frames[f], ga + p * (gb - ga))
    return frames


def _held_move(
    ctx, qa: np.ndarray, qb: np.ndarray, n: int, out: np.ndarray, back: np.ndarray
) -> np.ndarray:
    """``n`` frames moving a held part from ``qa`` to ``qb`` (:func:`_holding_frames`), one of
    them (``out``) the hands out at a bench or shelf, the other the carrying posture. When the
    direct move touches the scene (a part lifted off a shelf above the shoulder and lowered
    straight into the carrying posture: the arms swing down in an arc through the board's
    front edge), the hands go in straight lines (:func:`_straight_holding`) by way of ``out``
    with the hands moved by ``back`` (world, m: towards the operator, :func:`_hands_moved`),
    pulling the part clear of the shelf before lowering it (on the way out, the reverse);
    kept when it is clearer (:class:`~mjwalk.cycle.standoff.ArmClearance`)."""
    direct = _holding_frames(ctx, qa, qb, n)
    if n < 4:
        return direct
    check = _arm_clearance(ctx)
    touch = check.distance(direct)
    if touch >= 0.0:
        return direct
    best, best_d = direct, touch
    n1 = n // 2
    for share in HELD_BACK_SHARES:  # the least pull that is clear
        mid = _hands_moved(ctx, out, share * np.asarray(back, dtype=float))
        staged = np.vstack(
            [_straight_holding(ctx, qa, mid, n1), _straight_holding(ctx, mid, qb, n - n1)]
        )
        d = check.distance(staged)
        if d > best_d:
            best, best_d = staged, d
        if d == np.inf:
            break
    return best


#: How far :func:`_held_move` pulls a held part back from a shelf before lowering it, tried in
#: this order (shares of its ``back``, the pre-grasp approach's level part: 5, 10, 15 cm): the
#: least that clears the shelf keeps the part in front of the operator's face.
HELD_BACK_SHARES = (1.0 / 3.0, 2.0 / 3.0, 1.0)


def _straight_holding(ctx, qa: np.ndarray, qb: np.ndarray, n: int) -> np.ndarray:
    """:func:`_holding_frames` from ``qa`` to ``qb`` with each wrist moved onto the straight
    line between its positions in the two poses, on the same minimum-jerk profile
    (:func:`_hands_moved`): the hands carry the part along a line, not the arc that
    interpolated joint angles sweep."""
    from mjwalk.arms.kinematics import min_jerk
    from mjwalk.timeline.parts import hand_poses

    def wrists(qpos: np.ndarray) -> np.ndarray:  # (F, 2, 3): the hand bodies' origins
        return hand_poses(ctx.model, ctx.jointmap, qpos, ctx.scratch())[0]

    frames = _holding_frames(ctx, qa, qb, n)
    wa, wb = wrists(qa[None])[0], wrists(qb[None])[0]
    prof = min_jerk(np.arange(1, n + 1) / n)
    now = wrists(frames)
    for f in range(n - 1):  # the last frame is qb itself
        frames[f] = _hands_moved(ctx, frames[f], wa + prof[f] * (wb - wa) - now[f])
    return frames


def _hands_moved(ctx, q: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """Pose ``q`` with both hands moved by ``offset`` (world, m; (3,) for both, or (2, 3):
    left, right), each keeping its direction, the elbow swivelled least (two-link IK in the
    shoulder's frame, :func:`~mjwalk.arms.kinematics.two_link_ik_rows`; within the joint
    ranges)."""
    from mjwalk.arms.kinematics import arm_frames, arm_joint, arm_joint_angles, two_link_ik_rows

    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    offsets = np.broadcast_to(np.asarray(offset, dtype=float), (2, 3))
    out = np.array(q, dtype=float)
    sides: tuple[Side, Side] = ("left", "right")
    for side, move in zip(sides, offsets, strict=True):
        p = side_prefix(side)
        ids = [m.body(f"{jm.prefix}{b}_{p}").id for b in ("upper_arm", "forearm", "hand")]
        data.qpos[:] = q
        mujoco.mj_kinematics(m, data)
        shoulder, elbow, wrist = (data.xpos[b].copy() for b in ids)
        u_hand = -data.xmat[ids[2]].reshape(3, 3)[:, 2]
        # the shoulder's frame: the upper arm's with the shoulder's joints at zero
        data.qpos[:] = q
        for dof in ("flex", "abd", "rot"):
            data.qpos[jm.adr(arm_joint(f"shoulder_{dof}", side))] = 0.0
        mujoco.mj_kinematics(m, data)
        frame = data.xmat[ids[0]].reshape(3, 3)
        e, w = frame.T @ (elbow - shoulder), frame.T @ (wrist - shoulder)
        u1, u2 = two_link_ik_rows(
            (w + frame.T @ move)[None],
            float(np.linalg.norm(e)),
            float(np.linalg.norm(w - e)),
            e[None],
        )
        angles = arm_joint_angles(np.stack([u1[0], u2[0], frame.T @ u_hand])[None], side)
        out = arm_frames(out, jm, angles, side, np.ones(1))[0][0]
    return out


def _palm_gap(ctx, q: np.ndarray) -> float:
    """Distance (m) between the palms in pose ``q``."""
    from mjwalk.cycle.poses import hand_points

    h = hand_points(ctx, q[None])[0]
    return float(np.linalg.norm(h[0] - h[1]))


def _palms_apart(ctx, q: np.ndarray, want: float) -> np.ndarray:
    """Pose ``q`` with both shoulder abductions shifted together (by at most
    :data:`HOLD_SHIFT`, Brent's method) so the palms lie ``want`` metres apart. When no such
    shift reaches it (the arms low and forward, adducted to their limit, still too far apart),
    the abductions go to the end of that range nearest ``want`` and both shoulder rotations
    shift together instead (with the elbows bent, rotating the upper arms inwards brings the
    hands together); ``q`` itself when neither reaches it."""
    out, nearest = _shift_to_gap(ctx, q, want, "abd")
    if out is None:
        out, _ = _shift_to_gap(ctx, nearest, want, "rot")
    return q if out is None else out


def _shift_to_gap(ctx, q: np.ndarray, want: float, joint: str):
    """(pose with both ``shoulder_<side>_<joint>`` angles shifted together, within
    :data:`HOLD_SHIFT` and the joint limits, so the palms lie ``want`` metres apart, or None
    when no shift reaches it; the pose at the end of the shift range nearest ``want``)."""
    from scipy.optimize import brentq

    jm = ctx.jointmap
    ks = [jm.adr(f"shoulder_{p}_{joint}") for p in "lr"]
    lims = [jm.limits(f"shoulder_{p}_{joint}") for p in "lr"]

    def shifted(d: float) -> np.ndarray:
        out = q.copy()
        for k, (lo, hi) in zip(ks, lims, strict=True):
            out[k] = np.clip(q[k] + d, lo, hi)
        return out

    lo, hi = -HOLD_SHIFT, HOLD_SHIFT
    glo, ghi = _palm_gap(ctx, shifted(lo)) - want, _palm_gap(ctx, shifted(hi)) - want
    if glo * ghi >= 0.0:
        return None, shifted(lo if abs(glo) <= abs(ghi) else hi)
    return shifted(brentq(lambda d: _palm_gap(ctx, shifted(d)) - want, lo, hi, xtol=1e-5)), None


def _blend_dir(a: np.ndarray, b: np.ndarray, tau: float) -> np.ndarray:
    """Unit vector between unit vectors ``a`` (``tau`` = 0) and ``b`` (``tau`` = 1)."""
    v = (1.0 - tau) * a + tau * b
    return v / max(float(np.linalg.norm(v)), 1e-9)


def _two_hand_frames(
    ctx, q0, task, approach, hold, fps, timing=None, held=None, lean=False, drop=0.0
):
    """A two-handed reach (:func:`_two_hand_reach`) from ``q0``, or, with ``lean`` or
    ``drop`` (m), from ``q0`` crouched that much (:func:`~mjwalk.cycle.crouch.crouch_pose`)
    and with the trunk bent forward until both grips are within the arms' reach
    (:func:`_leaning`): a part on a pallet or a low bench, which no standing reach gets both
    hands to. The body goes down with the arms as they are in ``q0`` (hanging, or holding the
    part in the carrying posture), the reach runs from there, and the body comes back up with
    the arms as the reach leaves them (carrying the part it picked, hanging after a place),
    the feet planted throughout (:func:`~mjwalk.cycle.crouch.crouch_frames`). Going down and
    coming up are MTM-1's body motions "B" (bend, stoop) and "AB" (arise) at the operator's
    time factor, before and after the reach (MTM-1 adds body and hand motions). Returns what
    :func:`_two_hand_reach` returns."""
    if not lean and drop <= 0.0:
        return _two_hand_reach(ctx, q0, task, approach, hold, fps, timing, held)
    from mjwalk.arms.kinematics import arm_adrs
    from mjwalk.arms.reach import humanoid_arm
    from mjwalk.cycle.spec import grip_sites

    body = crouch_pose(ctx, q0, drop)
    grips: list[tuple[Side, np.ndarray]] = [
        ("right" if s == "right" else "left", ctx.workplace.station(n).pos)
        for s, n in grip_sites(task.site, "both")
    ]
    if lean:
        scale, lengths = humanoid_arm(ctx.reach_model_for("left"), ctx.spec.stature)
        body = _leaning(ctx, body, grips, float(lengths.sum()) / scale - LEAN_SPARE)
    frames, error, res, width = _two_hand_reach(ctx, body, task, approach, hold, fps, timing, held)
    factor = _time_factor(timing)
    share = 1.0
    if drop <= 0.0 and min(float(g[2]) for _, g in grips) >= knee_height(ctx.spec.stature):
        # MTM-1's bend is the one that lets the hands reach below the knee; a shallower bend
        # (a deep bench) assists the reach: it goes down and up at a full bend's pace (the
        # trunk's flexion range in the bend's time), for as long as its angle needs
        share = min(1.0, float(trunk_bend(ctx, body, q0)) / max(trunk_room(ctx, q0).sum(), 1e-9))
    n_down = max(1, round(share * body_motion_duration("B") * factor * fps))
    n_up = max(1, round(share * body_motion_duration("AB") * factor * fps))
    # down with the arms of q0; up with the arms of the reach's last frame (root and legs of
    # q0 standing, crouch_frames lowers the pelvis and solves the legs at each pose)
    down = crouch_frames(ctx, q0, body, _smooth(np.arange(1, n_down + 1) / n_down))
    last = frames[-1]
    standing = np.array(q0, dtype=float)
    arms = arm_adrs(ctx.jointmap)
    standing[arms] = last[arms]
    up = crouch_frames(ctx, standing, last, _smooth(np.arange(n_up) / n_up)[::-1])
    seq = np.vstack([down, frames, up])
    # hands free (going down for a pick, coming up after a place): the arms hang plumb from
    # the bending trunk instead of swinging back with it, and swing into (out of) the reach
    # over as long as the bend (arise) takes (at most a third of the reach)
    free = np.zeros(len(seq))
    if held is None:
        n_b = max(1, min(n_down, len(frames) // 3))
        free[:n_down] = 1.0
        free[n_down : n_down + n_b] = 1.0 - _smooth(np.arange(1, n_b + 1) / (n_b + 1))
    else:
        n_b = max(1, min(n_up, len(frames) // 3))
        free[len(seq) - n_up :] = 1.0
        free[len(seq) - n_up - n_b : len(seq) - n_up] = _smooth(np.arange(1, n_b + 1) / (n_b + 1))
    return _plumb_arms(ctx, seq, q0, free), error, res, width


def _plumb_arms(
    ctx, frames: np.ndarray, q0: np.ndarray, share: np.ndarray, sides=("left", "right")
) -> np.ndarray:
    """``frames`` (F, nq) with the shoulder flexions of ``sides`` raised by ``share`` (F,)
    times the trunk's forward bend beyond ``q0``'s (lumbar and thoracic flexion, radians;
    within the shoulder's range): at share 1 an arm hanging in ``q0`` hangs plumb from the
    bent trunk."""
    jm = ctx.jointmap
    bend = trunk_bend(ctx, frames, q0)
    out = frames.copy()
    for p in (side_prefix(side) for side in sides):
        k = jm.adr(f"shoulder_{p}_flex")
        lo, hi = jm.limits(f"shoulder_{p}_flex")
        out[:, k] = np.clip(frames[:, k] + share * bend, lo, hi)
    return out


def _two_hand_reach(ctx, q0, task, approach, hold, fps, timing=None, held=None):
    """A two-handed reach (``hand = "both"``): the left arm to the grip site ``<site>_left``, the
    right arm (the mirrored model) to ``<site>_right``, at the same time, holding and returning
    together. A pick's return brings the part into the carrying posture
    (:func:`~mjwalk.cycle.poses.carry_pose`) instead of back to rest; with ``held`` (the grip
    distance in metres of the part in the hands, ``q0`` in its carrying posture) the reach starts
    from that posture and the return goes to rest. Between the grips and the carrying posture
    the palms keep their distance (:func:`_holding_frames`). Returns (frames, the larger hand
    error in metres, the left arm's ReachResult with both arms' warnings, the grip distance in
    metres)."""
    from mjwalk.arms.kinematics import arm_adrs
    from mjwalk.cycle.poses import carry_pose, hand_points
    from mjwalk.cycle.spec import grip_sites

    jm = ctx.jointmap
    carrying = np.array(q0, dtype=float)
    if held is not None:  # the reach model starts from rest: the arms at the standing pose
        rest = jm.neutral_qpos(ctx.model, ctx.spec.stature)
        q0 = carrying.copy()
        arms = arm_adrs(jm)
        q0[arms] = rest[arms]
    wp = ctx.workplace
    parts = {}
    # Both hands of a bimanual reach start and arrive together (Kelso, Southard & Goodman 1979,
    # Science 203: 1029-1031): the second arm takes the first arm's durations.
    first: list[tuple[float, float]] = []

    def shared(dist: float) -> tuple[float, float]:
        if not first:
            first.append(timing(dist) if timing is not None else _default_timing(dist))
        return first[0]

    grips = {
        s: np.asarray(wp.station(n).pos, dtype=float) for s, n in grip_sites(task.site, "both")
    }
    normal = grips["right"] - grips["left"]  # of the grip faces: the line between the grips
    normal /= max(float(np.linalg.norm(normal)), 1e-9)
    for side_name, grip in grips.items():
        side: Side = "right" if side_name == "right" else "left"
        parts[side] = (
            grip,
            *_reach_frames(ctx, q0, grip, approach, hold, fps, side, timing=shared, face=normal),
        )
    (gl, fl, el, rl), (gr, fr, er, rr) = parts["left"], parts["right"]
    frames = fl.copy()
    moved = np.any(fr != q0[None], axis=0)  # the right arm's joints
    frames[:, moved] = fr[:, moved]
    rl.warnings = list(rl.warnings) + [w for w in rr.warnings if w not in rl.warnings]
    rl.outside = bool(rl.outside or rr.outside)
    width = float(np.linalg.norm(gl - gr))
    n_out = max(2, round(first[0][0] * fps))
    n_hold = max(0, round(hold * fps))
    n_back = len(frames) - n_out - n_hold
    grip = frames[n_out - 1]  # both hands on the grips
    # the last frames of the reach bring the hands from the pre-grasp point straight onto the
    # grips (above the bench and back towards the operator: :func:`_approach`); a held part
    # comes and goes the same way, so it is lowered onto the bench and lifted off it along
    # that line instead of swept from the carrying posture through the bench's edge
    app = _approach_frames(ctx, frames[:n_out], float(np.linalg.norm(approach)))
    n_app = min(len(app) - 1, n_out - 2, n_back - 2)
    if held is not None or task.kind == "pick":
        # the pre-grasp pose with the palms still the part's width apart
        pre = _palms_apart(ctx, frames[n_out - 1 - n_app], _palm_gap(ctx, grip))
        back = np.r_[approach[:2], 0.0]  # further back from the pre-grasp point, level
    if held is not None:  # carrying posture -> above the bench -> down onto the grips
        mid = [hand_points(ctx, q[None])[0].mean(axis=0) for q in (carrying, pre, grip)]
        on, down = np.linalg.norm(np.diff(mid, axis=0), axis=1)
        n_down = int(np.clip(round(n_out * down / max(on + down, 1e-9)), 1, n_out - 2))
        head = _held_move(ctx, carrying, pre, n_out - n_down, pre, back)
        frames[:n_out] = np.vstack([head, _holding_frames(ctx, pre, grip, n_down)])
    elif task.kind == "pick":  # lifted off the bench, then into the carrying posture
        q_carry = carry_pose(ctx, q0, width)
        # the return's time shared by the two moves in proportion to the palms' travel
        mid = [hand_points(ctx, q[None])[0].mean(axis=0) for q in (grip, pre, q_carry)]
        up, on = np.linalg.norm(np.diff(mid, axis=0), axis=1)
        n_lift = int(np.clip(round(n_back * up / max(up + on, 1e-9)), 1, n_back - 2))
        lift = _holding_frames(ctx, grip, pre, n_lift)
        rest_frames = _held_move(ctx, pre, q_carry, n_back - n_lift, pre, back)
        frames[n_out + n_hold :] = np.vstack([lift, rest_frames])
    return frames, max(el, er), rl, width


def _approach_frames(ctx, reach: np.ndarray, length: float) -> np.ndarray:
    """The final frames of ``reach`` (F, nq; a two-handed reach's frames up to the grips) in
    which both palms move along the straight pre-grasp approach of ``length`` metres: from the
    last frame with a palm at least 90 % of that length from its final position to the end
    (at least the last frame)."""
    from mjwalk.cycle.poses import hand_points

    h = hand_points(ctx, reach)
    d = np.linalg.norm(h - h[-1][None], axis=2).max(axis=1)
    far = np.flatnonzero(d >= 0.9 * length)
    return reach[int(far[-1]) if len(far) else len(reach) - 1 :]


def _approach(
    kind: str,
    site_pos: np.ndarray,
    x: float,
    y: float,
    facing: float | None = None,
    rise: float = APPROACH_UP,
) -> np.ndarray:
    """Pre-grasp offset (world, m): back towards the operator, and up for shelf work (by
    ``rise``, at most :data:`APPROACH_UP`: less under a shelf, :func:`_approach_rise`). Shelf
    work (pick, place) at a stand site facing ``facing`` (radians from +x) comes in along the
    site's facing, out of the shelf's opening, wherever in the stand zone the operator stands
    (towards the operator, an oblique approach swept the fingers across the rack's frame)."""
    if facing is not None and kind != "fasten":
        d = -np.array([math.cos(facing), math.sin(facing)])
    else:
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
    up = 0.0 if kind == "fasten" else min(APPROACH_UP, rise)
    return np.r_[APPROACH_BACK * d, up]


def _approach_rise(ctx, target: np.ndarray) -> float:
    """How far (m) the pre-grasp point may rise above ``target`` (world): :data:`APPROACH_UP`
    in the open; under a shelf, only so far that the hand at its pre-grasp point still has its
    own length free above it (the hand may point anywhere from level to straight down along
    its approach, and the wrist's range turns it further where the arm comes in steeply: a
    compartment's upper shelf otherwise took the thumb, palm and forearm of a reach into it,
    20-30 mm deep), none when the compartment is lower than that."""
    from mjwalk.arms.kinematics import arm_segment_lengths

    hand = float(arm_segment_lengths(ctx.spec.stature)[2])
    return float(np.clip(_headroom(ctx, target) - hand, 0.0, APPROACH_UP))


def _headroom(ctx, point: np.ndarray) -> float:
    """Free height (m) straight up from ``point`` (world) to the first scene geom that
    collides (geoms with neither contype nor conaffinity, and the humanoid's, let the ray
    through); ``inf`` when nothing is above."""
    from mjwalk.body.humanoid import HUMAN_GROUP

    m = ctx.model
    data = ctx.scratch()
    mujoco.mj_kinematics(m, data)  # the scene's geoms in place (the humanoid's do not count)
    groups = np.ones(6, dtype=np.uint8)
    groups[HUMAN_GROUP] = 0
    up = np.array([0.0, 0.0, 1.0])
    start = np.asarray(point, dtype=float).copy()
    gid = np.zeros(1, dtype=np.int32)
    travelled = 0.0
    for _ in range(HEADROOM_HITS):
        d = mujoco.mj_ray(m, data, start, up, groups, 1, -1, gid)
        if d < 0:
            return math.inf
        g = int(gid[0])
        if m.geom_contype[g] or m.geom_conaffinity[g]:
            return travelled + float(d)
        travelled += float(d) + 1e-6
        start = start + (float(d) + 1e-6) * up
    return travelled


def _target(ctx, kind: str, site_pos: np.ndarray, x: float, y: float) -> np.ndarray:
    if kind == "fasten":  # stop in front of the surface, towards the operator
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
        return site_pos + np.r_[FASTEN_STANDOFF * d, 0.0]
    return site_pos + np.array([0.0, 0.0, PICK_CLEARANCE])


@dataclass
class WorkingReach:
    """One reach task laid out at its standing spot (world frame, metres, radians, seconds).

    Attributes:
        x, y, yaw: where the operator stands and faces during the reach.
        step_back: metres the operator stepped back from where the walk ended
            (:mod:`mjwalk.cycle.standoff`), 0 when the reach was clear there; negative: they
            stepped in towards a target out of reach from there.
        turn: (F, nq) frames of the turn (and step back) towards the target.
        turn_time: its duration in seconds.
        frames: (G, nq) frames of the reach, hold and return.
        error: distance (m) of the hand's end from its target at the end of the reach, as
            the humanoid holds it.
        result: the reach model's ReachResult (left arm's for two hands, with both warnings).
        width: grip distance (m) of a two-handed part, else None.
        distance: the humanoid's smallest distance (m) to the scene over turn and reach among
            the close pairs (:meth:`~mjwalk.cycle.standoff.ArmClearance.distance`), ``inf``
            when clear.
    """

    x: float
    y: float
    yaw: float
    step_back: float
    turn: np.ndarray
    turn_time: float
    frames: np.ndarray
    error: float
    result: ReachResult
    width: float | None
    distance: float


def _arm_clearance(ctx: CycleContext) -> ArmClearance:
    if ctx.clearance is None:
        ctx.clearance = ArmClearance(ctx.model, ctx.jointmap)
    return ctx.clearance


def _reach_task(
    ctx,
    task,
    x,
    y,
    yaw,
    hold,
    fps,
    timing,
    facing=None,
    held: float | None = None,
    home: tuple[float, float] | None = None,
) -> WorkingReach:
    """Turn towards the target of a pick/place/fasten ``task`` and reach for it from the spot
    ``(x, y)`` where the walk ended (facing ``yaw``); when the arm would come closer to the
    scene than :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` (or the body touch it), step back
    from the target during the turn, :data:`~mjwalk.cycle.standoff.STEP_BACK` at a time, until
    it is clear: the first clear spot whose hand error (m) stays within
    :data:`~mjwalk.cycle.standoff.REACH_TOLERANCE` (or within the error at the walk's end
    spot, when that is larger); the clearest such spot when none within
    :data:`~mjwalk.cycle.standoff.MAX_STEP_BACK` is clear. When the hand falls short of the
    target from ``(x, y)`` (a spot a step back for the reach before left, a short operator), the
    operator first steps in towards it, by as much as the hand falls short: the first spot from
    which the hand is on its target and clear. A step never brings the pelvis closer to an
    obstacle or the floor's edge than the planner's body radius (or than it was).
    ``facing``: the stand site's facing (radians), along which shelf work comes in
    (:func:`_approach`). ``held``: grip distance (m) of a two-handed part in the hands (a
    two-handed place turns and starts its reach in the carrying posture). ``home``: where the
    walk ended (x, y), when the operator stands elsewhere now (a step for the reach before):
    the steps are measured from there, so each reach at a stand steps back or in as far as it
    needs from the walk's end, and step-backs do not add up (default: ``(x, y)``). When no
    spot brings the target (both grips of a two-handed part) within the arms' reach (low,
    below a standing reach), the search runs again with the trunk bent forward as far as the
    target needs (:func:`_leaning`), and that reach is kept when it brings the hand closer; one
    that still touches the scene or falls short crouches (:func:`_crouching_reach`)."""
    from mjwalk.cycle.poses import _standing, carry_pose

    assert task.site is not None  # the spec loader requires a site for reaches
    site_pos = ctx.workplace.station(task.site).pos
    hx, hy = (float(x), float(y)) if home is None else (float(home[0]), float(home[1]))
    back = np.array([hx, hy]) - _target(ctx, task.kind, site_pos, hx, hy)[:2]
    back /= max(float(np.linalg.norm(back)), 1e-9)
    check = _arm_clearance(ctx)
    room0 = float(ctx.workplace.walk_clearance(np.array([hx, hy]))[()])
    # a fastening's approach is level (_approach): no headroom to measure
    rise = (
        0.0
        if task.kind == "fasten"
        else _approach_rise(ctx, _target(ctx, task.kind, site_pos, hx, hy))
    )

    def candidate(s: float, lean: bool, drop: float = 0.0) -> WorkingReach | None:
        """The reach from ``s`` metres back (in: < 0) from the walk's end (``lean``: bending
        the trunk forward as far as the target needs; ``drop``: crouched, the pelvis that much
        lower); None when the spot is not clear for the next walk (the planner's body radius,
        or the room there was)."""
        xs, ys = float(hx + s * back[0]), float(hy + s * back[1])
        room = float(ctx.workplace.walk_clearance(np.array([xs, ys]))[()])
        if s != 0 and room < min(ctx.spec.radius, room0):
            return None
        target = _target(ctx, task.kind, site_pos, xs, ys)
        # face the target (turning on the spot) before reaching for it
        d = math.hypot(target[0] - xs, target[1] - ys)
        face = math.atan2(target[1] - ys, target[0] - xs)
        if task.hand != "both" and task.kind != "fasten":
            # shelf work: bring the target ahead of the shoulder
            side = 1 if task.hand == "left" else -1
            face -= side * math.asin(min(SHOULDER_OFFSET / d, 0.5))
        grip = held if task.hand == "both" else None
        pose = None if grip is None else carry_pose(ctx, _standing(ctx, x, y, yaw), grip)
        turn, dt = _turn_frames(ctx, x, y, yaw, face, fps, to=(xs, ys), pose=pose)
        approach = _approach(task.kind, site_pos, xs, ys, facing, rise)
        q0 = turn[-1]
        width = None
        if task.hand == "both":
            rf, err, res, width = _two_hand_frames(
                ctx, q0, task, approach, hold, fps, timing=timing, held=grip, lean=lean, drop=drop
            )
        else:
            arm: Side = "right" if task.hand == "right" else "left"
            rf, err, res = _reach_frames(
                ctx, q0, target, approach, hold, fps, arm, timing=timing, lean=lean, drop=drop
            )
        dist = check.distance(np.vstack([turn, rf]))
        return WorkingReach(xs, ys, face, float(s), turn, dt, rf, err, res, width, dist)

    def settle(lean: bool, drop: float = 0.0) -> WorkingReach:
        """The stand-off's search (see above) for reaches with or without the trunk's lean,
        standing or crouched."""
        offsets = step_back_offsets()
        first = candidate(float(offsets[0]), lean, drop)
        assert first is not None  # offsets start at 0: where the operator stands
        if first.error > REACH_TOLERANCE and len(offsets) > 1:
            # out of reach from here (a step back for the reach before, a short operator): step
            # in towards the target first, as far as the hand falls short, onto it and clear
            short = first.error - REACH_TOLERANCE
            n_in = min(len(offsets) - 1, math.ceil(short / STEP_BACK) + 1)
            for j in range(1, n_in + 1):
                cand = candidate(-STEP_BACK * j, lean, drop)
                if cand is not None and cand.distance == np.inf and cand.error <= REACH_TOLERANCE:
                    return cand
        tolerance = max(first.error, REACH_TOLERANCE)
        best = first
        for s in offsets:
            cand = first if s == offsets[0] else candidate(float(s), lean, drop)
            if cand is None:
                continue
            # a step back must not cost the hand its target (beyond REACH_TOLERANCE)
            if cand.distance == np.inf and cand.error <= tolerance:
                return cand
            if cand.distance > best.distance and cand.error <= tolerance:
                best = cand
        return best

    upright = settle(lean=False)
    best = upright
    if upright.error > REACH_TOLERANCE:
        # a target no step brings within the arm's reach (low, as a bin by the feet, or deep):
        # the operator bends forward for it, and keeps the lean when it brings the hand closer
        bent = settle(lean=True)
        best = bent if bent.error < upright.error else upright
    # still touching the scene from every spot (a compartment low under a shelf, where the
    # arm from a standing or stooping shoulder slopes down through the shelf's front edge) or
    # short of the target (a part on a pallet): the operator crouches
    return _crouching_reach(settle, best, ctx.spec.stature)


def _crouching_reach(settle, best: WorkingReach, stature: float) -> WorkingReach:
    """``best`` (a reach standing or stooping), or when it touches the scene from every spot
    or its hand ends short of the target (beyond :data:`REACH_TOLERANCE`: a part on a pallet),
    the reach crouched (:mod:`mjwalk.cycle.crouch`) the least of :data:`CROUCH_DROPS` deep
    that is on its target and clear. Short of the target, a crouch is kept when it brings the
    hand onto it (within :data:`REACH_TOLERANCE`) without touching the scene more (a crouch
    does not bring a far target nearer: a few millimetres closer is no reason to squat);
    touching the scene, when it is clearer with the hand still on its target.
    ``settle(lean, drop)``: the stand-off's search of :func:`_reach_task`."""
    if best.distance >= 0.0 and best.error <= REACH_TOLERANCE:
        return best
    for share in CROUCH_DROPS:
        cand = settle(True, float(share * stature))
        if best.error > REACH_TOLERANCE:  # short: on the target, and no more in the scene
            if cand.error <= REACH_TOLERANCE and min(cand.distance, 0.0) >= min(best.distance, 0.0):
                best = cand
        elif cand.error <= REACH_TOLERANCE and cand.distance > best.distance:
            best = cand
        if best.distance == np.inf and best.error <= REACH_TOLERANCE:
            break
    return best
