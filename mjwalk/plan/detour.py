"""Passing an obstacle in the way: which side people choose and the berth they give it.

When the smooth path between a walk's end poses (:mod:`mjwalk.plan.guide`) runs into an
obstacle, the walk's heading follows a path around it instead: the minimum-jerk path through a
waypoint beside the obstacle (Flash & Hogan's via-point solution), on the side the walker
chooses. Both come from studies of
people walking around obstacles to a visible goal:

- **Side.** People choose between the obstacle's two ends as between two competing waypoints,
  by the local distance d from the walker to each end and its deviation angle β from the goal
  direction, rather than by the whole route's length or curvature (PMC7875474: walkers going
  around a barrier to a visible goal, N = 19 and 15, mixed-effects logistic regression of
  Left/Right choices on Δβ and Δd; the 75 % choice threshold is 1.65 deg for Δβ and 0.75 m for
  Δd, from 50 % at no difference). The logistic model with those two slopes, ln 3 / 1.65 per
  degree and ln 3 / 0.75 per metre, and no side bias, is :func:`left_share` (open space). Where
  a wall or another obstacle stands beside the obstacle, the gap it leaves on that side weighs
  in as well (:mod:`mjwalk.plan.sides`: the critical aperture of Hackney & Cinelli 2013 and
  Warren & Whang 1987). The walker draws its side once per walk, at its start
  (:func:`choose_side`), and the guide keeps it to that side (no late switches).
- **Berth.** People who step around obstacles in their path keep a consistent protective gap
  of about 0.30 m between themselves and the obstacles at the time of crossing
  (doi:10.1080/17470218.2012.730532, Q J Exp Psychol 66, 2013: young adults walking to a goal
  past two obstacles; protective zone 3.80 m along the path, 0.30 m across). The waypoint lies
  that far from the obstacle's surface plus half the walker's shoulder width
  (:data:`mjwalk.anthropometry.SEG` ``shoulder_width``, Drillis & Contini via Winter), i.e. the
  pelvis's distance from the surface.
- **The berth grows with speed and differs between people, and is kept from obstacles beside
  the way too** (:mod:`mjwalk.plan.sides`: :func:`~mjwalk.plan.sides.passing_gap`,
  :func:`~mjwalk.plan.sides.intruding`); the heading round is set from the walk's start.

Every further obstacle the path round runs into is passed on the same side of the line from
start to goal (the side is the walk's, decided once: :func:`pass_on_side`), up to
:data:`MAX_PASSED`; where no such path keeps the body's clearance, or the walker's end is the
obstacle's own neighbourhood (a walk to and from a workbench), no guide is given and the route
search decides. Metres, radians (world
frame, yaw from +x).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.anthropometry import SEG
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.plan.guide import (
    densify,
    first_below,
    guide_is_clear,
    minimum_jerk_guide,
    resample_guide,
    via_points_guide,
)
from mjwalk.plan.sides import (
    PASSING_GAP,
    intruding,
    obstacle_bounds,
    passing_berth,
    side_gap,
    side_log_odds,
)
from mjwalk.world.clearance import ClearanceField, bilinear_at
from mjwalk.world.openings import passing_footprints

__all__ = [
    "MAX_PASSED",
    "PASSING_GAP",
    "SIDE_SLOPE_PER_DEG",
    "SIDE_SLOPE_PER_M",
    "GuideBody",
    "abreast",
    "choose_side",
    "detour_guide",
    "left_log_odds",
    "left_share",
    "obstacle_ends",
    "pass_on_side",
    "walk_guide",
    "walkable",
]

#: Logistic slopes of the side choice (module doc, PMC7875474): per degree of deviation angle
#: difference and per metre of distance difference between the obstacle's two ends.
SIDE_SLOPE_PER_DEG = math.log(3.0) / 1.65
SIDE_SLOPE_PER_M = math.log(3.0) / 0.75
#: The most obstacles one walk's guide passes (:func:`pass_on_side`).
MAX_PASSED = 4
#: Spacing (m) of the points of each side's route the gap is measured along (:func:`choose_side`).
GAP_SPACING = 0.1
#: Directions sampled round each corner of an obstacle for its inflated outline.
_ROUND = 16


def _extremes(footprint, start, goal, inflate: float) -> np.ndarray:
    """The points (4, 2) of the outline of ``footprint`` grown by ``inflate`` metres (its
    corners rounded by :data:`_ROUND` directions; the corners themselves for 0) at the largest
    and smallest angle from the direction ``start`` -> ``goal`` (left positive), and farthest
    left and right of that line."""
    s, g = np.asarray(start, dtype=float)[:2], np.asarray(goal, dtype=float)[:2]
    verts = np.ascontiguousarray(footprint.vertices, dtype=float)
    grow = inflate + float(footprint.radius)
    return _outline_extremes(verts, grow, s[0], s[1], g[0], g[1], _ROUND)


@njit
def _outline_extremes(verts, grow, sx, sy, gx, gy, n_round):
    """:func:`_extremes` compiled: every outline point (each corner plus ``grow`` times the
    unit vector at n_round even angles, or the corner itself for grow <= 0) scored by its
    signed angle atan2(u x r, u . r) and lateral offset u x r from the unit direction u, the
    first of equals kept."""
    dx, dy = gx - sx, gy - sy
    norm = math.hypot(dx, dy)
    ux, uy = dx / norm, dy / norm
    out = np.empty((4, 2))
    best = np.array([-np.inf, np.inf, -np.inf, np.inf])
    rounds = n_round if grow > 0.0 else 1
    step = 2.0 * math.pi / n_round
    for v in range(verts.shape[0]):
        for k in range(rounds):
            if grow > 0.0:
                a = k * step
                px, py = verts[v, 0] + grow * math.cos(a), verts[v, 1] + grow * math.sin(a)
            else:
                px, py = verts[v, 0], verts[v, 1]
            rx, ry = px - sx, py - sy
            lat = ux * ry - uy * rx
            ang = math.atan2(lat, rx * ux + ry * uy)
            for j in range(4):
                value = ang if j < 2 else lat
                if (value > best[j]) if j % 2 == 0 else (value < best[j]):
                    best[j] = value
                    out[j, 0], out[j, 1] = px, py
    return out


def obstacle_ends(footprint, start, goal, inflate: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The obstacle's left and right ends (x, y) as seen from ``start`` looking at ``goal``:
    the points of its outline grown by ``inflate`` metres farthest left and right of the goal
    direction.

    Args:
        footprint: the obstacle's :class:`~mjwalk.world.footprint.Footprint`.
        start: the walker's point (x, y), metres, world frame.
        goal: the goal point (x, y), metres.
        inflate: how far the outline is grown, metres.

    Returns:
        The left end and the right end, (2,) each, metres.
    """
    ext = _extremes(footprint, start, goal, inflate)
    return ext[0], ext[1]


