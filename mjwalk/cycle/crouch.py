"""Crouching for a reach: the pelvis lowered with both feet planted, the trunk bent for balance.

A target low under a shelf (a compartment at knuckle height) cannot be reached from a standing
or stooping shoulder without the forearm sloping down through the shelf's front edge: people
bend the knees to bring the shoulder down to the opening (a squat or semi-squat). Here the
pelvis drops by ``drop`` metres with the feet flat where they stand; it moves back only as far
as the ankle's dorsiflexion range needs (the shank tilts forward by at most that range, the
thigh takes the rest), the legs solved by :func:`~mjwalk.body.legs.kinematics.leg_ik`; then
the trunk bends forward (lumbar and thoracic flexion in proportion to their ranges, as the
reach's lean) until the body's centre of mass is as far forward of the ankles as standing --
static balance over the feet, since a pelvis behind the ankles would otherwise tip the body
back.

World frame: metres, z up, yaw from +x; angles in radians.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjwalk.anthropometry import ROM_DEG, leg_geometry
from mjwalk.body.legs.kinematics import leg_ik
from mjwalk.conventions import side_of_prefix as side_of

#: The shank's forward tilt (share of the ankle's dorsiflexion range) a crouch uses at most: a
#: tenth of the range kept in reserve, as the legs' IK never locks a joint at its limit.
DORSIFLEXION_SHARE = 0.9
#: Steps (radians) of the trunk's balancing lean.
BALANCE_STEP = math.radians(2.5)


def root_yaw(q: np.ndarray, root: int) -> float:
    """Heading (radians from +x) of the root quaternion (w, x, y, z) at ``q[root + 3:]``."""
    w, x, y, z = q[root + 3 : root + 7]
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _com_ahead(ctx, q: np.ndarray, data) -> float:
    """How far (m) the humanoid's centre of mass lies ahead of the midpoint of its ankle joints,
    along its heading, in pose ``q``."""
    m, jm = ctx.model, ctx.jointmap
    data.qpos[:] = q
    mujoco.mj_kinematics(m, data)
    mujoco.mj_comPos(m, data)
    yaw = root_yaw(q, jm.root)
    ahead = np.array([math.cos(yaw), math.sin(yaw)])
    ankles = [data.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id][:2] for p in "lr"]
    com = data.subtree_com[m.body(f"{jm.prefix}pelvis").id][:2]
    return float((com - 0.5 * (ankles[0] + ankles[1])) @ ahead)


def crouch_pose(ctx, q0: np.ndarray, drop: float, balance: bool = True) -> np.ndarray:
    """``q0`` (a standing pose, nq) with the pelvis ``drop`` metres lower and moved back as
    far as the ankles' dorsiflexion needs, the feet flat where they are in ``q0`` and, with
    ``balance``, the trunk bent forward until the centre of mass is as far ahead of the ankles
    as in ``q0`` (see the module docstring). ``drop`` 0 returns ``q0``."""
    if drop <= 0.0:
        return np.asarray(q0, dtype=float).copy()
    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    geom = leg_geometry(ctx.spec.stature)
    q = np.asarray(q0, dtype=float).copy()
    r = jm.root
    yaw = root_yaw(q, r)
    ahead = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    data.qpos[:] = q
    mujoco.mj_kinematics(m, data)
    ankle = {p: data.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id].copy() for p in "lr"}
    hip = {p: data.xanchor[m.joint(f"{jm.prefix}hip_{p}_flex").id].copy() for p in "lr"}
    com0 = _com_ahead(ctx, q, data) if balance else 0.0
    # the pelvis back as far as the shank's tilt needs (hip over the ankle while it suffices)
    tilt = DORSIFLEXION_SHARE * math.radians(ROM_DEG["ankle_flex"][1])
    height = 0.5 * sum(hip[p][2] - ankle[p][2] for p in "lr") - drop
    rise = height - geom.shank * math.cos(tilt)
    reach = math.sqrt(max(geom.thigh**2 - rise**2, 0.0))
    back = max(0.0, reach - geom.shank * math.sin(tilt))
    shift = -back * ahead - np.array([0.0, 0.0, drop])
    q[r : r + 3] = q[r : r + 3] + shift
    c, s = math.cos(yaw), math.sin(yaw)
    to_pelvis = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    for p in "lr":
        rel = to_pelvis @ (ankle[p] - (hip[p] + shift))
        for name, value in leg_ik(rel[None], np.zeros(1), np.zeros(1), side_of(p), geom).items():
            q[jm.adr(name)] = value[0]
    if not balance:
        return q
    joints = [jm.adr(j) for j in ("lumbar_flex", "thoracic_flex")]
    room = np.maximum(
        np.array([jm.limits(j)[1] for j in ("lumbar_flex", "thoracic_flex")]) - q[joints], 0.0
    )
    total = float(room.sum())
    upright = q[joints].copy()
    for theta in np.arange(0.0, total + 1e-9, BALANCE_STEP):
        q[joints] = upright + theta * room / max(total, 1e-9)
        if _com_ahead(ctx, q, data) >= com0:
            break
    return q


def crouch_frames(ctx, q0: np.ndarray, target: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Poses (len(w), nq) on the way from ``q0`` (standing) into ``target`` (a pose whose root
    and legs are :func:`crouch_pose`'s): every joint but the legs' interpolated by the weights
    ``w`` (0: ``q0``, 1: ``target``), the pelvis lowered by that share of the target's drop and
    the legs solved for it at each pose, so the feet stay planted all the way."""
    jm = ctx.jointmap
    r = jm.root
    q0 = np.asarray(q0, dtype=float)
    drop = float(q0[r + 2] - target[r + 2])
    frames = q0[None] + np.asarray(w, dtype=float)[:, None] * (target - q0)[None]
    if drop <= 0.0:
        return frames
    legs = [jm.adr(n) for n in _leg_joints()]
    for k, wk in enumerate(w):
        pose = crouch_pose(ctx, q0, drop * float(wk), balance=False)
        frames[k, r : r + 3] = pose[r : r + 3]
        frames[k, legs] = pose[legs]
    return frames


def _leg_joints() -> list[str]:
    from mjwalk.body.legs.kinematics import LEG_JOINTS

    return [j.format(p) for j in LEG_JOINTS if not j.startswith("toe") for p in "lr"]
