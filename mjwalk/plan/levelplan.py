"""Walks over several levels: a hierarchical plan (issue 47).

:func:`plan_level_walk` plans a walk whose start or goal stands on a raised surface -- a
platform, a mezzanine -- of a scene on several levels (:attr:`Workplace.levels
<mjwalk.world.workplace.Workplace.levels>`):

1. the route over levels (:func:`mjwalk.plan.levelsearch.level_route`): a Dijkstra over the
   crossings' stances, each level's obstacle-aware distance with the line-up and departure of
   3. walked from standing to standing (:func:`mjwalk.plan.levelcross.level_time`), each
   crossing at its gait's time, a step or stair only where every riser fits the walker's
   step-up limit and the head has room (a walker below a riser takes the ramp);
2. on each level the hybrid A* unchanged (:class:`~mjwalk.plan.hybrid.HybridPlanner`, kept
   per level view, goal, step model and options, so a route's legs are set up once) in the
   level's view (:func:`mjwalk.world.levelview.level_view`: its surfaces, its obstacles up to
   the walker's head; a leg of at most two step lengths along a clear line, turning within a
   step at either end, walked as footfalls along it unsearched: :mod:`mjwalk.plan.shortleg`),
   from the start or a crossing's stance to the next crossing's stance
   (ending in the planner's goal area about it; the heading up or down it a preference, its
   guide searched on :data:`HEADING_BUDGET` expansions before the route search alone) or the
   goal. After a crossing the walker stands on both feet: the leg is a standing start (a turn
   on the spot costed) whose first step swings the other foot than the crossing's last
   (:func:`next_foot`: step over step through every crossing), the turn walked as steps on
   the spot before it (:func:`mjwalk.plan.stepturn.stepped_turn`);
3. each crossing walked step by step (:func:`mjwalk.plan.levelcross.cross_walk`; a winder
   along its walk line, led in from its line-up point,
   :func:`mjwalk.plan.winderroute.winder_cross_walk`), where along
   its width it is nearest the walk (:func:`mjwalk.plan.levelroute.place_on_edge`), the
   walker's swinging arms a cited clearance from its sides (:func:`~mjwalk.plan.levelroute.
   side_margin`); a level
   leg to a crossing ends at its approach point a step length before the stance on its
   axis (:func:`mjwalk.plan.levelcross.approach_point`), and the walk over a stair goes on a
   step length past its far stance before the next leg (:func:`~mjwalk.plan.levelcross.
   departure`; a single step is left on the fly), where the legs are long enough and the body
   fits: the walker lines up with the flight (facing it within :data:`ENTRY_TURN`; a leg
   arriving further off turns into it while walking, :func:`mjwalk.plan.turnin.turn_into`);

stitched into one :class:`~mjwalk.plan.walkpath.WalkPath` with the surface height per sample and
under each footfall. Its ``meta["levels"]`` gives the route (levels and crossings) and the time,
length and steps of the walk per level and per kind (``level``, ``stairs``, ``ramps``, ``steps``;
each step by the surfaces its foot leaves and lands on, :func:`mjwalk.plan.levelstitch.
step_kinds`). A walk whose start and goal both stand on the floor is not this module's: it is
planned exactly as in a flat scene (:func:`needs_levels`). Metres, seconds, radians.
"""

from __future__ import annotations

import copy
import functools
import math
import time
import weakref
from dataclasses import dataclass, replace

import mujoco
import numpy as np

from mjwalk.conventions import other_side
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.hybrid import HybridPlanner, walker_step_length
from mjwalk.plan.levelcross import (
    ENTRY_TURN,
    approach_point,
    cross_walk,
    departure,
    entry_turn,
    flight_start,
    line_clear,
)
from mjwalk.plan.levelmemo import default_options, kept, variant
from mjwalk.plan.levelroute import (
    RouteLeg,
    place_crossings,
    step_up_limit,
)
from mjwalk.plan.levelsearch import STANCE_TOLERANCE, level_route
from mjwalk.plan.levelstitch import level_meta, stitch
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.request import WalkRequest
from mjwalk.plan.shortleg import short_leg
from mjwalk.plan.stepturn import stepped_turn
from mjwalk.plan.turnin import turn_into
from mjwalk.plan.walkpath import WalkPath
from mjwalk.plan.winderroute import oriented_legs, winder_cross_walk
from mjwalk.world.levelview import level_at, level_view
from mjwalk.world.norms import EXPOSED_MIN, HEAD_MARGIN, MAX_RISER
from mjwalk.world.workplace import Workplace