def abreast(footprint, start, goal, inflate: float, left: bool) -> np.ndarray:
    """The point (x, y) of the obstacle's outline grown by ``inflate`` metres farthest to the
    ``left`` (else right) of the line from ``start`` to ``goal``: where a walker passing on
    that side is abreast of it.

    Args:
        footprint: the obstacle's :class:`~mjwalk.world.footprint.Footprint`.
        start: the walker's point (x, y), metres, world frame.
        goal: the goal point (x, y), metres.
        inflate: how far the outline is grown, metres.
        left: the side the walker passes on (True: left of the line).

    Returns:
        (2,) the point, metres.
    """
    return _extremes(footprint, start, goal, inflate)[2 if left else 3]


def left_share(start, goal, left, right) -> float:
    """The probability that a walker from ``start`` to ``goal`` passes an obstacle on its left
    in open space (module doc): the logistic of :func:`left_log_odds`.

    Args:
        start: the walker's point (x, y), metres, world frame.
        goal: the goal point (x, y), metres.
        left: the obstacle's left end (x, y), metres (:func:`obstacle_ends`).
        right: its right end (x, y), metres.

    Returns:
        The probability 1 / (1 + exp(-z)), z = :func:`left_log_odds`.
    """
    return float(1.0 / (1.0 + math.exp(-left_log_odds(start, goal, left, right))))


