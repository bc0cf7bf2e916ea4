"""Probabilistic hybrid A* (agethen2018 §3.4, §4.2, Algorithm 1).

Walks are stitched from steps sampled from a learned :class:`~mjwalk.gait.model.StepModel`: the
search starts with ``n_starters`` gait-initiation steps drawn from the model's KDE, and every
expansion draws ``n_successors`` continuations of the expanded step from its Gaussian-process
transition model. Cost is the walked length, step by step, each step counting its straight
start-to-end distance (``cost="chord"``, the paper's) or the swaying pelvis arc
(``cost="path"``, which favours the long, low-sway steps of fast walking). By default
(``cost="energy"``) each walking step's chord is weighted by the metabolic cost of walking at
its speed relative to the walker's preferred one (:func:`~mjwalk.plan.stepcost.step_energy`:
Ralston 1958, least at the preferred speed; not the starters and closing steps, which set off
from and come to a stand), and each walk has its own preferred speed about the walker's
(:data:`~mjwalk.plan.options.WALK_PACE_SD`): people hold their pace step to step (Dingwell,
John & Cusumano, PLoS Comput Biol 6:e1000856, 2010), which the transition GP, first-order in
one step's features, does not (``docs/decisions/101``). While the goal is in sight a step's
cost also grows with its heading error (:data:`~mjwalk.plan.options.HEADING_WEIGHT`).

The heuristic is the straight-line distance to the goal centre or, by default, the larger of
that and an obstacle-aware bound from a 2-D Dijkstra over a 16-connected occupancy grid divided
by the grid's worst detour factor (both admissible). The search weights the heuristic by 1.01
(weighted A*: a walk is at most 1 % longer than the best continuation of the sampled steps);
``heuristic_weight=1.0`` is the paper's plain A*. Walks starting farther than
:data:`~mjwalk.plan.options.LONG_WALK` from the goal weigh the heuristic of nodes far from it
more (:data:`~mjwalk.plan.options.FAR_WEIGHT`). A successor is rejected when any sample of its
pelvis trajectory comes closer to an obstacle (or the floor's edge) than the body radius, when
its foot, knees or landing leg come too close, when the stance leg cannot follow it, or when it
ends in a grid cell (0.08 m, optionally with heading bins) that is already closed (near the
goal: closed for walking on after :data:`~mjwalk.plan.options.NEAR_GOAL_EXPANSIONS`
expansions, never for a closing step). The limits and defaults are in
:mod:`mjwalk.plan.options`.

Because the steps are random, repeated plans between the same points differ — they form the
corridor real walks form — while a fixed ``rng`` seed reproduces a plan exactly.

The search loop (:func:`mjwalk.plan.search.search`) with its GP draws
(:mod:`mjwalk.gait.gpdraw`) and step checks (:mod:`mjwalk.plan.stepcheck`) is compiled with
numba (``docs/decisions/106``). Per draw it makes one affine map from features to the step's
geometry (:class:`~mjwalk.plan.decoder.StepDecoder`), one clearance lookup per checked point in
:meth:`Workplace.walk_field`, stopping at the first point that fails, and the GP's dense
variance. Python keeps the setup (endpoint checks, the start heading, the KDE starters) and the
found chain's 120 Hz decode (:func:`~mjwalk.plan.assemble.assemble_walk`).
"""

from __future__ import annotations

import math
import time

import numpy as np

from mjwalk._args import finite_points, parse_point
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import PlanningError
from mjwalk.plan import search, slots
from mjwalk.plan.assemble import assemble_walk
from mjwalk.plan.decoder import StepDecoder, decoder_of
from mjwalk.plan.detour import walk_guide
from mjwalk.plan.grid import (
    BODY_RADIUS,
    CELL_SIZE,
    MOVES_16,
    OccupancyGrid,
    check_endpoint,
    shared_grid,
)
from mjwalk.plan.guide import guide_is_clear, resample_guide
from mjwalk.plan.heuristic import GoalDistance, goal_distance
from mjwalk.plan.options import (
    ATTEMPTS,
    FAR_FROM,
    FAR_WEIGHT,
    FOOT_CLEARANCE,
    HEADING_WEIGHT,
    KNEE_CLEARANCE,
    LONG_WALK,
    MAX_EXPANSIONS,
    ON_SPOT_TURN_SPEED,
    SAFETY_MARGIN,
    START_SPREAD,
    STOP_REACH,
    WALK_PACE_SD,
    WANDER_FACTOR,
    WANDER_SEARCHES,
    kernel_params,
)
from mjwalk.plan.options import LEG_PROBE_STEP as LEG_PROBE_STEP  # re-exported
from mjwalk.plan.options import lean_params as lean_params  # re-exported
from mjwalk.plan.options import leg_clearance as leg_clearance  # re-exported
from mjwalk.plan.stepcost import downhill_costs
from mjwalk.plan.stepgeom import in_goal
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.clearance import ClearanceField
from mjwalk.world.workplace import Workplace

