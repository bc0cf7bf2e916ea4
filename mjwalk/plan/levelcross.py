"""A walker's walk over one crossing between levels (:class:`~mjwalk.plan.levelroute.Crossing`):
its footfalls, their timing and the 120 Hz pelvis path, as a :class:`~mjwalk.plan.walkpath.
WalkPath` the level planner stitches between its level walks.

- **Stairs and steps**: one tread per step (step-over-step): a level step from the stance to
  half a tread before the first riser, then the feet land centred on the treads in turn
  (:func:`tread_setback`; the last riser's step half a tread onto the upper level), then one
  level step and a closing step bring the walker to stand a body clearance beyond the edge;
  down, the same in reverse. A step that climbs or descends a riser takes the stair gait's
  time for that riser and tread (:func:`mjwalk.gait.stairs.stair_gait`: cadence from the
  reference adult's, scaled by the walker's pace); a step on the level takes the walker's level
  step time.
- **Ramps**: equal steps from the stance before the foot to the stance after the head, each no
  longer than the ramp gait's step (:func:`mjwalk.gait.slope.slope_gait`, up or down the slope)
  and timed by it, the heights along the ramp's plane.

A walker who stands where the crossing's walk begins facing more than :data:`ENTRY_TURN` away
from its axis turns on the spot first, in steps of at most that (:func:`spot_turn`); a level
walk that arrives so turns into it while walking where it fits (:mod:`mjwalk.plan.turnin`).

Feet stand the walker's step width apart across the axis (left foot left of the walking
direction). The pelvis moves at even speed between the double-support instants, at the middle of
the two feet, and its height (:attr:`WalkPath.z`) is the mean height of the surfaces under the
two feet, eased (smoothstep) through each step, so it climbs with the stair's pitch line rather
than jumping at each riser. Heights are given above the floor. Metres, seconds, radians.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.slope import slope_gait
from mjwalk.gait.stairs import MIN_TREAD, StairGeometry, stair_gait
from mjwalk.gait.walker import Walker
from mjwalk.plan.footfallwalk import footfall_walk
from mjwalk.plan.levelmemo import kept
from mjwalk.plan.levelroute import Crossing
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.turnin import turned_steps
from mjwalk.plan.turnsplit import WALKING_TURN_MAX, wrap
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.world.norms import DESCENT_LOW_CLEARANCE, STAIR_TOE_CLEARANCE

#: How far (m) a walker standing before a crossing (no step brought it there) may stand from
#: the crossing's stance and start on it from where it stands: a grid cell of the planner's
#: occupancy grid (:data:`mjwalk.plan.occupancy.CELL_SIZE`, 0.05 m), the resolution the stance
#: itself is found at. Farther off, the walker steps to the stance first, one foot and then the
#: other (as the level planner's legs, which end within their goal area of the stance, are too
#: short to walk there).
STANCE_SLACK = 0.05
#: Lateral distance between the feet's centres when the walker gives none, metres: 0.12 m, within
#: the 0.08-0.13 m step widths adults walk with (Perry & Burnfield, "Gait Analysis", 2nd ed.
#: 2010, ch. 1, as quoted in gait texts; NOT verified here).
DEFAULT_STEP_WIDTH = 0.12


def _footfalls(c: Crossing, direction: str, walker: Walker) -> tuple[np.ndarray, np.ndarray]:
    """Positions along the axis (m) and step times (s) of the footfalls, the closing one last
    (kept on the crossing per direction and walker, read-only: :func:`mjwalk.plan.levelmemo.
    kept`)."""
    return kept(c, "_footfalls", (direction, walker), lambda: _steps(c, direction, walker))


def _steps(c: Crossing, direction: str, walker: Walker) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_footfalls` without its cache."""
    if c.kind == "ramp":
        angle = c.slope if direction == "up" else -c.slope
        gait = slope_gait(walker, angle)
        length = c.exit - c.approach
        k = max(1, math.ceil(length / (gait.step_length * math.cos(c.slope)) - 1e-9))
        s = c.approach + length * np.arange(1, k + 1) / k
        if direction == "down":
            s = c.exit - (s - c.approach)
        s = np.append(s, s[-1])
        return s, np.full(len(s), gait.step_time)
    # every footfall of the track: the one half a tread before the first riser (descending: past
    # the last) too, so that no step spans the stance's clearance and two treads at once
    if direction == "up":
        s = np.concatenate([c.track, _run(c.track[-1], c.exit, walker), [c.exit]])
        start = c.approach
    else:
        s = np.concatenate([c.track[::-1], _run(c.track[0], c.approach, walker), [c.approach]])
        start = c.exit
    z = c.height_at(s)
    geometry = StairGeometry(max(c.risers), max(c.tread, MIN_TREAD))
    climb = stair_gait(walker, geometry, "up" if direction == "up" else "down").step_time
    before = np.concatenate([[c.height_at(start)], z[:-1]])
    times = np.where(np.abs(z - before) > 1e-6, climb, walker.step_duration)
    return s, times


