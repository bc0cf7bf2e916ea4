"""Crouching for a reach: the pelvis lowered with both feet planted, the trunk bent for balance.

A target low under a shelf (a compartment at knuckle height) cannot be reached from a standing
or stooping shoulder without the forearm sloping down through the shelf's front edge: people
bend the knees to bring the shoulder down to the opening (a squat or semi-squat). Here the
pelvis drops by ``drop`` metres with the feet flat where they stand; it moves back only as far
as the ankle's dorsiflexion range needs (the shank tilts forward by at most that range, the
thigh takes the rest), the legs solved by :func:`~mjwalk.body.legs.ik.leg_ik`; then
the trunk bends forward (lumbar and thoracic flexion in proportion to their ranges, as the
reach's lean) until the body's centre of mass is as far forward of the ankles as standing --
static balance over the feet, since a pelvis behind the ankles would otherwise tip the body
back.

World frame: metres, z up, yaw from +x; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from mjwalk.anthropometry import ROM_DEG, leg_geometry
from mjwalk.body.legs.ik import LEG_JOINTS, leg_ik
from mjwalk.conventions import side_of_prefix as side_of
from mjwalk.cycle.tiptoe import heel_rise_of, tiptoe_frames

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: The shank's forward tilt (share of the ankle's dorsiflexion range) a crouch uses at most: a
#: tenth of the range kept in reserve, as the legs' IK never locks a joint at its limit.
DORSIFLEXION_SHARE = 0.9
#: Steps (radians) of the trunk's balancing lean.
BALANCE_STEP = math.radians(2.5)


#: The trunk's flexion joints a forward bend uses, in proportion to the range each has left.
TRUNK_FLEXION = ("lumbar_flex", "thoracic_flex")


def bend_trunk(ctx: CycleContext, q0: np.ndarray, step: float, enough) -> np.ndarray:
    """``q0`` with the trunk bent forward ``step`` radians at a time (lumbar and thoracic
    flexion in proportion to the range each has left) until ``enough(data)`` holds for the
    pose's forward kinematics in ``ctx.scratch()``; bent as far as the ranges go when it never
    does. The reach's lean (:func:`mjwalk.cycle.reaching.leaning`) and the crouch's balance
    both bend this way.

    Args:
        ctx: the cycle context (its humanoid and scratch data).
        q0: (nq,) the pose to bend.
        step: the bend's increment, radians (lumbar and thoracic flexion together).
        enough: ``enough(data) -> bool`` on the bent pose's kinematics.

    Returns:
        (nq,) the bent pose (a new array).
    """
    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    q0 = np.asarray(q0, dtype=float)
    joints = [jm.adr(j) for j in TRUNK_FLEXION]
    room = trunk_room(ctx, q0)
    total = float(room.sum())
    q = q0.copy()
    for theta in np.arange(0.0, total + 1e-9, float(step)):
        q[joints] = q0[joints] + theta * room / max(total, 1e-9)
        data.qpos[:] = q
        mujoco.mj_kinematics(m, data)
        if enough(data):
            return q
    q[joints] = q0[joints] + room
    return q


def trunk_room(ctx: CycleContext, q0: np.ndarray) -> np.ndarray:
    """How far each of :data:`TRUNK_FLEXION` can still flex forward in ``q0``.

    Args:
        ctx: the cycle context (its joint map's ranges).
        q0: (nq,) the pose.

    Returns:
        (2,) radians left to each joint's upper limit (lumbar, thoracic; at least 0).
    """
    jm = ctx.jointmap
    q0 = np.asarray(q0, dtype=float)
    return np.maximum([jm.limits(j)[1] - q0[jm.adr(j)] for j in TRUNK_FLEXION], 0.0)


def trunk_bend(ctx: CycleContext, q: np.ndarray, q0: np.ndarray) -> np.ndarray:
    """How far the trunk of pose(s) ``q`` is bent forward beyond ``q0``'s (lumbar and thoracic
    flexion together).

    Args:
        ctx: the cycle context (its joint map).
        q: (..., nq) the poses.
        q0: (nq,) the reference pose.

    Returns:
        (...,) the extra flexion, radians.
    """
    k = [ctx.jointmap.adr(j) for j in TRUNK_FLEXION]
    return np.asarray(q)[..., k].sum(axis=-1) - np.asarray(q0)[k].sum()


@dataclass(frozen=True)
class _Stance:
    """Where a standing pose's feet and hips are (world, m) and its pelvis frame (3, 3)."""

    q0: np.ndarray
    pelvis: np.ndarray
    ankle: dict[str, np.ndarray]
    hip: dict[str, np.ndarray]


def _stance(ctx: CycleContext, q0: np.ndarray) -> _Stance:
    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    q0 = np.asarray(q0, dtype=float)
    data.qpos[:] = q0
    mujoco.mj_kinematics(m, data)

    def anchor(name: str) -> np.ndarray:
        return data.xanchor[m.joint(f"{jm.prefix}{name}").id].copy()

    pelvis = data.xmat[m.body(f"{jm.prefix}pelvis").id].reshape(3, 3).copy()
    return _Stance(
        q0,
        pelvis,
        {p: anchor(f"ankle_{p}_flex") for p in "lr"},
        {p: anchor(f"hip_{p}_flex") for p in "lr"},
    )