#: :meth:`HybridPlanner.default_heading`'s 72 directions (radians) and its probes 0.3 m out
#: along them (metres), made once.
_HEADING_ANGLES = np.linspace(-math.pi, math.pi, 72, endpoint=False)
_HEADING_PROBES = 0.3 * np.stack([np.cos(_HEADING_ANGLES), np.sin(_HEADING_ANGLES)], axis=1)


class _Exhausted(PlanningError):
    """The open list ran dry (all sampled continuations blocked): worth a fresh search."""


def _goal_discs(discs, goal: np.ndarray) -> np.ndarray:
    """(k, 3) goal discs (x, y, radius; metres) checked: finite, positive radii, at most
    :data:`~mjwalk.plan.slots.MAX_GOAL_DISCS` less one, and the goal itself inside every
    one (the goal area must not be empty where the walk is aimed)."""
    arr = np.asarray(discs, dtype=float).reshape(-1, 3) if len(discs) else np.zeros((0, 3))
    if len(arr) > slots.MAX_GOAL_DISCS - 1:  # one kept for a spot's walk (plan)
        raise PlanningError(
            f"goal_within: at most {slots.MAX_GOAL_DISCS - 1} discs, got {len(arr)}"
        )
    if not np.all(np.isfinite(arr)) or np.any(arr[:, 2] <= 0):
        raise PlanningError("goal_within: discs are (x, y, radius) with finite x, y and radius > 0")
    out = np.hypot(arr[:, 0] - goal[0], arr[:, 1] - goal[1]) > arr[:, 2]
    if out.any():
        k = int(np.flatnonzero(out)[0])
        raise PlanningError(
            f"goal_within: the goal ({goal[0]:.3f}, {goal[1]:.3f}) lies outside disc {k} "
            f"({arr[k, 0]:.3f}, {arr[k, 1]:.3f}, radius {arr[k, 2]:.3f} m)"
        )
    return arr


def _parse_pose(workplace: Workplace, where) -> tuple[np.ndarray, float | None]:
    """(x, y) and an optional yaw from a site name, "x,y[,yaw_deg]" or a tuple (x, y[, yaw])."""
    if isinstance(where, str) and where.count(",") == 2 and where not in workplace.stations:
        xyyaw = parse_point(where, f"{workplace.name}: pose (x,y,yaw_deg)", n=3)
        if xyyaw is not None:
            return xyyaw[:2].copy(), math.radians(float(xyyaw[2]))
    if not isinstance(where, str):
        arr = np.asarray(where, dtype=float).ravel()
        if arr.size == 3:
            finite_points(arr, f"{workplace.name}: pose (x, y, yaw)")
            return arr[:2].copy(), float(arr[2])
    return workplace.point(where), None


def preferred_speed(model) -> float:
    """The preferred straight-walk speed (m/s) the energy cost is least at: the walker's a
    model was conditioned on (:meth:`~mjwalk.gait.model.StepModel.for_walker`), else the
    model's own steady pace (:meth:`~mjwalk.gait.model.StepModel.pace`)."""
    walker = getattr(model, "walker", None)
    if walker is not None:
        return float(walker.speed)
    return float(model.pace().speed)


