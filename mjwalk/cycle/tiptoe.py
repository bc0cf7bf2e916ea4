"""Rising on the toes for a reach: the heels lifted, the balls of the feet planted.

A part on a shelf above a short operator's head (the top shelf of
``scenes/shelving_station.xml``, 1.52 m, for operators of about 1.53-1.61 m) cannot be reached
from standing without the forearm coming up through the board's front edge: the shoulder
(Winter: 0.818 H, 1.25 m at H = 1.53 m) is too far below the board for the arm to come over
it. People rise on their toes for it (a heel rise: the ankles plantar flexed, the feet turning
about the balls, the toes flat on the floor). Here each foot turns heel-up by the angle that
lifts its ankle ``rise`` metres about its ball (:func:`~mjwalk.anthropometry.ball_offset` ahead
of the ankle, on the sole), the pelvis goes up and forward with the ankles and on forward,
the legs leaning at the ankles as far apart from the hips as standing, until the body's centre
of mass is over the balls (the weight on the forefoot: moved with the ankles alone it stays
7.7 cm behind them at H = 1.75 m); the legs are solved by :func:`~mjwalk.body.legs.ik.leg_ik`
for the pitched feet and the toes extend by the same angle to stay flat. The ergonomic scores
read a foot whose ankle is more than :data:`mjwalk.ergonomics.angles.FOOT_UP` (5 cm) above its
lowest as off the floor: a higher rise scores the legs as not supported (RULA, REBA, OWAS).

World frame: metres, z up, yaw from +x; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
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
#: On the toes the body's weight bears on the balls of the feet (the heads of the metatarsals):
#: the pelvis leans forward until the centre of mass is over them within this (m; ASSUMPTION:
#: 2 mm, well inside the forefoot's support, 0.2 of the foot's length = 4.6 cm from the balls to
#: the toe tips at H = 1.53 m), in at most :data:`BALANCE_ITERATIONS` corrections (each moves
#: the centre of mass by most of the correction: the feet stay).
BALANCE_TOLERANCE = 0.002
BALANCE_ITERATIONS = 6


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
    t = PLANTARFLEXION_SHARE * math.radians(-ROM_DEG["ankle_flex"][0])
    return _ankle_lift(t, leg_geometry(stature))[1]


def rise_steps(stature: float) -> np.ndarray:
    """The heel rises a reach tries, :data:`RISE_STEP` apart up to :func:`max_rise`.

    Args:
        stature: the operator's stature, metres.

    Returns:
        (n,) metres, increasing, the first :data:`RISE_STEP`.
    """
    n = math.floor(max_rise(stature) / RISE_STEP + 1e-9)
    return np.arange(1, n + 1) * RISE_STEP


def heel_rise_of(ctx: CycleContext, q: np.ndarray) -> float:
    """The heel rise (m) of a pose on the toes (:func:`tiptoe_pose`), from its toes'
    extension: the heel angle (the left foot's; both feet turn alike).

    Args:
        ctx: the cycle context (its humanoid and the operator's stature).
        q: (nq,) the pose.

    Returns:
        Metres; 0 for feet flat (toes not extended).
    """
    t = float(q[ctx.jointmap.adr("toe_l")])
    if t <= 0.0:
        return 0.0
    return _ankle_lift(t, leg_geometry(ctx.spec.stature))[1]


def _ankle_lift(t: float, geom: LegGeometry) -> tuple[float, float]:
    """How far (m) a foot turned heel-up ``t`` radians about its ball moves its ankle:
    forward (along the foot) and up."""
    b, a = ball_offset(geom), geom.ankle_height
    # the ankle over the ball, (-b, a) from it, turned heel-up by t
    return b * (1.0 - math.cos(t)) + a * math.sin(t), b * math.sin(t) + a * (math.cos(t) - 1.0)


def tiptoe_pose(ctx: CycleContext, q0: np.ndarray, rise: float) -> np.ndarray:
    """``q0`` (standing, feet flat under the pelvis's heading) on the toes: the ankles ``rise``
    metres higher, each foot turned heel-up about its ball by :func:`heel_angle`, the pelvis
    moved with the ankles and on forward (the legs leaning at the ankles, their hip-to-ankle
    distance kept) until the body's centre of mass is over the balls of the feet, the legs
    solved for the pitched feet and the toes extended to lie flat.

    Args:
        ctx: the cycle context (its humanoid and scratch data).
        q0: (nq,) a standing pose.
        rise: how far the heels lift the ankles, metres (0 or less: ``q0``); the pelvis rises
            as far less what the legs' lean costs (about 1 cm).

    Returns:
        (nq,) the pose (a new array).
    """
    if rise <= 0.0:
        return np.asarray(q0, dtype=float).copy()
    stance = _Stance.of(ctx, q0)
    t = heel_angle(rise, leg_geometry(ctx.spec.stature))
    lean = 0.0
    q = stance.raised(ctx, t, lean)
    for _ in range(BALANCE_ITERATIONS):
        behind = stance.com_behind(ctx, q)
        if abs(behind) < BALANCE_TOLERANCE:
            break
        lean += behind
        q = stance.raised(ctx, t, lean)
    return q


def tiptoe_frames(ctx: CycleContext, q0: np.ndarray, rise: float, w: np.ndarray) -> np.ndarray:
    """Poses on the way from ``q0`` (standing) onto the toes (:func:`tiptoe_pose` ``rise``):
    at weight ``w`` the heels lift by that share of the heel angle and the body leans by that
    share of its lean over the balls, the balls of the feet planted throughout.

    Args:
        ctx: the cycle context.
        q0: (nq,) the standing pose.
        rise: the heel rise at weight 1, metres.
        w: (n,) weights, 0 (``q0``) to 1 (on the toes).

    Returns:
        (n, nq) the poses.
    """
    full = tiptoe_pose(ctx, q0, rise)
    stance = _Stance.of(ctx, q0)
    t = heel_angle(rise, leg_geometry(ctx.spec.stature))
    lean = stance.lean_of(ctx, full)
    out = np.empty((len(w), len(full)))
    for k, wk in enumerate(np.asarray(w, dtype=float)):
        out[k] = stance.raised(ctx, t * float(wk), lean * float(wk)) if wk > 0.0 else q0
    return out


@dataclass(frozen=True)
class _Stance:
    """A standing pose's pelvis heading (unit, world), pelvis frame, ankle and hip joint
    centres (world, metres) and its ankle-to-hip vector's forward and up parts (metres)."""

    q0: np.ndarray
    pelvis: np.ndarray
    ahead: np.ndarray
    ankle: dict
    hip: dict
    forward: float
    up: float

    @staticmethod
    def of(ctx: CycleContext, q0: np.ndarray) -> _Stance:
        m, jm = ctx.model, ctx.jointmap
        data = ctx.scratch()
        q0 = np.asarray(q0, dtype=float)
        data.qpos[:] = q0
        mujoco.mj_kinematics(m, data)
        pelvis = data.xmat[m.body(f"{jm.prefix}pelvis").id].reshape(3, 3).copy()
        ahead = np.r_[pelvis[:2, 0], 0.0]
        ahead /= max(float(np.linalg.norm(ahead)), 1e-9)
        ankle = {p: data.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id].copy() for p in "lr"}
        hip = {p: data.xanchor[m.joint(f"{jm.prefix}hip_{p}_flex").id].copy() for p in "lr"}
        v = 0.5 * sum(hip[p] - ankle[p] for p in "lr")  # mean ankle-to-hip vector
        return _Stance(q0, pelvis, ahead, ankle, hip, float(v @ ahead), float(v[2]))

    def raised(self, ctx: CycleContext, t: float, lean: float) -> np.ndarray:
        """The pose with the feet turned heel-up ``t`` radians about their balls and the hips
        ``lean`` metres farther ahead of the ankles, as far from them as standing (the pelvis
        lower by what the legs' tilt costs)."""
        jm = ctx.jointmap
        geom = leg_geometry(ctx.spec.stature)
        forward, up = _ankle_lift(t, geom)
        lift = forward * self.ahead
        lift[2] += up
        f, h = self.forward, self.up
        dz = h - math.sqrt(max(h * h + f * f - (f + lean) ** 2, 0.0))
        shift = lift + lean * self.ahead - np.array([0.0, 0.0, dz])
        q = self.q0.copy()
        r = jm.root
        q[r : r + 3] += shift
        pitch = np.full(1, -t)  # heel up: toes down relative to the floor
        for p in "lr":
            rel = self.pelvis.T @ (self.ankle[p] + lift - self.hip[p] - shift)
            for name, value in leg_ik(rel[None], np.zeros(1), pitch, side_of(p), geom).items():
                q[jm.adr(name)] = value[0]
            q[jm.adr(f"toe_{p}")] = t  # extension (toes up to the foot): flat on the floor
        return q

    def com_behind(self, ctx: CycleContext, q: np.ndarray) -> float:
        """How far (m) the centre of mass of pose ``q`` lies behind the balls of the feet (the
        toe joints), along the heading."""
        m, jm = ctx.model, ctx.jointmap
        data = ctx.scratch()
        data.qpos[:] = q
        mujoco.mj_kinematics(m, data)
        mujoco.mj_comPos(m, data)
        balls = 0.5 * sum(data.xanchor[m.joint(f"{jm.prefix}toe_{p}").id] for p in "lr")
        com = data.subtree_com[m.body(f"{jm.prefix}pelvis").id]
        return float((balls - com) @ self.ahead)

    def lean_of(self, ctx: CycleContext, q: np.ndarray) -> float:
        """The lean (m) of a pose :meth:`raised` made: its pelvis's forward shift less the
        ankles' (read back from the root)."""
        jm = ctx.jointmap
        t = float(q[jm.adr("toe_l")])
        r = jm.root
        moved = float((q[r : r + 3] - self.q0[r : r + 3]) @ self.ahead)
        return moved - _ankle_lift(t, leg_geometry(ctx.spec.stature))[0]