def flight_start(c: Crossing, direction: str, walker: Walker) -> np.ndarray:
    """Where a crossing's first footfall lies on its walking line, as :func:`cross_walk`
    places it (:func:`tread_setback`): where a walk into it lines up.

    Args:
        c: the crossing.
        direction: "up" or "down".
        walker: the walker (stature, step length; a ramp's gait).

    Returns:
        (2,) world xy, metres (kept on the crossing, read-only).
    """

    def make() -> np.ndarray:
        s = _footfalls(c, direction, walker)[0][:1]
        back = tread_setback(c, s, walker.stature, direction)[0]
        return c.point(float(s[0]) - (back if direction == "up" else -back))

    return kept(c, "_flight_start", (direction, walker), make)


def _run(a: float, b: float, walker: Walker) -> np.ndarray:
    """Level footfalls from ``a`` (not included) to ``b`` along the axis, evenly spaced, none
    farther apart than the walker's step length: ``[b]`` for a stance within a step of the
    flight (:func:`departure`'s stance farther off: two or more)."""
    n = max(1, math.ceil(abs(b - a) / walker.step_length - 1e-9))
    return np.append(a + (b - a) * np.arange(1, n) / n, b)


#: Least gap (m) between a foot standing on a level next to a flight and the riser face its toes
#: (before the first riser going up) or its heel (past the last riser going down) turn to: the
#: least foot clearance over a stair edge, 3 cm after Hamel et al. 2005, that the legs' swing
#: keeps too (:data:`mjwalk.world.norms.STAIR_TOE_CLEARANCE`). A foot centred on half a tread's
#: depth (0.14 m) is longer than it and stood 7 mm off the riser (1.75 m walker), closer than
#: its toes reach forward of the flat foot at a heel strike (the ankle's height turned about
#: the heel, about 1.5 cm measured): the toes then touched the first riser (the multi-level
#: station's stair, run 0 of its cycle) and, going down, the heel the bottom riser.
RISER_GAP = STAIR_TOE_CLEARANCE

#: Least gap (m) between a foot on a tread and the riser face it turns to (the riser ahead of its
#: toes going up, behind its heel going down) for the foot to stand centred on its tread: the
#: clearance under which stair-descent studies count a foot's clearance as low
#: (:data:`mjwalk.world.norms.DESCENT_LOW_CLEARANCE`, 5 mm, Hamel et al. 2005, Foster et al.
#: 2014). A foot longer than the tread less twice this gap (0.27 m on a 0.28 m tread: statures
#: over about 1.78 m; :func:`mjwalk.anthropometry.leg_geometry`) does not fit and hangs over
#: the nosing it turns away from: going up, its toes keep this gap off the riser ahead and the
#: heel hangs back over the nosing (the ball of the foot on the tread); going down, its heel
#: keeps :data:`RISER_GAP` off the riser behind and the toes hang over the nosing ahead, since
#: the landing foot, pitched toes down, lowers its heel past the upper tread's nosing (a swing
#: crosses that edge; the ascent's toes cross none in stance). Centred, a 1.85 m walker's 0.281
#: m foot stood 0.6 mm into both risers of a 0.28 m tread, and with only this gap going down
#: its landing heel still caught the upper nosing (6.2 mm; 1.3 mm with 1 cm; measured on the
#: shipped stair, ``tests/timeline/test_collisions.py``); the multi-level station's cycle,
#: run 7 of 10 (a 1.85 m older adult): 225 contacts. Feet that fit stand as before. A walker
#: whose foot keeps less than :data:`mjwalk.world.norms.MIN_TREAD_SHARE` of it on a tread does
#: not take the flight (:mod:`mjwalk.plan.treadshare`).
TREAD_RISER_GAP = DESCENT_LOW_CLEARANCE