#: Expansions a level leg aimed at a crossing with its approach heading may spend before it is
#: searched again without (its guide can lead into a tight approach the route search finds at
#: once): a twentieth of MAX_EXPANSIONS' 8000; the station's legs that succeed with it spend at
#: most 150 (``benchmarks/bench_levels.py``; a cost bound, no behaviour of walkers).
HEADING_BUDGET = 400
#: Budget share (1000) of a step's leg searched again facing it (ramps: all): a cost bound.
RESEARCH_SHARE = 8
#: Level-leg planners kept per level view (:func:`_planner`): a memory bound, no behaviour.
LEG_PLANNERS = 64


@dataclass(frozen=True)
class Endpoint:
    """A walk's start or goal placed on a level.

    Attributes:
        where: as the caller gave it (site, "x,y[,yaw_deg]", tuple).
        xy: world xy, metres.
        level: the level it stands on.
    """

    where: object
    xy: np.ndarray
    level: int


def _site_z(workplace: Workplace, where) -> float | None:
    """The world height of a named site, else None."""
    if isinstance(where, str) and where in workplace.stations:
        return float(workplace.stations[where].pos[2])
    return None


def _xy(workplace: Workplace, where) -> np.ndarray:
    """World xy of a site, "x,y[,yaw_deg]" or (x, y[, yaw])."""
    if isinstance(where, str) and where not in workplace.stations and where.count(",") == 2:
        return workplace.point(",".join(where.split(",")[:2]))
    if not isinstance(where, str):
        return workplace.point(np.asarray(where, dtype=float).ravel()[:2])
    return workplace.point(where)


def needs_levels(workplace: Workplace, start, goal, radius: float) -> bool:
    """Whether a walk needs the level planner: its start or goal stands on a surface above the
    floor. A point clear on the floor (and a site no higher than
    :data:`mjwalk.world.norms.EXPOSED_MIN` above it) is on the floor without looking at the
    levels, so flat scenes never build them.

    Args:
        workplace: the scene.
        start: as :func:`mjwalk.plan.walks.plan_walk` takes it.
        goal: as :func:`mjwalk.plan.walks.plan_walk` takes it.
        radius: the body radius, metres.

    Returns:
        True when either end stands on another level than the floor's.
    """
    for where, what in ((goal, "goal"), (start, "start")):  # the goal first, as the planner
        xy = _xy(workplace, where)  # parses them
        z = _site_z(workplace, where)
        high = z is not None and z - workplace.floor_z > EXPOSED_MIN
        if not high and float(workplace.walk_clearance(xy)) >= radius:
            continue
        if len(workplace.levels.levels) > 1 and level_at(workplace, xy, z) not in (0, None):
            return True
        if z is not None and high:
            _refuse_raised_top(workplace, str(where), xy, z, what)
    return False


def _refuse_raised_top(workplace: Workplace, site: str, xy: np.ndarray, z: float, what: str):
    """Raise a PlanningError naming the raised top a site stands on when that top is no walk
    surface (no way up reaches it, or it has no room to stand): the walk would otherwise fail
    with "inside obstacle", which hides why. A site inside no obstacle, or over no geom top
    above :data:`~mjwalk.world.norms.EXPOSED_MIN` within that height of it, is left to the
    planner's own checks.

    Args:
        workplace: the scene.
        site: the site's name.
        xy: (2,) its world xy, metres.
        z: its world height, metres.
        what: "start" or "goal", for the message.
    """
    if not any(float(fp.signed_distance(xy[None])[0]) < 0.0 for fp in workplace.obstacles):
        return
    model = workplace.model
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    hit = np.array([-1], dtype=np.int32)
    above = z + EXPOSED_MIN  # a site a little below its top's face still finds it
    far = mujoco.mj_ray(
        model, data, np.array([xy[0], xy[1], above]), np.array([0.0, 0.0, -1.0]), None, 1, -1, hit
    )
    top = above - far - workplace.floor_z
    if hit[0] < 0 or far > 2.0 * EXPOSED_MIN or top <= EXPOSED_MIN:  # no top within 5 cm of it
        return
    name = model.geom(int(hit[0])).name or f"geom {int(hit[0])}"
    raise PlanningError(
        f"{what} site {site!r} stands on {name!r} (top +{top:.2f} m above the floor), which is "
        f"no walk surface of {workplace.name} (walk surfaces are reached from the floor by steps "
        f"of risers up to {MAX_RISER} m, ramps or stairs, and have room to stand); add a way up "
        "or move the site"
    )


