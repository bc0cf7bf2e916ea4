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
  same study's protective zone, 0.30 m, is the berth (:data:`PASSING_GAP`).
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
(0.9 m for a 1.75 m walker) leave the lengths to decide.

The distance a walker passes an obstacle at, its **berth**, is half its shoulder width plus
the protective gap (:data:`PASSING_GAP`: Hackney & Cinelli 2013, 0.30 m):

- **The berth grows with speed and differs between people** (:func:`passing_gap`). The space a
  walker claims grows with its speed: in single file, the distance people keep is 0.36 m plus
  1.06 s times their speed (Seyfried, Steffen, Klingsch & Boltes, J Stat Mech P10002, 2005;
  Weidmann's 1993 fundamental diagram has the same form), and pedestrians bypassing an
  obstacle at high speed keep more room from it than at normal speed (Experimental study on
  pedestrians' collision avoidance, IEEE 2014, qualitative). mjwalk scales the 0.30 m gap,
  measured at a comfortable pace (:data:`~mjwalk.gait.walker.REFERENCE_SPEED`, 1.37 m/s), by
  that space's ratio at the walker's speed to the reference's: 0.24 m at 1.0 m/s, 0.34 m at
  1.6 m/s. Taking the single-file relation sideways is mjwalk's assumption, and the studies
  disagree: Gérin-Lajoie, Richards, Fung & McFadyen (Gait Posture 27:239-247, 2008, N = 10)
  found the personal space kept round a cylinder of one size at slow, natural and fast
  speeds; the growth taken here is the larger of the two estimates. The berth differs
  between people through their speed (each walk's own pace, Bohannon & Andrews 2011's
  spread) and their shoulder width (their stature); no further draw: the cited studies give
  means only; no published between-person spread of the berth itself was found
  (``docs/decisions/109-planner-berth-spread.md`` lists the search).
- **An obstacle passed within the berth is passed at it** (:func:`intruding`): people keep
  that room from obstacles beside their way, not only from those they would hit, so a
  guide that passes a compact obstacle (one whose extent along the walk lies within it: not
  a wall the walk runs along, nor the obstacle a walk starts or ends beside) nearer than the
  walker's berth becomes the path through the waypoint at the berth, as for one in the way.
  That path, like every detour, is the minimum-jerk path over the whole walk (the via-point
  solution), so its heading is set from the walk's start, well before the obstacle: people
  start avoiding an obstacle 2-3 steps ahead (Vallis & McFadyen, Exp Brain Res 152:409-414,
  2003) and within a protective zone that reaches 3.80 m ahead along the path (Hackney &
  Cinelli 2013, above). Where the path at the berth is not walkable or not clear, the walk
  keeps its own guide (it keeps the body's clearance).

Metres, seconds, world frame.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.anthropometry import SEG
from mjwalk.gait.walker import REFERENCE_SPEED
from mjwalk.plan.guide import densify, first_below
from mjwalk.plan.nearcut import gap_room, intruding_candidates, pack
from mjwalk.world.openings import passing_footprints

__all__ = [
    "CONFINED_APERTURE",
    "CRITICAL_APERTURE",
    "GAP_OPEN",
    "PASSING_GAP",
    "SPACE_BODY",
    "SPACE_TIME",
    "gap_log_weight",
    "intruding",
    "passing_berth",
    "passing_gap",
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
#: Gap (m) people keep between themselves and an obstacle they walk round at a comfortable
#: pace, :data:`~mjwalk.gait.walker.REFERENCE_SPEED` (module doc).
PASSING_GAP = 0.30
#: The space a walker claims at speed v is SPACE_BODY + SPACE_TIME·v (metres; v in m/s):
#: Seyfried et al. 2005's single-file distance (module doc).
SPACE_BODY = 0.36
SPACE_TIME = 1.06
#: Spacing (m) of the points a path is checked at for obstacles within the berth.
BERTH_SPACING = 0.1
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


def obstacle_bounds(workplace) -> np.ndarray:
    """The bounding boxes of the scene's obstacle footprints, one row each (kept on the
    workplace: the side choice asks for them once per obstacle per walk, and building them
    anew took 40 % of a walk's planning on a 144-box hall, ``benchmarks/bench_scale.py``).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).

    Returns:
        (n, 4) each footprint's (xmin, ymin, xmax, ymax), metres, in the order of
        :func:`~mjwalk.world.openings.passing_footprints` (the obstacles', then the level's
        openings).
    """
    footprints = passing_footprints(workplace)
    bounds = workplace.__dict__.get("_footprint_bounds")
    if bounds is None or len(bounds) != len(footprints):
        bounds = np.array([fp.bounds() for fp in footprints]).reshape(-1, 4)
        workplace.__dict__["_footprint_bounds"] = bounds
    return bounds


def boxes_meeting(workplace, box) -> np.ndarray:
    """The indices of the obstacles (and the level's openings) whose bounding box meets ``box``
    (edges included), in :func:`~mjwalk.world.openings.passing_footprints`' order.

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        box: (xmin, ymin, xmax, ymax), metres.

    Returns:
        The obstacles' indices, ascending.
    """
    b = obstacle_bounds(workplace)
    x0, y0, x1, y1 = (float(v) for v in box)
    return np.flatnonzero((b[:, 2] >= x0) & (b[:, 0] <= x1) & (b[:, 3] >= y0) & (b[:, 1] <= y1))


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
    extent = (np.asarray(blocker.vertices, dtype=float) - s) @ u
    reach = float(blocker.radius)
    lo, hi = float(extent.min()) - reach, float(extent.max()) + reach
    beside = pts[(along >= lo) & (along <= hi)]
    if len(beside) == 0:
        beside = pts
    own = blocker.signed_distance(beside)
    footprints = passing_footprints(workplace)  # a level's openings too (issue 47)
    # the floor's edges and the obstacles within GAP_OPEN that may narrow it, the polygons'
    # distances in one compiled pass (nearcut.gap_room: exact; none: the floor's alone)
    pk = pack(workplace)
    passed = np.zeros(len(footprints), dtype=np.bool_)
    passed[pk.rows.get(id(blocker), [])] = True
    floor = np.asarray(workplace.floor_bounds, dtype=float)
    other, rounded = gap_room(
        np.ascontiguousarray(beside), floor, pk.bounds, pk.vertices, pk.first, pk.count,
        pk.radius, passed, GAP_OPEN,
    )  # fmt: skip
    for k in rounded:  # rounded segments: their own (NumPy) distance
        other = np.minimum(other, footprints[k].signed_distance(beside))
    return float(np.min(own + other))  # negative depth inside another obstacle narrows it


def passing_gap(speed: float) -> float:
    """The gap (m) a walker at ``speed`` keeps from an obstacle it passes (module doc):
    :data:`PASSING_GAP` times the ratio of the space claimed at that speed to the space
    claimed at :data:`~mjwalk.gait.walker.REFERENCE_SPEED` (:data:`SPACE_BODY` +
    :data:`SPACE_TIME`·v).

    Args:
        speed: the walking speed, m/s (<= 0 or not finite: the reference speed).

    Returns:
        The gap, metres (0.30 at 1.37 m/s).
    """
    v = speed if math.isfinite(speed) and speed > 0.0 else REFERENCE_SPEED
    return PASSING_GAP * (SPACE_BODY + SPACE_TIME * v) / (SPACE_BODY + SPACE_TIME * REFERENCE_SPEED)


def passing_berth(stature: float, speed: float) -> float:
    """The distance (m) from an obstacle's surface at which a walker passes it: half its
    shoulder width plus :func:`passing_gap` at its speed.

    Args:
        stature: the walker's body height, metres (its shoulder width).
        speed: the walker's speed, m/s (:func:`passing_gap`).

    Returns:
        The berth, metres (the pelvis's distance from the surface).
    """
    return 0.5 * SEG["shoulder_width"] * stature + passing_gap(speed)


def intruding(workplace, path, ends, berth: float):
    """The first obstacle along ``path`` that it passes nearer than ``berth`` metres and that
    the walk passes by (module doc): a footprint whose extent along the line start -> goal
    lies within the walk's (berth included) and that neither end stands within the berth of.
    Only the obstacles whose bounds leave the answer open are asked for their distances
    (:func:`mjwalk.plan.nearcut.intruding_candidates`: the same answer as asking all).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        path: (k >= 2, 2) the path, metres, world frame.
        ends: the walk's start and goal, (2,) each, metres.
        berth: the distance kept, metres (:func:`passing_berth`).

    Returns:
        The footprint, or None (none intrudes, or the path comes that near only walls,
        floor edges and the ends' own obstacles).
    """
    pts = np.asarray(path, dtype=float)
    footprints = passing_footprints(workplace)  # a level's openings too (issue 47)
    if not footprints or first_below(workplace, pts, berth) is None:
        return None  # nothing within the berth anywhere: the one compiled pass
    s, g = (np.asarray(v, dtype=float)[:2] for v in ends)
    length = float(np.hypot(*(g - s)))
    u = (g - s) / length
    dense = densify(pts, BERTH_SPACING)
    both = np.stack([s, g])
    pk = pack(workplace)
    best, first = None, len(dense)
    for k, along_open, ends_open in intruding_candidates(pk, dense, both, length, u, berth):
        fp = footprints[k]
        if along_open:
            along = (np.asarray(fp.vertices, dtype=float) - s) @ u
            if along.min() - fp.radius < -berth or along.max() + fp.radius > length + berth:
                continue  # not passed by: a wall the walk runs along, or behind an end
        if ends_open and float(fp.signed_distance(both).min()) < berth:
            continue  # an end's own obstacle (a walk to or from a bench)
        # only points before the best so far can take its place (distances are per point)
        near = np.flatnonzero(fp.signed_distance(dense[:first]) < berth)
        if len(near):
            best, first = fp, int(near[0])
    return best