def flight_setback(s: np.ndarray, track: np.ndarray, up: bool, stature: float) -> np.ndarray:
    """How far behind each footfall (against the walking direction) the point under the ankle
    is put: on a tread, half the foot's length ahead of the ankle less its length behind, so
    that the foot, not the ankle, is centred on its tread
    (:func:`mjwalk.anthropometry.leg_geometry`: 0.0665 m at 1.75 m); on the level before the
    first riser going up (after the last going down), at least enough to keep the toes (the
    heel) :data:`RISER_GAP` off that riser's face. Positions are along the walking direction;
    the risers lie halfway between consecutive track positions. The planner's
    (:func:`tread_setback`) and :func:`mjwalk.plan.synthetic.synthetic_stair_walk`'s rule.

    Args:
        s: (k,) footfall positions, metres along the walking direction.
        track: (t,) the flight's footfall positions in walking order (>= 2; the first before
            the first edge, the last past the last edge), metres along the walking direction.
        up: whether the walk climbs the flight.
        stature: the walker's stature, metres.

    Returns:
        (k,) the setbacks, metres.
    """
    s, track = np.asarray(s, dtype=float), np.asarray(track, dtype=float)
    g = leg_geometry(stature)
    centred = np.full(len(s), 0.5 * (g.foot_front - g.foot_back))
    edges = 0.5 * (track[:-1] + track[1:])  # the risers, in walking order
    if up:  # the toes of a foot on a tread, and of the foot before the first riser
        ahead = edges[np.clip(np.searchsorted(edges, s), 0, len(edges) - 1)]
        gap = np.where(np.abs(s - track[0]) < 1e-9, RISER_GAP, TREAD_RISER_GAP)
        toe_gap = np.where(s < edges[-1], s + g.foot_front + gap - ahead, -np.inf)
        return np.maximum(centred, toe_gap)
    # the heel of a foot on a tread, and of the foot past the last riser
    behind = edges[np.clip(np.searchsorted(edges, s) - 1, 0, len(edges) - 1)]
    # a foot that does not fit keeps its landing heel the least edge clearance off the riser
    # behind, whose nosing that heel passes as it lowers (TREAD_RISER_GAP's docstring)
    fits = s - centred - g.foot_back - behind >= TREAD_RISER_GAP - 1e-9
    gap = np.where((np.abs(s - track[-1]) < 1e-9) | ~fits, RISER_GAP, 0.0)
    heel_gap = np.where(s > edges[0], s - g.foot_back - gap - behind, np.inf)
    return np.minimum(centred, heel_gap)


def tread_setback(c: Crossing, s: np.ndarray, stature: float, direction: str = "up") -> np.ndarray:
    """How far behind each footfall (against the walking direction) the point under the ankle
    is put on a step or stair (:func:`flight_setback`: the foot centred on its tread, and off
    the riser it faces from the level before or after the flight); ramps and the stances: 0.
    Without it the toes of a foot on a 0.28 m tread stand 6 cm into the next riser going up
    (measured, the multi-level station's stair).

    Args:
        c: the crossing.
        s: (k,) footfall positions along its axis, metres.
        stature: the walker's stature, metres.
        direction: "up" (along the axis) or "down".

    Returns:
        (k,) the setbacks, metres (>= 0).
    """
    s = np.asarray(s, dtype=float)
    if c.kind == "ramp":
        return np.zeros(len(s))
    sign = 1.0 if direction == "up" else -1.0
    on_track = (s >= c.track[0] - 1e-9) & (s <= c.track[-1] + 1e-9)
    back = flight_setback(sign * s, np.sort(sign * c.track), direction == "up", stature)
    return np.where(on_track, back, 0.0)


