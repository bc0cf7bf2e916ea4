"""Two-handed work of a cycle: both arms reach for the grip sites ``<site>_left`` and
``<site>_right`` together, and between the grips and the carrying posture the hands keep the
part's width between the palms, pulling it clear of a shelf before lowering it. World frame:
metres, z up; frames at ``fps`` per second."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import mujoco
import numpy as np
from scipy.optimize import brentq

from mjwalk.anthropometry import knee_height
from mjwalk.arms.chain import (
    arm_adrs,
    arm_frames,
    arm_joint,
    arm_joint_angles,
    min_jerk,
    two_link_ik_rows,
)
from mjwalk.arms.reach import humanoid_arm
from mjwalk.body.legs.curves import smoothstep
from mjwalk.conventions import Side, side_prefix
from mjwalk.cycle import reaching
from mjwalk.cycle.crouch import crouch_frames, crouch_pose, trunk_bend, trunk_room
from mjwalk.cycle.handling import body_motion_duration
from mjwalk.cycle.poses import carry_pose, hand_points
from mjwalk.cycle.reaching import (
    LEAN_SPARE,
    STANDING,
    Lowering,
    ReachPace,
    default_timing,
    plumb_arms,
    time_factor,
)
from mjwalk.cycle.types import TASK_KINDS, Task, grip_sites
from mjwalk.timeline.parts import hand_poses

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: Largest shift (radians) of both shoulder abductions that :func:`_holding_frames` tries to keep
#: the palms' distance while the hands move a held part (the abduction's range is about 1.2 rad).
HOLD_SHIFT = 0.5
#: How far :func:`_held_move` pulls a held part back from a shelf before lowering it, tried in
#: this order (shares of its ``back``, the pre-grasp approach's level part: 5, 10, 15 cm): the
#: least that clears the shelf keeps the part in front of the operator's face.
HELD_BACK_SHARES = (1.0 / 3.0, 2.0 / 3.0, 1.0)


def two_hand_frames(
    ctx: CycleContext,
    q0: np.ndarray,
    task: Task,
    approach: np.ndarray,
    pace: ReachPace,
    held: float | None = None,
    lowering: Lowering = STANDING,
):
    """A two-handed reach (:func:`_two_hand_reach`) from ``q0``, or, with ``lowering.lean`` or
    ``lowering.drop`` (m), from ``q0`` crouched that much
    (:func:`~mjwalk.cycle.crouch.crouch_pose`) and with the trunk bent forward until both grips
    are within the arms' reach
    (:func:`~mjwalk.cycle.reaching.leaning`): a part on a pallet or a low bench, which no standing
    reach gets both hands to. The body goes down with the arms as they are in ``q0`` (hanging, or
    holding the part in the carrying posture), the reach runs from there, and the body comes back up
    with the arms as the reach leaves them (carrying the part it picked, hanging after a place), the
    feet planted throughout (:func:`~mjwalk.cycle.crouch.crouch_frames`). Going down and coming up
    are MTM-1's body motions "B" (bend, stoop) and "AB" (arise) at the operator's time factor,
    before and after the reach (MTM-1 adds body and hand motions).

    Args:
        ctx: the run's cycle context.
        q0: (nq,) the pose the reach starts and ends in (standing, or carrying with ``held``).
        task: the two-handed pick or place (``hand = "both"``; its site's grip sites
            ``<site>_left`` and ``<site>_right``).
        approach: (3,) the pre-grasp point's offset from the grips, world frame (m).
        pace: the hold time, frame rate and timing of the reach.
        held: grip distance (m) of a part in the hands (a place), None: hands free (a pick).
        lowering: the trunk's lean and the crouch the reach comes down with.

    Returns:
        What :func:`_two_hand_reach` returns: (frames (F, nq), the larger hand error (m), the
        left arm's ReachResult with both arms' warnings, the grip distance (m)).
    """
    assert task.site is not None  # the spec loader requires a site for reaches
    lean, drop = lowering.lean, lowering.drop
    if not lean and drop <= 0.0:
        return _two_hand_reach(ctx, q0, task, approach, pace, held)
    body = crouch_pose(ctx, q0, drop)
    grips: list[tuple[Side, np.ndarray]] = [
        ("right" if s == "right" else "left", ctx.workplace.station(n).pos)
        for s, n in grip_sites(task.site, "both")
    ]
    if lean:
        scale, lengths = humanoid_arm(ctx.reach_model_for("left"), ctx.spec.stature)
        body = reaching.leaning(ctx, body, grips, float(lengths.sum()) / scale - LEAN_SPARE)
    frames, error, res, width = _two_hand_reach(ctx, body, task, approach, pace, held)
    fps = pace.fps
    factor = time_factor(pace.timing)
    share = 1.0
    ground = ctx.ground(body[ctx.jointmap.root : ctx.jointmap.root + 2])  # the surface stood on
    if drop <= 0.0 and min(float(g[2]) for _, g in grips) - ground >= knee_height(ctx.spec.stature):
        # MTM-1's bend is the one that lets the hands reach below the knee; a shallower bend
        # (a deep bench) assists the reach: it goes down and up at a full bend's pace (the
        # trunk's flexion range in the bend's time), for as long as its angle needs
        share = min(1.0, float(trunk_bend(ctx, body, q0)) / max(trunk_room(ctx, q0).sum(), 1e-9))
    n_down = max(1, round(share * body_motion_duration("B") * factor * fps))
    n_up = max(1, round(share * body_motion_duration("AB") * factor * fps))
    # down with the arms of q0; up with the arms of the reach's last frame (root and legs of
    # q0 standing, crouch_frames lowers the pelvis and solves the legs at each pose)
    down = crouch_frames(ctx, q0, body, smoothstep(np.arange(1, n_down + 1) / n_down))
    last = frames[-1]
    standing = np.array(q0, dtype=float)
    arms = arm_adrs(ctx.jointmap)
    standing[arms] = last[arms]
    up = crouch_frames(ctx, standing, last, smoothstep(np.arange(n_up) / n_up)[::-1])
    seq = np.vstack([down, frames, up])
    # hands free (going down for a pick, coming up after a place): the arms hang plumb from
    # the bending trunk instead of swinging back with it, and swing into (out of) the reach
    # over as long as the bend (arise) takes (at most a third of the reach)
    free = np.zeros(len(seq))
    if held is None:
        n_b = max(1, min(n_down, len(frames) // 3))
        free[:n_down] = 1.0
        free[n_down : n_down + n_b] = 1.0 - smoothstep(np.arange(1, n_b + 1) / (n_b + 1))
    else:
        n_b = max(1, min(n_up, len(frames) // 3))
        free[len(seq) - n_up :] = 1.0
        free[len(seq) - n_up - n_b : len(seq) - n_up] = smoothstep(
            np.arange(1, n_b + 1) / (n_b + 1)
        )
    return plumb_arms(ctx, seq, q0, free), error, res, width


def _two_hand_reach(
    ctx: CycleContext,
    q0: np.ndarray,
    task: Task,
    approach: np.ndarray,
    pace: ReachPace,
    held: float | None = None,
):
    """A two-handed reach (``hand = "both"``): the left arm to the grip site ``<site>_left``, the
    right arm (the mirrored model) to ``<site>_right``, at the same time, holding and returning
    together. A pick's return brings the part into the carrying posture
    (:func:`~mjwalk.cycle.poses.carry_pose`) instead of back to rest; with ``held`` (the grip
    distance in metres of the part in the hands, ``q0`` in its carrying posture) the reach starts
    from that posture and the return goes to rest. Between the grips and the carrying posture
    the palms keep their distance (:func:`_holding_frames`). Returns (frames, the larger hand
    error in metres, the left arm's ReachResult with both arms' warnings, the grip distance in
    metres)."""
    assert task.site is not None  # the spec loader requires a site for reaches
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
    timing, hold, fps = pace.timing, pace.hold, pace.fps

    def shared(dist: float) -> tuple[float, float]:
        if not first:
            first.append(timing(dist) if timing is not None else default_timing(dist))
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
            *reaching.reach_frames(
                ctx, q0, grip, approach, replace(pace, timing=shared), side, face=normal
            ),
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
    # grips (above the bench and back towards the operator: targets.approach_offset); a held part
    # comes and goes the same way, so it is lowered onto the bench and lifted off it along
    # that line instead of swept from the carrying posture through the bench's edge
    app = _approach_frames(ctx, frames[:n_out], float(np.linalg.norm(approach)))
    n_app = min(len(app) - 1, n_out - 2, n_back - 2)
    takes = TASK_KINDS[task.kind].part == "take"
    if held is not None or takes:
        # the pre-grasp pose with the palms still the part's width apart
        pre = _palms_apart(ctx, frames[n_out - 1 - n_app], _palm_gap(ctx, grip))
        back = np.r_[approach[:2], 0.0]  # further back from the pre-grasp point, level
    if held is not None:  # carrying posture -> above the bench -> down onto the grips
        mid = [hand_points(ctx, q[None])[0].mean(axis=0) for q in (carrying, pre, grip)]
        on, down = np.linalg.norm(np.diff(mid, axis=0), axis=1)
        n_down = int(np.clip(round(n_out * down / max(on + down, 1e-9)), 1, n_out - 2))
        head = _held_move(ctx, carrying, pre, n_out - n_down, pre, back)
        frames[:n_out] = np.vstack([head, _holding_frames(ctx, pre, grip, n_down)])
    elif takes:  # lifted off the bench, then into the carrying posture
        q_carry = carry_pose(ctx, q0, width)
        # the return's time shared by the two moves in proportion to the palms' travel
        mid = [hand_points(ctx, q[None])[0].mean(axis=0) for q in (grip, pre, q_carry)]
        up, on = np.linalg.norm(np.diff(mid, axis=0), axis=1)
        n_lift = int(np.clip(round(n_back * up / max(up + on, 1e-9)), 1, n_back - 2))
        lift = _holding_frames(ctx, grip, pre, n_lift)
        rest_frames = _held_move(ctx, pre, q_carry, n_back - n_lift, pre, back)
        frames[n_out + n_hold :] = np.vstack([lift, rest_frames])
    return frames, max(el, er), rl, width


def _approach_frames(ctx: CycleContext, reach: np.ndarray, length: float) -> np.ndarray:
    """The final frames of ``reach`` (F, nq; a two-handed reach's frames up to the grips) in
    which both palms move along the straight pre-grasp approach of ``length`` metres: from the
    last frame with a palm at least 90 % of that length from its final position to the end
    (at least the last frame)."""
    h = hand_points(ctx, reach)
    d = np.linalg.norm(h - h[-1][None], axis=2).max(axis=1)
    far = np.flatnonzero(d >= 0.9 * length)
    return reach[int(far[-1]) if len(far) else len(reach) - 1 :]


def _holding_frames(ctx: CycleContext, qa: np.ndarray, qb: np.ndarray, n: int) -> np.ndarray:
    """``n`` frames (n, nq) that move both hands, holding a part, from pose ``qa`` to ``qb``
    (``qa`` excluded, ``qb`` included; same root): every joint on a minimum-jerk profile, and
    both shoulder abductions shifted together in each frame (:func:`_palms_apart`) so the palms'
    distance (m) follows the same profile from ``qa``'s to ``qb``'s: the hands keep the grips
    of the part they carry between the bench and the carrying posture."""
    ga, gb = _palm_gap(ctx, qa), _palm_gap(ctx, qb)
    prof = min_jerk(np.arange(1, n + 1) / n)
    frames = qa[None] + prof[:, None] * (qb - qa)[None]
    for f, p in enumerate(prof[:-1]):  # the last frame is qb itself
        frames[f] = _palms_apart(ctx, frames[f], ga + p * (gb - ga))
    return frames


def _held_move(
    ctx: CycleContext, qa: np.ndarray, qb: np.ndarray, n: int, out: np.ndarray, back: np.ndarray
) -> np.ndarray:
    """``n`` frames moving a held part from ``qa`` to ``qb`` (:func:`_holding_frames`), one of
    them (``out``) the hands out at a bench or shelf, the other the carrying posture. When the
    direct move touches the scene (a part lifted off a shelf above the shoulder and lowered
    straight into the carrying posture: the arms swing down in an arc through the board's
    front edge), the hands go in straight lines (:func:`_straight_holding`) by way of ``out``
    with the hands moved by ``back`` (world, m: towards the operator, :func:`hands_moved`),
    pulling the part clear of the shelf before lowering it (on the way out, the reverse);
    kept when it is clearer (:class:`~mjwalk.cycle.standoff.ArmClearance`)."""
    direct = _holding_frames(ctx, qa, qb, n)
    if n < 4:
        return direct
    check = ctx.clearance
    touch = check.distance(direct)
    if touch >= 0.0:
        return direct
    best, best_d = direct, touch
    n1 = n // 2
    for share in HELD_BACK_SHARES:  # the least pull that is clear
        mid = hands_moved(ctx, out, share * np.asarray(back, dtype=float))
        staged = np.vstack(
            [_straight_holding(ctx, qa, mid, n1), _straight_holding(ctx, mid, qb, n - n1)]
        )
        d = check.distance(staged)
        if d > best_d:
            best, best_d = staged, d
        if d == np.inf:
            break
    return best


def _straight_holding(ctx: CycleContext, qa: np.ndarray, qb: np.ndarray, n: int) -> np.ndarray:
    """:func:`_holding_frames` from ``qa`` to ``qb`` with each wrist moved onto the straight
    line between its positions in the two poses, on the same minimum-jerk profile
    (:func:`hands_moved`): the hands carry the part along a line, not the arc that
    interpolated joint angles sweep."""

    def wrists(qpos: np.ndarray) -> np.ndarray:  # (F, 2, 3): the hand bodies' origins
        return hand_poses(ctx.model, ctx.jointmap, qpos, ctx.scratch())[0]

    frames = _holding_frames(ctx, qa, qb, n)
    wa, wb = wrists(qa[None])[0], wrists(qb[None])[0]
    prof = min_jerk(np.arange(1, n + 1) / n)
    now = wrists(frames)
    for f in range(n - 1):  # the last frame is qb itself
        frames[f] = hands_moved(ctx, frames[f], wa + prof[f] * (wb - wa) - now[f])
    return frames


def hands_moved(ctx: CycleContext, q: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """Pose ``q`` with both hands moved by ``offset``, each keeping its direction, the elbow
    swivelled least (two-link IK in the shoulder's frame,
    :func:`~mjwalk.arms.chain.two_link_ik_rows`; within the joint ranges).

    Args:
        ctx: the cycle context (its scratch data is used).
        q: (nq,) the pose.
        offset: world frame, metres: (3,) for both hands, or (2, 3) left, right.

    Returns:
        (nq,) the pose with the arms re-solved (a new array).
    """
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


def _palm_gap(ctx: CycleContext, q: np.ndarray) -> float:
    """Distance (m) between the palms in pose ``q``."""
    h = hand_points(ctx, q[None])[0]
    return float(np.linalg.norm(h[0] - h[1]))


def _palms_apart(ctx: CycleContext, q: np.ndarray, want: float) -> np.ndarray:
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


def _shift_to_gap(ctx: CycleContext, q: np.ndarray, want: float, joint: str):
    """(pose with both ``shoulder_<side>_<joint>`` angles shifted together, within
    :data:`HOLD_SHIFT` and the joint limits, so the palms lie ``want`` metres apart, or None
    when no shift reaches it; the pose at the end of the shift range nearest ``want``)."""
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
