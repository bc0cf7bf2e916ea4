"""One-handed reaches of a cycle: an arm from the standing pose to a pick/place/fasten target
(the PCA + DCS reach model, alzubi-sommer; the right arm mirrors it), on along the pre-grasp
approach, holding and returning; the trunk's lean and the crouch that bring a low target within
reach. Two-handed reaches are in :mod:`mjwalk.cycle.holding`, where the operator stands for a
reach in :mod:`mjwalk.cycle.reachspot`. World frame: metres, z up; frames at ``fps`` per
second."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import mujoco
import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk.anthropometry import knee_height
from mjwalk.arms import reach as armreach  # reach_for_side looked up per call (tests spy on it)
from mjwalk.arms.anglerows import all_close, min_jerk_steps, retrace_rows, unit_steps
from mjwalk.arms.armpose import blend_dir, blend_dirs
from mjwalk.arms.chain import (
    arm_frames,
    arm_joint_angles,
    end_effector,
    rows_in_range,
    two_link_ik_rows,
    wrist_in_range,
)
from mjwalk.arms.reach import humanoid_arm
from mjwalk.body.humanoid import PALM_SHARE
from mjwalk.body.legs.curves import smoothstep
from mjwalk.conventions import Side, other_side, side_prefix
from mjwalk.cycle.crouch import bend_trunk, crouch_frames, crouch_pose, trunk_bend
from mjwalk.cycle.handling import RETURN_CASE, body_motion_duration, reach_duration
from mjwalk.cycle.tiptoe import tiptoe_pose
from mjwalk.timeline.geomposes import body_poses, supported

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: A hand movement's (reach, return) durations in seconds for its path length in metres
#: (:func:`default_timing`, :func:`mjwalk.cycle.handling.reach_duration`).
Timing = Callable[[float], tuple[float, float]]
#: Steps (radians) of the trunk's forward lean for a target out of the arm's reach, and the
#: reach (m) the lean leaves to spare: the smallest lean, 5 deg at a time, that brings the target
#: within the arm's length less 2 cm of the shoulder (a choice: a reach short of locking the
#: elbow). The lean goes into the lumbar and thoracic flexion in proportion to their ranges
#: (:data:`mjwalk.anthropometry.ROM_DEG`: 60 and 45 deg).
LEAN_STEP = np.radians(5.0)
LEAN_SPARE = 0.02
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
#: Poses of the ready phase, and poses per interval between two of the trajectory's samples,
#: along which :func:`_hand_path` measures the knuckle's path (the frames interpolate the joint
#: angles between the samples; a finer split changes the length by well under 1 %).
PATH_POSES = 16
PATH_SUBSTEPS = 4
#: The ready phase (bending the hanging arm into the reach model's ready posture, or back)
#: lasts at least this long (s): the elbow bends by about 85 deg into the ready posture, at
#: most about 600 deg/s (peak elbow speeds of quick human reaches are of that order).
READY_MIN = 0.15


def default_timing(dist: float) -> tuple[float, float]:
    """The reference adult's reach (MTM-1 case B) and return (case E) times for a hand movement
    of ``dist`` metres.

    Args:
        dist: the hand's path, metres.

    Returns:
        (reach seconds, return seconds).
    """
    return reach_duration(dist, None, "B"), reach_duration(dist, None, RETURN_CASE)


def time_factor(timing: Timing | None) -> float:
    """The operator's time factor of a timing: the return time of a 1 m movement over the
    reference adult's (factor / pace), which times the body's bend and arise.

    Args:
        timing: ``timing(distance) -> (reach s, return s)``; None: the reference adult.

    Returns:
        The factor (1 for the reference adult).
    """
    return 1.0 if timing is None else timing(1.0)[1] / default_timing(1.0)[1]


@dataclass(frozen=True)
class ReachPace:
    """How long a reach lasts and how finely it is sampled.

    Attributes:
        hold: seconds the hand stays on the target between the reach and the return.
        fps: frames per second of the reach's frames.
        timing: ``timing(distance)``, the (reach, return) durations in seconds of a hand
            movement of ``distance`` metres; None: the reference adult's
            (:func:`default_timing`).
    """

    hold: float
    fps: float
    timing: Timing | None = None


@dataclass(frozen=True)
class Lowering:
    """How the body comes down for a reach.

    Attributes:
        lean: the trunk bends forward until the target is within the arm's reach
            (:func:`leaning`).
        drop: metres the pelvis is lowered in a crouch (:func:`~mjwalk.cycle.crouch.crouch_pose`);
            0: standing.
        rise: metres the heels lift the pelvis, on the toes
            (:func:`~mjwalk.cycle.tiptoe.tiptoe_pose`; one-handed reaches standing upright
            only); 0: feet flat.
    """

    lean: bool = False
    drop: float = 0.0
    rise: float = 0.0


#: A reach standing upright (no lean, no crouch).
STANDING = Lowering()


@dataclass(frozen=True)
class _Arm:
    """The reaching arm: its side, the reach model of that side, and the humanoid's arm at the
    model's size (``scale`` and the upper arm, forearm and hand ``lengths``,
    :func:`~mjwalk.arms.reach.humanoid_arm`)."""

    side: Side
    model: Any
    scale: float
    lengths: np.ndarray


def reach_frames(
    ctx: CycleContext,
    q0: np.ndarray,
    target_w: np.ndarray,
    approach_w: np.ndarray,
    pace: ReachPace,
    side: Side = "left",
    face: np.ndarray | None = None,
    lowering: Lowering = STANDING,
):
    """Frames of reaching from pose ``q0`` to ``target_w`` (world, m), holding, returning.

    ``pace.timing(distance)`` gives the (reach, return) durations in seconds of a hand movement
    of ``distance`` metres (the hand's true path at the index knuckle, as MTM-1 measures a
    reach: from where the hand is in ``q0`` along the planned movement to the target); default:
    the reference adult's MTM-1 case B reach and case E return (:mod:`mjwalk.cycle.handling`).

    The reach model (PCA + DCS) brings the hand from rest to the pre-grasp point
    ``target_w + approach_w``; the hand then moves straight onto the target along
    ``-approach_w`` with a minimum-jerk profile (two-link IK, hand direction kept), so it comes
    over a shelf's front edge instead of through it. The return retraces the motion.

    Args:
        ctx: the run's cycle context (the humanoid, its reach models).
        q0: (nq,) the standing pose the reach starts and ends in.
        target_w: (3,) the hand's target, world frame (m).
        approach_w: (3,) the pre-grasp point's offset from the target, world frame (m).
        pace: the hold time, frame rate and timing of the reach.
        side: the reaching arm, "left" or "right" (the right mirrors the left-arm model).
        face: (3,) world unit normal of a grip face (a box's side): during the approach the
            hand also turns to lie flat on that face (the approach's direction less its
            component along the normal), so the palm comes onto the face; None: no face.
        lowering: the trunk's lean and the crouch the reach comes down with (the other arm
            then hangs plumb from the bending trunk).

    Returns:
        (frames (F, nq) of the reach, hold and return; the hand's end's distance (m) from
        ``target_w`` at the end of the reach, as the humanoid holds it; the reach model's
        ReachResult).
    """
    model = ctx.reach_model_for(side)
    # the reach is solved at the reach model's arm lengths; another stature has the same arm
    # shape scaled (Winter's shares): the targets are scaled to the model's size (same angles)
    scale, lengths = humanoid_arm(model, ctx.spec.stature)
    arm = _Arm(side, model, scale, lengths)
    # ``base``: q0, or q0 bent forward at the trunk (the lean comes in with the ready phase and
    # goes with the return; the arm's poses are solved from the leaning shoulder)
    base = q0
    if lowering.drop > 0.0:  # crouched: the pelvis lower, the trunk bent (mjwalk.cycle.crouch)
        base = crouch_pose(ctx, q0, lowering.drop)
    elif lowering.rise > 0.0:  # on the toes (mjwalk.cycle.tiptoe), for a high shelf
        base = tiptoe_pose(ctx, q0, lowering.rise)
    if lowering.lean:
        base = leaning(ctx, base, [(side, target_w)], float(lengths.sum()) / scale - LEAN_SPARE)
    q, res = _solve_arm(ctx, arm, base, target_w, approach_w, face)
    timing = default_timing if pace.timing is None else pace.timing
    r = ctx.jointmap.root
    over = target_w[2] - ctx.ground(q0[r : r + 2])  # above the surface the operator stands on
    low = lowering.drop > 0.0 or (lowering.lean and over < knee_height(ctx.spec.stature))
    frames, error = _reach_motion(
        ctx, arm, q0, base, q, target_w, replace(pace, timing=timing), low
    )
    if lowering.lean or lowering.drop > 0.0:  # the other arm hangs plumb from the bending trunk
        frames = plumb_arms(ctx, frames, q0, np.ones(len(frames)), (other_side(side),))
    return frames, error, res


def _solve_arm(
    ctx: CycleContext,
    arm: _Arm,
    base: np.ndarray,
    target_w: np.ndarray,
    approach_w: np.ndarray,
    face: np.ndarray | None,
):
    """The arm's joint angles (n, 7) of a reach from pose ``base`` to ``target_w`` by way of
    the pre-grasp point ``target_w + approach_w`` (world, m): the reach model's trajectory to
    the pre-grasp point, then the straight approach onto the target (:func:`reach_frames`),
    and the reach model's ReachResult."""
    side, model, scale, lengths = arm.side, arm.model, arm.scale, arm.lengths
    m, jm, data = ctx.model, ctx.jointmap, ctx.scratch()
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
    res = armreach.reach_for_side(model, pre, side, start, arm_lengths=lengths)
    u_last = res.directions[-1]
    n_app = max(4, len(res.directions) // 2)
    app = np.repeat(u_last[None], n_app, axis=0)
    taus = min_jerk_steps(n_app + 1)[1:]
    hands = pre + taus[:, None] * (end - pre)
    # the hand's direction on the target: along its approach (the hand, and the forearm as far as
    # the wrist follows, stay on the approach's line, in from the target's free side: a shelf's
    # opening, the operator at the car), or in the grip face's plane; as far as the wrist can
    # turn it, the elbow swivelled as it needs (_wrist_feasible): the fingers end on the target
    u_app = frame.T @ -np.asarray(approach_w, dtype=float)
    u_app /= max(float(np.linalg.norm(u_app)), 1e-9)
    if face is not None:
        u_app = _in_face(u_app, frame.T @ np.asarray(face, dtype=float), u_last)
    u_end, elbow_end = _wrist_feasible(ctx, base, side, end, u_app, u_last, lengths)
    model_dirs = res.directions
    if face is not None:
        # a grip face: the hand turns to it during the last third of the movement to the
        # pre-grasp point and comes onto the face along the approach without turning, so the
        # part held between the palms moves straight along that line as it is lifted off (or
        # set down), instead of tilting in the hands
        model_dirs = _turn_hand(model_dirs, u_end, lengths)
        u_last = model_dirs[-1]
        app[:] = u_last
    elif not all_close(u_end, u_last[2]):
        app[:, 2] = blend_dirs(u_last[2], u_end, taus)
    wrists = hands - lengths[2] * app[:, 2]
    # the elbow swivels from where the model left it to where the hand's end pose needs it
    hints = blend_dirs(u_last[0], elbow_end, taus) * lengths[0]
    app[:, 0], app[:, 1] = two_link_ik_rows(wrists, lengths[0], lengths[1], hints)  # (row-wise)
    directions = np.concatenate([model_dirs, app])
    return arm_joint_angles(directions, side), res


def _in_face(u_app: np.ndarray, n_s: np.ndarray, u_last: np.ndarray) -> np.ndarray:
    """The hand's direction (unit, shoulder frame) on a grip face of normal ``n_s``: in the
    face's plane, the approach's direction ``u_app`` there, which keeps the wrists level with
    the grips and the forearms above a shelf board's front edge (the model's last direction,
    up for a part above the shoulder, would not); the model's own (``u_last``'s hand) when the
    approach runs along the normal (grips one behind the other)."""
    u_face = u_app - (u_app @ n_s) * n_s
    if np.linalg.norm(u_face) < 0.1:
        u_face = u_last[2] - (u_last[2] @ n_s) * n_s
    u_face /= max(float(np.linalg.norm(u_face)), 1e-9)
    return u_face


def _reach_motion(
    ctx: CycleContext,
    arm: _Arm,
    q0: np.ndarray,
    base: np.ndarray,
    q: np.ndarray,
    target_w: np.ndarray,
    pace: ReachPace,
    low: bool,
) -> tuple[np.ndarray, float]:
    """The frames (F, nq) of a reach with the arm's joint angles ``q`` from ``base`` (``q0``
    leaning or crouched), at ``pace`` (its timing given), ``low``: coming down with a crouch
    or a stoop below the knee; and the hand's error (m) from ``target_w``."""
    m, jm, fps, side = ctx.model, ctx.jointmap, pace.fps, arm.side
    assert pace.timing is not None
    # (``ready_pose``: the arm at the trajectory's first angles in ``base``, ranges applied)
    n_ready, n_out, n_rise, n_arm_ready, reach_back, ready_pose = _phase_counts(
        ctx, arm, q0, base, q, pace, low
    )
    w = smoothstep(np.arange(1, n_ready + 1) / (n_ready + 1))
    # the feet stay planted while the pelvis lowers (the legs solved at every pose)
    ready = crouch_frames(ctx, q0, ready_pose, w)
    n_out -= n_ready
    out, _ = arm_frames(base, jm, q, side, unit_steps(n_out + 1)[1:])
    data = ctx.scratch()
    data.qpos[:] = out[-1]
    mujoco.mj_kinematics(m, data)
    # the hand's end as the humanoid holds it (its hand body's -z axis, after the joint ranges)
    tip = hand_tip(data, m, jm, side, arm.lengths[2] / arm.scale)
    error = float(np.linalg.norm(tip - target_w))
    n_hold = max(0, round(pace.hold * fps))
    n_back = max(1, round(reach_back * fps))
    n_back = max(2, n_back - n_arm_ready)
    back = _retraced(out, n_back)
    rise = ready[::-1]  # ... the ready posture, hanging (standing up from a crouch)
    if n_rise != n_ready:
        w = smoothstep(np.arange(1, n_rise + 1) / (n_rise + 1))[::-1]
        rise = crouch_frames(ctx, q0, ready_pose, w)
    # (one copy: ready, out, hold, back, rise, q0)
    hold = np.repeat(out[-1:], n_hold, axis=0)
    return np.concatenate([ready, out, hold, back[1:], rise, q0[None]]), error


def _phase_counts(
    ctx: CycleContext,
    arm: _Arm,
    q0: np.ndarray,
    base: np.ndarray,
    q: np.ndarray,
    pace: ReachPace,
    low: bool,
) -> tuple[int, int, int, int, float, np.ndarray]:
    """Frame counts of a reach's phases: (ready phase with any crouch, reach out including
    the ready phase, rise, the arm's own ready phase), the return's duration (s) and the
    ready posture (:func:`_hand_path`'s first pose of the movement)."""
    assert pace.timing is not None
    timing, fps = pace.timing, pace.fps
    # MTM-1 times a reach by the true path of the hand, not the straight line from start to
    # end (MTM-1 data card, Reach: "distance moved ... is the true path"; Freivalds & Niebel
    # 2014, ch. 12): the humanoid's index knuckle from where it is in q0 (the ready phase bends
    # the arm into the model's start), along the model's trajectory and the approach
    knuckle = PALM_SHARE * arm.lengths[2] / arm.scale
    ready_len, model_len, ready_pose = _hand_path(ctx, q0, q, arm.side, knuckle, base)
    reach_out, reach_back = timing(ready_len + model_len)
    n_out = max(2, round(reach_out * fps))
    # The reach model's trajectories start at its ready posture (ReachModel.rest_hand; the
    # default model's REST_HAND: elbow bent, hand in front of the thigh), the standing arm
    # hangs straight: the first frames bend the arm into the ready posture (joint-space, the
    # hand stays by the body), their share of the reach time the share of the hand's path they
    # cover (one pace along the path), the rest follows the model's trajectory; the return
    # ends the same way, so the elbow bends into and out of the ready posture smoothly.
    share = ready_len / max(ready_len + model_len, 1e-9)
    n_ready = min(n_out - 2, max(1, round(max(share * n_out, READY_MIN * fps))))
    n_arm_ready = n_rise = n_ready
    if low:
        # the crouch (or a stoop for a target below the knee: MTM-1's bend) comes with the
        # ready phase and the rise with the return's, each taking at least MTM-1's bend /
        # arise at the operator's time factor (its return time over the reference adult's:
        # factor / pace); the reach lasts longer by what they add
        factor = time_factor(timing)
        n_down = round(body_motion_duration("B") * factor * fps)
        n_ready = max(n_ready, n_down)
        n_out += n_ready - n_arm_ready
        n_rise = max(n_arm_ready, round(body_motion_duration("AB") * factor * fps))
    return n_ready, n_out, n_rise, n_arm_ready, reach_back, ready_pose


def _retraced(out: np.ndarray, n_back: int) -> np.ndarray:
    """``n_back`` poses retracing the reach's frames ``out`` (F, nq) backwards: poses
    interpolated between the reach's frames (hinge angles; the root does not move during a
    reach), so the hand moves smoothly however the return's frame count divides the reach's."""
    n_out = len(out)
    src = np.linspace(0.0, n_out - 1.0, n_back)
    back = np.empty((n_back, out.shape[1]))
    retrace_rows(np.ascontiguousarray(out, dtype=float), src, back)  # (compiled, same numbers)
    return back


def leaning(ctx: CycleContext, q0: np.ndarray, targets, reach: float) -> np.ndarray:
    """``q0`` with the trunk bent forward just far enough that every ``(side, target)`` of
    ``targets`` lies within ``reach`` metres of that side's shoulder (lumbar and thoracic
    flexion, within their ranges, :data:`LEAN_STEP` at a time:
    :func:`~mjwalk.cycle.crouch.bend_trunk`); bent as far as they go when that is not enough.

    Args:
        ctx: the cycle context.
        q0: (nq,) the pose to bend.
        targets: (side, (3,) target in the world frame, m) pairs.
        reach: the distance (m) each target must come within of its shoulder.

    Returns:
        (nq,) the leaning pose.
    """
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


def hand_tip(data, m, jm, side, hand_length: float) -> np.ndarray:
    """World position of the end of ``side``'s hand in the pose ``data`` holds (kinematics
    done): the hand body's origin (the wrist) plus ``hand_length`` m along its -z axis, the
    direction the humanoid's hand points (:mod:`mjwalk.body.humanoid`).

    Args:
        data: MjData of ``m`` with the kinematics done.
        m: the humanoid's model.
        jm: its joint map (for the name prefix).
        side: "left" or "right".
        hand_length: metres from the wrist along the hand.

    Returns:
        (3,) world frame, metres.
    """
    b = m.body(f"{jm.prefix}hand_{side_prefix(side)}").id
    return data.xpos[b] - hand_length * data.xmat[b].reshape(3, 3)[:, 2]


def _turn_hand(directions: np.ndarray, u_end: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """``directions`` (n, 3, 3: upper arm, forearm, hand; shoulder frame) with the hand turned
    to ``u_end`` over the last third of the samples (a smooth blend reaching ``u_end`` at the
    last), the hand's end kept where it was (the upper arm and forearm re-solved for the
    moved wrist, the elbow swivelled as little as it can)."""
    out = np.array(directions, dtype=float)
    n_turn = max(2, len(out) // 3)
    tail = out[-n_turn:]
    taus = smoothstep(np.arange(1, n_turn + 1) / n_turn)
    ends = end_effector(tail, lengths)
    hands = blend_dirs(tail[:, 2], u_end, taus)
    wrists = ends - lengths[2] * hands
    u1, u2 = two_link_ik_rows(wrists, lengths[0], lengths[1], tail[:, 0] * lengths[0])
    out[-n_turn:] = np.stack([u1, u2, hands], axis=1)
    return out


def _wrist_feasible(
    ctx: CycleContext, q0, side, end, u_hand, u_last, lengths
) -> tuple[np.ndarray, np.ndarray]:
    """A hand direction (unit, shoulder frame) the humanoid's wrist can hold with the hand's
    end on ``end`` (model size), and the upper arm's direction for it: ``u_hand`` (turned
    towards ``end`` as far as the arm needs to reach it: :func:`_within_reach`) with the elbow
    where the model's last pose has it (``u_last``) when the arm's joint angles are within their
    ranges there; else ``u_hand`` with the elbow swivelled about the shoulder-wrist axis (the
    nearest of :data:`SWIVELS` that keeps every joint in range: people turn the elbow out or in
    to orient the hand); else the hand turned only as far as the humanoid's wrist ranges allow,
    the arm re-solved for that hand (:func:`~mjwalk.arms.chain.wrist_in_range`)."""
    u = _within_reach(np.asarray(u_hand, dtype=float), end, lengths)
    hint = u_last[0] * lengths[0]
    wrist = end - lengths[2] * u
    # the nearest swivel (0: the hint itself) alone first: the batch's row 0, most often in range
    u1, u2 = two_link_ik_rows(wrist[None], lengths[0], lengths[1], hint[None])
    q1 = arm_joint_angles(np.stack([u1, u2, u[None]], axis=1), side, None, True)
    if rows_in_range(ctx.jointmap, q1, side)[0]:
        return u, u1[0]
    axis = wrist / max(float(np.linalg.norm(wrist)), 1e-9)
    # else the hint turned by each swivel about the shoulder-wrist axis, all solved at once
    hints = Rotation.from_rotvec(SWIVELS[:, None] * axis).apply(hint)
    wrists = np.repeat(wrist[None], len(hints), axis=0)
    u1, u2 = two_link_ik_rows(wrists, lengths[0], lengths[1], hints)
    dirs = np.stack([u1, u2, np.repeat(u[None], len(hints), axis=0)], axis=1)
    ok = np.flatnonzero(rows_in_range(ctx.jointmap, arm_joint_angles(dirs, side, None, True), side))
    if len(ok):
        return u, u1[ok[0]]
    # no swivel will do: the wrist at the humanoid's range limits, the arm re-solved for it
    limits = np.array(
        [ctx.jointmap.limits(f"wrist_{side_prefix(side)}_{dof}") for dof in ("flex", "dev")]
    )
    arm = wrist_in_range(end[None], u[None], lengths, hint[None], limits, side, WRIST_ITERATIONS)
    return arm[0, 2], arm[0, 0]


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
        v = blend_dir(u, radial, float(b))
        if np.linalg.norm(end - lengths[2] * v) <= reach:
            return v
    return radial


def _hand_path(
    ctx: CycleContext, q0, q, side, knuckle: float, base=None
) -> tuple[float, float, np.ndarray]:
    """Lengths (m) of the path of the humanoid's index knuckle in a reach, where MTM-1 measures
    a hand's reach (Freivalds & Niebel 2014, *Niebel's Methods, Standards, and Work Design*,
    13th ed., ch. 12): ``(ready, movement)``, through the ready phase's poses (the joint angles
    from ``q0`` into the trajectory's first pose) and the trajectory's poses (joint angles ``q``,
    (n, 7), each interval split as the frames interpolate it), after the joint ranges.
    ``knuckle``: its distance (m) from the wrist along the hand (the operator's size).
    ``base``: the pose the arm's angles are set in (q0 bent forward, for a leaning reach).
    Forward kinematics compiled over all poses (:func:`~mjwalk.timeline.geomposes.body_poses`;
    in the context's scratch data, pose by pose, for a model it does not support). Also
    returns the movement's first pose, (nq,): ``base`` with the arm at ``q[0]`` after the
    ranges (the ready posture; what ``arm_frames`` gives for ``q[:1]`` at any time)."""
    m, jm = ctx.model, ctx.jointmap
    base = q0 if base is None else base
    steps = unit_steps(PATH_SUBSTEPS * (len(q) - 1) + 1)
    move, _ = arm_frames(base, jm, q, side, steps)
    # (from q0 into move[0], the trajectory's first pose: np.interp gives a sample's own value)
    ready = q0[None] + unit_steps(PATH_POSES)[:, None] * (move[0] - q0)[None]
    hand = m.body(f"{jm.prefix}hand_{side_prefix(side)}").id
    # the hand body's origin and -z axis in every pose, ready phase and movement in one call
    # (compiled kinematics over all poses where the model allows it: a pose's numbers are its
    # own, whatever comes before it), then :func:`hand_tip`'s point ``knuckle`` m along the
    # hand for all of them at once
    poses = np.concatenate([ready, move])
    if supported(m):
        xpos, xmat = body_poses(m, poses, np.array([hand]))
        origin, axis = xpos[:, 0], xmat[:, 0, 2::3]
    else:
        data = ctx.scratch()
        origin, axis = np.empty((len(poses), 3)), np.empty((len(poses), 3))
        for k, pose in enumerate(poses):
            data.qpos[:] = pose
            mujoco.mj_kinematics(m, data)
            origin[k] = data.xpos[hand]
            axis[k] = data.xmat[hand, 2::3]
    points = origin - knuckle * axis

    def length(path: np.ndarray) -> float:
        return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())

    return length(points[: len(ready)]), length(points[len(ready) :]), move[0]


def plumb_arms(
    ctx: CycleContext,
    frames: np.ndarray,
    q0: np.ndarray,
    share: np.ndarray,
    sides=("left", "right"),
) -> np.ndarray:
    """``frames`` with the shoulder flexions of ``sides`` raised by ``share`` times the trunk's
    forward bend beyond ``q0``'s (lumbar and thoracic flexion; within the shoulder's range): at
    share 1 an arm hanging in ``q0`` hangs plumb from the bent trunk.

    Args:
        ctx: the cycle context.
        frames: (F, nq) poses.
        q0: (nq,) the upright pose the bend is measured from.
        share: (F,) how much of the bend each frame's arms make up for, 0 to 1.
        sides: the arms, "left" and/or "right".

    Returns:
        (F, nq) the poses (a new array).
    """
    jm = ctx.jointmap
    bend = trunk_bend(ctx, frames, q0)
    out = frames.copy()
    for p in (side_prefix(side) for side in sides):
        k = jm.adr(f"shoulder_{p}_flex")
        lo, hi = jm.limits(f"shoulder_{p}_flex")
        out[:, k] = np.clip(frames[:, k] + share * bend, lo, hi)
    return out