def cross_walk(
    c: Crossing,
    direction: str,
    walker: Walker,
    start: tuple[np.ndarray, float],
    last: PathStep | None,
    floor_z: float,
    step_width: float | None = None,
    lead_in: bool | tuple = False,
) -> WalkPath:
    """The walk over a crossing (module docstring).

    Args:
        c: the crossing.
        direction: "up" (lower to upper level) or "down".
        walker: the walker (pace, step time, step width).
        start: the pelvis' world xy (metres) and heading (radians) where the walk begins, at
            or near the crossing's stance on the level it leaves.
        last: the step that brought the walker there (its landing foot stays the stance foot
            of the first step here; level steps lead from there into the flight, :func:`_lead_in`),
            or None (standing with the feet side by side; more than :data:`STANCE_SLACK` from
            the stance, two level steps bring the feet onto it).
        floor_z: the floor's world height, metres (heights are given above it).
        step_width: lateral distance of the feet, metres (None: the walker's, else
            :data:`DEFAULT_STEP_WIDTH`).
        lead_in: the walk that brought the walker there ended at the flight's approach point
            (:func:`approach_point`), up to a step length and its goal area before the stance:
            led in as from any walk's end (with ``last`` given; steps, stairs, ramps); or the
            turn into the flight while walking (:func:`mjwalk.plan.turnin.turn_into`:
            footfalls, headings, the end heading), stepped before its first footfall.

    Returns:
        The crossing's walk from t = 0: 120 Hz pelvis xy, yaw and height, its steps with the
        surfaces' heights under both feet; ``meta`` names the crossing.
    """
    width = step_width or walker.step_width or DEFAULT_STEP_WIDTH
    s, times = _footfalls(c, direction, walker)
    yaw = c.yaw if direction == "up" else c.yaw + math.pi
    heading = np.array([math.cos(yaw), math.sin(yaw)])
    left = np.array([-heading[1], heading[0]])
    xy0, yaw0 = np.asarray(start[0], dtype=float), float(start[1])
    turned = lead_in if isinstance(lead_in, tuple) else None  # turnin.turn_into's turn
    yaw = turned[2] if turned else yaw0 + (yaw - yaw0 + math.pi) % (2 * math.pi) - math.pi
    begin = c.approach if direction == "up" else c.exit
    if turned is None and last is not None:  # led in from a walk's end (_lead_in)
        s, times = _lead_in(c, s, times, start[0], walker)
    if last is None and float(np.hypot(*(c.point(begin) - xy0))) > STANCE_SLACK:
        # standing off the stance: both feet step onto it first, at the level step time
        s = np.concatenate([[begin, begin], s])
        times = np.concatenate([[walker.step_duration] * 2, times])
    if last is not None:
        side = "left" if last.side == "right" else "right"
        feet = {last.side: (np.asarray(last.foot, dtype=float), float(last.foot_z) + floor_z)}
        feet[side] = (np.asarray(last.stance, dtype=float), float(last.stance_z) + floor_z)
    else:
        side = "left"
        z0 = float(c.height_at(begin))
        feet = {
            name: (np.array([*(xy0 + sign * 0.5 * width * left), yaw0]), z0)
            for name, sign in (("left", 1.0), ("right", -1.0))
        }
    pelvis_z = 0.5 * (feet["left"][1] + feet["right"][1])
    s = np.asarray(s, dtype=float)
    back = _setback(c, s, walker.stature, direction) * (1.0 if direction == "up" else -1.0)
    points, heights = c.point(s - back), c.height_at(s)  # per footfall, as one by one
    if turned is None:  # steps on the spot first, each within ENTRY_TURN (spot_turn)
        turned = (np.repeat(xy0[None, :], (spot := spot_turn(yaw0, yaw)).size, 0), spot, yaw)
    here = (xy0, float(c.height_at(begin)))
    points, heights, times, headings, across, was, turns = turned_steps(
        turned, (points, heights, times), here, (yaw0, yaw), walker.step_duration, left
    )
    xy, z, yaws, steps = footfall_walk(
        (points, heights, times, headings, across, width), feet, side, (xy0, pelvis_z, yaw0),
        (was, turns, yaw), floor_z,
    )  # fmt: skip
    n = steps[-1].end if steps else 0
    meta = {"crossing": c.kind, "direction": direction, "lower": c.lower, "upper": c.upper,
            "edges": _riser_lines(c, floor_z)}  # fmt: skip
    return WalkPath(
        t=np.arange(n + 1) / SAMPLE_RATE_HZ, xy=xy, yaw=yaws, steps=steps, meta=meta,
        z=z - floor_z,
    )  # fmt: skip


