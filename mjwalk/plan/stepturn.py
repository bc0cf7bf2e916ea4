"""The turn on the spot after a crossing, stepped (issue 47): a walker who stands beyond a
stair, step or ramp and sets off on the next level leg at another heading turns there in steps
on the spot, each foot in turn lifted and set down turned.

The level leg after a crossing is a standing start (:func:`mjwalk.plan.levelplan.next_foot`):
the hybrid A* costs its turn on the spot and leaves it to the caller
(``WalkRequest(turn_on_spot=True)``). The flat cycle turns the operator before the walk
(:func:`mjwalk.cycle.poses.turn_frames`); inside a walk over levels the turn must be part of
the walk, or the pelvis heading jumps between two samples while the feet stay put (130-140 deg
in one 1/120 s sample on the shipped station). :func:`stepped_turn` puts steps on the spot
before the leg's first step: the pelvis turns from the crossing's last heading to the leg's
first in equal parts, one per step (eased, as :func:`mjwalk.plan.footfallwalk.footfall_walk`
turns a step), each foot landing at its step's heading half a step width beside the spot the
turn ends on, the pelvis moving to the middle of the feet (as on a crossing). The last step
lands on the leg's first stance footprint and the one before a step width beside it, where the
leg's first step lifts it (:func:`mjwalk.body.legs.steps.step_frames`: after a walk's first
step, a swing lifts the foot the step before stood on). The steps alternate from the
crossing's last step on and their number is even, so the leg's first step swings the foot it
was planned with. Young adults turn 180 degrees as one pivot, older ones in more,
smaller steps (Thigpen et al. 2000, Phys Ther 80: 1174-1187); the split here is bounded by the
hip's rotation range (:data:`TURN_PER_STEP`). A turn within that range is not stepped on the
spot but walked on (a walker leaving a stair at a small angle does not stop to turn): the leg's
first step stands on the crossing's last footprint and the pelvis eases into the leg's heading
over that step. Metres, seconds, radians; world frame.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ, other_side
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH
from mjwalk.plan.options import SWING_LIFT_TURN
from mjwalk.plan.turnsplit import wrap
from mjwalk.plan.walkpath import PathStep, WalkPath

#: Most the pelvis turns in one step on the spot, radians: the hip's rotation range
#: (``ROM_DEG["hip_rot"]``, 45 deg; :data:`mjwalk.plan.options.SWING_LIFT_TURN`). A foot stands
#: through two steps, so the pelvis leaves it at most this far off its landing heading at
#: lift-off (within the hip's range, no pivot needed) and each swing turns a foot by at most
#: twice this. ASSUMPTION: the range, not a measured turning-step figure, bounds the split (a
#: half turn in four steps; the planner's ON_SPOT_TURN_SPEED costs it in about two).
TURN_PER_STEP = SWING_LIFT_TURN
#: Feet and heading closer than this to where the leg's first step expects them need no turn
#: (metres, radians): a millimetre, a twentieth of a degree (no step's visible change).
ALREADY_THERE = 1e-3


def turn_steps(turn: float) -> int:
    """How many steps on the spot make a turn: the fewest even number (the leg's first step
    keeps its foot) whose equal parts are each within :data:`TURN_PER_STEP`, at least two.

    Args:
        turn: the pelvis's turn, radians (either sign).

    Returns:
        The number of steps.
    """
    return 2 * max(1, math.ceil(abs(turn) / (2.0 * TURN_PER_STEP) - 1e-9))


def stepped_turn(walk: WalkPath, crossing: WalkPath, walker: Walker) -> WalkPath:
    """``walk`` (a level leg planned as a standing start after a crossing) with the turn on the
    spot from where the crossing left the walker stepped before it (module docstring).

    Args:
        walk: the level leg from t = 0, its first step swinging the other foot than the
            crossing's last, its heights None (its level's, set when stitched) or per sample.
        crossing: the crossing's walk before it (its last sample's pelvis xy and heading, its
            last step's world footprints: ``foot`` of that step's side, ``stance`` of the
            other, where the walker stands).
        walker: the walker: a step on the spot lasts its step, the feet its step width apart
            (else :data:`~mjwalk.plan.levelcross.DEFAULT_STEP_WIDTH`, as on a crossing).

    Returns:
        The walk from t = 0: the steps on the spot, then ``walk``'s samples and steps (its
        ``meta`` with ``turn_steps``, their number); a turn within :data:`TURN_PER_STEP`
        walked on in the leg's first step instead (``turn_steps`` 0, :func:`_walked_on`);
        ``walk`` itself when the feet and the heading are already where its first step
        expects them.

    Raises:
        PlanningError: either walk has no steps, or the leg's first step swings the crossing's
            last step's foot.
    """
    if not walk.steps or not crossing.steps:
        raise PlanningError("stepped turn: the level leg or the crossing has no steps")
    last, side0 = crossing.steps[-1], walk.steps[0].side
    if side0 == last.side:
        raise PlanningError("stepped turn: the level leg's first step must swing the other foot")
    yaw1 = float(walk.yaw[0])
    yaw0 = yaw1 - wrap(yaw1 - float(crossing.yaw[-1]))
    feet = {last.side: np.asarray(last.foot, float), side0: np.asarray(last.stance, float)}
    width = walker.step_width or DEFAULT_STEP_WIDTH  # as the crossing's feet (cross_walk)
    stance = np.asarray(walk.steps[0].stance, float)  # the leg's first stance foot
    sign = 1.0 if side0 == "left" else -1.0
    target = {last.side: stance, side0: np.array([*(stance[:2] + sign * width * _left(yaw1)), 0])}
    moved = max(float(np.max(np.abs(feet[s][:2] - target[s][:2]))) for s in target)
    if moved <= ALREADY_THERE and abs(yaw1 - yaw0) <= ALREADY_THERE:
        return walk
    if abs(yaw1 - yaw0) <= TURN_PER_STEP:  # the hip's range takes it in the leg's first step
        return _walked_on(walk, crossing, yaw0)
    m = turn_steps(yaw1 - yaw0)
    spot = 0.5 * (target["left"][:2] + target["right"][:2])  # the feet's middle at the end
    n = max(1, round(walker.step_duration * SAMPLE_RATE_HZ))
    here = np.asarray(crossing.xy[-1], float)  # the pelvis
    u = np.arange(1, n + 1) / n
    steps, yaws, xys = [], [np.array([yaw0])], [here[None, :]]
    for j in range(1, m + 1):
        side = side0 if j % 2 == 1 else last.side
        h0, h = yaw0 + (yaw1 - yaw0) * (j - 1) / m, yaw0 + (yaw1 - yaw0) * j / m
        if j == m:  # the leg's stance foot
            land = target[side].copy()
        elif j == m - 1:  # a step width beside it, where the leg's first step lifts it
            land = np.array([*target[side][:2], h])
        else:  # half a step width beside the spot the turn ends on, at this step's heading
            to_left = 0.5 * width * (1.0 if side == "left" else -1.0)
            land = np.array([*(spot + to_left * _left(h)), h])
        steps.append(PathStep(side, (j - 1) * n, j * n, land, feet[other_side(side)].copy()))
        feet[side] = land
        yaws.append(h0 + (u * u * (3 - 2 * u)) * (h - h0))
        # the pelvis to the middle of the feet, the last step to where the leg begins
        end = walk.xy[0] if j == m else 0.5 * (feet["left"][:2] + feet["right"][:2])
        xys.append(here + (np.asarray(end, float) - here) * u[:, None])
        here = np.asarray(end, float)
    return _joined(walk, (np.concatenate(yaws), np.vstack(xys)), steps, m * n)


def _walked_on(walk: WalkPath, crossing: WalkPath, yaw0: float) -> WalkPath:
    """``walk`` set off from where the crossing left the walker, with no step on the spot: its
    first step stands on the crossing's last footprint (it lifts the other foot from where that
    stood, :func:`mjwalk.body.legs.steps.step_frames`), and over that step the pelvis eases
    from the crossing's last heading and place into the leg's own (a smoothstep), the stance
    foot left at most :data:`TURN_PER_STEP` off the pelvis (the hip's rotation range, as a
    step on the spot leaves it). The leg's samples after its first step are unchanged."""
    first = walk.steps[0]
    k = first.end - first.start
    u = np.arange(k + 1) / max(k, 1)
    fade = 1.0 - u * u * (3.0 - 2.0 * u)  # 1 at the crossing, 0 where the first step lands
    yaw, xy = walk.yaw.copy(), walk.xy.copy()
    span = slice(first.start, first.end + 1)
    yaw[span] += (yaw0 - float(walk.yaw[first.start])) * fade
    xy[span] += (np.asarray(crossing.xy[-1], float) - walk.xy[first.start]) * fade[:, None]
    stood = replace(first, stance=np.asarray(crossing.steps[-1].foot, float).copy())
    steps = [stood, *walk.steps[1:]]
    return replace(walk, xy=xy, yaw=yaw, steps=steps, meta={**walk.meta, "turn_steps": 0})


