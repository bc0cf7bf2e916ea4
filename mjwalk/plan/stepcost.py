"""What a sampled step costs and what is left to the goal: the energy cost of its length,
the heading factor while the goal is in sight, the goal distance's grid bound and the way left
along a walk's guide from its segment lengths (compiled).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.gait.features import MIN_DURATION
from mjwalk.world.clearance import bilinear_at


@njit
def grid_bound(dist, x0, y0, cell, top_x, top_y, nx, x, y):
    """:meth:`GoalDistance.__call__`'s grid bound at (``x``, ``y``) (metres) on the flat field
    ``dist`` (origin ``x0``, ``y0``, spacing ``cell``, last column/row ``top_x``/``top_y``,
    ``nx`` columns): the nearest node's distance to the goal less the way to that node.

    Args:
        dist: the flat field (:meth:`GoalDistance.flat_bound`), metres.
        x0: the field's origin x, metres, world frame.
        y0: its origin y, metres.
        cell: its spacing, metres.
        top_x: its last column index (as a float).
        top_y: its last row index (as a float).
        nx: its number of columns.
        x: the point's x, metres.
        y: the point's y, metres.
    """
    gi = min(max(np.rint((x - x0) / cell), 0.0), top_x)
    gj = min(max(np.rint((y - y0) / cell), 0.0), top_y)
    off = math.hypot(x - (x0 + gi * cell), y - (y0 + gj * cell))
    return dist[int(gj) * nx + int(gi)] - off


@njit
def grid_sight(dist, x0, y0, cell, top_x, top_y, nx, x, y):
    """Whether the goal is in sight from (``x``, ``y``): the sight flag of the nearest node of
    the flat field ``dist`` (:meth:`GoalDistance.flat_bound`: the bounds, then the flags).

    Args:
        dist: the flat field (:meth:`GoalDistance.flat_bound`: the bounds, then the flags).
        x0: the field's origin x, metres, world frame.
        y0: its origin y, metres.
        cell: its spacing, metres.
        top_x: its last column index (as a float).
        top_y: its last row index (as a float).
        nx: its number of columns.
        x: the point's x, metres.
        y: the point's y, metres.
    """
    gi = min(max(np.rint((x - x0) / cell), 0.0), top_x)
    gj = min(max(np.rint((y - y0) / cell), 0.0), top_y)
    return dist[int((top_y + 1.0) * nx) + int(gj) * nx + int(gi)] > 0.5


@njit
def downhill_costs(xy, probes, clear, cx0, cy0, cres, floor, radius, dist, gx0, gy0, gcell,
                   top_x, top_y, goal_x, goal_y, offset):  # fmt: skip
    """:meth:`~mjwalk.plan.hybrid.HybridPlanner.default_heading`'s costs at ``xy + probes``
    (k, 2), with NumPy's arithmetic of :meth:`ClearanceField.__call__` on the obstacle field
    ``clear`` (origin cx0, cy0, spacing cres), :meth:`Workplace.edge_distance` on ``floor``
    (xmin, ymin, xmax, ymax), and :meth:`GoalDistance.__call__` on the flat grid bound
    ``dist`` (origin gx0, gy0, cell gcell, last column/row top_x, top_y) less ``offset``, or
    the straight line to (``goal_x``, ``goal_y``) where longer: the distance to the goal,
    plus 1e3 where the walking clearance is short of ``radius`` (metres).

    Args:
        xy: (2,) the walker's point, metres, world frame.
        probes: (k, 2) offsets of the probes from it, metres.
        clear: the obstacle clearance field's node values (ny, nx), metres.
        cx0: its origin x, metres.
        cy0: its origin y, metres.
        cres: its spacing, metres.
        floor: (4,) the floor's bounds (xmin, ymin, xmax, ymax), metres.
        radius: the body radius, metres.
        dist: the goal's flat grid bound (:meth:`GoalDistance.flat_bound`), metres.
        gx0: the grid's origin x, metres.
        gy0: its origin y, metres.
        gcell: its cell size, metres.
        top_x: its last column index (as a float).
        top_y: its last row index (as a float).
        goal_x: the goal point's x, metres.
        goal_y: its y, metres.
        offset: what the field's distance is lowered by, metres (a spot's offset).
    """
    n = probes.shape[0]
    out = np.empty(n)
    for k in range(n):
        x = xy[0] + probes[k, 0]
        y = xy[1] + probes[k, 1]
        c = bilinear_at(clear, cx0, cy0, cres, x, y)
        edge = min(min(min(x - floor[0], floor[2] - x), y - floor[1]), floor[3] - y)
        free = min(c, edge) >= radius
        bound = grid_bound(dist, gx0, gy0, gcell, top_x, top_y, int(top_x) + 1, x, y) - offset
        euclid = math.hypot(x - goal_x, y - goal_y)
        out[k] = max(euclid, bound) + (0.0 if free else 1e3)
    return out


@njit
def step_energy(length, duration, pace):
    """A step's cost in metres walked at the walker's preferred speed ``pace`` (m/s): its
    ``length`` (m) times c(v) = (pace / v + v / pace) / 2 at its speed v = length / duration
    (s; at least :data:`~mjwalk.gait.features.MIN_DURATION`), that is
    (pace·T + L² / (pace·T)) / 2. c is the metabolic cost of walking a metre at speed v
    relative to its least, at the preferred speed: Ralston's net power a + b·v² per kg
    (Ralston, "Energy-speed relation and optimal speed during level walking", Int Z angew
    Physiol 17:277-283, 1958: 29 + 0.0053 v² cal/kg/min, v in m/min) gives a/v + b·v per
    metre, least at v* = sqrt(a/b) (1.23 m/s there), and people walk at about that speed
    (ibid.; Zarrugh, Todd & Ralston, Eur J Appl Physiol 33:293-306, 1974); the walker's own
    preferred speed stands for v*. c >= 1, so the walked length is still a lower bound and the
    heuristic stays admissible; a step that stands still costs pace·T/2.

    Args:
        length: the step's length L, metres.
        duration: its duration T, seconds.
        pace: the walker's preferred speed, m/s.
    """
    t = max(duration, MIN_DURATION) * pace
    return 0.5 * (t + length * length / t)


@njit
def heading_factor(heading, want, weight):
    """A step's cost factor 1 + weight·ψ² for heading towards a goal in sight: ψ (radians) is
    the angle between the walker's ``heading`` (world radians; the search passes the mean of
    the step's start and end frame headings, which averages out the pelvis's yaw swing
    between left and right heel strikes) and the heading it ``want``s there (world radians:
    :func:`mjwalk.plan.guide.guide_aim`, the straight direction from the step's end to the
    goal, or along the walk's smooth guide between its end poses). People walking to a goal
    keep their body turned towards it: in the inverse optimal control of human walking by
    Mombaur, Truong & Laumond ("From human to humanoid locomotion - an inverse optimal control
    approach", Auton Robot 28:369-383, 2010) the cost per second is 1 (time) + ... + 5.2·ψ²
    (their weights α0 = 1, α4 = 5.2); a step's cost, its walked metres at the preferred pace,
    is its time times the pace, so the ratio carries over as this factor. The factor is >= 1:
    the heuristic stays admissible.

    Args:
        heading: the walker's heading, radians from +x CCW.
        want: the heading it wants, radians.
        weight: the weight per squared radian.
    """
    psi = want - heading
    psi = (psi + math.pi) % (2.0 * math.pi) - math.pi
    return 1.0 + weight * psi * psi


@njit
def guide_lengths(guide):
    """The lengths of a guide's segments, as :func:`mjwalk.plan.guide.guide_ahead_at` sums
    them: a walk's guide is fixed, so the search takes them once per walk
    (:data:`~mjwalk.plan.slots.P_GUIDE_LEN0`) rather than per scored step.

    Args:
        guide: the guide, flat (x0, y0, x1, y1, ...), metres, world frame.

    Returns:
        (points - 1,) the segment lengths, metres.
    """
    n = guide.shape[0] // 2
    out = np.empty(n - 1)
    for k in range(n - 1):
        out[k] = math.hypot(guide[2 * k + 2] - guide[2 * k], guide[2 * k + 3] - guide[2 * k + 1])
    return out


@njit
def guide_rest(lengths, best_k, best_w, best_d2):
    """The way (m) left along a guide from its point nearest the walker
    (:func:`mjwalk.plan.guide.guide_ahead_at`): the distance to that point plus the rest of
    its segment and the segments after it, summed in order.

    Args:
        lengths: the guide's segment lengths (:func:`guide_lengths`), metres.
        best_k: the segment of the guide's point nearest the walker.
        best_w: the share (0..1) along it of that point.
        best_d2: the squared distance (m^2) from the walker to that point.
    """
    rest = 0.0
    for k in range(best_k, lengths.shape[0]):
        rest += lengths[k] * (1.0 - best_w) if k == best_k else lengths[k]
    return math.sqrt(best_d2) + rest