def left_log_odds(start, goal, left, right) -> float:
    """The log-odds that a walker from ``start`` to ``goal`` passes an obstacle on its left
    in open space (module doc): the logistic model on the differences of deviation angle
    (degrees: how far left, or right, of the goal direction the walker must head to pass the
    end, 0 where it already passes) and distance (metres) between the obstacle's ``right`` and
    ``left`` ends (x, y). An end at a smaller angle and distance draws the walker.

    Args:
        start: the walker's point (x, y), metres, world frame.
        goal: the goal point (x, y), metres.
        left: the obstacle's left end (x, y), metres (:func:`obstacle_ends`).
        right: its right end (x, y), metres.

    Returns:
        z = :data:`SIDE_SLOPE_PER_DEG`·(b_right - b_left) + :data:`SIDE_SLOPE_PER_M`·(d_right -
        d_left).
    """
    sx, sy = (float(v) for v in np.asarray(start, dtype=float)[:2])
    gx, gy = (float(v) for v in np.asarray(goal, dtype=float)[:2])
    norm = math.hypot(gx - sx, gy - sy)
    ux, uy = (gx - sx) / norm, (gy - sy) / norm

    def angle_and_distance(end) -> tuple[float, float]:
        rx, ry = float(end[0]) - sx, float(end[1]) - sy
        return math.degrees(math.atan2(ux * ry - uy * rx, rx * ux + ry * uy)), math.hypot(rx, ry)

    (a_left, d_left), (a_right, d_right) = angle_and_distance(left), angle_and_distance(right)
    # how far the walker must turn from the goal direction to pass each end (0: already clear)
    b_left, b_right = max(0.0, a_left), max(0.0, -a_right)
    return SIDE_SLOPE_PER_DEG * (b_right - b_left) + SIDE_SLOPE_PER_M * (d_right - d_left)


def _blocking(workplace, path: np.ndarray, radius: float):
    """The obstacle footprint the path ``path`` (k, 2) first comes within ``radius`` of, or
    None (clear, or first short of it at the floor's edge)."""
    p = first_below(workplace, path, radius)  # sampled every 5 cm
    footprints = passing_footprints(workplace)  # a level's openings too (issue 47)
    if p is None or not footprints:
        return None
    bounds = obstacle_bounds(workplace)
    near = np.flatnonzero(
        (bounds[:, 0] - radius <= p[0])
        & (p[0] <= bounds[:, 2] + radius)
        & (bounds[:, 1] - radius <= p[1])
        & (p[1] <= bounds[:, 3] + radius)
    )  # only footprints whose box, grown by the radius, holds the point can be that near
    if len(near) == 0:
        return None
    field = workplace.clearance
    if isinstance(field, ClearanceField):
        # the lookup that found the point: the obstacles' clearance there is the floor's
        # edge's doing where it is enough
        room = bilinear_at(field.values, field.x0, field.y0, field.resolution, p[0], p[1])
        if room >= radius:
            return None
        if len(near) == 1:
            return footprints[int(near[0])]
    dist = [float(footprints[k].signed_distance(p[None])[0]) for k in near]
    if min(dist) >= radius:  # the floor's edge, not an obstacle
        return None
    return footprints[int(near[int(np.argmin(dist))])]