def _setback(c: Crossing, s: np.ndarray, stature: float, direction: str) -> np.ndarray:
    """:func:`tread_setback` kept on the crossing per footfall positions (their bytes: the same
    floats), stature and direction (read-only: :func:`mjwalk.plan.levelmemo.kept`): a
    crossing's footfalls are the same walk after walk but for a lead-in's."""
    key = (s.tobytes(), stature, direction)
    return kept(c, "_setbacks", key, lambda: tread_setback(c, s, stature, direction))


def _riser_lines(c: Crossing, floor_z: float) -> list[dict]:
    """:meth:`~mjwalk.plan.levelroute.Crossing.riser_lines`, kept on the crossing per floor
    height; each walk gets its own copies (its dicts and lists), so no walk's meta is
    another's."""
    lines = kept(c, "_riser_lines", floor_z, lambda: tuple(c.riser_lines(floor_z)))
    return [{**e, "xy": list(e["xy"]), "normal": list(e["normal"])} for e in lines]


#: The most (radians) a walk arriving at a crossing may face away from its axis: the crossing's
#: first step turns the walker onto the axis, and people change direction by at most 60 degrees
#: within one step (Patla et al. 1991, :data:`mjwalk.plan.turnsplit.WALKING_TURN_MAX`). A walk
#: that came to a ramp's stance facing 120 degrees off turned onto the ramp in one step (the
#: platform cycle's run 14): the legs could not reach and lowered the pelvis 0.21 m. A walk
#: that still arrives further off (rack1 -> mezzanine: 106-147 deg, its floor leg a hairpin
#: out of the gap between the stair's wall and the trolley) turns into it while walking
#: (:mod:`mjwalk.plan.turnin`), else on the spot there (:func:`spot_turn`), by at most this a step.
ENTRY_TURN = WALKING_TURN_MAX


def entry_turn(walk: WalkPath, c: Crossing, direction: str) -> float:
    """How far the crossing's first step must turn a walker whose level walk ``walk`` ends
    before it: the walk's last heading against the crossing's (up or down its axis).

    Args:
        walk: the level walk to the crossing.
        c: the crossing.
        direction: "up" or "down".

    Returns:
        The turn, radians (>= 0).
    """
    yaw = c.yaw if direction == "up" else c.yaw + math.pi
    return abs(wrap(yaw - float(walk.yaw[-1])))