def endpoint(workplace: Workplace, where, what: str) -> Endpoint:
    """Place a start or goal on its level; a site's or a text's placing is kept on the
    workplace (a cycle's walks start and end at the same sites; :func:`mjwalk.plan.levelmemo.
    kept`, its ``xy`` read-only).

    Args:
        workplace: the scene.
        where: a site, "x,y[,yaw_deg]" or (x, y[, yaw]).
        what: "start" or "goal", for messages.

    Returns:
        The endpoint.

    Raises:
        PlanningError: the point stands on no level (on a ramp, or on no surface).
    """
    if isinstance(where, str):  # the same text, the same point and level
        return kept(workplace, "_endpoints", where, lambda: _endpoint(workplace, where, what))
    return _endpoint(workplace, where, what)


def _endpoint(workplace: Workplace, where, what: str) -> Endpoint:
    """:func:`endpoint` without its memo."""
    xy = _xy(workplace, where)
    z = _site_z(workplace, where)
    high = z is not None and z - workplace.floor_z > EXPOSED_MIN
    if not high and float(workplace.walk_clearance(xy)) > 0.0:
        xy.flags.writeable = False
        return Endpoint(where, xy, 0)
    lv = level_at(workplace, xy, z)
    if lv is None:
        raise PlanningError(
            f"{what} ({xy[0]:.3f}, {xy[1]:.3f}) stands on no level of {workplace.name} (on a ramp "
            "or on no walk surface)"
        )
    xy.flags.writeable = False  # kept by endpoint: no caller changes it for the next
    return Endpoint(where, xy, int(lv))


def _walker(model) -> Walker:
    """The walker a model was conditioned on, else the reference adult."""
    walker = getattr(model, "walker", None)
    return walker if isinstance(walker, Walker) else Walker()


def _planner(view: Workplace, goal: np.ndarray, model, options: PlannerOptions) -> HybridPlanner:
    """The hybrid planner of one level leg's goal, kept on the level's view per goal, step model
    and options: a route's legs end at the same crossing stances walk after walk, so the goal's
    distance field, sight cells and kernel vectors are set up once (the planner holds nothing of
    a walk: :meth:`HybridPlanner.plan` draws from the walk's own random stream)."""
    cache = view.__dict__.setdefault("_leg_planners", {})
    key = (float(goal[0]), float(goal[1]), id(model), options)
    hit = cache.get(key)
    if hit is not None and hit[0]() is model:
        return hit[1]
    planner = HybridPlanner(view, goal, model, options)
    while len(cache) >= LEG_PLANNERS:  # the oldest first (a cycle's operators come and go)
        cache.pop(next(iter(cache)))
    cache[key] = (weakref.ref(model), planner)
    return planner


def next_foot(last_side: str | None) -> str | None:
    """The foot that swings first after a crossing: the other one than the crossing's last step
    (gait continuity: feet alternate, step over step, also where a walk sets off again).

    Args:
        last_side: "left" or "right", the side of the crossing's last step; None: no crossing.

    Returns:
        "right" after "left", "left" after "right", None (either foot) after no crossing.
    """
    return None if last_side is None else other_side(last_side)


def _foot_model(model, side: str | None):
    """``model`` whose gait-initiation draws (``sample_first_features``) swing ``side`` only,
    kept per model and side (its decoder too is then shared); ``model`` itself for None."""
    if side is None:
        return model
    key = (id(model), side)
    hit = _FOOT_MODELS.get(key)
    if hit is not None and hit[0]() is model:
        return hit[1]
    first = copy.copy(model)  # shallow: the same KDEs, GPs and walker
    # an instance attribute before the class's method: the draws swing ``side`` only
    vars(first)["sample_first_features"] = functools.partial(model.sample_first_features, side=side)
    _FOOT_MODELS[key] = (weakref.ref(model), first)
    return first