def _left(yaw: float) -> np.ndarray:
    """(2,) the unit vector left of heading ``yaw`` (radians)."""
    return np.array([-math.sin(yaw), math.cos(yaw)])


def _joined(walk: WalkPath, samples: tuple, steps: list[PathStep], k: int) -> WalkPath:
    """The turn's ``k + 1`` samples (yaw, xy; its last the walk's first) and steps before
    ``walk``'s, the walk's step indices shifted by ``k``."""
    yaw, xy = samples
    after = [
        PathStep(s.side, s.start + k, s.end + k, s.foot, s.stance, s.foot_z, s.stance_z)
        for s in walk.steps
    ]
    z = None
    if walk.z is not None:
        z = np.concatenate([np.full(k, float(walk.z[0])), walk.z])
        steps = [
            PathStep(s.side, s.start, s.end, s.foot, s.stance, float(walk.z[0]), float(walk.z[0]))
            for s in steps
        ]
    return WalkPath(
        t=np.arange(k + len(walk.t)) / SAMPLE_RATE_HZ,
        xy=np.vstack([xy[:-1], walk.xy]),
        yaw=np.concatenate([yaw[:-1], walk.yaw]),
        steps=steps + after,
        meta={**walk.meta, "turn_steps": len(steps)},
        z=z,
    )
