"""The timeline of one reach in a scene: the humanoid standing at a site reaching to another.

World frame: metres, seconds, radians, z up, yaw from +x CCW.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
from numpy.typing import ArrayLike

from mjwalk.arms.chain import arm_frames, arm_joint_angles
from mjwalk.arms.hands import finger_trajectory
from mjwalk.arms.reach import ReachModel, humanoid_arm, reach_for_side
from mjwalk.body.humanoid import HUMAN_GROUP, attach_humanoid, pelvis_height
from mjwalk.conventions import DEFAULT_STATURE, Side, side_prefix
from mjwalk.errors import MjwalkError
from mjwalk.timeline.frames import yaw_quat
from mjwalk.timeline.timeline import Timeline
from mjwalk.world.norms import LEVEL_TOLERANCE


def _site_pose(model, name: str):
    sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name)
    if sid < 0:
        raise MjwalkError(f"scene has no site {name!r}")
    return model.site_pos[sid], model.site_quat[sid], sid


@dataclass(frozen=True)
class SceneReachOptions:
    """How :func:`reach_in_scene` solves and samples a reach.

    Attributes:
        constraint: the model's constraint vector (default None: the start and end hand
            positions, for an ``"endpoints"`` model; pass it for an ``"obstacle"`` or
            ``"grasp"`` model, in the left shoulder's frame).
        duration: the reach's duration, seconds.
        fps: frame rate of the timeline, frames per second.
        object_size: the size of the grasped object (metres) for the model's prediction; None
            without one.
    """

    constraint: np.ndarray | None = None
    duration: float = 1.2
    fps: float = 30.0
    object_size: float | None = None


def ground_under(model: mujoco.MjModel, data: mujoco.MjData, point) -> float:
    """The world height of the surface a person standing at ``point`` stands on: the first
    static scene geom (not the humanoid's) straight below ``point`` raised by
    ``norms.LEVEL_TOLERANCE`` (a site written a hair under a deck's top stands on the deck, as
    the cycle's :func:`~mjwalk.cycle.levelsite.site_level` takes it), found by MuJoCo's ray cast.

    Args:
        model: the compiled scene.
        data: its MjData with the kinematics computed.
        point: (3,) world point (a standing site's), metres.

    Returns:
        World z of the surface, metres (a floor, a platform's or a mezzanine's top); 0 when no
        geom lies below the point.
    """
    start = np.asarray(point, dtype=float).copy()
    start[2] += LEVEL_TOLERANCE
    groups = np.ones(6, dtype=np.uint8)
    groups[HUMAN_GROUP] = 0
    hit = np.zeros(1, dtype=np.int32)
    down = np.array([0.0, 0.0, -1.0])
    dist = mujoco.mj_ray(model, data, start, down, groups, 1, -1, hit)
    return 0.0 if hit[0] < 0 else float(start[2] - dist)


def _stand_pose(mj, jm, stand_site: str, stature: float):
    """The humanoid's standing pose (nq,) at ``stand_site`` (facing the site's +x, the pelvis at
    its standing height over the surface under the site, :func:`ground_under`) and the MjData of
    the scene's neutral pose (for the sites' world poses)."""
    _site_pose(mj, stand_site)
    data = mujoco.MjData(mj)
    mujoco.mj_kinematics(mj, data)  # site_xpos of bodies' sites need the kinematics
    sid_stand = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_SITE, stand_site)
    xmat = data.site_xmat[sid_stand].reshape(3, 3)
    yaw = float(np.arctan2(xmat[1, 0], xmat[0, 0]))
    q0 = jm.neutral_qpos(mj, stature)
    r = jm.root
    at = data.site_xpos[sid_stand]
    q0[r : r + 3] = [at[0], at[1], pelvis_height(stature) + ground_under(mj, data, at)]
    q0[r + 3 : r + 7] = yaw_quat(np.array([yaw]))[0]
    return q0, data


def _reach_frames(q0, jm, res, side: Side, stature: float, opts: SceneReachOptions):
    """(qpos (F, nq), clipped joints, frame times (F,) as shares 0-1) of the solved reach
    ``res`` resampled to the timeline's frames."""
    q = arm_joint_angles(res.directions, side, None if res.extras is None else res.extras[:, 1])
    n_out = max(2, round(opts.duration * opts.fps) + 1)
    src = np.linspace(0.0, 1.0, len(q))
    dst = np.linspace(0.0, 1.0, n_out)
    qpos, clipped = arm_frames(q0, jm, q, side, dst)
    if res.extras is not None:
        ap = np.interp(dst, src, res.extras[:, 0])
        for name, vals in finger_trajectory(ap, side, stature).items():
            qpos[:, jm.adr(name)] = vals
    return qpos, clipped, dst


def reach_in_scene(
    scene,
    model: ReachModel,
    stand_site: str,
    target_site: str,
    *,
    side: Side = "left",
    stature: float = DEFAULT_STATURE,
    target_offset: ArrayLike = (0.0, 0.0, 0.0),
    options: SceneReachOptions | None = None,
):
    """A :class:`~mjwalk.timeline.timeline.Timeline` of the humanoid standing at ``stand_site``
    (facing the site's +x, on the surface under it: the floor, a platform's top) and
    reaching its ``side`` hand to ``target_site`` (+ ``target_offset``, world metres): the
    hand starts where the model's reaches start
    (:attr:`~mjwalk.arms.reach.ReachModel.rest_hand`: for the generated models
    :data:`~mjwalk.arms.chain.REST_HAND`, relaxed, elbow slightly bent) and ends on the
    target within 1 cm; joint angles outside the humanoid's ranges are clipped (noted in
    ``meta``). The target is scaled into the model's size by ``meta["scale"]``
    (:func:`~mjwalk.arms.reach.arm_scale`; 1 for the default model at 1.75 m), and fitted
    for the humanoid's arm at that size (``meta["arm_lengths"]``).

    Args:
        scene: an MJCF scene file or an MjSpec; the humanoid is attached.
        model: the reach model.
        stand_site: the site the humanoid stands on, facing its +x.
        target_site: the site the hand reaches to.
        side: the reaching hand, "left" or "right" (a right-arm reach mirrors the left-arm
            model and takes no explicit constraint).
        stature: the humanoid's stature, metres.
        target_offset: (3,) offset of the target from ``target_site``, world metres.
        options: constraint, duration, frame rate and object size (default
            :class:`SceneReachOptions`).

    Returns:
        ``(timeline, result)``: the timeline, and the :class:`~mjwalk.arms.reach.ReachResult`
        in the shoulder frame at the model's arm lengths.

    Raises:
        MjwalkError: an unknown side or site, or a constraint with a right-arm reach.
    """
    opts = SceneReachOptions() if options is None else options
    constraint = opts.constraint
    if side not in ("left", "right"):
        raise MjwalkError(f"reach_in_scene: side must be 'left' or 'right', got {side!r}")
    if side == "right" and constraint is not None:
        raise MjwalkError(
            "reach_in_scene: a right-arm reach mirrors the left-arm model's endpoint constraint;"
            " pass constraint=None (an explicit constraint is in the left shoulder's frame)"
        )
    mj, jm = attach_humanoid(scene, stature)
    q0, data = _stand_pose(mj, jm, stand_site, stature)
    sid_target = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_SITE, target_site)
    if sid_target < 0:
        raise MjwalkError(f"scene has no site {target_site!r}")
    data.qpos[:] = q0
    mujoco.mj_kinematics(mj, data)
    prefix = jm.prefix
    ua = mj.body(f"{prefix}upper_arm_{side_prefix(side)}").id
    shoulder = data.xpos[ua].copy()
    frame = data.xmat[ua].reshape(3, 3).copy()  # shoulder frame at zero shoulder angles
    target_w = data.site_xpos[sid_target] + np.asarray(target_offset, dtype=float)
    # solved at the model's arm lengths: the target scaled into the model's size, as the cycle
    # does (segment directions, hence joint angles, do not change with the scale)
    scale, lengths = humanoid_arm(model, stature)
    end = frame.T @ (target_w - shoulder) * scale
    start = model.rest_hand
    if constraint is None:  # either arm (a right arm mirrors the left-arm model)
        res = reach_for_side(model, end, side, start, opts.object_size, arm_lengths=lengths)
    else:
        c = np.asarray(constraint, dtype=float)
        res = model.predict(
            c, start=start, end=end, object_size=opts.object_size, arm_lengths=lengths
        )
    qpos, clipped, dst = _reach_frames(q0, jm, res, side, stature, opts)
    tl = Timeline(
        model=mj,
        jointmap=jm,
        fps=opts.fps,
        t=dst * opts.duration,
        qpos=qpos,
        scene=str(scene),
        stature=stature,
    )
    tl.meta = {
        "clipped_joints": clipped,
        "target_world": target_w,
        "shoulder": shoulder,
        "frame": frame,
        "scale": scale,
        "arm_lengths": lengths,
    }
    return tl, res