#: The start-foot models of :func:`_foot_model`, by (id(model), side); the model held weakly.
_FOOT_MODELS: dict[tuple[int, str], tuple[weakref.ref, object]] = {}


def _level_leg(workplace, leg: RouteLeg, nxt: RouteLeg | None, start, model, rng, options, head):
    """The hybrid-A* walk of one level leg; None when its ends are within reach already.

    ``start`` is (pose, foot): the walk's start, or after a crossing the stance beyond it
    (x, y, yaw), where the walker stands on both feet: a standing start that may turn on the
    spot (its turn costed), its first step with ``foot`` (:func:`next_foot`). Arriving over
    :data:`ENTRY_TURN` off a ramp or step, it is searched again facing it (RESEARCH_SHARE)."""
    view = level_view(workplace, leg.level, head)
    if float(np.hypot(*(leg.end - leg.start))) <= max(STANCE_TOLERANCE, options.goal_tolerance):
        return None  # the walker stands in the leg's goal area already: no level walk
    pose, foot = start
    standing = foot is not None
    walker_model = _foot_model(model, foot)
    planner = _planner(view, leg.end, model, options)
    request = WalkRequest(pose, model=walker_model, turn_on_spot=standing)
    here = _start_pose(workplace, pose, leg)
    if nxt is None:  # to the walk's goal
        short = _short(view, here, leg.end, (model, foot, None), rng, options)
        return short if short is not None else planner.plan(request, rng)
    c = nxt.crossing
    assert c is not None
    heading = c.yaw if nxt.direction == "up" else c.yaw + math.pi
    goal = _approach(view, leg, nxt, walker_step_length(walker_model), options)
    aim = leg.end if goal is None else goal
    walk = _short(view, here, aim, (model, foot, heading), rng, options)
    if walk is not None:  # a step or two along a clear line: nothing to search
        if goal is not None:
            walk.meta["approach_point"] = [float(goal[0]), float(goal[1])]
        return walk
    if goal is not None:  # lined up with the flight a step before its stance
        planner = _planner(view, goal, model, options)
    # the approach heading a preference: its guide on a small budget, else the route search
    budget = min(options.max_expansions, HEADING_BUDGET)
    aimed = _planner(view, aim, model, variant(options, max_expansions=budget))
    try:
        walk = aimed.plan(replace(request, goal_heading=heading), rng)
    except PlanningError:
        walk = planner.plan(request, rng)
        # the aimed search's spent budget counts (any earlier searches of it not)
        walk.meta["expansions_all"] = walk.meta.get("expansions_all", 0) + budget
    if c.kind != "stair" and entry_turn(walk, c, nxt.direction) > ENTRY_TURN:  # re-searched
        spent = walk.meta.get("expansions_all", 0)
        cap = options.max_expansions // (1 if c.kind == "ramp" else RESEARCH_SHARE)
        again = variant(options, goal_yaw=heading, max_expansions=cap)
        draws = rng if c.kind == "ramp" else rng.spawn(1)[0]  # a step's: later legs as before
        try:
            walk = _planner(view, aim, model, again).plan(request, draws)
            walk.meta["expansions_all"] = walk.meta.get("expansions_all", 0) + spent
        except PlanningError:  # its budget spent (or its open list dry before)
            walk.meta["expansions_all"] = spent + cap  # the walk as found
    if goal is not None:
        walk.meta["approach_point"] = [float(goal[0]), float(goal[1])]
    return walk


def _start_pose(workplace: Workplace, pose, leg: RouteLeg):
    """A level leg's start as (world xy, heading or None: free), as the hybrid planner reads
    it (a site or a point without a heading: free), or None for a text pose "x,y,yaw_deg"
    (left to the search)."""
    if isinstance(pose, str):
        return (leg.start, None) if pose in workplace.stations or pose.count(",") < 2 else None
    arr = np.asarray(pose, dtype=float).ravel()
    return (arr[:2], float(arr[2])) if arr.size == 3 else (leg.start, None)


