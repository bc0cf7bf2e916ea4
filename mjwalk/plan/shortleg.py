"""A level leg too short for a search to choose anything, walked as footfalls along its line.

A walk over levels plans each level leg with the hybrid A* (:mod:`mjwalk.plan.levelplan`). Next
to a step or a ramp many legs are a step or two long (the station's step: 0.47 m to its stance,
0.89 m from it to the platform's site); the search returns a straight walk of one or two steps
there after 1-8 expansions (``benchmarks/bench_levels.py``), yet its guide, search call and
assembly cost about as much as a flat walk's whole plan. :func:`short_leg` walks such a leg
instead as footfalls along the straight line from its start to its goal, with the footfall
machinery the crossings use (:func:`mjwalk.plan.footfallwalk.footfall_walk`): from standing with
the feet side by side, footfalls evenly spaced along the line, none farther apart than the
walker's step length nor twice the planner's goal tolerance, each at the walker's step time,
the last at the goal; the pelvis, between the last two, ends half a step short of it, inside
the goal area, as a searched leg ends there walking on (no closing step: the next crossing
or leg follows step over step). The first step turns the walker from where it faced onto the
line.

It does so only where there is nothing to choose: the line at most :data:`SHORT_LEG_STEPS` of
the walker's step lengths, the body radius clear all along it on the leg's level
(:func:`mjwalk.plan.levelcross.line_clear`), the turn onto it at the start and, at a crossing,
off it onto the crossing's heading each within one step's direction change
(:data:`mjwalk.plan.levelcross.ENTRY_TURN`). Anywhere else it returns None and the leg is
searched as before. Flat walks never come here. Metres, seconds, radians, world xy; the walk's
heights None (its level's, set when stitched: :func:`mjwalk.plan.levelstitch.stitch`).
"""

from __future__ import annotations

import math
import time

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.walker import Walker
from mjwalk.plan.footfallwalk import footfall_walk
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH, ENTRY_TURN, line_clear
from mjwalk.plan.turnsplit import wrap
from mjwalk.plan.walkpath import WalkPath

#: The longest level leg (in the walker's step lengths) walked straight rather than searched.
#: ASSUMPTION: within two step lengths a walk from standing has one to three footfalls (three
#: where twice the goal area is shorter than a step); with its straight line clear of every
#: obstacle by the body radius and its turns within one step's direction change, the search
#: has no route to choose between and returns a straight walk (the station's legs of 0.31-0.9
#: m: one or two steps after 1-8 expansions, seeds 1-2, ``benchmarks/bench_levels.py``).
#: Longer legs have room for the search's pace, sway and curvature, which stay its own.
SHORT_LEG_STEPS = 2


def short_leg(
    view,
    start: tuple[np.ndarray, float | None],
    aim: np.ndarray,
    walker: Walker,
    reach: tuple[float, float],
    ends: tuple[str | None, float | None],
    rng: np.random.Generator,
) -> WalkPath | None:
    """Walk a short, clear level leg as footfalls along its line (module docstring).

    Args:
        view: the leg's level view (its ``walk_clearance``, world xy).
        start: (pelvis world xy (2,), heading in radians the walker stands at, or None: free,
            the walker sets off facing along the line).
        aim: (2,) world xy where the walker stands at the end (the leg's goal or approach
            point).
        walker: the walker (step length, step time, step width).
        reach: (the body radius, the planner's goal tolerance), metres.
        ends: (the first step's swinging foot, "left" or "right", or None: either; the
            heading in radians the walk goes on with at its end, a crossing's up or down its
            axis, or None).
        rng: draws the first foot where ``ends`` leaves it open, with even odds (ASSUMPTION:
            no leading limb preferred; drawn only for a leg walked here, so a searched leg's
            draws are as before).

    Returns:
        The walk from t = 0 (120 Hz pelvis xy and yaw, its steps on the level, ``meta`` with 0
        expansions), or None where the leg is longer than :data:`SHORT_LEG_STEPS` step lengths,
        not clear, has no length, or turns more than :data:`ENTRY_TURN` at either end.
    """
    t0 = time.perf_counter()
    side, heading = ends
    radius, tolerance = reach
    xy0 = np.asarray(start[0], dtype=float)
    line = np.asarray(aim, dtype=float) - xy0
    d, step = float(np.hypot(*line)), walker.step_length
    if not 1e-9 < d <= SHORT_LEG_STEPS * step:
        return None
    psi = math.atan2(float(line[1]), float(line[0]))
    # a crossing's stance heading may lie past pi (its yaw + pi): the walk's and its feet's
    # headings within (-pi, pi], as the search's, so no foot turns a full circle into it
    yaw0 = psi if start[1] is None else wrap(float(start[1]))
    psi = yaw0 + wrap(psi - yaw0)  # the nearer turn, unwrapped from where the walker faces
    if abs(psi - yaw0) > ENTRY_TURN:
        return None
    if heading is not None and abs(wrap(heading - psi)) > ENTRY_TURN:
        return None
    if not line_clear(view, xy0, np.asarray(aim, dtype=float), radius):
        return None
    if side is None:
        side = "left" if rng.random() < 0.5 else "right"
    # footfalls evenly along the line, the last at the aim: the pelvis ends half a step short
    # of it, inside the planner's goal area as a searched leg's (walking on into a crossing)
    n = max(1, math.ceil(d / min(step, 2.0 * tolerance) - 1e-9))
    u = np.arange(1, n + 1) / n
    k = len(u)
    points = xy0 + np.outer(u, line)
    across = np.tile([-math.sin(psi), math.cos(psi)], (k, 1))
    width = walker.step_width or DEFAULT_STEP_WIDTH
    left = np.array([-math.sin(yaw0), math.cos(yaw0)])
    feet = {
        name: (np.array([*(xy0 + sign * 0.5 * width * left), yaw0]), 0.0)
        for name, sign in (("left", 1.0), ("right", -1.0))
    }
    headings = np.full(k, psi)
    was = np.concatenate([[yaw0], headings[1:]])
    lay = (points, np.zeros(k), np.full(k, walker.step_duration), headings, across, width)
    xy, _, yaws, steps = footfall_walk(lay, feet, side, (xy0, 0.0, yaw0), (was, 0, psi), 0.0)
    meta = {
        "planner": "footfall_line",
        "goal": [float(aim[0]), float(aim[1])],
        "expansions": 0,
        "expansions_all": 0,
        "searches": 0,
        "seconds": time.perf_counter() - t0,
    }
    t = np.arange(len(xy)) / SAMPLE_RATE_HZ
    return WalkPath(t=t, xy=xy, yaw=yaws, steps=steps, meta=meta)
