"""A level walk that comes to a flight from the side turns into it while walking.

A walk to a stair, step or ramp ends at the flight's approach point, a step before its stance
on its axis (:func:`mjwalk.plan.levelcross.approach_point`), and lines up from there. Where the
level walk arrives there facing more than :data:`~mjwalk.plan.levelcross.ENTRY_TURN` off the
flight (the multi-level station's rack1 -> mezzanine: up the gap between the stair's wall and a
trolley, 106-147 deg off), the walker used to stop and turn on the spot
(:func:`~mjwalk.plan.levelcross.spot_turn`). People walking there turn into the flight while
walking: a stepping turn, each step changing direction by at most 60 deg (Patla, Prentice,
Robinson & Neufeld 1991, "Visual control of locomotion: strategies for changing direction and
for going over obstacles", J Exp Psychol Hum Percept Perform 17:603-634), so their path is a
curve of bounded curvature.

The hybrid search cannot be asked for that cheaply (measured, ``benchmarks/bench_levels.py``'s
notes): its goal heading is only a preference, and a walk required to end facing the flight
floods the floor about the approach point, its distance-to-goal heuristic blind to the heading
(3 of 10 walks found in 1000 expansions, all 10 in 4000 at 8x the cost; with a Dubins bound
added to the heuristic and a guide routed round the stair's wall still 1-9 of 10 in 1000, at
22-42 ms). So the level planner re-places the walk's last steps instead (:func:`turn_into`):
the walk is cut after one of its last :data:`CUT_STEPS` walking steps (its closing step
dropped: the walker does not stop), and from the pelvis's pose there its steps follow the
shortest path of bounded curvature (Dubins 1957, :mod:`mjwalk.plan.dubins`) to a point one step
before the flight's first footfall on its axis, facing along the flight, at the turning radius
of one step length per :data:`~mjwalk.plan.turnsplit.WALKING_TURN_MAX` (60 deg: Patla et al.'s
most within a step), in equal steps no longer than the walker's step length, the path keeping
the body radius clear (:func:`mjwalk.plan.guide.guide_is_clear`). Of the cuts and words that
fit, the one with the fewest steps; where none fits, the walker turns on the spot as before.
Metres, radians, world frame (yaw from +x CCW).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.plan.dubins import dubins_words, trace
from mjwalk.plan.guide import guide_is_clear
from mjwalk.plan.turnsplit import WALKING_TURN_MAX
from mjwalk.plan.walkpath import WalkPath

#: How many of a level walk's last walking steps the turn into a flight may start after, the
#: last first (:func:`turn_in_steps`): a bound on the work (four steps, about 2.5 m of walk).
CUT_STEPS = 4
#: The step lengths a turn into a flight is tried with, as shares of the walker's step length,
#: the longest first: people shorten and slow their steps into a sharp turn (Orendurff,
#: "Turning gait", VA Motion Analysis Lab abstract, 2005: "the steps before a turn slow you
#: down"; qualitative), so a tighter turn (60 deg a step, Patla et al. 1991) is taken in shorter
#: steps, each at the walker's level step time. ASSUMPTION: down to half the step length (the
#: level planner's closing steps move the pelvis 0.2-0.5 m, :mod:`mjwalk.plan.options`).
TURN_STEP_SHARES = (1.0, 0.75, 0.5)


def turn_in_steps(
    view, walk: WalkPath, heading: float, walker, radius: float, first
) -> tuple | None:
    """Where a level walk turns into a flight, and the turn's footfalls (module docstring).

    Args:
        view: the level's view (its ``walk_clearance``).
        walk: the level walk to the flight's approach point (its last step a closing step).
        heading: the flight's heading up or down it, radians.
        walker: the walker (step length).
        radius: the body radius, metres.
        first: (2,) world xy of the flight's first footfall on its walking line, metres.

    Returns:
        (j, points (m, 2), headings (m,), end heading): the walk's step ``j`` after which it
        turns, the turn's footfalls on its walking line (world xy, metres) and their headings
        (radians, unwrapped from the walk's), the last a step before ``first`` facing along
        the flight, and that heading; None where no cut fits.
    """
    first = np.asarray(first, dtype=float)
    target = first - walker.step_length * np.array([math.cos(heading), math.sin(heading)])
    walking = len(walk.steps) - 1  # the last is the closing step
    tried: list[tuple] = []  # (steps in all, order tried, j, n, yaw, pose, word)
    for j in range(walking - 1, max(-1, walking - 1 - CUT_STEPS), -1):
        at = walk.steps[j].end
        yaw = float(walk.yaw[at])
        # from the step's footfall on the walking line (its landing foot's along the heading):
        # the turn's first footfall a step beyond it, as the walk's own next one would be
        u = np.array([math.cos(yaw), math.sin(yaw)])
        line = walk.xy[at] + float((walk.steps[j].foot[:2] - walk.xy[at]) @ u) * u
        for share in TURN_STEP_SHARES:
            step = share * float(walker.step_length)
            turning = step / WALKING_TURN_MAX  # 60 deg a step
            pose = (line, yaw, target, heading, turning)
            for word in dubins_words(*pose):
                n = max(1, math.ceil(word[0] / step - 1e-9))
                tried.append((j + n, len(tried), j, n, yaw, pose, word))
    # the fewest steps in all, the first tried of those (latest cut, longest steps, shortest
    # word): traced in that order, the first clear of the body is the turn
    for _, _, j, n, yaw, (line, at_yaw, end, end_yaw, turning), word in sorted(
        tried, key=lambda c: c[:2]
    ):
        traced = trace(line, at_yaw, end, end_yaw, turning, word)
        # clear of the body (on from its end: the line-up's, levelplan._approach)
        if traced is not None and guide_is_clear(view, traced[0], radius):
            return (j, *_stepped(traced[0], n, yaw, traced[1]))
    return None


#: The stride (m) and directions of :func:`walked_back`'s descent of a distance field: a
#: tenth of a metre in 16 directions, a cost bound (the field's cells are 0.08 m).
BACK_STRIDE = 0.1
_BACK_RING = BACK_STRIDE * np.stack(
    [np.cos(np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)),
     np.sin(np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False))], axis=1
)  # fmt: skip


def walked_back(field, end, step: float) -> list[tuple[np.ndarray, float]]:
    """Where a level walk arriving at ``end`` is 1 .. :data:`CUT_STEPS` step lengths before
    it, by its shortest route: ``field`` (the distance to the walk's start) descended from
    ``end`` in :data:`BACK_STRIDE` strides, each pose's heading the route's towards ``end``.

    Args:
        field: the distance field to the walk's start (callable on (m, 2) world xy, metres).
        end: (2,) world xy where the walk arrives, metres.
        step: the walker's step length, metres.

    Returns:
        [(xy (2,), heading in radians)], nearest ``end`` first; fewer where the route back
        reaches the start sooner.
    """
    pts = [np.asarray(end, dtype=float)]
    here = float(field(pts[0][None])[0])
    for _ in range(math.ceil(CUT_STEPS * step / BACK_STRIDE)):
        around = pts[-1] + _BACK_RING
        values = field(around)
        k = int(np.argmin(values))
        if not values[k] < here:  # the start (or no way back): the route ends
            break
        pts.append(around[k])
        here = float(values[k])
    path = np.array(pts)
    cum = BACK_STRIDE * np.arange(len(path))
    out = []
    for k in range(1, CUT_STEPS + 1):
        i = int(np.searchsorted(cum, k * step))
        if i >= len(path):
            break
        d = path[i - 1] - path[i]  # the way the walk goes there: towards the end
        out.append((path[i], math.atan2(d[1], d[0])))
    return out


def turn_in_time(view, poses: list, flight: tuple, walker, radius: float) -> float | None:
    """How much longer a level walk arriving at a flight takes when it turns into the flight
    while walking (:func:`turn_in_steps`), for the route over levels to price
    (:func:`mjwalk.plan.levelplan.level_route`): the walk cut ``k`` step lengths before where
    it arrives (``poses[k - 1]``, :func:`walked_back`) and the turn's ``n`` steps of
    :data:`TURN_STEP_SHARES` step lengths at the walker's level step time (as
    :func:`turned_steps` times them) in place of those ``k`` step lengths at its speed; of the
    cuts and words whose path keeps the body clear, the one with the fewest steps in all, as
    :func:`turn_in_steps` chooses.

    Args:
        view: the level's view (its ``walk_clearance``).
        poses: [(xy (2,) metres, heading radians)] of the walk 1, 2, ... step lengths before
            where it arrives (:func:`walked_back`).
        flight: (the flight's heading up or down it in radians, (2,) world xy in metres of
            its first footfall: :func:`mjwalk.plan.levelcross.flight_start`).
        walker: the walker (step length, step time, speed).
        radius: the body radius, metres.

    Returns:
        Seconds (>= 0), or None where no turn fits (the walker turns on the spot).
    """
    heading, first = flight
    step = float(walker.step_length)
    target = np.asarray(first, dtype=float) - step * np.array(
        [math.cos(heading), math.sin(heading)]
    )
    tried: list[tuple] = []  # (steps the turn adds, order tried, k, n, pose, word)
    for k, (line, yaw) in enumerate(poses, start=1):
        for share in TURN_STEP_SHARES:
            turning = share * step / WALKING_TURN_MAX  # 60 deg a step
            pose = (line, yaw, target, heading, turning)
            for word in dubins_words(*pose):
                n = max(1, math.ceil(word[0] / (share * step) - 1e-9))
                tried.append((n - k, len(tried), k, n, pose, word))
    for _, _, k, n, (line, yaw, end, end_yaw, turning), word in sorted(tried, key=lambda c: c[:2]):
        traced = trace(line, yaw, end, end_yaw, turning, word)
        if traced is not None and guide_is_clear(view, traced[0], radius):
            return max(0.0, n * float(walker.step_duration) - k * step / float(walker.speed))
    return None


def _stepped(pts: np.ndarray, n: int, yaw: float, end: float) -> tuple:
    """``n`` equal steps along the path ``pts`` (k, 2): their points, headings (the path's
    tangent, unwrapped from ``yaw``; the last ``end``) and ``end``."""
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    at = cum[-1] * np.arange(1, n + 1) / n
    points = np.stack([np.interp(at, cum, pts[:, 0]), np.interp(at, cum, pts[:, 1])], axis=1)
    d = np.gradient(pts, axis=0)
    tang = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    tang += 2.0 * math.pi * round((yaw - tang[0]) / (2.0 * math.pi))
    tang[-1] = end
    return points, np.interp(at, cum, tang), end


def turn_into(view, walk: WalkPath, flight: tuple, walker, radius: float) -> tuple | None:
    """A level walk to a flight's approach point cut where it turns into the flight while
    walking (:func:`turn_in_steps`), and that turn for the crossing's walk
    (:func:`mjwalk.plan.levelcross.cross_walk`'s ``lead_in``).

    Args:
        view: the level's view (its ``walk_clearance``).
        walk: the level walk to the approach point.
        flight: (the flight's heading up or down it in radians, (2,) world xy in metres of
            its first footfall: :func:`mjwalk.plan.levelcross.flight_start`).
        walker: the walker (step length).
        radius: the body radius, metres.

    Returns:
        (the walk up to the end of its step the turn follows, (footfalls (m, 2), headings (m,),
        end heading)), or None where no turn fits.
    """
    found = turn_in_steps(view, walk, flight[0], walker, radius, flight[1])
    if found is None:
        return None
    j, points, headings, end = found
    e = walk.steps[j].end + 1
    cut = WalkPath(
        t=walk.t[:e],
        xy=walk.xy[:e],
        yaw=walk.yaw[:e],
        steps=list(walk.steps[: j + 1]),
        meta={**walk.meta, "turned_in": len(points)},
        z=None if walk.z is None else walk.z[:e],
    )
    return cut, (points, headings, end)


def turned_steps(lead: tuple, footfalls: tuple, here: tuple, turn: tuple, step_time: float, left):
    """The crossing's footfalls with a turn before them, as :func:`mjwalk.plan.levelcross.
    cross_walk` steps it: the turn into it (:func:`turn_into`), or the steps on the spot
    (:func:`mjwalk.plan.levelcross.spot_turn`: its footfalls all where the walker stands).

    Args:
        lead: (footfalls (m, 2) world xy, headings (m,), end heading) of the turn.
        footfalls: (points (k, 2) world xy, heights (k,) world z, times (k,) s) of the steps.
        here: (xy (2,), world z) where the walker is, metres.
        turn: (the walker's heading, the crossing's heading), radians.
        step_time: a turning step's duration, seconds (the walker's level step).
        left: (2,) the unit vector left of the crossing's heading.

    Returns:
        points, heights, times, the heading of each step, the unit vector left of it (k', 2),
        the heading each step turns from, and the number of turning steps.
    """
    pts, heads, _ = lead
    points, heights, times = footfalls
    m = len(pts)
    points = np.concatenate([pts, points])
    heights = np.concatenate([np.full(m, here[1]), heights])
    times = np.concatenate([np.full(m, step_time), times])
    headings = np.concatenate([heads, np.full(len(times) - m, turn[1])])
    across = np.tile(left, (len(times), 1))
    across[:m] = np.stack([-np.sin(heads), np.cos(heads)], axis=1)
    was = np.concatenate([[turn[0]], headings[:-1]])
    return points, heights, times, headings, across, was, m