@dataclass(frozen=True)
class GuideBody:
    """The walker a guide is drawn for: the clearance it keeps and the figures it walks with.

    Attributes:
        radius: the body's clearance from obstacles, metres (the planner's body radius).
        stature: the walker's body height, metres (its shoulder width sets the berth).
        step_length: the walker's step length, metres (the sharpest turn a guide may make,
            :func:`walkable`; 0: any).
        speed: the walker's pace on this walk, m/s (its berth,
            :func:`~mjwalk.plan.sides.passing_gap`; 0: the reference pace's).
    """

    radius: float
    stature: float = DEFAULT_STATURE
    step_length: float = 0.0
    speed: float = 0.0


def detour_guide(
    workplace,
    direct,
    start,
    goal,
    start_heading: float | None,
    goal_heading: float | None,
    body: GuideBody,
    rng: np.random.Generator,
) -> np.ndarray | None:
    """The path a walk's heading follows past the obstacles ``direct`` runs into.

    The path goes from ``start`` to ``goal`` past the first obstacle the path ``direct`` runs
    into (module doc), or else the first it passes nearer than the walker's berth
    (:func:`~mjwalk.plan.sides.intruding`), on a side drawn once with ``rng``
    (:func:`choose_side`: the ends' angles and distances and the gap each side leaves),
    through a waypoint abreast of it (:func:`abreast`) at the walker's berth
    (:func:`~mjwalk.plan.sides.passing_berth` of ``body.stature`` at ``body.speed``), and past
    every further obstacle that path runs into on the
    same side of the line ``start`` -> ``goal`` (:func:`pass_on_side`).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        direct: (k, 2) the path to check, metres: the minimum-jerk path between the two poses,
            or the caller's own.
        start: the walk's start (x, y), metres, world frame.
        goal: the walk's goal (x, y), metres, world frame.
        start_heading: the heading (radians, from +x CCW) the walker sets off along; None: free.
        goal_heading: the heading (radians) the walker arrives along; None: free.
        body: the walker's clearance radius, stature and step length.
        rng: the random stream the side is drawn from (one draw when an obstacle blocks).

    Returns:
        The (k, 2) path round the obstacles (metres), or None when the direct path is clear
        and passes no obstacle within the berth, when no obstacle blocks it (the floor's edge
        does), or when no path round on the drawn side keeps ``body.radius`` from every
        obstacle and turns no sharper than steps of
        ``body.step_length`` can (:func:`walkable`); then the route search decides.
    """
    s, g = np.asarray(start, dtype=float)[:2], np.asarray(goal, dtype=float)[:2]
    if not np.hypot(*(g - s)) > 1e-6:
        return None
    blocker = _blocking(workplace, np.asarray(direct, dtype=float), body.radius)
    if blocker is None:  # none in the way: one passed within the berth, if any
        blocker = intruding(workplace, direct, (s, g), passing_berth(body.stature, body.speed))
    if blocker is None:
        return None
    headings = (start_heading, goal_heading)
    go_left = choose_side(workplace, blocker, (s, g), body, rng)
    return pass_on_side(workplace, blocker, (s, g), headings, body, go_left)


def choose_side(workplace, blocker, ends, body: GuideBody, rng) -> bool:
    """Draw the side a walker passes ``blocker`` on, once, at the walk's start: the logistic
    of :func:`mjwalk.plan.sides.side_log_odds`, the open-space log-odds of the obstacle's two
    ends (:func:`left_log_odds`) with the gap each side's route leaves beside it
    (:func:`mjwalk.plan.sides.side_gap`: walls and other obstacles), the route being the
    straight legs through the waypoint at the cited berth on that side (beside the obstacle
    the minimum-jerk path runs within a few centimetres of them).

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        blocker: the obstacle's :class:`~mjwalk.world.footprint.Footprint`.
        ends: the walk's start and goal, (2,) each, metres, world frame.
        body: the walker (its stature sets shoulder width and berth).
        rng: the random stream (one draw).

    Returns:
        Whether the walker passes on the left of the line start -> goal.
    """
    s, g = ends
    shoulder = SEG["shoulder_width"] * body.stature
    berth = passing_berth(body.stature, body.speed)
    gaps = []
    for left in (True, False):  # the route: straight legs through the waypoint, densified
        route = densify(np.array([s, abreast(blocker, s, g, berth, left), g]), GAP_SPACING)
        gaps.append(side_gap(workplace, blocker, route, s, g))
    z = side_log_odds(
        left_log_odds(s, g, *obstacle_ends(blocker, s, g)), gaps[0], gaps[1], shoulder
    )
    share = 1.0 / (1.0 + math.exp(-z)) if z > -700.0 else 0.0
    return bool(rng.random() < share)


