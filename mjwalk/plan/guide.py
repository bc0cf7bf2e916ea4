"""The smooth path a walk's heading follows: a minimum-jerk curve between its two end poses.

People walking from one pose to another do not turn onto the straight line and walk it: their
paths are smooth curves set by where and how they start and end, and they are stereotyped
enough to be predicted by a maximum-smoothness principle. Pham, Hicheur, Arechavaleta, Laumond
& Berthoz ("The formation of trajectory during goal-oriented locomotion in humans. II. A
maximum smoothness model", Eur J Neurosci 26:2391-2403, 2007) fit the trajectories of people
walking to a goal position and orientation with the path that minimises the integrated squared
jerk between the two end states; Hicheur, Pham, Arechavaleta, Laumond & Berthoz (part I of the
same study, Eur J Neurosci 26:2376-2390, 2007) show the paths are as alike across people and
trials as that model makes them. The minimum-jerk path between two states of position,
velocity and acceleration, over a duration T, is the quintic Hermite curve (Flash & Hogan,
J Neurosci 5:1688-1703, 1985). mjwalk's guide (:func:`minimum_jerk_guide`) is that curve in the
normalized time s = t / T in [0, 1]:

- from the walk's start (x, y) to its goal point;
- end velocities of the walker's pace v along the start and end headings, so the tangents
  dp/ds = v·T·h are the walk's own length L times the unit heading h (T = L / v: walking at
  its pace the whole way); a walker who stands, or a goal without a heading, gives the
  straight line's direction there;
- zero acceleration at both ends (steady walking in and out).

Nothing in it is a free parameter: with both headings along the straight line it *is* the
straight line, and the heading term (:func:`mjwalk.plan.stepcost.heading_factor`) reduces to
aiming at the goal (Mombaur, Truong & Laumond 2010). The search follows the guide as a
polyline of :data:`GUIDE_POINTS` points (:func:`resample_guide`; a caller may give its own,
``WalkRequest(guide=...)``), and only where it keeps the body's clearance from every
obstacle (:func:`guide_is_clear`); around obstacles the route search decides. Metres, radians
(world frame, yaw from +x).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.gait.walker import REFERENCE_CADENCE, REFERENCE_SPEED
from mjwalk.plan.stepcost import guide_lengths, guide_rest
from mjwalk.world.clearance import ClearanceField, bilinear_at

__all__ = [
    "GUIDE_POINTS",
    "PURSUIT_AHEAD",
    "densify",
    "first_below",
    "guide_ahead",
    "guide_ahead_at",
    "guide_aim",
    "guide_aim_at",
    "guide_is_clear",
    "guide_nearest",
    "guide_start_heading",
    "minimum_jerk_guide",
    "resample_guide",
    "via_point_guide",
    "via_points_guide",
]

#: Points of the polyline the compiled search follows (evenly spaced along it): 24 segments of
#: a walk of a few metres are a few dozen centimetres each, a few degrees of turn at most.
GUIDE_POINTS = 25

#: How far along the guide (m) the point lies that a walker off it steers for: two steps of an
#: adult at a comfortable pace (REFERENCE_SPEED / cadence: 1.37 m/s at 113 steps/min, 0.73 m a
#: step). People walking where they must place their feet look about two steps ahead (Patla &
#: Vickers, "How far ahead do we look when required to step on specific locations in the travel
#: path during locomotion?", Exp Brain Res 148:133-138, 2003; Matthis & Fajen, "Visual control
#: of foot placement when walking over complex terrain", J Exp Psychol Hum Percept Perform
#: 40:106-115, 2014), and their heading is drawn to the point they steer for as to a goal
#: (Fajen & Warren, "Behavioral dynamics of steering, obstacle avoidance, and route selection",
#: J Exp Psychol Hum Percept Perform 29:343-362, 2003: the goal an attractor of heading).
#: Steering for a point on the way two steps on turns a sideways offset s into a heading error
#: atan(s / PURSUIT_AHEAD), which the heading term then costs as any other: a walk drifting off
#: its guide is drawn back within a few steps, as people's stepping corrects their position on
#: the way step by step (Dingwell & Cusumano, PLoS Comput Biol 15:e1006850, 2019).
PURSUIT_AHEAD = 2.0 * REFERENCE_SPEED / (REFERENCE_CADENCE / 60.0)

# Quintic Hermite basis with zero end accelerations (Flash & Hogan 1985), as polynomial
# coefficients in s (constant term first): position 0, tangent 0, tangent 1, position 1.
_H = np.array(
    [
        [1.0, 0.0, 0.0, -10.0, 15.0, -6.0],
        [0.0, 1.0, 0.0, -6.0, 8.0, -3.0],
        [0.0, 0.0, 0.0, -4.0, 7.0, -3.0],
        [0.0, 0.0, 0.0, 10.0, -15.0, 6.0],
    ]
)


def minimum_jerk_guide(
    start, goal, start_heading: float | None, goal_heading: float | None, n: int = 400
) -> np.ndarray:
    """``n`` points (n, 2) of the minimum-jerk path (module doc) from ``start`` to ``goal``
    (x, y, metres), leaving along ``start_heading`` and arriving along ``goal_heading`` (world
    radians; None: along the straight line, a walker who stands or a goal without a
    heading), at evenly spaced normalized times.

    Args:
        start: the start point (x, y), metres, world frame.
        goal: the goal point (x, y), metres.
        start_heading: the heading to leave along, radians from +x CCW; None: the straight line.
        goal_heading: the heading to arrive along, radians; None: the straight line.
        n: the number of points.

    Returns:
        (n, 2) the path's points, metres.
    """
    p0 = np.asarray(start, dtype=float)[:2]
    p1 = np.asarray(goal, dtype=float)[:2]
    chord = p1 - p0
    length = float(np.hypot(*chord))
    if not length > 1e-9:
        raise ValueError("minimum_jerk_guide: start and goal coincide")
    t0 = chord if start_heading is None else _heading_tangent(start_heading, length)
    t1 = chord if goal_heading is None else _heading_tangent(goal_heading, length)
    return _poly_points(_H.T @ np.array([p0, t0, t1, p1]), n)  # rows (4, 2)


def _heading_tangent(h: float, length: float) -> np.ndarray:
    """The tangent ``length`` times the unit heading ``h`` (radians), (2,)."""
    return length * np.array([math.cos(h), math.sin(h)])


# Quintic Hermite basis with end accelerations too, in s in [0, 1] (constant term first):
# position 0, velocity 0 (x T), acceleration 0 (x T^2), acceleration 1 (x T^2), velocity 1
# (x T), position 1.
_H6 = np.array(
    [
        [1.0, 0.0, 0.0, -10.0, 15.0, -6.0],
        [0.0, 1.0, 0.0, -6.0, 8.0, -3.0],
        [0.0, 0.0, 0.5, -1.5, 1.5, -0.5],
        [0.0, 0.0, 0.0, 0.5, -1.0, 0.5],
        [0.0, 0.0, 0.0, -4.0, 7.0, -3.0],
        [0.0, 0.0, 0.0, 10.0, -15.0, 6.0],
    ]
)
#: Third derivatives of the :data:`_H6` basis in s: coefficients of 1, s, s^2 (6, 3).
_JERK = _H6[:, 3:] * np.array([6.0, 24.0, 60.0])


@njit
def _poly_points(coef, m):
    """Points (m, 2) of the polynomial with coefficients ``coef`` (6, 2: constant term first)
    at m evenly spaced s in [0, 1] (Horner's scheme)."""
    out = np.empty((m, 2))
    for i in range(m):
        t = 1.0 if i == m - 1 else i / (m - 1)
        for a in range(2):
            v = coef[5, a]
            for c in range(4, -1, -1):
                v = v * t + coef[c, a]
            out[i, a] = v
    return out


@njit
def _via_point_solve(p0, w, p1, v0, v1, t1, t2, jerk):
    """The via point's velocity and acceleration (2, 2: rows velocity, acceleration; per
    axis) minimising the squared jerk of :func:`via_point_guide`'s two pieces, sampled at 64
    normalized times each and weighted by the pieces' times: the jerk is linear in them, so
    this is least squares in two unknowns per axis, solved by its normal equations."""
    m00 = m01 = m11 = 0.0
    r = np.zeros((2, 2))
    ns = 64
    jb = np.empty(6)
    for piece in range(2):
        t = t1 if piece == 0 else t2
        for i in range(ns):
            s = i / (ns - 1)
            for b in range(6):
                jb[b] = jerk[b, 0] + jerk[b, 1] * s + jerk[b, 2] * s * s
            if piece == 0:
                a0, a1 = jb[4] / t1**2, jb[3] / t1
            else:
                a0, a1 = jb[1] / t2**2, jb[2] / t2
            m00 += t * a0 * a0
            m01 += t * a0 * a1
            m11 += t * a1 * a1
            for k in range(2):
                if piece == 0:
                    known = (jb[0] * p0[k] + jb[1] * v0[k] * t1 + jb[5] * w[k]) / t1**3
                else:
                    known = (jb[0] * w[k] + jb[4] * v1[k] * t2 + jb[5] * p1[k]) / t2**3
                r[0, k] -= t * a0 * known
                r[1, k] -= t * a1 * known
    det = m00 * m11 - m01 * m01
    out = np.empty((2, 2))
    for k in range(2):
        out[0, k] = (m11 * r[0, k] - m01 * r[1, k]) / det
        out[1, k] = (m00 * r[1, k] - m01 * r[0, k]) / det
    return out


def via_point_guide(
    start, via, goal, start_heading: float | None, goal_heading: float | None, n: int = 400
) -> np.ndarray:
    """``n`` points (n, 2) of the minimum-jerk path from ``start`` through ``via`` to ``goal``
    (x, y, metres): two quintic pieces joined at ``via`` with continuous velocity and
    acceleration, chosen to minimise the integrated squared jerk (the via-point solution of
    Flash & Hogan 1985). The ends are as :func:`minimum_jerk_guide`'s (velocities of the whole
    length along the headings, along the way to and from ``via`` where None; zero
    accelerations); the pieces' times are in proportion to their straight lengths.

    Args:
        start: the start point (x, y), metres, world frame.
        via: the point to pass through (x, y), metres.
        goal: the goal point (x, y), metres.
        start_heading: the heading to leave along, radians from +x CCW; None: towards ``via``.
        goal_heading: the heading to arrive along, radians; None: from ``via``.
        n: the number of points.

    Returns:
        (n, 2) the path's points, metres.
    """
    p0, w, p1 = (np.asarray(v, dtype=float)[:2] for v in (start, via, goal))
    l1, l2 = math.hypot(*(w - p0)), math.hypot(*(p1 - w))
    if not (l1 > 1e-9 and l2 > 1e-9):
        raise ValueError("via_point_guide: the via point coincides with an end")
    length = l1 + l2
    t1, t2 = l1 / length, l2 / length  # the pieces' normalized times
    # end velocities: the whole length along the heading, or along the way to / from ``via``
    v0 = (
        length * ((w - p0) / l1)
        if start_heading is None
        else _heading_tangent(start_heading, length)
    )
    v1 = (
        length * ((p1 - w) / l2) if goal_heading is None else _heading_tangent(goal_heading, length)
    )
    m1 = min(n - 1, max(2, round(n * t1)))
    vw, aw = _via_point_solve(p0, w, p1, v0, v1, t1, t2, _JERK)
    zero = np.zeros(2)
    first = _poly_points(_H6.T @ np.array([p0, v0 * t1, zero, aw * t1**2, vw * t1, w]), m1)
    second = _poly_points(_H6.T @ np.array([w, vw * t2, aw * t2**2, zero, v1 * t2, p1]), n - m1 + 1)
    return np.concatenate([first, second[1:]])


def via_points_guide(
    start, vias, goal, start_heading: float | None, goal_heading: float | None, n: int = 400
) -> np.ndarray:
    """About ``n`` points of a smooth path from ``start`` through the points ``vias`` (in
    order) to ``goal`` (x, y, metres): :func:`via_point_guide` for one via point; for more, a
    chain of minimum-jerk pieces (:func:`minimum_jerk_guide`) joined at the via points along
    the direction from the point before to the point after (continuous direction, zero
    acceleration at the joins: the chain's jerk is near the joint solution's for via points
    a piece's length apart or more).

    Args:
        start: the start point (x, y), metres, world frame.
        vias: (m >= 1, 2) the points to pass through, in order, metres.
        goal: the goal point (x, y), metres.
        start_heading: the heading to leave along, radians from +x CCW; None: towards the
            first via point.
        goal_heading: the heading to arrive along, radians; None: from the last via point.
        n: about the number of points (each piece gets its share by straight length).

    Returns:
        (k, 2) the path's points, metres.
    """
    ways = np.asarray(vias, dtype=float).reshape(-1, 2)
    if len(ways) == 1:
        return via_point_guide(start, ways[0], goal, start_heading, goal_heading, n)
    pts = np.vstack([np.asarray(start, dtype=float)[None, :2], ways, np.asarray(goal)[None, :2]])
    lengths = np.hypot(*np.diff(pts, axis=0).T)
    if not np.all(lengths > 1e-9):
        raise ValueError("via_points_guide: two consecutive points coincide")
    headings: list[float | None] = [start_heading]
    for k in range(1, len(pts) - 1):
        d = pts[k + 1] - pts[k - 1]
        headings.append(math.atan2(d[1], d[0]))
    headings.append(goal_heading)
    pieces = []
    for k in range(len(pts) - 1):
        m = max(8, round(n * lengths[k] / lengths.sum()))
        piece = minimum_jerk_guide(pts[k], pts[k + 1], headings[k], headings[k + 1], m)
        pieces.append(piece if k == 0 else piece[1:])
    return np.vstack(pieces)


def _checked(points) -> np.ndarray:
    """``points`` as a contiguous float (k, 2) array, or the ValueError every guide function
    raises for anything else."""
    pts = np.ascontiguousarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not _all_finite(pts):
        raise ValueError("a guide must be finite (x, y) points, at least two")
    return pts


@njit
def _all_finite(pts):
    """Whether every coordinate of ``pts`` (k, 2) is finite (np.isfinite(pts).all())."""
    for i in range(pts.shape[0]):
        if not (math.isfinite(pts[i, 0]) and math.isfinite(pts[i, 1])):
            return False
    return True


@njit
def _cumulative(pts):
    """The cumulative length (k,) of the polyline ``pts`` (k, 2) at each of its points."""
    cum = np.empty(pts.shape[0])
    cum[0] = 0.0
    for i in range(1, pts.shape[0]):
        cum[i] = cum[i - 1] + math.hypot(pts[i, 0] - pts[i - 1, 0], pts[i, 1] - pts[i - 1, 1])
    return cum


@njit
def _station(pts, cum, i, n, j):
    """The i-th of n points evenly spaced along the polyline ``pts`` (cumulative length
    ``cum``), as np.interp at np.linspace's stations gives it: (segment j, x, y), searching
    on from segment ``j`` (the previous station's)."""
    total = cum[cum.shape[0] - 1]
    u = total if i == n - 1 else i * (total / (n - 1))
    while j < pts.shape[0] - 2 and cum[j + 1] <= u:  # np.interp: the last point at or below u
        j += 1
    seg = cum[j + 1] - cum[j]
    w = (u - cum[j]) / seg if seg > 0.0 else 0.0
    return (
        j,
        pts[j, 0] + w * (pts[j + 1, 0] - pts[j, 0]),
        pts[j, 1] + w * (pts[j + 1, 1] - pts[j, 1]),
    )


def resample_guide(points, n: int = GUIDE_POINTS) -> np.ndarray:
    """The polyline ``points`` (k >= 2, 2) as ``n`` points evenly spaced along it (metres).

    Args:
        points: (k >= 2, 2) the polyline, metres.
        n: the number of points.

    Returns:
        (n, 2) points evenly spaced by arc length, the ends kept, metres.
    """
    out = _resampled(_checked(points), int(n))
    if len(out) == 0:
        raise ValueError("a guide must have a length")
    return out


@njit
def _resampled(pts, n):
    """:func:`resample_guide`'s points (n, 2), compiled (:func:`_station`); (0, 2) for a
    polyline of no length."""
    cum = _cumulative(pts)
    if cum[-1] <= 1e-9:
        return np.empty((0, 2))
    out = np.empty((n, 2))
    j = 0
    for i in range(n):
        j, out[i, 0], out[i, 1] = _station(pts, cum, i, n, j)
    return out


def guide_start_heading(guide) -> float:
    """The direction a walker whose facing is unknown sets off in: its guide's first segment.

    People's walking paths are smooth with the body's heading along their tangent (the
    nonholonomic model of Arechavaleta, Laumond, Hicheur & Berthoz, "An optimality principle
    governing human walking", IEEE Trans Robot 24:5-14, 2008), and they set off from a stand
    along the way they mean to walk: in gait initiation the centre of pressure's shift back
    drives the centre of gravity forward along the direction of progression, with a lateral
    shift onto the stance limb (Jian, Winter, Ishac & Gilchrist, "Trajectory of the body COG
    and COP during initiation and termination of gait", Gait Posture 1:9-22, 1993). My
    modelling step: a walk with no start yaw thus sets off along its guide (the
    straight line to the goal in an open hall) rather than anywhere around the downhill
    heading (:data:`~mjwalk.plan.options.START_SPREAD`): a first step set off a few degrees
    from the line carries the walk several centimetres off its chord before the heading term
    draws it back (issue 48, the empty hall).

    Args:
        guide: (k >= 2, 2) the guide, metres, world frame (:func:`resample_guide`).

    Returns:
        The direction from its first point to its second, radians from +x CCW.
    """
    g = np.asarray(guide, dtype=float)
    return float(math.atan2(g[1, 1] - g[0, 1], g[1, 0] - g[0, 0]))


def densify(points, spacing: float = 0.05) -> np.ndarray:
    """The polyline ``points`` resampled at points at most ``spacing`` metres apart (the
    clearance checks' sampling: :func:`guide_is_clear`, :mod:`mjwalk.plan.detour`).

    Args:
        points: (k >= 2, 2) the polyline, metres.
        spacing: the largest gap between points, metres.

    Returns:
        (k', 2) the resampled points, metres, the ends kept.
    """
    out = _densified(_checked(points), float(spacing))
    if len(out) == 0:
        raise ValueError("a guide must have a length")
    return out


@njit
def _densified(pts, spacing):
    """:func:`densify`'s points, compiled (:func:`_resampled` at :func:`_dense_count`'s
    number); (0, 2) for a polyline of no length."""
    return _resampled(pts, _dense_count(_cumulative(pts)[-1], spacing))


@njit
def _dense_count(length, spacing):
    """Points that sample a polyline of ``length`` metres at most ``spacing`` apart."""
    return max(2, math.ceil(length / spacing) + 1)


def first_below(workplace, points, clearance: float, spacing: float = 0.05):
    """The first point (x, y) of the polyline ``points`` (k >= 2, 2), sampled as
    :func:`densify` samples it, where the room to walk (:meth:`Workplace.walk_clearance`) is
    less than ``clearance`` metres; None where there is none. On a workplace whose clearance
    is a :class:`~mjwalk.world.clearance.ClearanceField` (every loaded one) one compiled pass
    that stops at that point, with the lookup's own arithmetic; else densify and look up.

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        points: (k >= 2, 2) the polyline, metres, world frame.
        clearance: the room to walk required, metres.
        spacing: the largest gap between checked points, metres.
    """
    pts = _checked(points)
    field = workplace.clearance
    if not isinstance(field, ClearanceField):
        dense = densify(pts, spacing)
        low = np.flatnonzero(workplace.walk_clearance(dense) < clearance)
        return dense[low[0]] if len(low) else None
    xmin, ymin, xmax, ymax = (float(v) for v in workplace.floor_bounds)
    k, x, y = _first_below(
        pts, field.values, float(field.x0), float(field.y0), float(field.resolution), xmin,
        ymin, xmax, ymax, float(clearance), float(spacing),
    )  # fmt: skip
    if k == -2:
        raise ValueError("a guide must have a length")
    return None if k < 0 else np.array([x, y])


@njit
def _first_below(pts, values, x0, y0, res, xmin, ymin, xmax, ymax, clearance, spacing):
    """:func:`first_below` on a clearance field: (index among the densified points, x, y) of
    the first point below ``clearance``, -1 for none, -2 for a polyline of no length. The
    points are :func:`densify`'s (:func:`_station`), the room is min(bilinear clearance,
    distance to the floor's edge) as :meth:`Workplace.walk_clearance` computes it."""
    cum = _cumulative(pts)
    if cum[-1] <= 1e-9:
        return -2, math.nan, math.nan
    n = _dense_count(cum[-1], spacing)
    j = 0
    for i in range(n):
        j, x, y = _station(pts, cum, i, n, j)
        room = min(bilinear_at(values, x0, y0, res, x, y), x - xmin, xmax - x, y - ymin, ymax - y)
        if room < clearance:
            return i, x, y
    return -1, math.nan, math.nan


def guide_is_clear(workplace, points, clearance: float, spacing: float = 0.05) -> bool:
    """Whether the polyline ``points`` keeps ``clearance`` metres from the workplace's
    obstacles and floor edges (:meth:`Workplace.walk_clearance`) at points ``spacing`` apart
    (:func:`first_below`).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        points: (k >= 2, 2) the polyline, metres, world frame.
        clearance: the room to walk required, metres.
        spacing: the largest gap between checked points, metres.

    Returns:
        Whether no checked point is short of ``clearance``.
    """
    return first_below(workplace, points, clearance, spacing) is None


@njit
def guide_nearest(guide, p):
    """The guide's point nearest ``p`` (x + iy): its segment k, the share w along it and the
    squared distance (guide flat x0, y0, x1, y1, ...). :func:`guide_aim_at` and
    :func:`guide_ahead_at` take it, so a caller needing both finds it once.

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres, world frame.
        p: the walker's point, x + iy, metres.
    """
    best_d2 = np.inf
    best_k = 0
    best_w = 0.0
    for k in range(guide.shape[0] // 2 - 1):
        ax, ay = guide[2 * k], guide[2 * k + 1]
        ux, uy = guide[2 * k + 2] - ax, guide[2 * k + 3] - ay
        uu = ux * ux + uy * uy
        w = 0.0
        if uu > 0.0:
            w = min(max(((p.real - ax) * ux + (p.imag - ay) * uy) / uu, 0.0), 1.0)
        qx, qy = ax + w * ux, ay + w * uy
        d2 = (qx - p.real) ** 2 + (qy - p.imag) ** 2
        if d2 < best_d2:
            best_d2, best_k, best_w = d2, k, w
    return best_k, best_w, best_d2


@njit
def guide_aim(guide, p, goal):
    """The heading (world radians) a walker at ``p`` (x + iy) heading for ``goal`` (x + iy)
    keeps along the guide ``guide`` (flat x0, y0, x1, y1, ...: :func:`resample_guide`'s
    points; nan first: no guide, the straight direction to the goal): the guide's direction
    at its point q nearest ``p`` (the segments' directions, blended linearly between their
    midpoints), turned by the angle between the goal's directions seen from ``p`` and from
    q, and back towards the guide by atan(s / a) for a walker s metres off it, a =
    :data:`PURSUIT_AHEAD` (or the way left to the goal, if shorter): the walker steers for
    the guide's point two steps on. On the guide that is its direction; off it, the walker's
    own way to the goal bends it, as much as the goal's direction differs, and the pull
    back onto the guide; on a straight guide it is the direction to the goal on the guide.

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres; nan first: none.
        p: the walker's point, x + iy, metres, world frame.
        goal: the goal point, x + iy, metres.
    """
    if math.isnan(guide[0]):
        d = goal - p
        return math.atan2(d.imag, d.real)
    k, best_w, _ = guide_nearest(guide, p)
    return guide_aim_at(guide, p, goal, k, best_w)


@njit
def guide_aim_at(guide, p, goal, k, best_w):
    """:func:`guide_aim` along a guide, from its point nearest ``p`` (segment ``k``, share
    ``best_w``: :func:`guide_nearest`).

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres.
        p: the walker's point, x + iy, metres, world frame.
        goal: the goal point, x + iy, metres.
        k: the segment of the guide's point nearest ``p``.
        best_w: the share (0..1) along segment ``k`` of that point.
    """
    d = goal - p
    direct = math.atan2(d.imag, d.real)
    n = guide.shape[0] // 2
    ax, ay = guide[2 * k], guide[2 * k + 1]
    bx, by = guide[2 * k + 2], guide[2 * k + 3]
    qx, qy = ax + best_w * (bx - ax), ay + best_w * (by - ay)
    here = math.atan2(by - ay, bx - ax)
    # blend towards the neighbouring segment's direction beyond this one's midpoint
    j = k + 1 if best_w >= 0.5 else k - 1
    tang = here
    if 0 <= j < n - 1:
        other = math.atan2(guide[2 * j + 3] - guide[2 * j + 1], guide[2 * j + 2] - guide[2 * j])
        turn = (other - here + math.pi) % (2.0 * math.pi) - math.pi
        tang = here + abs(best_w - 0.5) * turn
    gx, gy = goal.real - qx, goal.imag - qy
    if gx * gx + gy * gy < 1e-12:
        return direct
    # the point the walker steers for, PURSUIT_AHEAD on along the guide: off it by s (signed,
    # left of its direction positive), that point lies atan(s / ahead) back towards it
    side = math.cos(tang) * (p.imag - qy) - math.sin(tang) * (p.real - qx)
    ahead = min(PURSUIT_AHEAD, math.sqrt(gx * gx + gy * gy))
    return tang + (direct - math.atan2(gy, gx)) - math.atan2(side, ahead)


@njit
def guide_ahead(guide, p):
    """The way (metres) left along the guide ``guide`` (as :func:`guide_aim`'s; nan first:
    none, 0) for a walker at ``p`` (x + iy): the distance to the guide's nearest point q plus
    the guide's length from q to its end. The search takes it as its estimate of the way to
    the goal where it is the larger (the walker means to go that way, not straight).

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres; nan first: none.
        p: the walker's point, x + iy, metres, world frame.
    """
    if math.isnan(guide[0]):
        return 0.0
    best_k, best_w, best_d2 = guide_nearest(guide, p)
    return guide_ahead_at(guide, best_k, best_w, best_d2)


@njit
def guide_ahead_at(guide, best_k, best_w, best_d2):
    """:func:`guide_ahead` along a guide, from its point nearest the walker (segment
    ``best_k``, share ``best_w``, squared distance ``best_d2``: :func:`guide_nearest`).

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres.
        best_k: the segment of the guide's point nearest the walker.
        best_w: the share (0..1) along it of that point.
        best_d2: the squared distance (m^2) from the walker to that point.
    """
    return guide_rest(guide_lengths(guide), best_k, best_w, best_d2)
