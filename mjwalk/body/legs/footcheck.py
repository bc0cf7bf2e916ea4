"""Checks of synthesized legs by MuJoCo forward kinematics: where the feet really are.

:func:`foot_points` poses the humanoid frame by frame from a :class:`LegMotion` and reads the
heel and ball of each foot, the foot pitch and the lowest point of the feet;
:func:`stance_drift` measures how far a stance foot's contact point moves while it should stay
planted. Used by the leg tests and the leg benchmarks (one implementation for both).

World frame: metres, z up; pitch in radians, positive toes up.
"""

from __future__ import annotations

import mujoco
import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.humanoid import humanoid_model
from mjwalk.body.legs.pelvistilt import pelvis_quat
from mjwalk.conventions import DEFAULT_STATURE


def posed(legs, stature: float = DEFAULT_STATURE):
    """Pose the humanoid frame by frame: its neutral pose with the legs' root, yaw and joint
    angles of that frame, after MuJoCo forward kinematics (``data`` is reused from frame to
    frame).

    Args:
        legs: a :class:`~mjwalk.body.legs.synthesis.LegMotion`.
        stature: the humanoid's stature, metres.

    Yields:
        ``(i, model, data)`` for every frame ``i``.
    """
    model, jm = humanoid_model(stature)
    data = mujoco.MjData(model)
    tilt = legs.meta.get("pelvis_tilt", np.zeros(len(legs.t)))  # stair ascent (pelvistilt)
    for i in range(len(legs.t)):
        q = jm.neutral_qpos(model, stature)
        q[:3] = legs.root[i]
        q[3:7] = pelvis_quat(legs.yaw[i : i + 1], tilt[i : i + 1])[0]
        for name, v in legs.angles.items():
            q[jm.adr(name)] = v[i]
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        yield i, model, data


#: The eight corners of a box geom, as signs of its half-sizes.
_CORNERS = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T


def box_corners(model: mujoco.MjModel, data: mujoco.MjData, g: int) -> np.ndarray:
    """The eight corners of box geom ``g`` in ``data``'s pose (after forward kinematics).

    Args:
        model: the compiled model.
        data: its data after forward kinematics.
        g: the id of a box geom.

    Returns:
        (8, 3) the corners, metres, world frame.
    """
    return data.geom_xpos[g] + (_CORNERS * model.geom_size[g]) @ data.geom_xmat[g].reshape(3, 3).T


def lowest_point(model: mujoco.MjModel, data: mujoco.MjData, geoms) -> float:
    """Height of the lowest corner of box geoms in ``data``'s pose (after forward kinematics):
    the feet's lowest point.

    Args:
        model: the compiled model.
        data: its data after forward kinematics.
        geoms: ids of box geoms.

    Returns:
        the height, metres, world frame.
    """
    return min(float(box_corners(model, data, g)[:, 2].min()) for g in geoms)


def foot_points(legs, stature: float = DEFAULT_STATURE):
    """Heel and ball world positions, foot pitch and the lowest foot point of ``legs``, by
    MuJoCo forward kinematics of the humanoid.

    Args:
        legs: a :class:`~mjwalk.body.legs.synthesis.LegMotion` with N frames.
        stature: the humanoid's stature, metres.

    Returns:
        points (N, 2, 2, 3) [frame, side l/r, heel/ball] in metres, pitch (N, 2) in radians
        (+ toes up), lowest foot point (N,) in metres.
    """
    n = len(legs.t)
    pts, pitch, low = np.zeros((n, 2, 2, 3)), np.zeros((n, 2)), np.zeros(n)
    back = leg_geometry(stature).foot_back
    feet: list[int] = []
    for i, model, data in posed(legs, stature):
        feet = feet or [model.geom(g).id for g in ("foot_l", "foot_r", "toes_l", "toes_r")]
        for k, s in enumerate("lr"):
            R = data.xmat[model.body(f"foot_{s}").id].reshape(3, 3)
            pts[i, k, 0] = data.site_xpos[model.site(f"sole_{s}").id] - back * R[:, 0]
            pts[i, k, 1] = data.xpos[model.body(f"toes_{s}").id]
            pitch[i, k] = np.arcsin(R[2, 0])
        low[i] = lowest_point(model, data, feet)
    return pts, pitch, low


def stance_drift(walk, pts: np.ndarray, pitch: np.ndarray, eps: float = 1e-4) -> float:
    """Worst drift of the stance foot's contact point during each step: the heel while the
    foot is flat or toes-up, the ball while flat or heel-up (both pivots stay put); a drift is
    twice the largest distance from the point's mean over the stance.

    Args:
        walk: a :class:`~mjwalk.plan.walkpath.WalkPath` (its steps' sides and sample ranges).
        pts: :func:`foot_points`'s points (N, 2, 2, 3).
        pitch: :func:`foot_points`'s pitch (N, 2), radians.
        eps: the pitch tolerance of "flat", radians.

    Returns:
        the worst drift, metres.
    """
    worst = 0.0
    for st in walk.steps:
        k = 1 if st.side == "left" else 0  # the stance foot is the other one
        sl = slice(st.start, st.end + 1)
        for j, mask in ((0, pitch[sl, k] >= -eps), (1, pitch[sl, k] <= eps)):
            p = pts[sl, k, j][mask]
            if len(p):
                worst = max(worst, float(np.linalg.norm(p - p.mean(0), axis=1).max() * 2))
    return worst
