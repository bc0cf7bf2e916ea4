"""Rising on the toes for a reach: the heels lifted, the balls of the feet planted.

A part on a shelf above a short operator's head (the top shelf of
``scenes/shelving_station.xml``, 1.52 m, for operators of about 1.53-1.61 m) cannot be reached
from standing without the forearm coming up through the board's front edge: the shoulder
(Winter: 0.818 H, 1.25 m at H = 1.53 m) is too far below the board for the arm to come over
it. People rise on their toes for it (a heel rise: the ankles plantar flexed, the feet turning
about the balls, the toes flat on the floor). Here each foot turns heel-up by the angle that
lifts its ankle ``rise`` metres about its ball (:func:`~mjwalk.anthropometry.ball_offset` ahead
of the ankle, on the sole), the pelvis goes up and forward with the ankles (the legs keep
their shape: straight), the legs are solved by :func:`~mjwalk.body.legs.ik.leg_ik` for the
pitched feet and the toes extend by the same angle to stay flat.

World frame: metres, z up, yaw from +x; angles in radians.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from mjwalk.anthropometry import ROM_DEG, LegGeometry, ball_offset, leg_geometry
from mjwalk.body.legs.ik import leg_ik
from mjwalk.conventions import side_of_prefix as side_of

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: The heel rise's plantar flexion (share of the ankle's plantar flexion range, 50 deg:
#: :data:`mjwalk.anthropometry.ROM_DEG`, AAOS) used at most: a tenth of the range kept in
#: reserve, as the crouch keeps of the dorsiflexion
#: (:data:`~mjwalk.cycle.crouch.DORSIFLEXION_SHARE`) and the legs' IK never locks a joint at
#: its limit.
PLANTARFLEXION_SHARE = 0.9
#: Steps (m) of the heel rise a reach tries, smallest first (ASSUMPTION: 1 cm, the
#: :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` the arm keeps, so a rise is no higher than
#: the clearance needs by more than that).
RISE_STEP = 0.01


def heel_angle(rise: float, geom: LegGeometry) -> float:
    """The foot's heel-up angle that lifts its ankle ``rise`` metres, the ball of the foot
    (on the sole, :func:`~mjwalk.anthropometry.ball_offset` ahead of the ankle and
    ``ankle_height`` below it) staying where it is.

    Args:
        rise: how far the ankle goes up, metres (0 or less: 0).
        geom: the leg and foot lengths (:func:`~mjwalk.anthropometry.leg_geometry`).

    Returns:
        The angle, radians (0 to pi/2; the largest for a rise beyond what a foot can give).
    """
    if rise <= 0.0:
        return 0.0
    b, a = ball_offset(geom), geom.ankle_height
    # ankle over the ball: (-b, a) turned heel-up by t; its height b sin t + a cos t
    r, phi = math.hypot(a, b), math.atan2(a, b)
    return min(math.asin(min((rise + a) / r, 1.0)) - phi, math.pi / 2 - phi)


def max_rise(stature: float) -> float:
    """The highest heel rise a reach uses: the ankle's lift at :data:`PLANTARFLEXION_SHARE` of
    the plantar flexion range.

    Args:
        stature: the operator's stature, metres.

    Returns:
        Metres (0.075 m at H = 1.53 m).
    """
    geom = leg_geometry(stature)
    t = PLANTARFLEXION_SHARE * math.radians(-ROM_DEG["ankle_flex"][0])
    b, a = ball_offset(geom), geom.ankle_height
    return b * math.sin(t) + a * (math.cos(t) - 1.0)


def rise_steps(stature: float) -> np.ndarray:
    """The heel rises a reach tries, :data:`RISE_STEP` apart up to :func:`max_rise`.

    Args:
        stature: the operator's stature, metres.

    Returns:
        (n,) metres, increasing, the first :data:`RISE_STEP`.
    """
    n = math.floor(max_rise(stature) / RISE_STEP + 1e-9)
    return np.arange(1, n + 1) * RISE_STEP


def tiptoe_pose(ctx: CycleContext, q0: np.ndarray, rise: float) -> np.ndarray:
    """``q0`` (standing, feet flat under the pelvis's heading) on the toes: the ankles ``rise``
    metres higher, each foot turned heel-up about its ball by :func:`heel_angle`, the pelvis
    moved with the ankles, the legs solved for the pitched feet and the toes extended to lie
    flat.

    Args:
        ctx: the cycle context (its humanoid and scratch data).
        q0: (nq,) a standing pose.
        rise: how far the heels lift the ankles (and the pelvis), metres (0 or less: ``q0``).

    Returns:
        (nq,) the pose (a new array).
    """
    q = np.asarray(q0, dtype=float).copy()
    if rise <= 0.0:
        return q
    m, jm = ctx.model, ctx.jointmap
    geom = leg_geometry(ctx.spec.stature)
    t = heel_angle(rise, geom)
    b, a = ball_offset(geom), geom.ankle_height
    data = ctx.scratch()
    data.qpos[:] = q
    mujoco.mj_kinematics(m, data)
    pelvis = data.xmat[m.body(f"{jm.prefix}pelvis").id].reshape(3, 3).copy()
    ahead = np.r_[pelvis[:2, 0], 0.0]
    ahead /= max(float(np.linalg.norm(ahead)), 1e-9)
    # the ankle over the ball turned heel-up by t: forward and up (the legs move with it)
    forward = b * (1.0 - math.cos(t)) + a * math.sin(t)
    shift = forward * ahead + np.array([0.0, 0.0, b * math.sin(t) + a * (math.cos(t) - 1.0)])
    r = jm.root
    q[r : r + 3] += shift
    for p in "lr":
        ankle = data.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id]
        hip = data.xanchor[m.joint(f"{jm.prefix}hip_{p}_flex").id]
        rel = pelvis.T @ (ankle - hip)
        pitch = np.full(1, -t)  # heel up: toes down relative to the floor
        for name, value in leg_ik(rel[None], np.zeros(1), pitch, side_of(p), geom).items():
            q[jm.adr(name)] = value[0]
        q[jm.adr(f"toe_{p}")] = t  # extension (toes up to the foot): flat on the floor
    return q