def spot_turn(yaw0: float, yaw: float) -> np.ndarray:
    """The headings of the steps a walker standing at a crossing's stance or approach point
    turns on the spot before it steps onto the crossing, when the turn from ``yaw0`` to the
    crossing's heading ``yaw`` is more than :data:`ENTRY_TURN`: the turn in equal parts, none
    over :data:`ENTRY_TURN` (a direction change within one step, Patla et al. 1991), the last
    part left to the crossing's first step. People turn up to 180 degrees in place, young
    adults as one pivot, older ones in more, smaller steps (Thigpen et al. 2000, Phys Ther 80:
    1174-1187, quoted in :mod:`mjwalk.plan.turnsplit`); equal parts of at most 60 degrees are
    a modelling choice within that, no figure of the source. The walk to the crossing ends
    standing (a level walk's closing step), so a turn the level planner could not make while
    walking (a hairpin into a stair's foot, issue 47) is made there, not in one step.

    Args:
        yaw0: the walker's heading where the crossing's walk begins, radians.
        yaw: the crossing's heading up or down its axis, the nearer turn from ``yaw0``
            (``|yaw - yaw0| <= pi``), radians.

    Returns:
        (m,) the headings (radians) after each step on the spot, in order; empty when the turn
        is within :data:`ENTRY_TURN`.
    """
    parts = math.ceil(abs(yaw - yaw0) / ENTRY_TURN - 1e-9)
    if parts <= 1:
        return np.empty(0)
    return yaw0 + (yaw - yaw0) * np.arange(1, parts) / parts


def line_clear(view, a: np.ndarray, b: np.ndarray, radius: float) -> bool:
    """Whether the body fits along a segment on a level (checked every grid cell's length,
    :data:`~mjwalk.plan.occupancy.CELL_SIZE`).

    Args:
        view: the level's view (:func:`mjwalk.world.levelview.level_view`, its
            ``walk_clearance``).
        a: (2,) the segment's start, world xy, metres.
        b: (2,) its end, world xy, metres.
        radius: the body radius, metres.

    Returns:
        True when the clearance is at least ``radius`` all along (kept on the view per
        segment and radius).
    """
    key = (float(a[0]), float(a[1]), float(b[0]), float(b[1]), float(radius))
    return kept(view, "_clear_lines", key, lambda: _line_clear(view, a, b, radius))


def _line_clear(view, a: np.ndarray, b: np.ndarray, radius: float) -> bool:
    """:func:`line_clear` without its cache."""
    u = np.linspace(0.0, 1.0, max(2, math.ceil(float(np.hypot(*(b - a))) / CELL_SIZE) + 1))
    return float(np.min(view.walk_clearance(a + np.outer(u, b - a)))) >= radius


def approach_point(c: Crossing, direction: str, lead: float) -> np.ndarray:
    """The point on a flight's axis ``lead`` metres before its stance, away from the flight: a
    level walk aimed there lines the walker up with the flight before it steps on, as people
    approaching steps do: they adapt their last approach steps so that one foot is planted
    just before the step and the other lifted onto it without a break in the walk's rhythm
    (PTMATE, "Analysis of stepping up", skillsforaction.com; qualitative). "Stair gait in older
    adults worsens with smaller step treads and when transitioning between level and stair
    walking" (Di Giulio, Reeves, Roys, Buckley, Jones, Gavin, Baltzopoulos & Maganaris, Front.
    Sports Act. Living 2:63, 2020, doi:10.3389/fspor.2020.00063) compares stair
    walks with and without such a walking approach. With ``lead`` one step length the walk's
    last level steps land on the axis (:func:`cross_walk`'s ``lead_in``): a modelling choice,
    no figure of those sources.

    Args:
        c: the crossing.
        direction: "up" (the point lies before the approach stance on the lower level) or
            "down" (past the exit stance on the upper level).
        lead: distance from the stance, metres.

    Returns:
        (2,) world xy, metres.
    """
    return c.point(c.approach - lead if direction == "up" else c.exit + lead)


def departure(c: Crossing, direction: str, lead: float) -> Crossing:
    """The crossing walked on ``lead`` metres past its far stance along its axis: the walker
    steps off a flight straight ahead before it turns to where it goes next (the mirror of
    :func:`approach_point`; the steps there no longer than the walker's step length).

    Args:
        c: the crossing.
        direction: "up" (the exit stance moves up the axis) or "down" (the approach stance
            moves down it).
        lead: distance past the stance, metres.

    Returns:
        The crossing with that stance moved (its :meth:`~Crossing.end` there), kept on ``c``
        per direction and lead (so its own kept values are found again).
    """
    if direction == "up":
        return kept(c, "_departures", (direction, lead), lambda: replace(c, exit=c.exit + lead))
    return kept(c, "_departures", (direction, lead), lambda: replace(c, approach=c.approach - lead))