def com_ahead(ctx: CycleContext, data) -> float:
    """How far the humanoid's centre of mass lies ahead of the midpoint of its ankle joints,
    along its pelvis's heading (+x), in the pose whose kinematics ``data`` holds.

    Args:
        ctx: the cycle context (its humanoid model).
        data: MjData of ``ctx.model`` with the kinematics done (its ``subtree_com`` is
            computed here).

    Returns:
        The horizontal distance, metres (negative: behind the ankles).
    """
    m, jm = ctx.model, ctx.jointmap
    mujoco.mj_comPos(m, data)
    pelvis = m.body(f"{jm.prefix}pelvis").id
    ahead = data.xmat[pelvis].reshape(3, 3)[:2, 0]
    ankles = [data.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id][:2] for p in "lr"]
    com = data.subtree_com[pelvis][:2]
    return float((com - 0.5 * (ankles[0] + ankles[1])) @ ahead / np.linalg.norm(ahead))


def _lowered(ctx: CycleContext, stance: _Stance, drop: float) -> np.ndarray:
    """The stance's pose with the pelvis ``drop`` metres lower and back as far as the ankles'
    dorsiflexion needs, the legs solved for the feet where they stand (see the module doc)."""
    q = stance.q0.copy()
    if drop <= 0.0:
        return q
    jm = ctx.jointmap
    geom = leg_geometry(ctx.spec.stature)
    ahead = stance.pelvis[:, 0]
    # the pelvis back as far as the shank's tilt needs (hip over the ankle while it suffices)
    tilt = DORSIFLEXION_SHARE * math.radians(ROM_DEG["ankle_flex"][1])
    height = 0.5 * sum(stance.hip[p][2] - stance.ankle[p][2] for p in "lr") - drop
    rise = height - geom.shank * math.cos(tilt)
    reach = math.sqrt(max(geom.thigh**2 - rise**2, 0.0))
    back = max(0.0, reach - geom.shank * math.sin(tilt))
    shift = -back * ahead - np.array([0.0, 0.0, drop])
    r = jm.root
    q[r : r + 3] = q[r : r + 3] + shift
    for p in "lr":
        rel = stance.pelvis.T @ (stance.ankle[p] - (stance.hip[p] + shift))
        for name, value in leg_ik(rel[None], np.zeros(1), np.zeros(1), side_of(p), geom).items():
            q[jm.adr(name)] = value[0]
    return q


def crouch_pose(ctx: CycleContext, q0: np.ndarray, drop: float) -> np.ndarray:
    """``q0`` with the pelvis ``drop`` metres lower and moved back as far as the ankles'
    dorsiflexion needs, the feet flat where they are in ``q0``, and the trunk bent forward
    until the centre of mass is as far ahead of the ankles as in ``q0`` (see the module
    docstring).

    Args:
        ctx: the cycle context.
        q0: (nq,) a standing pose.
        drop: how far the pelvis goes down, metres (0 or less: ``q0``).

    Returns:
        (nq,) the crouched pose (a new array).
    """
    if drop <= 0.0:
        return np.asarray(q0, dtype=float).copy()
    stance = _stance(ctx, q0)
    com0 = com_ahead(ctx, ctx.scratch())  # the kinematics of q0, from _stance
    lowered = _lowered(ctx, stance, drop)
    return bend_trunk(ctx, lowered, BALANCE_STEP, lambda data: com_ahead(ctx, data) >= com0)


def crouch_frames(
    ctx: CycleContext, q0: np.ndarray, target: np.ndarray, w: np.ndarray
) -> np.ndarray:
    """Poses on the way from ``q0`` (standing) into ``target`` (a pose whose root and legs are
    :func:`crouch_pose`'s, :func:`~mjwalk.cycle.tiptoe.tiptoe_pose`'s, or ``q0``'s): every
    joint interpolated by the weights ``w`` (0: ``q0``, 1: ``target``), and when the target
    is crouched, the pelvis lowered by that share of its drop and the legs solved for it at
    each pose, so the feet stay planted all the way; when it is on the toes (the pelvis
    higher), the heels lifted by that share of the rise, the balls of the feet planted.

    Args:
        ctx: the cycle context.
        q0: (nq,) the standing pose.
        target: (nq,) the pose to go into.
        w: (n,) the weights of ``target``, 0 to 1.

    Returns:
        (n, nq) the poses.
    """
    jm = ctx.jointmap
    r = jm.root
    q0 = np.asarray(q0, dtype=float)
    drop = float(q0[r + 2] - target[r + 2])
    frames = q0[None] + np.asarray(w, dtype=float)[:, None] * (target - q0)[None]
    if drop < -1e-9:  # on the toes (mjwalk.cycle.tiptoe): the balls of the feet stay planted
        legs = [jm.adr(n) for n in _leg_joints(toes=True)]
        poses = tiptoe_frames(ctx, q0, heel_rise_of(ctx, target), w)
        frames[:, r : r + 3] = poses[:, r : r + 3]
        frames[:, legs] = poses[:, legs]
        return frames
    if drop <= 0.0:
        return frames
    legs = [jm.adr(n) for n in _leg_joints()]
    stance = _stance(ctx, q0)
    for k, wk in enumerate(w):
        pose = _lowered(ctx, stance, drop * float(wk))
        frames[k, r : r + 3] = pose[r : r + 3]
        frames[k, legs] = pose[legs]
    return frames


def _leg_joints(toes: bool = False) -> list[str]:
    return [j.format(p) for j in LEG_JOINTS if toes or not j.startswith("toe") for p in "lr"]
