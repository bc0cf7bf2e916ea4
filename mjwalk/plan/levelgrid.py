"""The grid-A* baseline of a walk over levels (issue 47: "the grid-A* baseline work per level").

A planner's deterministic tool walks between two points on different levels as one route: the
route over levels the level search finds for the walker (:func:`mjwalk.plan.levelsearch.
level_route`: which step, ramp or stair, from whose stance to whose), on each level the
shortest 8-connected grid route (:func:`mjwalk.plan.grid.plan_grid`) in that level's view
(:func:`mjwalk.world.levelview.level_view`: its surfaces, its obstacles up to the walker's
head) between the crossings' stances, and each crossing walked straight from stance to
stance. Its length is what the cycle report's ``vs A*`` compares a walk over levels with, as
:func:`~mjwalk.plan.grid.plan_grid`'s route for a walk on the floor. Metres, seconds; z is the
surface height above the floor, as in a walk over levels.
"""

from __future__ import annotations

import numpy as np

from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.grid import NOMINAL_SPEED, plan_grid
from mjwalk.plan.levelplan import Endpoint, endpoint
from mjwalk.plan.levelroute import RouteLeg, step_up_limit
from mjwalk.plan.levelsearch import level_route
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.levelview import level_at, level_view
from mjwalk.world.norms import HEAD_MARGIN
from mjwalk.world.workplace import Workplace


def level_grid_route(
    workplace: Workplace,
    start,
    goal,
    *,
    walker: Walker | None = None,
    max_riser: float | None = None,
    radius: float = BODY_RADIUS,
    cell: float = CELL_SIZE,
    speed: float = NOMINAL_SPEED,
) -> WalkPath:
    """The grid-A* route between two points on any levels (module docstring).

    Args:
        workplace: the scene.
        start: a site, "x,y" or (x, y) on its level (the highest surface there with room to
            stand), or (x, y, z) with z the world height it stands at (a walk's own end).
        goal: the same for the goal.
        walker: the walker the route over levels is found for (its stature, pace and stair
            gait; None: the reference adult).
        max_riser: the walker's step-up limit, metres (None:
            :func:`mjwalk.plan.levelroute.step_up_limit`'s default).
        radius: body radius, metres (the grid routes' clearance).
        cell: grid cell size, metres.
        speed: the speed (m/s) that gives the route its times.

    Returns:
        The route: the start, the grid routes' cell centres and the crossings' stances, the
        goal; ``z`` the surface height above the floor (linear along a crossing);
        ``meta["levels"]`` the levels walked and crossings taken, in order.

    Raises:
        PlanningError: an end on no level, no route over levels for the walker, or no grid
            route on a level.
    """
    walker = Walker() if walker is None else walker
    a, b = _end(workplace, start, "start"), _end(workplace, goal, "goal")
    if a.level == b.level:
        legs = [RouteLeg("level", a.level, a.xy, b.xy)]
    else:
        options = PlannerOptions(radius=radius)
        legs = level_route(workplace, a, b, walker, options, step_up_limit(walker, max_riser))
    head = walker.stature + HEAD_MARGIN
    heights = [lv.height - workplace.floor_z for lv in workplace.levels.levels]
    xy, z, route = [np.asarray(a.xy, dtype=float)[None]], [np.array([heights[a.level]])], []
    for leg in legs:
        if leg.kind == "level":
            view = level_view(workplace, leg.level, head)
            pts = plan_grid(view, leg.start, leg.end, cell=cell, radius=radius).xy[1:]
            z.append(np.full(len(pts), heights[leg.level]))
            route.append(f"L{leg.level}")
        else:
            c = leg.crossing
            assert c is not None  # a "cross" leg has its crossing
            top = c.upper if leg.direction == "up" else c.lower
            pts = np.asarray(leg.end, dtype=float)[None]
            z.append(np.array([heights[top]]))
            route.append(f"{c.kind} {leg.direction}")
        xy.append(pts)
    pts = np.vstack(xy)
    seg = np.diff(pts, axis=0)
    keep = np.concatenate([[True], np.hypot(seg[:, 0], seg[:, 1]) > 0.0])  # legs meet at stances
    pts, zs = pts[keep], np.concatenate(z)[keep]
    seg = np.diff(pts, axis=0)
    dist = np.concatenate([[0.0], np.cumsum(np.hypot(seg[:, 0], seg[:, 1]))])
    yaw = np.arctan2(seg[:, 1], seg[:, 0]) if len(seg) else np.zeros(0)
    yaw = np.unwrap(np.append(yaw, yaw[-1])) if len(yaw) else np.zeros(1)
    meta = {"planner": "grid_astar_levels", "cell": cell, "radius": radius, "levels": route}
    return WalkPath(t=dist / speed, xy=pts, yaw=yaw, meta=meta, z=zs).stamp_scene(workplace)


def _end(workplace: Workplace, where, what: str) -> Endpoint:
    """A start or goal on its level: (x, y, z) on the level at that height, else as
    :func:`mjwalk.plan.levelplan.endpoint` places it."""
    if isinstance(where, str) or len(where) != 3:
        return endpoint(workplace, where, what)
    xy = np.asarray(where, dtype=float)[:2]
    lv = level_at(workplace, xy, float(where[2]))
    if lv is None:
        raise PlanningError(
            f"{what} ({xy[0]:.3f}, {xy[1]:.3f}, z {float(where[2]):.3f}) stands on no level of "
            f"{workplace.name} (on a ramp or on no walk surface)"
        )
    return Endpoint(where, xy, int(lv))
