"""Which side of an obstacle a walker passes: the room each side leaves, and the way's length.

People passing an obstacle in their way choose between its two ends as between two competing
waypoints, by each end's distance and deviation angle from the goal direction (PMC7875474:
:func:`mjwalk.plan.detour.left_share`). That is the choice in open space. Beside an obstacle
there may be a wall or another obstacle, and the gap between them is an aperture the walker
must fit through. The aperture studies give when people do:

- **Critical aperture.** Walking in open space towards a goal, young adults walked *round*
  two obstacles whose gap was narrower than 1.4 times their shoulder width (the critical
  point), and through it when it was wider (Hackney & Cinelli, Q J Exp Psychol 66:1104-1112,
  2013, doi:10.1080/17470218.2012.730532; N = 12, apertures 0.6-1.8 shoulder widths). The
  same study's protective zone, 0.30 m, is the berth (:data:`mjwalk.plan.detour.PASSING_GAP`).
- **Its spread.** In a confined space (a doorway) the point where people start to rotate
  their shoulders is 1.3 shoulder widths (Warren & Whang, J Exp Psychol Hum Percept Perform
  13:371-383, 1987): the same body-scaled decision, 0.1 shoulder widths lower. mjwalk takes
  that difference as the spread of the decision: a gap of 1.3 shoulder widths is taken by a
  quarter of walkers who would take a wide one, 1.4 by half, 1.5 by three quarters
  (:func:`gap_log_weight`, a logistic in the gap over the shoulder width).

A side's **gap** is the narrowest free width along its route while the walker is abreast of
the obstacle (:func:`side_gap`): at each point of the route, its distance from the obstacle
plus its distance from the nearest *other* obstacle or the floor's edge (for a point between
the two, the width of the passage there). The walker's choice multiplies the open-space odds
of passing on the left (:func:`mjwalk.plan.detour.left_log_odds`) by the ratio of the two
sides' gap weights (:func:`side_log_odds`): at equal lengths a side as narrow as the critical
aperture against a wide one is taken by one walker in three, one at 1.3 shoulder widths by
one in four and narrower ones almost never; two sides both wider than about 2 shoulder widths
(0.9 m for a 1.75 m walker) leave the lengths to decide. Metres, world frame.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "CONFINED_APERTURE",
    "CRITICAL_APERTURE",
    "GAP_OPEN",
    "gap_log_weight",
    "side_gap",
    "side_log_odds",
]

#: Gap (in shoulder widths) below which people walk round rather than through (module doc:
#: Hackney & Cinelli 2013, open space): half of walkers take it.
CRITICAL_APERTURE = 1.4
#: Gap (in shoulder widths) where people start to turn their shoulders in a doorway (Warren &
#: Whang 1987): the 25 % point of the gap's weight (module doc).
CONFINED_APERTURE = 1.3
#: Gaps are looked for this far (m) from the obstacle: wider is open space for any walker
#: (the weight of a gap 1.5 m wide is 1 - 1e-30 for a 0.45 m shoulder width).
GAP_OPEN = 1.5
_SLOPE = math.log(3.0) / (CRITICAL_APERTURE - CONFINED_APERTURE)  # per shoulder width


def gap_log_weight(gap: float, shoulder: float) -> float:
    """The log of the share of walkers who take a gap of ``gap`` metres (module doc): the
    logistic in gap / shoulder with its 50 % point at :data:`CRITICAL_APERTURE` and its 25 %
    point at :data:`CONFINED_APERTURE`.

    Args:
        gap: the gap's free width, metres (:func:`side_gap`).
        shoulder: the walker's shoulder width, metres.

    Returns:
        log(1 / (1 + exp(-x))), x = ln 3 · (gap / shoulder - 1.4) / 0.1 (<= 0).
    """
    x = _SLOPE * (gap / shoulder - CRITICAL_APERTURE)
    return -math.log1p(math.exp(-x)) if x > -30.0 else x  # log-sigmoid, without overflow


def side_log_odds(
    length_log_odds: float, gap_left: float, gap_right: float, shoulder: float
) -> float:
    """The log-odds of passing an obstacle on the left (module doc): the open-space log-odds
    of the two ends' angles and distances plus the log-ratio of the two sides' gap weights.

    Args:
        length_log_odds: the open-space log-odds of the left side
            (:func:`mjwalk.plan.detour.left_log_odds`).
        gap_left: the narrowest gap along the left route, metres (:func:`side_gap`).
        gap_right: the narrowest gap along the right route, metres.
        shoulder: the walker's shoulder width, metres.

    Returns:
        length_log_odds + :func:`gap_log_weight` (left) - :func:`gap_log_weight` (right).
    """
    return (
        length_log_odds + gap_log_weight(gap_left, shoulder) - gap_log_weight(gap_right, shoulder)
    )


def side_gap(workplace, blocker, route, start, goal) -> float:
    """The narrowest free width (m) along ``route`` while it is abreast of ``blocker`` (module
    doc): over the route's points whose projection on the line ``start`` -> ``goal`` lies within
    the obstacle's own extent along it (all points if none does), the least of the distance
    from the obstacle plus the distance from the nearest other obstacle or floor edge, at
    most the distance from the obstacle plus :data:`GAP_OPEN`.

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        blocker: the obstacle's :class:`~mjwalk.world.footprint.Footprint`.
        route: (k, 2) the way round the obstacle on one side, metres, world frame.
        start: the walk's start (x, y), metres.
        goal: the walk's goal (x, y), metres.

    Returns:
        The gap, metres.
    """
    pts = np.asarray(route, dtype=float)
    s, g = np.asarray(start, dtype=float)[:2], np.asarray(goal, dtype=float)[:2]
    u = (g - s) / max(float(np.hypot(*(g - s))), 1e-12)
    along = (pts - s) @ u
    outline = np.asarray(blocker.vertices, dtype=float)
    reach = float(blocker.radius)
    lo, hi = float(((outline - s) @ u).min()) - reach, float(((outline - s) @ u).max()) + reach
    beside = pts[(along >= lo) & (along <= hi)]
    if len(beside) == 0:
        beside = pts
    own = blocker.signed_distance(beside)
    xmin, ymin, xmax, ymax = (float(v) for v in workplace.floor_bounds)
    other = np.minimum.reduce(
        [beside[:, 0] - xmin, xmax - beside[:, 0], beside[:, 1] - ymin, ymax - beside[:, 1]]
    )
    other = np.minimum(other, GAP_OPEN)
    x0, y0 = beside.min(axis=0) - GAP_OPEN
    x1, y1 = beside.max(axis=0) + GAP_OPEN
    for fp in workplace.obstacles:
        if fp is blocker:
            continue
        bx0, by0, bx1, by1 = fp.bounds()
        if bx1 < x0 or bx0 > x1 or by1 < y0 or by0 > y1:
            continue  # too far from the route to narrow it
        other = np.minimum(other, fp.signed_distance(beside))
    return float(np.min(own + other))  # negative depth inside another obstacle narrows it