def pass_on_side(workplace, first, ends, headings, body: GuideBody, left: bool):
    """The smooth path from the walk's start past ``first`` and every further obstacle that
    path runs into (up to :data:`MAX_PASSED` in all), each on the ``left`` (else right) of
    the line start -> goal: through waypoints abreast of each (:func:`abreast`, in order along
    the line; :func:`~mjwalk.plan.guide.via_points_guide`) at the walker's berth
    (:func:`~mjwalk.plan.sides.passing_berth`), or at ``body.radius`` plus 5 cm from an
    obstacle where the berth does not fit, or from all where the path turns too sharply.

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        first: the first obstacle in the way (:class:`~mjwalk.world.footprint.Footprint`).
        ends: the walk's start and goal, (2,) each, metres, world frame.
        headings: the start and goal headings (radians from +x CCW; None: free).
        body: the walker's clearance radius, stature and step length.
        left: the side chosen (:func:`choose_side`).

    Returns:
        (k, 2) the path (metres), or None where none keeps ``body.radius`` from every
        obstacle and the floor's edge and is :func:`walkable`.
    """
    s, g = ends
    u = (g - s) / float(np.hypot(*(g - s)))
    tight = body.radius + 0.05
    passed: list = []
    gaps: list[float] = []
    blocker = first
    while True:
        # in the way again, or the path meets the neighbour that forms the gap beside it
        # (their extents along the line overlap): the cited berth does not fit there
        hit = [i for i, fp in enumerate(passed) if _overlap(fp, blocker, s, u)]
        if hit:
            if all(gaps[i] <= tight for i in hit):
                return None
            for i in hit:
                gaps[i] = tight
        elif blocker is not None:
            if len(passed) == MAX_PASSED:
                return None
            passed.append(blocker)
            gaps.append(passing_berth(body.stature, body.speed))
        ways = np.array(
            [abreast(fp, s, g, gap, left) for fp, gap in zip(passed, gaps, strict=True)]
        )
        ways = ways[np.argsort((ways - s) @ u, kind="stable")]
        if np.hypot(*(ways - s).T).min() < 1e-6 or np.hypot(*(ways - g).T).min() < 1e-6:
            return None
        try:
            path = via_points_guide(s, ways, g, *headings)
        except ValueError:
            return None
        blocker = _blocking(workplace, path, body.radius)
        if blocker is not None:
            continue
        if walkable(path, body.step_length) and guide_is_clear(workplace, path, body.radius):
            return path
        if max(gaps) <= tight:
            return None
        gaps = [tight] * len(gaps)  # the floor's edge or too sharp a turn: the body's berth


def _overlap(passed, blocker, s: np.ndarray, u: np.ndarray) -> bool:
    """Whether ``blocker`` is the obstacle ``passed`` itself or one whose extent along the
    unit direction ``u`` from ``s`` overlaps that of ``passed`` (beside it: the two form a
    gap); False for None."""
    if blocker is None:
        return False
    if blocker is passed:
        return True

    def extent(fp) -> tuple[float, float]:
        along = (np.asarray(fp.vertices, dtype=float) - s) @ u
        return float(along.min()) - fp.radius, float(along.max()) + fp.radius

    (a0, a1), (b0, b1) = extent(passed), extent(blocker)
    return a0 <= b1 and b0 <= a1


