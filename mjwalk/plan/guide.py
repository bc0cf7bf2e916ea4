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
``HybridPlanner.plan(guide=...)``), and only where it keeps the body's clearance from every
obstacle (:func:`guide_is_clear`); around obstacles the route search decides. Metres, radians
(world frame, yaw from +x).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit

__all__ = [
    "GUIDE_POINTS",
    "guide_aim",
    "guide_is_clear",
    "minimum_jerk_guide",
    "resample_guide",
]

#: Points of the polyline the compiled search follows (evenly spaced along it): 24 segments of
#: a walk of a few metres are a few dozen centimetres each, a few degrees of turn at most.
GUIDE_POINTS = 25

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
    heading), at evenly spaced normalized times."""
    p0 = np.asarray(start, dtype=float)[:2]
    p1 = np.asarray(goal, dtype=float)[:2]
    chord = p1 - p0
    length = float(np.hypot(*chord))
    if not length > 1e-9:
        raise ValueError("minimum_jerk_guide: start and goal coincide")

    def tangent(h: float | None) -> np.ndarray:
        return chord if h is None else length * np.array([math.cos(h), math.sin(h)])

    rows = np.stack([p0, tangent(start_heading), tangent(goal_heading), p1])  # (4, 2)
    s = np.linspace(0.0, 1.0, n)
    return (s[:, None] ** np.arange(6)) @ (_H.T @ rows)


def resample_guide(points, n: int = GUIDE_POINTS) -> np.ndarray:
    """The polyline ``points`` (k >= 2, 2) as ``n`` points evenly spaced along it (metres)."""
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
        raise ValueError("a guide must be finite (x, y) points, at least two")
    seg = np.hypot(*np.diff(pts, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] <= 1e-9:
        raise ValueError("a guide must have a length")
    u = np.linspace(0.0, s[-1], n)
    return np.stack([np.interp(u, s, pts[:, 0]), np.interp(u, s, pts[:, 1])], axis=1)


def guide_is_clear(workplace, points, clearance: float, spacing: float = 0.05) -> bool:
    """Whether the polyline ``points`` keeps ``clearance`` metres from the workplace's
    obstacles and floor edges (:meth:`Workplace.walk_clearance`) at points ``spacing`` apart."""
    pts = np.asarray(points, dtype=float)
    length = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    dense = resample_guide(pts, max(2, math.ceil(length / spacing) + 1))
    return bool(np.all(workplace.walk_clearance(dense) >= clearance))


@njit
def guide_aim(guide, p, goal):
    """The heading (world radians) a walker at ``p`` (x + iy) heading for ``goal`` (x + iy)
    keeps along the guide ``guide`` (flat x0, y0, x1, y1, ...: :func:`resample_guide`'s
    points; nan first: no guide, the straight direction to the goal): the guide's direction
    at its point q nearest ``p`` (the segments' directions, blended linearly between their
    midpoints), turned by the angle between the goal's directions seen from ``p`` and from
    q. On the guide that is its direction; off it, the walker's own way to the goal bends it,
    as much as the goal's direction differs; for a straight guide it is the direction to the
    goal."""
    d = goal - p
    direct = math.atan2(d.imag, d.real)
    if math.isnan(guide[0]):
        return direct
    n = guide.shape[0] // 2
    best_d2 = np.inf
    best_k = 0
    best_w = 0.0
    for k in range(n - 1):
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
    k = best_k
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
    return tang + (direct - math.atan2(gy, gx))
