"""The route over levels: a Dijkstra over the crossings' stances, its edges made as it needs them.

:func:`level_route` finds a walk's legs over levels (:func:`mjwalk.plan.levelplan.plan_level_walk`,
step 1): the nodes are the walk's start and goal and each usable crossing's lower and upper
stance (usable: its risers within the walker's step-up limit, headroom for it, and treads that
hold its foot, :mod:`mjwalk.plan.treadshare` and :func:`mjwalk.plan.winderroute.foot_refusal`);
a crossing joins its two stances at its gait's time (:func:`mjwalk.plan.levelcross.
crossing_time`; a conforming winder, :func:`mjwalk.plan.winderroute.winder_time`), and two
nodes on one level are joined by the level walk between them, its
obstacle-aware distance (each node's distance field on the level's view,
:func:`mjwalk.plan.heuristic.goal_distance`) walked from standing to standing with the line-up
and departure of a stair (:func:`mjwalk.plan.levelcross.walked_distance`,
:func:`~mjwalk.plan.levelcross.level_time`) and the turn into a stair or winder as walked
(:func:`_entry`).

A node's edges are made when the search first pops it (:class:`_Edges`), in the order a table of
every edge would hold them, so the route is the one that table gives; a level whose nodes the
search never pops before the goal builds no view, no distance field and no line-up check (a walk
from the floor onto a platform does not set up the mezzanine behind a stair). Metres, seconds.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Iterator, Mapping

import numpy as np

from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.heuristic import goal_distance
from mjwalk.plan.levelcross import (
    ENTRY_TURN,
    arrival_heading,
    crossing_time,
    entry_time,
    flight_start,
    level_time,
    line_clear,
    route_leads,
    walked_distance,
)
from mjwalk.plan.levelroute import (
    Crossing,
    RouteLeg,
    crossing_headroom,
    crossings,
    dijkstra,
)
from mjwalk.plan.occupancy import CELL_SIZE, MOVES_16, shared_grid
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.treadshare import flight_notes, flight_refusal
from mjwalk.plan.turnin import turn_in_time, walked_back
from mjwalk.plan.winderroute import (
    foot_refusal,
    route_winders,
    winder_entry_time,
    winder_notes,
    winder_time,
)
from mjwalk.world.levelview import level_view
from mjwalk.world.norms import HEAD_MARGIN
from mjwalk.world.workplace import Workplace

#: Route legs shorter than this are not walked (the walker stands there already), metres.
STANCE_TOLERANCE = 0.15


def level_route(
    workplace: Workplace,
    start,
    goal,
    walker: Walker,
    options: PlannerOptions,
    max_riser: float,
) -> list[RouteLeg]:
    """The route over levels (module docstring), kept on the workplace per ends and walker.

    Args:
        workplace: the scene.
        start: the walk's start on its level (:class:`mjwalk.plan.levelplan.Endpoint`).
        goal: the walk's goal on its level (the same).
        walker: the walker (speed, stature, stair and ramp gait).
        options: the planner's options (body radius, goal field cells).
        max_riser: the walker's step-up limit, metres.

    Returns:
        The legs: walks on levels and crossings, in order.

    Raises:
        PlanningError: no route the walker can take.
    """
    cache = workplace.__dict__.setdefault("_routes", {})  # walks repeat their ends
    key = (
        start.level, *np.round(start.xy, 6), goal.level, *np.round(goal.xy, 6), walker,
        options, round(max_riser, 6),
    )  # fmt: skip
    if key not in cache:
        cache[key] = _route(workplace, start, goal, walker, options, max_riser)
    return list(cache[key])


class _Leads:
    """Each node's line-up and departure points (:func:`~mjwalk.plan.levelcross.route_leads`,
    kept where the body fits from the stance to them), made when first asked for: node ``k``'s
    is ``leads[k]``; the start's and goal's are (None, None)."""

    def __init__(self, workplace: Workplace, usable: list[Crossing], reach: float, setup):
        self.workplace, self.usable, self.reach = workplace, usable, reach
        self.options, self.head = setup
        self.known: dict[int, tuple] = {0: (None, None), 1: (None, None)}

    def __getitem__(self, k: int) -> tuple:
        if k not in self.known:
            c = self.usable[(k - 2) // 2]
            lv = c.lower if k % 2 == 0 else c.upper
            ends = route_leads(c, lv, self.reach)  # the line-up's point is set
            if ends[1] is not None:
                view = level_view(self.workplace, lv, self.head)
                if not line_clear(view, c.end(lv), ends[1], self.options.radius):
                    ends = (None, None)
            self.known[k] = ends
        return self.known[k]


class _Edges(Mapping):
    """The route graph's edges, node ``u``'s made when first asked for (``edges[u]``): its
    crossing's (a crossing stance) first, then the level walks to the other nodes on its level
    in node order (none from the goal, none to the start), each at its time."""

    def __init__(self, workplace: Workplace, route: tuple, walker: Walker, options, reach):
        self.workplace, self.walker, self.options, self.reach = workplace, walker, options, reach
        self.usable, self.nodes, self.leads = route
        self.head = walker.stature + HEAD_MARGIN
        self.known: dict[int, list[tuple[int, float]]] = {}

    def __len__(self) -> int:
        return len(self.nodes)

    def __iter__(self) -> Iterator[int]:
        return iter(range(len(self.nodes)))

    def __getitem__(self, u: int) -> list[tuple[int, float]]:
        if not 0 <= u < len(self.nodes):
            raise KeyError(u)
        if u not in self.known:
            self.known[u] = self._make(u)
        return self.known[u]

    def _make(self, u: int) -> list[tuple[int, float]]:
        out: list[tuple[int, float]] = []
        if u >= 2:  # the crossing between this stance and the other
            c = self.usable[(u - 2) // 2]
            timed = winder_time if c.kind == "winder" else crossing_time
            if u % 2 == 0:
                out.append((u + 1, timed(c, "up", self.walker)))
            else:
                out.append((u - 1, timed(c, "down", self.walker)))
        lu, uxy = self.nodes[u]
        if u == 1:
            return out  # nothing walks on from the goal
        for v, (lv, xy) in enumerate(self.nodes):
            if v in (0, u) or lv != lu:
                continue  # nothing walks to the start
            field = _node_field(self.workplace, lv, xy, self.head, self.options)
            d = _distance(self.workplace, field, uxy) if v >= 2 and u >= 2 else float(field(uxy))
            if math.isfinite(d):  # each level leg a walk from standing to standing
                ends = ((uxy, self.leads[u][0]), (xy, self.leads[v][1]))
                d = walked_distance(d, field, *ends, self.reach)
                far = float(np.hypot(*(uxy - xy))) > max(STANCE_TOLERANCE, self.reach[1])
                t = level_time(d, far, self.walker)
                if far and v >= 2:  # a stair's turn on the spot, as the leg comes in
                    route = (self.usable, self.nodes, self.leads)
                    t += _entry(self.workplace, route, (u, v), (self.walker, self.options))
                out.append((v, t))
        return out


def _route(workplace, start, goal, walker: Walker, options, max_riser):
    """:func:`level_route` without its cache."""
    head = walker.stature + HEAD_MARGIN
    clear = options.radius + CELL_SIZE
    usable = [
        c
        for c in [*_crossings(workplace, clear), *route_winders(workplace.levels, clear)]
        if c.fits(max_riser)
        and _head_fits(workplace, c, walker.stature)
        and foot_refusal(c, walker) is None  # a winder's treads hold the walker's foot
        and flight_refusal(c, walker) is None  # and a straight flight's
    ]
    # nodes: 0 start, 1 goal, then each crossing's lower and upper stance
    nodes = [(start.level, start.xy), (goal.level, goal.xy)]
    for c in usable:
        nodes += [(c.lower, c.end(c.lower)), (c.upper, c.end(c.upper))]
    reach = (walker.step_length, options.goal_tolerance)  # the line-up and departure
    leads = _Leads(workplace, usable, reach[0], (options, head))
    edges = _Edges(workplace, (usable, nodes, leads), walker, options, reach)
    path, _ = dijkstra(len(nodes), edges, 0, 1)
    if path is None:
        why = [
            *workplace.levels.notes,
            *flight_notes(_crossings(workplace, clear), walker),
            *winder_notes(workplace.levels, clear, walker, max_riser),
        ]
        notes = "".join(f"; {n}" for n in why)  # a ramp that links none, a winder stair
        raise PlanningError(
            f"no route from level L{start.level} to level L{goal.level} of {workplace.name} for "
            f"this walker (step-up limit {max_riser:.2f} m, stature {walker.stature:.2f} m)" + notes
        )
    return _legs(path, nodes, usable)


def _entry(workplace: Workplace, route: tuple, leg: tuple, setup: tuple) -> float:
    """What turning into the stair whose stance is route node ``leg[1]``, walked to from node
    ``leg[0]``, adds to the walk (s), arriving at the heading of :func:`~mjwalk.plan.levelcross.
    arrival_heading`: nothing within :data:`ENTRY_TURN`; else the turn into it while walking
    as the walk makes it (:func:`mjwalk.plan.turnin.turn_in_time`), or where no such turn fits
    the turn on the spot (:func:`~mjwalk.plan.levelcross.entry_time`); 0 before a step or
    ramp: its leg is searched again facing it (:func:`mjwalk.plan.levelplan._level_leg`).
    A winder's turn is its steps on the spot as its walk makes them (:func:`~mjwalk.plan.
    winderroute.winder_entry_time`). ``route``: (crossings, nodes, leads)."""
    (usable, nodes, leads), (u, v), (walker, options) = route, leg, setup
    c, (lv, uxy), xy = usable[(v - 2) // 2], nodes[u], nodes[v][1]
    if c.kind not in ("stair", "winder"):
        return 0.0
    ends = (uxy if leads[u][0] is None else leads[u][0], xy if leads[v][1] is None else leads[v][1])
    if float(np.hypot(*(xy - uxy))) <= walker.step_length + options.goal_tolerance:
        ends = (uxy, xy)  # walked between directly (walked_distance)
    head = walker.stature + HEAD_MARGIN
    field = functools.partial(_node_field, workplace, lv, uxy, head, options)
    view = level_view(workplace, lv, head)
    yaw = arrival_heading(view, ends, field, options.radius, walker.step_length)
    direction = "up" if v % 2 == 0 else "down"
    if c.kind == "winder":  # led in from its line-up point, turned on the spot there first
        return winder_entry_time(c, direction, walker, yaw)
    heading = c.yaw if direction == "up" else c.yaw + math.pi
    if abs(math.remainder(heading - yaw, math.tau)) <= ENTRY_TURN or leads[v][1] is None:
        return entry_time(c, direction, walker, yaw)  # 0 within ENTRY_TURN
    flight = (heading, flight_start(c, direction, walker))
    poses = walked_back(field(), ends[1], walker.step_length)
    turned = turn_in_time(view, poses, flight, walker, options.radius)
    return entry_time(c, direction, walker, yaw) if turned is None else turned


def _node_field(workplace: Workplace, level: int, xy: np.ndarray, head: float, options):
    """The distance field (:func:`mjwalk.plan.heuristic.goal_distance`) to a route node on its
    level's view, kept on the workplace per node, head height and planner grid."""
    cache = workplace.__dict__.setdefault("_node_fields", {})
    key: tuple = (level, float(xy[0]), float(xy[1]), round(head, 3))
    key += (options.radius, options.cell, options.field_cells)
    if key not in cache:
        view = level_view(workplace, level, head)
        grid = shared_grid(view, options.cell, options.radius, MOVES_16)
        cache[key] = goal_distance(grid, xy, options.field_cells)
    return cache[key]


def _distance(workplace: Workplace, field, xy: np.ndarray) -> float:
    """``field(xy)`` between two crossing stances, kept on the workplace."""
    cache = workplace.__dict__.setdefault("_node_distances", {})
    key = (id(field), float(xy[0]), float(xy[1]))
    return cache[key] if key in cache else cache.setdefault(key, float(field(xy)))


def _crossings(workplace: Workplace, clear: float) -> list[Crossing]:
    """:func:`mjwalk.plan.levelroute.crossings` of the workplace's levels, kept on it."""
    cache = workplace.__dict__.setdefault("_crossings", {})
    key = round(clear, 6)
    return cache[key] if key in cache else cache.setdefault(key, crossings(workplace.levels, clear))


def _head_fits(workplace: Workplace, c: Crossing, stature: float) -> bool:
    """:func:`mjwalk.plan.levelroute.head_fits_crossing`: the crossing's least free height
    (:func:`~mjwalk.plan.levelroute.crossing_headroom`) kept on the workplace, once for every
    stature, against the stature plus margin (the same comparison)."""
    cache = workplace.__dict__.setdefault("_crossing_headroom", {})
    if id(c) not in cache:
        cache[id(c)] = (c, crossing_headroom(workplace.levels, c))  # c held: its id stays its
    return not cache[id(c)][1] < stature + HEAD_MARGIN


def _legs(path: list[int], nodes, usable: list[Crossing]) -> list[RouteLeg]:
    """The route's legs from its Dijkstra nodes, a crossing between every two level legs.

    The route may pass through the stance of a crossing it does not take (the level walks'
    times, each from standing to standing with its line-up and turn into a stair, need not
    add up like distances): that stance is no place to stop, so the level walks on either side
    of it are one walk, from the first's start to the second's end, which the level's own
    search routes."""
    legs: list[RouteLeg] = []
    for u, v in itertools.pairwise(path):
        (lu, uxy), (_, vxy) = nodes[u], nodes[v]
        if u >= 2 and v >= 2 and (u - 2) // 2 == (v - 2) // 2:
            c = usable[(u - 2) // 2]
            direction = "up" if lu == c.lower else "down"
            legs.append(RouteLeg("cross", lu, uxy, vxy, c, direction))
        elif legs and legs[-1].kind == "level":  # through a stance not crossed (above)
            legs[-1] = RouteLeg("level", lu, legs[-1].start, vxy)
        else:
            legs.append(RouteLeg("level", lu, uxy, vxy))
    return legs