def walkable(path: np.ndarray, step_length: float) -> bool:
    """Whether ``path`` (k, 2, metres) turns no sharper than a quarter turn per step of
    ``step_length`` metres (a radius of curvature of at least step_length / (pi / 2)): the
    sharpest turn the step model's walking steps make (no planned step turns the pelvis by
    90 deg or more: tests/plan/test_hybrid.py). A path sharper than that cannot be walked
    along, only turned on: the search would fight it.

    Args:
        path: (k, 2) the path, metres.
        step_length: the walker's step length, metres (<= 0: any path is walkable).

    Returns:
        Whether |x'y'' - y'x''|·step_length <= (pi / 2)·|p'|^3 at every point.
    """
    if step_length <= 0.0:
        return True
    return bool(_walkable(np.ascontiguousarray(path, dtype=float), float(step_length)))


@njit
def _gradient(f):
    """np.gradient of ``f`` (k >= 2, 2) along its rows, unit spacing: central differences
    inside, one-sided at the ends."""
    k = f.shape[0]
    out = np.empty_like(f)
    for a in range(2):
        out[0, a] = f[1, a] - f[0, a]
        out[k - 1, a] = f[k - 1, a] - f[k - 2, a]
        for i in range(1, k - 1):
            out[i, a] = (f[i + 1, a] - f[i - 1, a]) / 2.0
    return out


@njit
def _walkable(path, step_length):
    """:func:`walkable`'s test: |x'y'' - y'x''| · step_length <= (pi / 2)·|p'|^3 at every
    point (the curvature from np.gradient's differences)."""
    d = _gradient(path)
    dd = _gradient(d)
    for i in range(path.shape[0]):
        speed = max(math.hypot(d[i, 0], d[i, 1]), 1e-12)
        bend = abs(d[i, 0] * dd[i, 1] - d[i, 1] * dd[i, 0])
        if not bend * step_length <= (math.pi / 2) * speed**3:
            return False
    return True


def walk_guide(
    workplace,
    start,
    goal,
    walking_yaw: float | None,
    goal_heading: float | None,
    guide,
    body: GuideBody,
    rng: np.random.Generator,
) -> np.ndarray | None:
    """The path a walk's heading follows from ``start`` to ``goal``.

    The caller's ``guide``, or for a walker already walking along ``walking_yaw`` or meaning to
    arrive along ``goal_heading`` the minimum-jerk path between the end poses, or else the
    straight line; where that runs into an obstacle, the way past it on a side drawn from
    ``rng`` (:func:`detour_guide`), else itself. The straight line too is a guide (issue 48):
    the search's steps are drawn back onto it (:data:`~mjwalk.plan.guide.PURSUIT_AHEAD`), so a
    straight walk in an empty hall keeps to its chord rather than drifting with its samples.

    Args:
        workplace: the scene (:class:`~mjwalk.world.workplace.Workplace`).
        start: the walk's start (x, y), metres, world frame.
        goal: the walk's goal (x, y), metres, world frame.
        walking_yaw: the heading (radians, from +x CCW) of a walker already walking; None: one
            setting off from a stand.
        goal_heading: the heading (radians) the walker means to arrive along; None: free.
        guide: the caller's (k, 2) path (metres) to follow, or None.
        body: the walker's clearance radius, stature and step length (:class:`GuideBody`).
        rng: the random stream of the detour's side (:func:`detour_guide`).

    Returns:
        The (:data:`~mjwalk.plan.guide.GUIDE_POINTS`, 2) path (metres), or None when start
        and goal coincide.
    """
    s, g = np.asarray(start, dtype=float)[:2], np.asarray(goal, dtype=float)[:2]
    if not np.hypot(*(g - s)) >= 1e-6:
        return None  # no walk (the search refuses it)
    direct = guide
    if direct is None and (walking_yaw is not None or goal_heading is not None):
        direct = minimum_jerk_guide(s, g, walking_yaw, goal_heading)
    way = np.array([s, g]) if direct is None else direct
    path = detour_guide(workplace, way, s, g, walking_yaw, goal_heading, body, rng)
    if path is None:
        path = way
    return resample_guide(path)
