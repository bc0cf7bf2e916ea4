"""Shortest paths of bounded curvature between two poses (Dubins 1957), compiled.

Dubins ("On curves of minimal length with a constraint on average curvature, and with
prescribed initial and terminal positions and tangents", Am J Math 79:497-516, 1957) showed
that the shortest path of curvature at most 1/r from a pose to a pose is one of six words of
arcs (L, R: turning left or right at radius r) and straight runs (S): LSL, RSR, LSR, RSL, RLR,
LRL. :func:`word_lengths` gives each word's three segments in closed form (Shkel & Lumelsky
2001, "Classification of the Dubins set", Robot Auton Syst 34:179-202; the formulas as LaValle
2006, "Planning Algorithms" §15.3.1, gives them, quoted from memory: tests trace each word to
its end pose), :func:`dubins_length` the shortest. The hybrid search takes it as the
heading-aware part of its heuristic where the goal has a heading (the non-holonomic heuristic
without obstacles of Dolgov, Thrun, Montemerlo & Diebel 2010, "Path planning for autonomous
vehicles in unknown semi-structured environments", Int J Robot Res 29:485-501, quoted from
memory); :mod:`mjwalk.plan.turnin` traces the words into a guide. Metres, radians (yaw from +x).
"""

from __future__ import annotations

import math

from mjwalk._jit import njit

#: The words, in :func:`word_lengths`' numbering.
WORDS = ("LSL", "RSR", "LSR", "RSL", "RLR", "LRL")

_TAU = 2.0 * math.pi


@njit
def _mod(a):
    return a % _TAU


@njit
def word_lengths(word, d, alpha, beta):
    """The segments of Dubins word ``word`` (index into :data:`WORDS`) from heading ``alpha``
    at the origin to heading ``beta`` at (d, 0), all in turning radii (the turns in radians).

    Args:
        word: 0-5, the word's index in :data:`WORDS`.
        d: the distance between the two points, in turning radii.
        alpha: the start heading against the line between them, radians.
        beta: the end heading against that line, radians.

    Returns:
        (exists, t, p, q): whether the word joins the poses, and its three segments.
    """
    sa, ca, sb, cb = math.sin(alpha), math.cos(alpha), math.sin(beta), math.cos(beta)
    cab = math.cos(alpha - beta)
    if word == 0:  # LSL
        tmp = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)
        if tmp < 0.0:
            return False, 0.0, 0.0, 0.0
        th = math.atan2(cb - ca, d + sa - sb)
        return True, _mod(th - alpha), math.sqrt(tmp), _mod(beta - th)
    if word == 1:  # RSR
        tmp = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)
        if tmp < 0.0:
            return False, 0.0, 0.0, 0.0
        th = math.atan2(ca - cb, d - sa + sb)
        return True, _mod(alpha - th), math.sqrt(tmp), _mod(th - beta)
    if word == 2:  # LSR
        tmp = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)
        if tmp < 0.0:
            return False, 0.0, 0.0, 0.0
        p = math.sqrt(tmp)
        th = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        return True, _mod(th - alpha), p, _mod(th - beta)
    if word == 3:  # RSL
        tmp = d * d - 2.0 + 2.0 * cab - 2.0 * d * (sa + sb)
        if tmp < 0.0:
            return False, 0.0, 0.0, 0.0
        p = math.sqrt(tmp)
        th = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        return True, _mod(alpha - th), p, _mod(beta - th)
    if word == 4:  # RLR
        tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0
        if abs(tmp) > 1.0:
            return False, 0.0, 0.0, 0.0
        p = _mod(_TAU - math.acos(tmp))
        t = _mod(alpha - math.atan2(ca - cb, d - sa + sb) + p / 2.0)
        return True, t, p, _mod(alpha - beta - t + p)
    tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0  # LRL
    if abs(tmp) > 1.0:
        return False, 0.0, 0.0, 0.0
    p = _mod(_TAU - math.acos(tmp))
    t = _mod(-alpha - math.atan2(ca - cb, d + sa - sb) + p / 2.0)
    return True, t, p, _mod(beta - alpha - t + p)


@njit
def frame(x, y, yaw0, gx, gy, yaw1, radius):
    """The normalised problem of a Dubins path: (d, alpha, beta) of :func:`word_lengths`.

    Args:
        x: the start's x, metres.
        y: the start's y, metres.
        yaw0: the start heading, radians.
        gx: the goal's x, metres.
        gy: the goal's y, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).
    """
    dx, dy = (gx - x) / radius, (gy - y) / radius
    theta = math.atan2(dy, dx)
    return math.hypot(dx, dy), _mod(yaw0 - theta), _mod(yaw1 - theta)


@njit
def dubins_length(x, y, yaw0, gx, gy, yaw1, radius):
    """The length (m) of the shortest path of curvature at most 1/``radius`` from (x, y)
    heading ``yaw0`` to (gx, gy) heading ``yaw1`` (the shortest of the six words).

    Args:
        x: the start's x, metres.
        y: the start's y, metres.
        yaw0: the start heading, radians.
        gx: the goal's x, metres.
        gy: the goal's y, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).
    """
    d, alpha, beta = frame(x, y, yaw0, gx, gy, yaw1, radius)
    best = math.inf
    for w in range(6):
        ok, t, p, q = word_lengths(w, d, alpha, beta)
        if ok and t + p + q < best:
            best = t + p + q
    return best * radius


#: The turning radius (m) of :func:`turn_in_bound`: the tightest the search's walking steps
#: turn, a quarter turn (no planned step turns the pelvis by 90 deg or more,
#: ``tests/plan/test_hybrid.py``; :func:`mjwalk.plan.detour.walkable`) in a step of 0.4 m
#: (ASSUMPTION: a short walking step; a bound on the search's work, no behaviour of walkers).
TURN_RADIUS = 0.4 / (math.pi / 2.0)


@njit
def turn_in_bound(x, y, yaw, goal, goal_yaw, tolerance, yaw_tolerance):
    """A bound (m) on the way left for a walker at (x, y) heading ``yaw`` to a goal area it must
    end in facing ``goal_yaw`` (within ``yaw_tolerance``): the Dubins path to the goal point
    along the goal heading at :data:`TURN_RADIUS`, less the goal area's radius and the arc the
    heading's tolerance spares.

    Args:
        x: the walker's x, metres.
        y: the walker's y, metres.
        yaw: its heading, radians.
        goal: the goal point, x + iy, metres.
        goal_yaw: the heading to arrive along, radians.
        tolerance: the goal area's radius, metres.
        yaw_tolerance: how far (radians) the arrival may face off ``goal_yaw``.
    """
    way = dubins_length(x, y, yaw, goal.real, goal.imag, goal_yaw, TURN_RADIUS)
    return way - tolerance - TURN_RADIUS * yaw_tolerance