def _short(view: Workplace, here, aim: np.ndarray, walk: tuple, rng, options) -> WalkPath | None:
    """:func:`mjwalk.plan.shortleg.short_leg` of a level leg from ``here`` (:func:`_start_pose`;
    None: no walk) to ``aim``; ``walk``: (step model, first foot or None: either, the heading
    the walk goes on with or None)."""
    model, foot, heading = walk
    if here is None:
        return None
    reach = (options.radius, options.goal_tolerance)
    return short_leg(view, here, aim, _walker(model), reach, (foot, heading), rng)


def _approach(view: Workplace, leg: RouteLeg, nxt: RouteLeg, lead: float, options):
    """The goal of a level leg to a crossing: its approach point ``lead`` before the stance
    (:func:`mjwalk.plan.levelcross.approach_point`) where the leg starts farther from the stance
    than that point and its goal area, and the body radius fits all the way from the point to
    the stance (every :data:`~mjwalk.plan.occupancy.CELL_SIZE`); else None (the stance)."""
    c = nxt.crossing
    assert c is not None
    if float(np.hypot(*(leg.start - leg.end))) <= lead + options.goal_tolerance:
        return None
    point = approach_point(c, nxt.direction, lead)
    return point if line_clear(view, leg.end, point, options.radius) else None


def _departure(workplace: Workplace, leg: RouteLeg, nxt: RouteLeg | None, lead: float, setup):
    """The crossing of ``leg`` as walked: past a stair the walker steps ``lead`` on along its
    axis (:func:`mjwalk.plan.levelcross.departure`) where a level leg follows that is longer
    than that and its goal area, and the body radius fits all the way on the level it arrives
    at (``setup``: the planner's options and the head height); else the crossing itself."""
    c = leg.crossing
    assert c is not None
    options, head = setup
    if c.kind != "stair" or nxt is None or nxt.kind != "level":
        return c
    if float(np.hypot(*(nxt.end - nxt.start))) <= lead + options.goal_tolerance:
        return c
    level = c.upper if leg.direction == "up" else c.lower
    walked = departure(c, leg.direction, lead)
    view = level_view(workplace, level, head)
    return walked if line_clear(view, c.end(level), walked.end(level), options.radius) else c


def _turned(workplace: Workplace, parts: list, crossing: tuple, walker: Walker, setup):
    """The level walk before a crossing and its lead-in (:func:`~mjwalk.plan.levelcross.
    cross_walk`'s ``lead_in``): a walk ending at the flight's approach point facing more than
    :data:`ENTRY_TURN` off it turns into it while walking where the turn fits
    (:func:`mjwalk.plan.turnin.turn_into`; the walk cut in ``parts`` there), else it lines up
    from the point (True); no walk or no approach point: (walk or None, False).
    ``crossing``: (the route leg, the crossing as walked); ``setup``: (options, head height)."""
    prev = parts[-1][1] if parts else None
    if prev is None or "approach_point" not in prev.meta:
        return prev, False
    (leg, walked), (options, head) = crossing, setup
    if entry_turn(prev, walked, leg.direction) <= ENTRY_TURN:
        return prev, True
    view = level_view(workplace, leg.level, head)
    heading = walked.yaw if leg.direction == "up" else walked.yaw + math.pi
    flight = (heading, flight_start(walked, leg.direction, walker))
    found = turn_into(view, prev, flight, walker, options.radius)
    if found is None:
        return prev, True
    parts[-1] = (parts[-1][0], found[0])
    return found


