"""Whole-body poses of a cycle's humanoid: standing, turning on the spot (with a short step
back), the frames of a walk with its arm swing or carrying posture, and hand positions.
World frame: metres, z up, yaw in radians from +x; frames at ``fps`` per second."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import mujoco
import numpy as np
from scipy.optimize import brentq

from mjwalk.arms.chain import ARM_JOINTS, arm_joint
from mjwalk.body.humanoid import pelvis_height
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.curves import smoothstep
from mjwalk.plan.lowtops import with_low_tops
from mjwalk.plan.rampside import with_ramps_beside
from mjwalk.timeline.collisions import collision_report
from mjwalk.timeline.frames import (
    CARRY_POSE,
    Carry,
    Clearance,
    ease_arms,
    frames_from_legs,
    room_and_away,
    yaw_quat,
)
from mjwalk.timeline.parts import hand_poses
from mjwalk.timeline.timeline import Timeline

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: Turning speed on the spot (rad/s) and shortest turn (s) of the reference adult
#: (:data:`~mjwalk.gait.walker.REFERENCE_CADENCE`): ASSUMPTION, a half turn in about two steps
#: (1.06 s at 113 steps/min). An operator turns at their cadence (``CycleContext.turn_rate``).
TURN_SPEED = math.radians(180.0)


MIN_TURN = 0.25


#: Speed (m/s) of a step back before a reach (:mod:`mjwalk.cycle.standoff`): a slow walk's
#: speed (about half the preferred 1.3 m/s walking speed; Bohannon 1997).
STEP_SPEED = 0.6
#: The eight corners of a box geom, as signs of its half-sizes (the order of
#: :func:`~mjwalk.body.legs.footcheck.lowest_point`'s).
_BOX_CORNERS = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T


def standing_pose(ctx: CycleContext, x: float, y: float, yaw: float) -> np.ndarray:
    """The humanoid's standing pose (its neutral joint angles) at ``(x, y)`` facing ``yaw``,
    the pelvis at its standing height over the walk surface there (:meth:`CycleContext.ground
    <mjwalk.cycle.context.CycleContext.ground>`: the floor in a flat cycle, a platform's or
    mezzanine's height in a cycle over levels).

    Args:
        ctx: the cycle context (the humanoid and its stature).
        x: the pelvis's position, world frame (m).
        y: the pelvis's position, world frame (m).
        yaw: the heading, radians from +x (counter-clockwise).

    Returns:
        (nq,) the pose.
    """
    q = ctx.jointmap.neutral_qpos(ctx.model, ctx.spec.stature)
    r = ctx.jointmap.root
    q[r : r + 3] = [x, y, pelvis_height(ctx.spec.stature) + ctx.ground((x, y))]
    q[r + 3 : r + 7] = yaw_quat(np.array([yaw]))[0]
    return q


def turn_frames(
    ctx: CycleContext,
    at: tuple[float, float],
    yaw0,
    yaw1,
    fps,
    to=None,
    pose: np.ndarray | None = None,
    settle: np.ndarray | None = None,
) -> tuple[np.ndarray, float]:
    r"""Frames of turning on the spot ``at`` from ``yaw0`` to ``yaw1`` (the shorter way),
    lasting :math:`\max(\mathrm{MIN\_TURN}, |\Delta\psi| / \mathrm{TURN\_SPEED}) /
    \mathrm{turn\_rate}` seconds (the context's ``turn_rate``); with ``to`` the pelvis moves
    there during the turn (a short step back, :mod:`mjwalk.cycle.standoff`; the turn lasts
    at least as long as that step at :data:`STEP_SPEED`). The body's joints hold ``pose``
    (e.g. the two-handed carrying posture, :func:`carry_pose`), the standing pose by default;
    only the root moves.

    With ``settle`` (the pose the body is in when the turn starts: a walk's last frame, the
    last step's landing, knee flexed and pelvis low) the turn also settles into the standing
    pose: the joints and the pelvis height go from ``settle`` to the turn's own pose with a
    smoothstep over the turn, instead of snapping there in one frame (unless the settling leg
    would touch the scene).

    Args:
        ctx: the cycle context.
        at: (x, y) where the operator stands, world frame (m).
        yaw0: the heading at the start, radians.
        yaw1: the heading at the end, radians.
        fps: frames per second.
        to: (x1, y1) where the pelvis ends, world frame (m); None: ``at``.
        pose: (nq,) the joint angles held (its root ignored); None: the standing pose.
        settle: (nq,) the pose before the turn to settle from; None: none.

    Returns:
        (frames (n, nq), duration in seconds = n / fps).
    """
    x, y = at
    d = (yaw1 - yaw0 + math.pi) % (2 * math.pi) - math.pi
    duration = max(MIN_TURN, abs(d) / TURN_SPEED) / ctx.turn_rate  # at the operator's cadence
    x1, y1 = (x, y) if to is None else to
    shift = math.hypot(x1 - x, y1 - y)
    if shift > 0.0:
        duration = max(duration, shift / STEP_SPEED)
    n = max(1, round(duration * fps))
    k = np.arange(1, n + 1)
    r = ctx.jointmap.root
    base = standing_pose(ctx, x, y, yaw0)
    if pose is not None:
        base[r + 7 :] = pose[r + 7 :]
    frames = np.repeat(base[None], n, axis=0)
    frames[:, r] = x + (x1 - x) * k / n
    frames[:, r + 1] = y + (y1 - y) * k / n
    frames[:, r + 3 : r + 7] = yaw_quat(yaw0 + d * k / n)
    if settle is not None:
        settled = frames.copy()
        _settle(settled, np.asarray(settle, float), r, ctx.jointmap.qposadr)
        _feet_above_floor(ctx, settled)
        if not _touches(ctx, settled):
            frames = settled
        # else: the settling leg would brush the scene (a foot landed beside a post): the body
        # goes straight to its standing pose, as it did before the settle, rather than touch
    return frames, n / fps


def _touches(ctx: CycleContext, frames: np.ndarray) -> bool:
    """Whether any of ``frames`` (n, nq) touches the scene (:func:`frame_contacts`)."""
    return bool(frame_contacts(ctx, frames))


def frame_contacts(ctx: CycleContext, frames: np.ndarray, fps: float = 30.0) -> list:
    """The humanoid-scene contacts of ``frames`` of ``ctx``'s model: the cycle's own contact
    check (:func:`~mjwalk.timeline.collisions.collision_report`, times from 0 s).

    Args:
        ctx: the cycle context.
        frames: (n, nq) poses.
        fps: their frame rate (for the contacts' times).

    Returns:
        The contacts (:class:`~mjwalk.timeline.collisions.Contact`), empty when none.
    """
    tl = Timeline(
        model=ctx.model,
        jointmap=ctx.jointmap,
        fps=fps,
        t=np.arange(len(frames)) / fps,
        qpos=frames,
        scene=str(ctx.spec.scene),
        stature=ctx.spec.stature,
    )
    return collision_report(tl, data=ctx.scratch())


def _feet_above_floor(ctx: CycleContext, frames: np.ndarray) -> None:
    """Raise the pelvis of ``frames`` (n, nq) in place where a blended pose puts a foot's lowest
    corner below the walk surface it stands on (the floor, z = 0, in a flat cycle): blending a
    landing pose (trailing heel raised, knee flexed) into the standing pose joint by joint
    swings that foot's toes through the floor. MuJoCo poses each frame; the corners of all
    frames are then placed at once (:func:`_lowest_points`)."""
    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    feet = np.array(
        [m.geom(f"{jm.prefix}{g}").id for g in ("foot_l", "foot_r", "toes_l", "toes_r")]
    )
    ground = ctx.ground(frames[-1, jm.root : jm.root + 2]) if len(frames) else 0.0
    xpos = np.empty((len(frames), len(feet), 3))
    xmat = np.empty((len(frames), len(feet), 9))
    qpos, gpos, gmat = data.qpos, data.geom_xpos, data.geom_xmat  # views, fetched once
    kinematics = mujoco.mj_kinematics
    for i, q in enumerate(frames):
        qpos[:] = q
        kinematics(m, data)
        gpos.take(feet, axis=0, out=xpos[i])
        gmat.take(feet, axis=0, out=xmat[i])
    low = _lowest_points(m.geom_size[feet], xpos, xmat)
    below = np.flatnonzero(low < ground)
    frames[below, jm.root + 2] += ground - low[below]


def _lowest_points(size: np.ndarray, xpos: np.ndarray, xmat: np.ndarray) -> np.ndarray:
    """(n,) the lowest corner's height (m) of G box geoms of half-sizes ``size`` (G, 3) placed
    at ``xpos`` (n, G, 3) and turned by ``xmat`` (n, G, 9) in each of n poses: the number
    :func:`~mjwalk.body.legs.footcheck.lowest_point` gives for each pose (the same products,
    one (8, 3) by (3, 3) matrix product per geom and pose, stacked)."""
    offsets = _BOX_CORNERS[None] * size[:, None]  # (G, 8, 3) in the geoms' axes
    turn = xmat.reshape(*xmat.shape[:2], 3, 3).swapaxes(-1, -2)
    corners = xpos[:, :, None, :] + offsets[None] @ turn  # (n, G, 8, 3)
    return corners[..., 2].min(axis=(1, 2))


def _settle(frames: np.ndarray, start: np.ndarray, r: int, hinges: np.ndarray) -> None:
    """Blend ``frames`` (n, nq) in place from ``start`` (the pose before them) into their own
    poses: weight smoothstep(k / n) for frame k = 1..n (the last frame is the frames' own pose).
    Hinge joints and the pelvis position blend linearly; the pelvis orientation keeps the
    frames' yaw and loses ``start``'s tilt (normalized linear blend of the quaternions)."""
    n = len(frames)
    s = np.arange(1, n + 1) / n
    w = smoothstep(s)[:, None]
    joints = np.r_[r : r + 3, np.asarray(hinges, int)]  # pelvis position, the humanoid's hinges
    frames[:, joints] = start[joints] + w * (frames[:, joints] - start[joints])
    q0 = start[r + 3 : r + 7]
    q1 = frames[:, r + 3 : r + 7]
    q0 = np.where((q1 @ q0)[:, None] < 0.0, -q0, q0)  # the shorter way round
    q = q0 + w * (q1 - q0)
    frames[:, r + 3 : r + 7] = q / np.linalg.norm(q, axis=1, keepdims=True)


def hand_points(ctx: CycleContext, qpos: np.ndarray) -> np.ndarray:
    """World positions of the left and right palm (the hand geoms' centres) in the poses
    ``qpos``.

    Args:
        ctx: the cycle context.
        qpos: (F, nq) poses.

    Returns:
        (F, 2, 3) metres, world frame (left, right).
    """
    return hand_poses(ctx.model, ctx.jointmap, qpos, ctx.scratch())[2]


def carry_abduction(ctx: CycleContext, width: float) -> float:
    """Shoulder abduction (both arms) of the two-handed carrying posture
    (:data:`~mjwalk.timeline.frames.CARRY_POSE` otherwise) that puts the palms ``width``
    metres apart: the hands stay on the grips of the part while it is carried. Solved by
    Brent's method within the joint's range (at most 1.2 rad; clipped to it when the part is
    wider or narrower than the arms can span).

    Args:
        ctx: the cycle context.
        width: the part's grip distance (m).

    Returns:
        The abduction, radians.
    """
    jm = ctx.jointmap
    q = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    for side in "lr":
        q[jm.adr(f"shoulder_{side}_flex")] = CARRY_POSE["shoulder_flex"]
        q[jm.adr(f"elbow_{side}")] = CARRY_POSE["elbow"]

    def gap(abd: float) -> float:
        for side in "lr":
            q[jm.adr(f"shoulder_{side}_abd")] = abd
        h = hand_points(ctx, q[None])[0]
        return float(np.linalg.norm(h[0] - h[1])) - width

    lo, hi = jm.limits("shoulder_l_abd")
    hi = min(hi, 1.2)
    if gap(lo) >= 0.0:
        return float(lo)
    if gap(hi) <= 0.0:
        return float(hi)
    return float(brentq(gap, lo, hi, xtol=1e-4))


def carry_pose(ctx: CycleContext, q: np.ndarray, width: float) -> np.ndarray:
    """``q`` with both arms in the two-handed carrying posture for a part whose grips are
    ``width`` metres apart: :data:`~mjwalk.timeline.frames.CARRY_POSE` with the shoulder
    abduction of :func:`carry_abduction`, the other arm joints at the standing pose (as in the
    carrying walk's frames, :func:`walk_frames`).

    Args:
        ctx: the cycle context.
        q: (nq,) the pose (root, trunk and legs kept).
        width: the part's grip distance (m).

    Returns:
        (nq,) the pose, radians (a new array).
    """
    jm = ctx.jointmap
    rest = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    out = np.array(q, dtype=float)
    abd = carry_abduction(ctx, width)
    for side in ("left", "right"):
        for name in ARM_JOINTS:
            k = jm.adr(arm_joint(name, side))
            out[k] = abd if name == "shoulder_abd" else CARRY_POSE.get(name, rest[k])
    return out


def walk_frame_times(walk, fps: float) -> np.ndarray:
    """The times of a walk's frames after its first sample (:func:`walk_frames`).

    Args:
        walk: the walk (:class:`~mjwalk.plan.walkpath.WalkPath`).
        fps: frames per second.

    Returns:
        (n,) seconds from the walk's start, ``1/fps`` apart, the last at its end.
    """
    t = np.arange(1, math.floor(walk.duration * fps) + 1) / fps
    if len(t) == 0 or t[-1] < walk.duration - 1e-9:
        t = np.append(t, walk.duration)
    return t


def walk_ground(ctx: CycleContext, walk, fps: float) -> np.ndarray:
    """The world height (m) of the walk surface under the pelvis in each of a walk's frames
    (:func:`walk_frames`): the floor's plus the walk's own surface heights
    (:attr:`WalkPath.ground <mjwalk.plan.walkpath.WalkPath.ground>`) at the frames' times.

    Args:
        ctx: the cycle context.
        walk: the walk.
        fps: frames per second.

    Returns:
        (n,) world z, metres (the floor's, ``Workplace.floor_z``, all along a floor walk).
    """
    t = walk_frame_times(walk, fps)
    return ctx.workplace.floor_z + np.interp(t, walk.t, walk.ground)


def walk_frames(
    ctx: CycleContext, walk, fps, carry: str | None = None, carry_width: float | None = None
) -> np.ndarray:
    """Frames of a walk after its first sample (legs from the footprints, arm swing from the
    legs). The arms swing fully only in mid-walk: the swing fades in over the first and out
    over the last :data:`~mjwalk.timeline.frames.ARM_EASE` seconds, so they are at rest when
    the operator stops at a rack or the car.

    Args:
        ctx: the cycle context.
        walk: the walk (:class:`~mjwalk.plan.walkpath.WalkPath`).
        fps: frames per second.
        carry: "left"/"right": that hand holds the part in front of the body (elbow flexed,
            forearm close to the trunk) instead of swinging; "both": both hands hold a part
            whose grips are ``carry_width`` metres apart in the carrying posture throughout,
            without fading (:func:`carry_abduction`); None: both arms swing.
        carry_width: the two-handed part's grip distance (m), with ``carry="both"``.

    Returns:
        (n, nq) the frames, at ``1/fps`` s apart from the walk's start (the last at its end).
    """
    if ctx.on_levels:  # feet on a ramp's low end the walk cuts past (a flat cycle has none)
        walk = with_ramps_beside(ctx.workplace, walk, ctx.spec.stature)
    walk = with_low_tops(ctx.workplace, walk, ctx.spec.stature)  # a mat, a cable bridge
    legs = legs_from_walk(walk, ctx.spec.stature)
    t = walk_frame_times(walk, fps)
    frames = frames_from_legs(ctx.model, ctx.jointmap, legs, t, ctx.spec.stature, "swing", None)
    jm = ctx.jointmap
    frames[:, jm.root + 2] += ctx.workplace.floor_z  # the walk's heights are above the floor
    room, away = room_and_away(ctx.workplace, frames[:, jm.root : jm.root + 2])
    rest = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    abd = carry_abduction(ctx, carry_width) if carry == "both" and carry_width else None
    ease_arms(
        frames,
        t,
        walk.duration,
        jm,
        rest,
        Clearance(room, away),
        None if carry is None else Carry(carry, abd),
        stature=ctx.spec.stature,
    )
    return frames
