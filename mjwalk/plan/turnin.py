"""A level walk's way into a flight it must enter along its axis: the guide that turns into it.

A walk that comes to a stair's foot from the side or from behind (the multi-level station's
rack1 -> mezzanine: up the gap between the stair's wall and a trolley, 106-147 deg off the
flight at its foot) cannot be turned into the flight by the search's goal heading alone: the
minimum-jerk guide between the two poses runs through the stair's wall, the detour guide finds
no way round it, and the search, its distance-to-goal heuristic blind to the heading, floods
the floor about the approach point (a heading-conditioned search: 3 of 10 walks found in 1000
expansions, all 10 in 4000 at 8x the cost; ``benchmarks/bench_levels.py``'s history). People
do not stop there and turn on the spot: they walk past the flight's foot and turn into it
while walking (a stepping turn, Patla, Prentice, Robinson & Neufeld 1991, "Visual control of
locomotion: strategies for changing direction and for going over obstacles", J Exp Psychol
Hum Percept Perform 17:603-634: up to 60 deg within one step), their path a curve of bounded
curvature.

:func:`turn_in_guide` is that path, for the search to follow (``WalkRequest(guide=...)``,
:mod:`mjwalk.plan.guide`): the obstacle-aware route from the start along the goal's distance
field (:func:`field_route`) up to a point on it, then the shortest path of bounded curvature
from that point and the route's heading there to the approach point along the flight's
heading (Dubins 1957, :func:`dubins_paths`), its turning radius a step length per
:data:`~mjwalk.plan.levelcross.ENTRY_TURN` of turn (Patla et al. 1991's 60 deg a step). Of
the points along the route's last stretch and the six Dubins words, the shortest whole path
that keeps the body radius clear is taken. Metres, radians, world frame (yaw from +x).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.plan.dubins import WORDS, frame, word_lengths
from mjwalk.plan.guide import guide_is_clear
from mjwalk.plan.heuristic import GoalDistance
from mjwalk.plan.turnsplit import WALKING_TURN_MAX
from mjwalk.plan.walkpath import WalkPath

#: Spacing (m) of the points a Dubins path is sampled at, as the guide's clearance check
#: samples (:func:`mjwalk.plan.guide.guide_is_clear`: 5 cm).
SPACING = 0.05
#: How far back along the route (in turning radii) junction points are tried: a turn of up to
#: a full circle's length and the straight run to the goal fit in it (a bound on the work).
REACH_RADII = 8.0
#: Spacing of the junction points tried along the route, in turning radii (a bound on the
#: work: a quarter radius moves a junction by 14 deg of the turn).
JUNCTION_RADII = 0.25

def _trace(start: np.ndarray, yaw: float, word: str, lengths, radius: float) -> np.ndarray:
    """The points (m) of a Dubins path from ``start`` heading ``yaw``, every :data:`SPACING`
    or closer, its end included."""
    pts = [np.asarray(start, dtype=float)]
    x, y = float(start[0]), float(start[1])
    for kind, seg in zip(word, lengths, strict=True):
        n = max(1, math.ceil(seg * radius / SPACING))
        u = np.arange(1, n + 1) / n * seg
        if kind == "S":
            xs, ys = x + radius * u * math.cos(yaw), y + radius * u * math.sin(yaw)
            turn = 0.0
        else:
            sign = 1.0 if kind == "L" else -1.0
            cx, cy = x - sign * radius * math.sin(yaw), y + sign * radius * math.cos(yaw)
            h = yaw + sign * u
            xs, ys = cx + sign * radius * np.sin(h), cy - sign * radius * np.cos(h)
            turn = sign * seg
        pts.append(np.stack([xs, ys], axis=1))
        x, y, yaw = float(xs[-1]), float(ys[-1]), yaw + turn
    return np.vstack([p.reshape(-1, 2) for p in pts])


def dubins_paths(start, yaw0: float, goal, yaw1: float, radius: float) -> list[tuple]:
    """The Dubins paths (Dubins 1957, "On curves of minimal length with a constraint on average
    curvature, and with prescribed initial and terminal positions and tangents", Am J Math 79:
    497-516) from a pose to a pose: each of the six words that exists, as (length in metres,
    (k, 2) points every :data:`SPACING` or closer), shortest first. A word whose traced end
    misses the goal pose (by 1 mm or 1e-6 rad) is left out.

    Args:
        start: (2,) world xy, metres.
        yaw0: the heading there, radians.
        goal: (2,) world xy, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).

    Returns:
        [(length, points)], shortest first.
    """
    s, g = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
    d, alpha, beta = frame(s[0], s[1], yaw0, g[0], g[1], yaw1, radius)
    out = []
    for k, word in enumerate(WORDS):
        ok, *seg = word_lengths(k, d, alpha, beta)
        if not ok:
            continue
        pts = _trace(s, yaw0, word, seg, radius)
        turn = sum((1.0 if w == "L" else -1.0) * v for w, v in zip(word, seg, strict=True) if w != "S")
        if np.hypot(*(pts[-1] - g)) > 1e-3 or abs(math.remainder(yaw0 + turn - yaw1, math.tau)) > 1e-6:
            continue
        out.append((radius * sum(seg), pts))
    return sorted(out, key=lambda c: c[0])


def field_route(distance: GoalDistance, start) -> np.ndarray | None:
    """The route (m) from ``start`` down the goal's distance field to its goal area: cell by
    cell over the grid's free moves to the nearer neighbour whose field value and move length
    sum least, then the goal centre; None where no route leads there.

    Args:
        distance: the goal's distance field (the level planner's, :class:`GoalDistance`).
        start: (2,) world xy, metres.

    Returns:
        (k, 2) the cell centres along the route from the start's cell, then the goal, metres.
    """
    g, cells = distance.grid, distance.cells
    j, i = g.index(np.asarray(start, dtype=float))
    if not math.isfinite(cells[j, i]):
        return None
    ny, nx = cells.shape
    moves = [(k, di, dj, g.cell * math.hypot(di, dj)) for k, (di, dj) in enumerate(g.offsets)]
    route = [(j, i)]
    for _ in range(ny * nx):
        best, least, here = None, math.inf, cells[j, i]
        for k, di, dj, step in moves:
            jj, ii = j + dj, i + di
            if not (0 <= jj < ny and 0 <= ii < nx and g.moves[k, j, i]):
                continue
            if cells[jj, ii] < here - 1e-9 and cells[jj, ii] + step < least:
                least, best = cells[jj, ii] + step, (jj, ii)
        if best is None:
            break
        j, i = best
        route.append(best)
    pts = np.array([g.centre(jj, ii) for jj, ii in route])
    return np.vstack([pts, distance.goal[None, :]])


def turn_in_guide(
    view, distance: GoalDistance, start, heading: float, radius: float, turn_radius: float
) -> np.ndarray | None:
    """The path a level walk to a flight's approach point follows to arrive along the flight
    (module docstring): the route down ``distance`` from ``start`` to a junction on its last
    stretch, then the shortest Dubins path from there (the route's heading at the junction) to
    the goal along ``heading``; the shortest such whole path whose points all keep ``radius``
    clear (:func:`mjwalk.plan.guide.guide_is_clear`).

    Args:
        view: the level's view (its ``walk_clearance``).
        distance: the distance field to the approach point (its goal).
        start: (2,) the walk's start, world xy, metres.
        heading: the heading to arrive along, radians.
        radius: the body radius, metres.
        turn_radius: the turning radius, metres.

    Returns:
        (k, 2) the path, metres, or None (no route, or no clear turn found).
    """
    route = field_route(distance, start)
    if route is None or len(route) < 3:
        return None
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(route, axis=0).T))])
    total = float(cum[-1])
    best: tuple[float, np.ndarray] | None = None
    back = np.arange(0.0, min(total, REACH_RADII * turn_radius), JUNCTION_RADII * turn_radius)
    for b in back:
        at = total - b
        k = int(np.searchsorted(cum, at, side="right") - 1)
        k = min(max(k, 0), len(route) - 2)
        # the route's heading at the junction: over the last half radius before it
        k0 = int(np.searchsorted(cum, max(0.0, at - 0.5 * turn_radius)))
        k0 = min(k0, k)
        here = route[k]
        d = here - route[k0] if k > k0 else route[k + 1] - here
        yaw = math.atan2(d[1], d[0])
        for length, pts in dubins_paths(here, yaw, route[-1], heading, turn_radius):
            whole = float(cum[k]) + length
            if best is not None and whole >= best[0]:
                break
            if guide_is_clear(view, pts, radius):
                best = (whole, np.vstack([route[: k + 1], pts[1:]]))
                break
    return None if best is None else best[1]


#: How many of a level walk's last walking steps the turn into a flight may start after
#: (:func:`turn_in_steps`), the last first: a bound on the work (four steps, about 2.5 m).
CUT_STEPS = 4


def turn_in_steps(view, walk, c, direction: str, walker, radius: float, first) -> tuple | None:
    """Where a level walk that arrives at a flight's approach point facing more than
    :data:`~mjwalk.plan.levelcross.ENTRY_TURN` off it turns into the flight while walking
    (module docstring): after one of its last walking steps (:data:`CUT_STEPS`, its closing
    step dropped), along the shortest Dubins path from the pelvis' pose there to the flight's
    stance along the flight, then on along the axis to its first footfall ``first``, at a
    turning radius of a step length per :data:`~mjwalk.plan.levelcross.ENTRY_TURN` (Patla et
    al. 1991: at most that within one step), the path keeping ``radius`` clear; stepped in
    equal steps of at most the walker's step length. Of the cuts and words that fit, the one
    with the fewest steps in all, the latest cut of those.

    Args:
        view: the level's view (its ``walk_clearance``).
        walk: the level walk to the flight's approach point (its steps, pelvis xy and yaw).
        c: the crossing (:class:`~mjwalk.plan.levelroute.Crossing`).
        direction: "up" or "down".
        walker: the walker (step length).
        radius: the body radius, metres.
        first: (2,) world xy of the flight's first footfall on its axis, metres.

    Returns:
        (j, points (m, 2), headings (m,), end heading): the walk's step ``j`` after which it
        turns, the turn's footfalls on its walking line (world xy, metres) and headings
        (radians, unwrapped from the walk's), the flight's first footfall not included, and
        the heading along the flight it ends at (unwrapped); None where no cut fits (the walk
        then turns on the spot, :func:`mjwalk.plan.levelcross.spot_turn`).
    """
    heading = c.yaw if direction == "up" else c.yaw + math.pi
    step = float(walker.step_length)
    r = step / WALKING_TURN_MAX
    # the turn's last footfall a step before the flight's first, on its axis, facing along it
    target = np.asarray(first, dtype=float) - step * np.array([math.cos(heading), math.sin(heading)])
    best = None
    walking = len(walk.steps) - 1  # the last is the closing step
    for j in range(walking - 1, max(-1, walking - 1 - CUT_STEPS), -1):
        at = walk.steps[j].end
        xy, yaw = walk.xy[at], float(walk.yaw[at])
        for length, pts in dubins_paths(xy, yaw, target, heading, r):
            n = max(1, math.ceil(length / step - 1e-9))
            if best is not None and j + n >= best[0]:
                break
            if not guide_is_clear(view, pts, radius):
                continue
            cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
            at_s = cum[-1] * np.arange(1, n + 1) / n
            points = np.stack([np.interp(at_s, cum, pts[:, 0]), np.interp(at_s, cum, pts[:, 1])], 1)
            d = np.gradient(pts, axis=0)
            tang = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
            tang += 2.0 * math.pi * round((yaw - tang[0]) / (2.0 * math.pi))
            tang[-1] += math.remainder(heading - tang[-1], 2.0 * math.pi)  # along the axis
            best = (j + n, j, points, np.interp(at_s, cum, tang), float(tang[-1]))
            break
    return None if best is None else best[1:]


def turn_into(view, walk: WalkPath, c, direction: str, walker, radius: float):
    """A level walk to a flight's approach point cut where it turns into the flight while
    walking (:func:`turn_in_steps`), and that turn for the crossing's walk
    (:func:`mjwalk.plan.levelcross.cross_walk`'s ``lead_in``).

    Args:
        view: the level's view (its ``walk_clearance``).
        walk: the level walk to the approach point.
        c: the crossing as walked.
        direction: "up" or "down".
        walker: the walker (step length, stature).
        radius: the body radius, metres.

    Returns:
        (the walk up to its step the turn follows, (footfalls (m, 2), headings (m,), end
        heading)), or None where no turn fits.
    """
    from mjwalk.plan.levelcross import _footfalls, tread_setback  # levelcross imports this

    s, _ = _footfalls(c, direction, walker)
    sign = 1.0 if direction == "up" else -1.0
    first = c.point(s[0] - sign * tread_setback(c, s[:1], walker.stature, direction)[0])
    found = turn_in_steps(view, walk, c, direction, walker, radius, first)
    if found is None:
        return None
    j, points, headings, end = found
    e = walk.steps[j].end + 1
    cut = WalkPath(
        t=walk.t[:e], xy=walk.xy[:e], yaw=walk.yaw[:e], steps=list(walk.steps[: j + 1]),
        meta={**walk.meta, "turned_in": len(points)}, z=None if walk.z is None else walk.z[:e],
    )  # fmt: skip
    return cut, (points, headings, end)


def turned_steps(lead: tuple, footfalls: tuple, here: tuple, turn: tuple, step_time: float, left):
    """The crossing's footfalls with the turn into it (:func:`turn_into`) before them, as
    :func:`mjwalk.plan.levelcross._spot_steps` gives the steps on the spot.

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