def plan_level_walk(
    workplace: Workplace,
    start,
    goal,
    model,
    rng: np.random.Generator,
    options: PlannerOptions | None = None,
    max_riser: float | None = None,
) -> WalkPath:
    """Plan a walk between points on any levels (module docstring).

    Args:
        workplace: the scene.
        start: a site, "x,y", "x,y,yaw_deg" or (x, y[, yaw]) (metres, radians), on any level.
        goal: a site, "x,y" or (x, y), on any level.
        model: the step model (its walker, if conditioned, gives speed, stature and gait).
        rng: the random stream of the level walks.
        options: the planner's options (None: the defaults).
        max_riser: the walker's step-up limit, metres (None:
            :func:`mjwalk.plan.levelroute.step_up_limit`'s default).

    Returns:
        The stitched walk: 120 Hz pelvis xy, yaw and surface height, the steps with their feet's
        heights, ``meta["levels"]`` (route, and time, length, steps per level and kind),
        ``meta["expansions_all"]`` (the level walks' expansions over all their searches).

    Raises:
        PlanningError: an end on no level, no route for the walker, or a level walk not found.
    """
    t0 = time.perf_counter()
    options = default_options() if options is None else options
    walker = _walker(model)
    limit = step_up_limit(walker, max_riser)
    head = walker.stature + HEAD_MARGIN
    a, b = endpoint(workplace, start, "start"), endpoint(workplace, goal, "goal")
    if a.level == b.level:
        legs = [RouteLeg("level", a.level, a.xy, b.xy)]
    else:
        legs = place_crossings(
            workplace, level_route(workplace, a, b, walker, options, limit), options, head
        )
        legs = oriented_legs(legs)  # a winder lined up with at the end it is entered from
    parts: list[tuple[RouteLeg, WalkPath]] = []
    pose: object = start
    foot: str | None = None  # the first step's side after a crossing
    for k, leg in enumerate(legs):
        if leg.kind == "level":
            nxt = legs[k + 1] if k + 1 < len(legs) else None
            walk = _level_leg(workplace, leg, nxt, (pose, foot), model, rng, options, head)
            if walk is not None and foot is not None:  # after a crossing: turn in steps
                walk = stepped_turn(walk, parts[-1][1], walker)
            if walk is not None:
                parts.append((leg, walk))
            continue
        c = leg.crossing
        assert c is not None
        nxt = legs[k + 1] if k + 1 < len(legs) else None
        walked = _departure(workplace, leg, nxt, walker.step_length, (options, head))
        if c.kind == "winder":  # its lead-in turns on the spot where the walk arrives off it
            prev = parts[-1][1] if parts else None
        else:
            prev, lead_in = _turned(workplace, parts, (leg, walked), walker, (options, head))
        # no walk before it: the walker stands where the walk starts (the level leg to the
        # crossing's stance was within its goal area), facing up or down it after the turn on
        # the spot the cycle makes before a walk; the crossing's walk steps to its stance first
        standing = legs[k - 1].start if k > 0 else leg.start
        facing = c.yaw if leg.direction == "up" else c.yaw + math.pi
        here = (prev.xy[-1], float(prev.yaw[-1])) if prev is not None else (standing, facing)
        last = prev.steps[-1] if prev is not None and prev.steps else None
        if last is not None and prev is not None and prev.z is None:
            # a level walk's steps stand on its level (stitch lifts them later): the crossing's
            # first step keeps that height under its stance foot, not the floor's
            h = workplace.levels.levels[parts[-1][0].level].height - workplace.floor_z
            last = replace(last, foot_z=h, stance_z=h)
        if c.kind == "winder":  # led in (or from standing) along its walk line
            walk = winder_cross_walk(c, leg.direction, walker, here, last, workplace.floor_z)
        else:
            walk = cross_walk(
                walked, leg.direction, walker, here, last, workplace.floor_z, lead_in=lead_in
            )
        parts.append((leg, walk))
        end_yaw = c.yaw if leg.direction == "up" else c.yaw + math.pi
        if c.kind == "winder":  # the heading off its far nosing
            end_yaw = float(walk.yaw[-1])
        stance = walked.end(c.upper if leg.direction == "up" else c.lower)
        pose = (float(stance[0]), float(stance[1]), end_yaw)
        foot = next_foot(walk.steps[-1].side if walk.steps else None)
    if not parts:
        raise PlanningError("start and goal are within reach already: there is no walk to plan")
    path = stitch(workplace, parts)
    path.meta["levels"] = level_meta(workplace, parts, limit)
    # the level walks' searches (the planning cost: :func:`_level_leg`)
    path.meta["expansions_all"] = sum(
        int(w.meta.get("expansions_all", 0)) for leg, w in parts if leg.kind == "level"
    )
    path.meta["goal"] = np.asarray(b.xy, dtype=float).tolist()
    path.meta["seconds"] = time.perf_counter() - t0  # the route, the level walks, the crossings
    return path.stamp_scene(workplace)