def route_leads(c: Crossing, level: int, lead: float) -> tuple[np.ndarray | None, ...]:
    """Where the level walks at a crossing's stance on ``level`` end and begin as walked: a
    walk to a stair, step or ramp ends at its :func:`approach_point`, ``lead`` before the
    stance, and lines up from there; a walk away from a stair begins at its :func:`departure`
    stance, ``lead`` past it (a single step and a ramp are left on the fly). Both are the point
    ``lead`` from the stance along the axis, away from the flight.

    Args:
        c: the crossing.
        level: its lower or upper level (index).
        lead: the walker's step length, metres.

    Returns:
        (departure point, line-up point): world xy (metres) each, or None where the walks end
        or begin at the stance itself.
    """
    point = approach_point(c, "up" if level == c.lower else "down", lead)
    return (point if c.kind == "stair" else None, point)


def walked_distance(d: float, field, leaving: tuple, arriving: tuple, reach: tuple) -> float:
    """The level distance between two route nodes (a crossing's stance, the walk's start or
    goal) with the line-up and departure walked (:func:`route_leads`): at least the step
    length to or from each such point along the axis plus the distance to it, and never less
    than the direct distance ``d``. The line-up point's distance is taken straight (no field
    is built to it): a lower bound of the walk around obstacles. Nodes no farther apart than a
    step length and the goal tolerance are walked between directly (as the level planner
    does).

    Args:
        d: the distance field's distance between the nodes, metres.
        field: the distance field to the arriving node (callable on (2,) world xy, metres).
        leaving: (xy, departure point or None) of the node the walk leaves, metres.
        arriving: (xy, line-up point or None) of the node it goes to, metres.
        reach: (the walker's step length, the planner's goal tolerance), metres.

    Returns:
        The distance, metres.
    """
    lead, tolerance = reach
    here = np.asarray(leaving[0], dtype=float)
    if float(np.hypot(*(np.asarray(arriving[0]) - here))) <= lead + tolerance:
        return d
    extra = 0.0
    if leaving[1] is not None:
        here, extra = np.asarray(leaving[1], dtype=float), lead
        d = max(d, extra + float(field(here)))
    if arriving[1] is not None:
        d = max(d, extra + float(np.hypot(*(np.asarray(arriving[1]) - here))) + lead)
    return d


def level_time(distance: float, walked: bool, walker: Walker) -> float:
    """How long a level leg of a route takes (:func:`mjwalk.plan.levelplan.plan_level_walk`
    plans each as a walk of its own, from standing to standing): its distance at the walker's
    speed plus one step duration where it is walked at all. From standing with the feet side
    by side the pelvis covers half a step length in the first step and half in the closing
    step that brings the feet together again, so ``n`` step lengths take ``n + 1`` steps (the
    planner's own walks from rest to rest on the open floor, 1.5-6 m, seeds 0-4: 0.62-1.09,
    mean 0.87 step durations over ``distance / speed``, ending within their goal area).

    Args:
        distance: the level distance with the line-up and departure walked
            (:func:`walked_distance`), metres.
        walked: whether the leg is walked (False: its ends are within the planner's goal area).
        walker: the walker (speed, step duration).

    Returns:
        Seconds.
    """
    return distance / walker.speed + (walker.step_duration if walked else 0.0)