class HybridPlanner:
    """Reusable planning context for one workplace, model and goal.

    Building it costs the Dijkstra distance field (and, once per workplace, cell size and
    radius, the 16-connected occupancy grid: :func:`~mjwalk.plan.grid.shared_grid`);
    :meth:`plan` then only samples and searches. :func:`plan_walk` and :func:`plan_walks` wrap
    it.

    ``field_tolerance`` (metres; None: ``goal_tolerance``): the goal cells the distance field
    starts from. The field measures the way to the goal centre either way; planners of one goal
    with different goal areas (a stand zone per operator) share one field when they give the
    same ``field_tolerance`` (:func:`~mjwalk.plan.heuristic.goal_distance` keeps a field per
    goal cells: in a 100 m hall a field takes about a second).
    """

    def __init__(
        self,
        workplace: Workplace,
        goal,
        model,
        *,
        goal_tolerance: float = 0.25,
        goal_yaw: float | None = None,
        goal_yaw_tolerance: float = math.radians(30.0),
        radius: float = BODY_RADIUS,
        cell: float = CELL_SIZE,
        heading_bins: int | None = None,
        n_starters: int = 30,
        n_successors: int = 10,
        heuristic: str = "dijkstra",
        max_expansions: int = MAX_EXPANSIONS,
        samples_per_step: int = 16,
        heuristic_weight: float = 1.01,
        far_weight: float = FAR_WEIGHT,
        cost: str = "energy",
        attempts: int = ATTEMPTS,
        heading_weight: float = HEADING_WEIGHT,
        grid: OccupancyGrid | None = None,
        n_stops: int = 5,
        goal_within=(),
        field_tolerance: float | None = None,
    ):
        if heuristic not in ("dijkstra", "euclidean"):
            raise PlanningError(f"heuristic must be 'dijkstra' or 'euclidean', not {heuristic!r}")
        self.workplace = workplace
        self.model = model
        goal_xy, _ = _parse_pose(workplace, goal)
        self.goal = goal_xy
        self.goal_yaw = goal_yaw
        self.goal_yaw_tolerance = goal_yaw_tolerance
        self.tolerance = goal_tolerance
        self.goal_within = _goal_discs(goal_within, self.goal)
        self.radius = radius
        self.cell = cell
        if heading_bins is None:  # a goal heading needs nodes of other headings kept apart
            heading_bins = 1 if goal_yaw is None else 8
        self.heading_bins = max(1, int(heading_bins))
        self.n_starters = n_starters
        self.n_successors = n_successors
        self.heuristic = heuristic
        self.max_expansions = max_expansions
        self.samples_per_step = samples_per_step
        if heuristic_weight < 1.0:
            raise PlanningError(f"heuristic_weight must be >= 1, not {heuristic_weight}")
        self.heuristic_weight = heuristic_weight
        if far_weight < 0.0:
            raise PlanningError(f"far_weight must be >= 0, not {far_weight}")
        self.far_weight = far_weight
        if cost not in ("chord", "path", "energy"):
            raise PlanningError(f"cost must be 'chord', 'path' or 'energy', not {cost!r}")
        self.cost = cost
        self.attempts = max(1, int(attempts))
        if not heading_weight >= 0.0:
            raise PlanningError(f"heading_weight must be >= 0, not {heading_weight}")
        self.heading_weight = float(heading_weight)
        # closing steps near the goal, when the model has them (module constant STOP_REACH)
        self.n_stops = max(0, int(n_stops)) if getattr(model, "can_stop", False) else 0
        check_endpoint(workplace, self.goal, radius, "goal")
        if grid is None or grid.cell != cell or grid.radius != radius:
            grid = shared_grid(workplace, cell, radius, MOVES_16)
        self.grid = grid
        self.distance: GoalDistance = goal_distance(
            grid, self.goal, goal_tolerance if field_tolerance is None else field_tolerance
        )
        self.walk_field = workplace.walk_field()  # its clearance field
        # per checked point of a successor: m pelvis samples, the landing ankle and its toes,
        # the swing knee at half and three quarters of the step
        self._thresholds = np.array(
            [radius + SAFETY_MARGIN] * samples_per_step
            + [FOOT_CLEARANCE] * 2
            + [KNEE_CLEARANCE] * 2
        )
        self._params: dict[float, tuple[np.ndarray, np.ndarray]] = {}
        self._kernel_params()  # the default walker's, with the distance field: per goal

    def _kernel_params(self, stature: float = DEFAULT_STATURE) -> tuple[np.ndarray, np.ndarray]:
        """The float and integer parameter vectors of :func:`~mjwalk.plan.stepcheck.check_steps`
        for a walker of ``stature`` metres (the landing leg's clearance scales with it); fresh
        copies of the ones made on this planner's first plan for that stature."""
        held = self._params.get(stature)
        if held is None:
            held = self._params[stature] = kernel_params(self, stature)
        return held[0].copy(), held[1].copy()

    def _check_spot(self, spot) -> tuple[float, float, float]:
        """``spot`` of :meth:`plan` as floats, checked: finite, a positive tolerance, and in
        the planner's goal area (within its tolerance of the goal and inside every goal disc)."""
        try:
            x, y, tol = (float(v) for v in spot)
        except (TypeError, ValueError):
            raise PlanningError(f"spot must be (x, y, tolerance) in metres, got {spot!r}") from None
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(tol) and tol > 0):
            raise PlanningError(f"spot must be finite with a tolerance > 0, got {spot!r}")
        inside = math.hypot(x - self.goal[0], y - self.goal[1]) <= self.tolerance + 1e-9 and all(
            math.hypot(x - dx, y - dy) <= dr + 1e-9 for dx, dy, dr in self.goal_within
        )
        if not inside:
            raise PlanningError(
                f"spot ({x:.3f}, {y:.3f}) lies outside the goal area of the planner (within "
                f"{self.tolerance} m of ({self.goal[0]:.3f}, {self.goal[1]:.3f}) and its "
                f"{len(self.goal_within)} goal discs)"
            )
        return x, y, tol

    def _decoder(self, model=None) -> StepDecoder:
        return decoder_of(self.model if model is None else model, self.samples_per_step)

    # -- helpers ---------------------------------------------------------------------------

    def h(self, xy: np.ndarray) -> np.ndarray:
        """Weighted heuristic (metres) at points (..., 2): ``heuristic_weight`` times h, plus
        ``far_weight`` times its excess over :data:`FAR_FROM` (the search adds the latter
        only on walks starting beyond :data:`LONG_WALK`)."""
        h = self._h(xy)
        return self.heuristic_weight * h + self.far_weight * np.maximum(h - FAR_FROM, 0.0)

    def _h(self, xy: np.ndarray) -> np.ndarray:
        if self.heuristic == "dijkstra":
            return self.distance(xy)
        return np.hypot(xy[..., 0] - self.goal[0], xy[..., 1] - self.goal[1])

    def default_heading(self, xy: np.ndarray, goal=None) -> float:
        """Direction in which the obstacle-aware distance to the goal falls fastest (radians):
        the larger of the goal's field and the straight line to the goal point (``goal``: x, y
        of another point in the goal area, a walk's spot; None: the planner's goal)."""
        gx, gy = (float(self.goal[0]), float(self.goal[1])) if goal is None else goal
        # the field measures the way to the planner's goal; the way to another point is at
        # least that less the straight line between the two (triangle inequality; a spot and
        # its goal see each other in a stand zone)
        offset = math.hypot(gx - self.goal[0], gy - self.goal[1])
        wp, g, c = self.workplace, self.grid, self.workplace.clearance
        if not isinstance(c, ClearanceField):  # another clearance model: its own lookup
            probe = xy + _HEADING_PROBES
            free = wp.walk_clearance(probe) >= self.radius
            # (the field's bound is at least the straight line to the goal centre: for the
            # goal itself, offset 0, the larger of the two is the field's)
            dist = np.maximum(self.distance(probe) - offset, np.hypot(*(probe - (gx, gy)).T))
            cost = dist + np.where(free, 0.0, 1e3)
            return float(_HEADING_ANGLES[int(np.argmin(cost))])
        cost = downhill_costs(
            np.asarray(xy, dtype=float), _HEADING_PROBES, c.values, c.x0, c.y0, c.resolution,
            np.asarray(wp.floor_bounds, dtype=float), float(self.radius),
            self.distance.flat_bound(), g.x0, g.y0, g.cell, g.free.shape[1] - 1.0,
            g.free.shape[0] - 1.0, gx, gy, offset,
        )  # fmt: skip
        return float(_HEADING_ANGLES[int(np.argmin(cost))])

    # -- search ----------------------------------------------------------------------------

    def plan(
        self,
        start,
        rng: np.random.Generator,
        *,
        model=None,
        spot=None,
        turn_on_spot=False,
        goal_heading: float | None = None,
        guide=None,
    ) -> WalkPath:
        """Plan one walk from ``start`` (site, "x,y", "x,y,yaw_deg" or (x, y[, yaw])).

        ``model``: sample the steps from this step model instead of the planner's (e.g. the
        planner's model conditioned on the run's operator, :meth:`StepModel.for_walker`); the
        goal's distance field and grid are shared. It must have the planner model's feature
        dimensions and GPs (a conditioned copy does).

        ``spot``: (x, y, tolerance), metres: this walk ends within ``tolerance`` of the point
        (x, y) and in the planner's goal area (within its goal tolerance of its goal and its
        goal discs, ``goal_within``); the point must lie in that area (where the walker means
        to stand in a stand zone: :func:`mjwalk.cycle.walking.plan_task_walk`). The distance
        field stays the goal's: a spot costs no new field.

        ``turn_on_spot`` (with a start yaw): the walker stands facing the start yaw and sets
        off as without one (its first step anywhere within :data:`START_SPREAD` of the
        downhill heading, :meth:`default_heading`), but the turn on the spot from the start
        yaw to the first step's heading costs its time at :data:`ON_SPOT_TURN_SPEED` times
        the walk's pace (metres, as the steps), against the heading term
        (:data:`HEADING_WEIGHT`) of setting off away from the goal: the search weighs turning
        first against turning while walking. The draws are those of a walk without a yaw.
        Without it a start yaw is the heading of the first step's frame (a walker already
        walking that way). The walk's
        first sample faces where the turn ended (``yaw[0]``): the turn itself is the caller's
        (the cycle animates it).

        ``goal_heading`` (world radians; None: none): the heading the walker means to arrive
        at (facing the work after the walk). Unlike the planner's ``goal_yaw`` it is no
        condition of the goal: it shapes the smooth path the walk's heading follows
        (:mod:`mjwalk.plan.guide`: the minimum-jerk curve between the start pose, a walking
        start's heading or the straight line for a standing one, and the goal pose), so the
        walk bends into it as people's do rather than turning at the end. The guide is used
        where it keeps the body's clearance and the goal is in sight from the start.
        ``guide`` ((k, 2) metres, from near the start to near the goal): the caller's own
        path for the heading to follow instead (e.g. a minimum-jerk curve between two
        poses on the way, :func:`mjwalk.plan.guide.minimum_jerk_guide`), on the same terms.

        When the open list runs dry (every sampled continuation blocked, which happens now and
        then in tight places), the search starts over with fresh samples, up to ``attempts``
        times in all; a spent expansion budget ends the planning at once. A walk that loops
        (:data:`WANDER_FACTOR`) is searched again too, up to :data:`WANDER_SEARCHES` searches
        in all, and the shortest is kept.
        """
        if spot is not None:  # checked once, before any search
            spot = self._check_spot(spot)
        if goal_heading is not None:
            try:
                goal_heading = float(goal_heading)
            except (TypeError, ValueError):
                goal_heading = math.nan
            if not math.isfinite(goal_heading):
                raise PlanningError(f"goal_heading must be finite radians, got {goal_heading!r}")
        if guide is not None:
            try:
                guide = resample_guide(guide)
            except (TypeError, ValueError) as exc:
                raise PlanningError(f"guide: {exc}") from None
        pose = _parse_pose(self.workplace, start)  # parsed once, before any draw
        t0 = time.perf_counter()
        model = model or self.model
        pace = math.nan
        if self.cost == "energy":  # this walk's own pace (WALK_PACE_SD)
            pace = preferred_speed(model) * math.exp(WALK_PACE_SD * rng.standard_normal())
        if self.heading_weight > 0.0:  # the way the walk's heading follows
            guide = self._guide(pose, spot, turn_on_spot, goal_heading, guide, rng, model)
            if guide is not None and not guide_is_clear(self.workplace, guide, self.radius):
                guide = None  # the route search decides
        best: WalkPath | None = None
        bound = None
        limit = max(self.attempts, WANDER_SEARCHES)
        exhausted = 0
        for attempt in range(limit):
            try:
                path, start_distance = self._plan_once(
                    pose, rng, model, spot, pace, turn_on_spot, guide
                )
            except _Exhausted as exc:
                exhausted += 1
                guide = None  # a dead end along the guide: the route search decides from now
                if exhausted >= self.attempts or attempt == limit - 1:
                    if best is not None:
                        break
                    raise PlanningError(
                        f"{exc} ({exhausted} searches with fresh samples)"
                    ) from None
                continue
            path.meta["attempts"] = attempt + 1
            path.meta["seconds"] = time.perf_counter() - t0  # all searches, not the last one
            if bound is None:
                tolerance = self.tolerance if spot is None else spot[2]
                bound = WANDER_FACTOR * max(start_distance, tolerance)
            path.meta["wandering"] = bool(path.length > bound)
            if not path.meta["wandering"]:
                return path
            if best is None or path.length < best.length:
                best = path  # a loop: try fresh samples, keep the shortest
        assert best is not None  # a search returned, or the last attempt raised
        best.meta["seconds"] = time.perf_counter() - t0
        best.meta["searches"] = attempt + 1
        return best

    def _plan_once(
        self,
        pose,
        rng: np.random.Generator,
        model,
        spot=None,
        pace: float = math.nan,
        turn_on_spot: bool = False,
        guide: np.ndarray | None = None,
    ) -> tuple[WalkPath, float]:
        """One search: the walk and the obstacle-aware distance (m) from its start to the goal
        (to the ``spot`` of :meth:`plan`, checked there, when given). ``pose``: the start's
        (x, y) and optional yaw, as :meth:`plan` parsed it."""
        start_xy, start_yaw = pose
        check_endpoint(self.workplace, start_xy, self.radius, "start")
        # infinite exactly where GoalDistance.reachable is False (the same nearest cell)
        start_distance = float(self.distance(start_xy))
        if not math.isfinite(start_distance):
            raise PlanningError(
                f"goal ({self.goal[0]:.3f}, {self.goal[1]:.3f}) is unreachable from start "
                f"({start_xy[0]:.3f}, {start_xy[1]:.3f}) in {self.workplace.name}: no "
                f"collision-free route for body radius {self.radius} m"
            )
        free_heading = start_yaw is None or turn_on_spot
        facing = start_yaw  # the heading the walker stands at before any turn on the spot
        if free_heading:
            start_yaw = self.default_heading(start_xy, None if spot is None else spot[:2])
        dec = self._decoder(model)
        walker = getattr(model, "walker", None)  # a model conditioned on the run's operator
        stature = float(getattr(walker, "stature", None) or DEFAULT_STATURE)
        par, ipar = self._kernel_params(stature)
        par[slots.P_PACE] = pace
        goal_x, goal_y, tolerance = float(self.goal[0]), float(self.goal[1]), self.tolerance
        field_distance = start_distance
        if spot is not None:  # this walk's own goal point (module doc of plan)
            goal_x, goal_y, tolerance = spot
            par[slots.P_GOAL_X] = goal_x
            par[slots.P_GOAL_Y] = goal_y
            par[slots.P_TOLERANCE] = tolerance
            par[slots.P_STOP_REACH] = tolerance + STOP_REACH
            par[slots.P_HEADING_FROM] = tolerance + STOP_REACH
            # the goal's field bounds the way to the spot from below only less the way between
            # them (triangle inequality; a spot sees its goal in a stand zone)
            offset = math.hypot(goal_x - self.goal[0], goal_y - self.goal[1])
            par[slots.P_DIST_OFFSET] = offset
            field_distance -= offset
            # ... and the walk still ends in the planner's own goal area: one more disc
            k = int(ipar[slots.I_N_DISCS])
            j = slots.P_DISC0 + 3 * k
            par[j : j + 3] = (float(self.goal[0]), float(self.goal[1]), self.tolerance)
            ipar[slots.I_N_DISCS] = k + 1
            start_distance = max(
                field_distance, math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y) - tolerance
            )
        if guide is not None and par[slots.P_HEADING_WEIGHT] > 0.0:  # clear (plan checked)
            par[slots.P_GUIDE0 : slots.P_DISC0] = guide.ravel()
        if math.isnan(par[slots.P_GUIDE0]) and not self.distance.sees(start_xy):
            # HEADING_WEIGHT without a guide: only for a goal in sight from the start
            par[slots.P_HEADING_WEIGHT] = 0.0
        if in_goal(complex(*start_xy), start_yaw, par, ipar):
            raise PlanningError(
                f"start ({start_xy[0]:.3f}, {start_xy[1]:.3f}) already lies in the goal area "
                f"(within {tolerance} m of ({goal_x:.3f}, {goal_y:.3f})): "
                "there is no walk to plan"
            )
        # the starters, for the first expansion (the start node's)
        z0, side0 = model.sample_first_features(self.n_starters, rng)
        frame0 = np.full(len(z0), float(start_yaw))
        if free_heading:  # the walker may set off anywhere around the downhill heading
            frame0 += rng.uniform(-START_SPREAD, START_SPREAD, len(frame0))
        if turn_on_spot and facing is not None:  # the turn there from the walker's heading
            walk_pace = pace if math.isfinite(pace) else preferred_speed(model)
            par[slots.P_START_YAW] = float(facing)
            par[slots.P_TURN_COST] = walk_pace / ON_SPOT_TURN_SPEED
        weight = self.heuristic_weight
        # as stepcheck.check_steps bounds a node: the field's distance, the straight line to
        # the goal point
        h0 = field_distance if self.heuristic == "dijkstra" else 0.0
        euclid = float(math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y))
        h_start = max(h0, euclid)
        far = self.far_weight if h_start > LONG_WALK else 0.0  # only long walks
        par[slots.P_FAR_WEIGHT] = far
        f0 = weight * h_start  # as stepcheck.check_steps scores a node
        if h_start > FAR_FROM:
            f0 += far * (h_start - FAR_FROM)
        gps = (model.gp["left"].kernel, model.gp["right"].kernel)
        stops = (model.stop_gp["left"].kernel, model.stop_gp["right"].kernel) if (
            self.n_stops
        ) else gps  # fmt: skip
        outcome, goal_node, stats, *nodes = search.search(
            np.ascontiguousarray(z0, dtype=float),
            frame0,
            np.ascontiguousarray(side0 == "left"),
            complex(*start_xy),
            float(start_yaw),
            f0,
            gps,
            stops,
            rng,
            dec.matrix,
            dec.offset,
            self._thresholds,
            par,
            ipar,
            self.walk_field.values,
            self.distance.flat_bound(),
        )
        expansions, generated, rejected, stop_draws = stats.tolist()
        if outcome == search.BUDGET:
            raise PlanningError(
                f"expansion budget of {self.max_expansions} spent before reaching the "
                f"goal ({goal_x:.3f}, {goal_y:.3f}) from "
                f"({start_xy[0]:.3f}, {start_xy[1]:.3f}); {generated} steps sampled, "
                f"{rejected} rejected"
            )
        if outcome == search.EXHAUSTED:
            raise _Exhausted(
                f"search exhausted after {expansions} expansions: no sequence of sampled "
                f"steps reached the goal ({goal_x:.3f}, {goal_y:.3f}) from "
                f"({start_xy[0]:.3f}, {start_xy[1]:.3f}) without coming closer than "
                f"{self.radius} m to an obstacle"
            )
        parent, rows, pos, frames, lefts, feats, closing = nodes
        path = self._assemble(
            model,
            goal_node,
            (parent, rows, pos, frames, lefts),
            feats,
            {
                "expansions": expansions,
                "generated": generated,
                "rejected": rejected,
                "stop_draws": stop_draws,
                # whether the walk ends with a closing step (StepModel.sample_stop)
                "closing_step": bool(closing[rows[goal_node]]),
                **({} if spot is None else {"spot": [goal_x, goal_y], "spot_tolerance": tolerance}),
            },
        )
        return path, start_distance

    def _guide(self, pose, spot, turn_on_spot, goal_heading, guide, rng, model):
        """:func:`mjwalk.plan.detour.walk_guide` for a walk of :meth:`plan` (a start yaw is a
        walker already walking unless ``turn_on_spot``)."""
        (x, y), yaw = pose
        walking = None if yaw is None or turn_on_spot else yaw
        goal = self.goal if spot is None else spot[:2]
        walker = getattr(model, "walker", None)
        stature = float(getattr(walker, "stature", None) or DEFAULT_STATURE)
        step = float(walker.step_length if walker is not None else model.pace().step_length)
        return walk_guide(
            self.workplace, (x, y), goal, walking, goal_heading, guide, self.radius, rng,
            stature, step,
        )  # fmt: skip

    def _assemble(self, model, nid, nodes, feats, stats) -> WalkPath:
        meta = {
            "planner": "hybrid_astar",
            "goal": self.goal.tolist(),
            "goal_tolerance": self.tolerance,
            "radius": self.radius,
            "heuristic": self.heuristic,
            **stats,
        }
        return assemble_walk(model, nid, nodes, feats, meta).stamp_scene(self.workplace)