def _lead_in(c: Crossing, s: np.ndarray, times: np.ndarray, xy0, walker: Walker):
    """``s`` and ``times`` with the level steps from ``xy0`` along the axis into the flight's
    first footfall, evenly spaced, none longer than the walker's step length; at least two where
    ``xy0`` lies more than :data:`STANCE_SLACK` off the axis, so that the foot that leaves for the
    flight's first footfall has stood on the axis (multi-level station, seed 7 run 1: the walk's
    last foot 0.48 m off the stair's axis, the knee climbing from it 8 cm into its side wall)."""
    here = float(np.dot(offset := np.asarray(xy0, dtype=float) - c.origin, c.axis))
    gap, off = float(s[0]) - here, abs(float(c.axis[0] * offset[1] - c.axis[1] * offset[0]))
    n = max(1 + (off > STANCE_SLACK), math.ceil(abs(gap) / walker.step_length - 1e-9))
    extra = here + gap * np.arange(1, n) / n
    return np.concatenate([extra, s]), np.concatenate([np.full(n - 1, walker.step_duration), times])


def crossing_time(
    c: Crossing, direction: str, walker: Walker, arrival: float | None = None
) -> float:
    """How long the walk over a crossing takes (from its stance to standing beyond it), with
    the turn on the spot before it when the walker arrives facing ``arrival``
    (:func:`entry_time`).

    Args:
        c: the crossing.
        direction: "up" or "down".
        walker: the walker.
        arrival: the heading the walker arrives at (radians), or None (no turn counted).

    Returns:
        Seconds (the sum of its steps' times, the steps on the spot included).
    """
    t = float(np.sum(_footfalls(c, direction, walker)[1]))
    return t if arrival is None else t + entry_time(c, direction, walker, arrival)


def entry_time(c: Crossing, direction: str, walker: Walker, arrival: float) -> float:
    """How long a walker who arrives at a crossing facing ``arrival`` turns on the spot before
    it: one level step time (:attr:`Walker.step_duration <mjwalk.gait.walker.Walker.
    step_duration>`) per step on the spot (:func:`spot_turn`: the turn in equal parts of at
    most :data:`ENTRY_TURN`, Patla et al. 1991; a turn in place, Thigpen et al. 2000), the last
    part taken by the crossing's first step, as :func:`cross_walk` walks them.

    Args:
        c: the crossing.
        direction: "up" or "down".
        walker: the walker (its level step time).
        arrival: the walker's heading where the crossing's walk begins, radians.

    Returns:
        Seconds (0 for a turn within :data:`ENTRY_TURN`).
    """
    yaw = c.yaw if direction == "up" else c.yaw + math.pi
    return spot_turn(0.0, wrap(yaw - arrival)).size * walker.step_duration


#: How far (m) before the point a level walk arrives at its route's last stretch is read, as a
#: share of the walker's step length (:func:`arrival_heading`): the walk's last half step, a
#: modelling choice (no figure of a source).
ARRIVAL_REACH = 0.5


def arrival_heading(view, ends: tuple, field, radius: float, step_length: float) -> float:
    """The heading (radians) at which a level walk from one point arrives at another, as its
    shortest route comes in: along the straight line where the body fits along it
    (:func:`line_clear`), else from the point :data:`ARRIVAL_REACH` step lengths before the end
    (of 32 around it) nearest the walk's start by the distance field ``field`` to that start.
    A level leg to a stair is searched once (:func:`mjwalk.plan.levelplan.plan_level_walk`:
    steps and ramps again, facing them), and arrives as its route comes in (the multi-level
    station's rack1 -> mezzanine: 135-146 deg off the flight by the field, 117-152 walked).

    Args:
        view: the level's view (its ``walk_clearance``).
        ends: (start, end) world xy, metres.
        field: a callable returning the distance field to the start (built only when needed).
        radius: the body radius, metres.
        step_length: the walker's step length, metres.

    Returns:
        Radians from +x CCW.
    """
    a, b = (np.asarray(p, dtype=float) for p in ends)
    if not line_clear(view, a, b, radius):
        turns = np.linspace(0.0, 2.0 * math.pi, 32, endpoint=False)
        around = b + ARRIVAL_REACH * step_length * np.stack([np.cos(turns), np.sin(turns)], 1)
        a = around[int(np.argmin(field()(around)))]
    return math.atan2(b[1] - a[1], b[0] - a[0])
