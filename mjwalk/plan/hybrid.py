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
by the grid's worst detour factor (both admissible; ``field_sway``: :func:`~mjwalk.plan.
heuristic.walkable_distance`). The search weights the heuristic by 1.01 (weighted A*: a walk
is at most 1 % longer than the best continuation of the sampled steps);
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
from dataclasses import replace

import numpy as np

from mjwalk._args import finite_points, parse_point
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import PlanningError
from mjwalk.gait.model import StepModel
from mjwalk.plan import search
from mjwalk.plan.assemble import assemble_walk
from mjwalk.plan.decoder import StepDecoder, decoder_of
from mjwalk.plan.detour import GuideBody, walk_guide
from mjwalk.plan.guide import guide_is_clear, guide_start_heading
from mjwalk.plan.heuristic import PELVIS_SWAY, GoalDistance, walkable_distance
from mjwalk.plan.occupancy import MOVES_16, check_endpoint, shared_grid
from mjwalk.plan.options import (
    FAR_FROM,
    LONG_WALK,
    SAFETY_MARGIN,
    START_SPREAD,
    WALK_PACE_SD,
    WANDER_FACTOR,
    WANDER_SEARCHES,
    PlannerOptions,
)
from mjwalk.plan.params import KernelParams, WalkTerms, goal_discs, spot_offset
from mjwalk.plan.request import WalkRequest
from mjwalk.plan.stepcost import downhill_costs
from mjwalk.plan.stepgeom import in_goal
from mjwalk.plan.turnsplit import starter_frames
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.clearance import ClearanceField
from mjwalk.world.workplace import Workplace

#: :meth:`HybridPlanner.default_heading`'s 72 directions (radians) and its probes 0.3 m out
#: along them (metres), made once.
_HEADING_ANGLES = np.linspace(-math.pi, math.pi, 72, endpoint=False)
_HEADING_PROBES = 0.3 * np.stack([np.cos(_HEADING_ANGLES), np.sin(_HEADING_ANGLES)], axis=1)


class _Exhausted(PlanningError):
    """The open list ran dry (all sampled continuations blocked): worth a fresh search.
    ``expansions``: what the search spent."""

    expansions = 0


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


def preferred_speed(model: StepModel) -> float:
    """The preferred straight-walk speed the energy cost is least at.

    Args:
        model: the step model; its :attr:`~mjwalk.gait.model.StepModel.walker` is the walker
            it was conditioned on (:meth:`~mjwalk.gait.model.StepModel.for_walker`) or None.

    Returns:
        The conditioning walker's speed (m/s), else the model's own steady pace's
        (:meth:`~mjwalk.gait.model.StepModel.pace`).
    """
    walker = model.walker
    if walker is not None:
        return float(walker.speed)
    return float(model.pace().speed)


def walker_stature(model: StepModel) -> float:
    """The stature the planner checks a walk's body for.

    Args:
        model: the step model; its :attr:`~mjwalk.gait.model.StepModel.walker` is the walker
            it was conditioned on or None.

    Returns:
        The conditioning walker's stature (m), else :data:`~mjwalk.conventions.DEFAULT_STATURE`.
    """
    walker = model.walker
    return DEFAULT_STATURE if walker is None else float(walker.stature)


def walker_step_length(model: StepModel) -> float:
    """The step length a walk's guide may turn no sharper than (:func:`~mjwalk.plan.detour.
    walkable`).

    Args:
        model: the step model; its :attr:`~mjwalk.gait.model.StepModel.walker` is the walker
            it was conditioned on or None.

    Returns:
        The conditioning walker's preferred step length (m), else the model's own steady
        pace's.
    """
    walker = model.walker
    return float(walker.step_length if walker is not None else model.pace().step_length)


class HybridPlanner:
    """Reusable planning context for one workplace, model and goal.

    Building it costs the Dijkstra field(s) (:func:`~mjwalk.plan.heuristic.walkable_distance`;
    once per workplace, cell and radius, the grids: :func:`~mjwalk.plan.occupancy.shared_grid`);
    :meth:`plan` then only samples and searches. :func:`plan_walk` and :func:`plan_walks` wrap
    it.

    Args:
        workplace: the scene.
        goal: a site name, ``"x,y"`` or ``(x, y)`` (metres); walks end within
            ``options.goal_tolerance`` of it.
        model: the :class:`~mjwalk.gait.model.StepModel` the steps are drawn from.
        options: how to plan (:class:`~mjwalk.plan.options.PlannerOptions`; None: the
            defaults). Planners of one goal with different goal areas (a stand zone per
            operator) share one distance field when they give the same ``field_tolerance``
            (:func:`~mjwalk.plan.heuristic.goal_distance` keeps a field per goal cells: in a
            100 m hall a field takes about a second).

    Raises:
        PlanningError: the goal off the floor, in or too near an obstacle, or outside one of
            the goal discs (before any search).
    """

    def __init__(
        self, workplace: Workplace, goal, model: StepModel, options: PlannerOptions | None = None
    ):
        options = PlannerOptions() if options is None else options
        if options.n_stops and not getattr(model, "can_stop", False):
            options = replace(options, n_stops=0)  # closing steps only where the model has them
        self.options = options
        self.workplace = workplace
        self.model = model
        goal_xy, _ = _parse_pose(workplace, goal)
        self.goal = goal_xy
        self.goal_within = goal_discs(options, self.goal)
        self.radius = options.radius
        check_endpoint(workplace, self.goal, self.radius, "goal")
        self.grid = shared_grid(workplace, options.cell, self.radius, MOVES_16)
        sway = self.radius + SAFETY_MARGIN + PELVIS_SWAY  # passages the steps get through
        roomy = shared_grid(workplace, options.cell, sway, MOVES_16) if options.field_sway else None
        self.distance: GoalDistance = walkable_distance(
            self.grid, roomy or self.grid, self.goal, options.field_cells
        )
        self.walk_field = workplace.walk_field()  # its clearance field
        # (the kernels' vectors are made for a walker's stature on its first walk: a cycle's
        # planner serves one operator, seldom of the default stature)
        self.params = KernelParams(
            options, self.goal, self.goal_within, self.grid, self.walk_field, self.distance
        )

    def _check_spot(self, spot: tuple[float, float, float]) -> None:
        """Refuse a walk's ``spot`` (:class:`~mjwalk.plan.request.WalkRequest`) outside the
        planner's goal area (within its tolerance of the goal and inside every goal disc)."""
        x, y, _ = spot
        tolerance = self.options.goal_tolerance
        inside = math.hypot(x - self.goal[0], y - self.goal[1]) <= tolerance + 1e-9 and all(
            math.hypot(x - dx, y - dy) <= dr + 1e-9 for dx, dy, dr in self.goal_within
        )
        if not inside:
            raise PlanningError(
                f"spot ({x:.3f}, {y:.3f}) lies outside the goal area of the planner (within "
                f"{tolerance} m of ({self.goal[0]:.3f}, {self.goal[1]:.3f}) and its "
                f"{len(self.goal_within)} goal discs)"
            )

    def decoder(self, model=None) -> StepDecoder:
        """The affine map of ``model``'s step features (None: the planner's model) to the
        checked geometry of a step of ``samples_per_step`` samples.

        Args:
            model: the step model; None: the planner's.

        Returns:
            The model's :class:`~mjwalk.plan.decoder.StepDecoder` (shared, :func:`decoder_of`).
        """
        return decoder_of(self.model if model is None else model, self.options.samples_per_step)

    # -- helpers ---------------------------------------------------------------------------

    def h(self, xy: np.ndarray) -> np.ndarray:
        """Weighted heuristic (metres) at points (..., 2): ``heuristic_weight`` times h, plus
        ``far_weight`` times its excess over :data:`FAR_FROM` (the search adds the latter
        only on walks starting beyond :data:`LONG_WALK`).

        Args:
            xy: (..., 2) points, metres, world frame.

        Returns:
            (...) the weighted heuristic, metres.
        """
        h, o = self._h(xy), self.options
        return o.heuristic_weight * h + o.far_weight * np.maximum(h - FAR_FROM, 0.0)

    def _h(self, xy: np.ndarray) -> np.ndarray:
        if self.options.heuristic == "dijkstra":
            return self.distance(xy)
        return np.hypot(xy[..., 0] - self.goal[0], xy[..., 1] - self.goal[1])

    def default_heading(self, xy: np.ndarray, goal=None) -> float:
        """Direction in which the obstacle-aware distance to the goal falls fastest (radians):
        the larger of the goal's field and the straight line to the goal point (``goal``: x, y
        of another point in the goal area, a walk's spot; None: the planner's goal).

        Args:
            xy: (2,) the walker's point, metres, world frame.
            goal: (x, y) of another point in the goal area, metres; None: the planner's goal.

        Returns:
            The heading, radians from +x CCW (one of 72 directions).
        """
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

    def plan(self, walk, rng: np.random.Generator) -> WalkPath:
        """Plan one walk: ``walk`` is a :class:`~mjwalk.plan.request.WalkRequest` or its start
        alone (site, "x,y", "x,y,yaw_deg" or (x, y[, yaw]); metres, radians).

        The request's ``model`` samples the steps instead of the planner's; the goal's distance
        field and grid are shared. A ``spot`` ends the walk within its tolerance of its point
        and in the planner's goal area (within its goal tolerance of its goal and its goal
        discs, ``goal_within``; where the walker means to stand in a stand zone:
        :func:`mjwalk.cycle.walking.plan_task_walk`); the distance field stays the goal's, a
        spot costs no new field.

        With ``turn_on_spot`` and a start yaw the walker stands facing the start yaw and sets
        off as without one (its first step anywhere within :data:`START_SPREAD` of the
        downhill heading, :meth:`default_heading`), but the turn on the spot from the start yaw
        to the first step's heading costs its time at
        :data:`~mjwalk.plan.options.ON_SPOT_TURN_SPEED` times the walk's pace (metres, as the
        steps), against the heading term (:data:`~mjwalk.plan.options.HEADING_WEIGHT`) of
        setting off away from the goal: the search weighs turning first against turning while
        walking. With ``at_work`` (a walker standing at the work it faced) a turn of more than
        a quarter is split (:mod:`mjwalk.plan.turnsplit`): the walker turns on the spot all but
        a one-step direction change and sets off that far from the way, turning the rest along
        its first steps, never nearer the work's front (``work_heading``) than square to it. The
        draws are otherwise those of a walk without a yaw. Without ``turn_on_spot`` a start yaw
        is the heading of the first step's frame (a walker already walking that way); with no
        start yaw the walker sets off along its guide
        (:func:`~mjwalk.plan.guide.guide_start_heading`). The walk's first sample faces where
        the turn ended (``yaw[0]``): the turn itself is the caller's (the cycle animates it).

        A ``goal_heading``, unlike the options' ``goal_yaw``, is no condition of the goal: it
        shapes the smooth path the walk's heading follows (:mod:`mjwalk.plan.guide`: the
        minimum-jerk curve between the start pose, a walking start's heading or the straight
        line for a standing one, and the goal pose), so the walk bends into it as people's do
        rather than turning at the end. The guide is used where it keeps the body's clearance
        and the goal is in sight from the start. A request's own ``guide`` (e.g. a minimum-jerk
        curve between two poses on the way, :func:`mjwalk.plan.guide.minimum_jerk_guide`) is
        followed instead, on the same terms.

        When the open list runs dry (every sampled continuation blocked, which happens now and
        then in tight places: a rack beside a split turn's first steps), the search starts over
        with fresh samples, no guide and the whole turn on the spot, up to ``attempts`` times;
        a spent budget ends the planning at once. A walk that loops (:data:`WANDER_FACTOR`) is
        searched again too, up to :data:`WANDER_SEARCHES` searches, and the shortest is kept;
        the searches after a loop make the whole turn on the spot (no split,
        :mod:`mjwalk.plan.turnsplit`).

        Args:
            walk: a :class:`~mjwalk.plan.request.WalkRequest`, or its start alone.
            rng: the random stream of the walk's draws (its pace, the guide's side, the steps).

        Returns:
            The walk (120 Hz pelvis positions and yaw, world frame; its steps; ``meta`` with the
            last search's counts, attempts and seconds (of all searches), whether it wanders,
            and ``expansions_all``: the expansions of all its searches, those run dry and those
            whose walk looped included: the planning cost).

        Raises:
            InputError: a malformed request (:class:`~mjwalk.plan.request.WalkRequest`).
            PlanningError: a spot outside the goal area, a start off the floor or too near an
                obstacle, no route, the start already in the goal area (all before any search),
                or no walk found.
        """
        request = walk if isinstance(walk, WalkRequest) else WalkRequest(walk)
        if request.spot is not None:  # checked once, before any search
            self._check_spot(request.spot)
        pose = _parse_pose(self.workplace, request.start)  # parsed once, before any draw
        t0 = time.perf_counter()
        o = self.options
        model = request.model or self.model
        pace = math.nan
        if o.cost == "energy":  # this walk's own pace (WALK_PACE_SD)
            pace = preferred_speed(model) * math.exp(WALK_PACE_SD * rng.standard_normal())
        guide = None
        if o.heading_weight > 0.0:  # the way the walk's heading follows
            guide = self._guide(pose, request, rng, model, pace)
            if guide is not None and not guide_is_clear(self.workplace, guide, self.radius):
                guide = None  # the route search decides
        best: WalkPath | None = None
        bound = None
        limit = max(o.attempts, WANDER_SEARCHES)
        exhausted = 0
        spent = 0  # expansions over all searches (meta "expansions_all")
        for attempt in range(limit):
            try:
                path, start_distance = self._plan_once(pose, rng, request, model, pace, guide)
            except _Exhausted as exc:
                spent += exc.expansions
                exhausted += 1
                guide = None  # a dead end along the guide: the route search decides from now
                request = replace(request, at_work=False)  # and the whole turn on the spot
                if exhausted >= o.attempts or attempt == limit - 1:
                    if best is not None:
                        break
                    raise PlanningError(
                        f"{exc} ({exhausted} searches with fresh samples)"
                    ) from None
                continue
            path.meta["attempts"] = attempt + 1
            spent += path.meta["expansions"]
            path.meta["expansions_all"] = spent
            path.meta["seconds"] = time.perf_counter() - t0  # all searches, not the last one
            if bound is None:
                tolerance = o.goal_tolerance if request.spot is None else request.spot[2]
                bound = WANDER_FACTOR * max(start_distance, tolerance)
            path.meta["wandering"] = bool(path.length > bound)
            if not path.meta["wandering"]:
                return path
            if best is None or path.length < best.length:
                best = path  # a loop: try fresh samples, keep the shortest
            # a split turn that loops is made wholly on the spot (mjwalk.plan.turnsplit)
            request = replace(request, at_work=False)
        assert best is not None  # a search returned, or the last attempt raised
        best.meta["seconds"] = time.perf_counter() - t0
        best.meta["searches"] = attempt + 1
        best.meta["expansions_all"] = spent
        return best

    def _plan_once(
        self,
        pose,
        rng: np.random.Generator,
        request: WalkRequest,
        model: StepModel,
        pace: float,
        guide: np.ndarray | None,
    ) -> tuple[WalkPath, float]:
        """One search: the walk and the obstacle-aware distance (m) from its start to the goal
        (to the request's spot, checked by :meth:`plan`, when given). ``pose``: the start's
        (x, y) and optional yaw, as :meth:`plan` parsed it; ``pace``: the walk's preferred
        speed (m/s; nan: no energy cost); ``guide``: the path its heading follows, or None."""
        o, spot = self.options, request.spot
        start_xy, start_yaw = pose
        start_distance = self._start_distance(start_xy)
        free_heading = start_yaw is None or request.turn_on_spot
        facing = start_yaw  # the heading the walker stands at before any turn on the spot
        along = facing is None and guide is not None  # facing unknown: sets off along its guide
        if along:
            start_yaw = guide_start_heading(guide)
        elif free_heading:
            start_yaw = self.default_heading(start_xy, None if spot is None else spot[:2])
        dec = self.decoder(model)
        stature = walker_stature(model)  # a model conditioned on the run's operator
        aim, start_distance, h_start = self._aim(start_xy, spot, start_distance)
        far = o.far_weight if h_start > LONG_WALK else 0.0  # only long walks
        turn = request.turn_on_spot and facing is not None  # the turn there from the heading
        terms = WalkTerms(
            start_xy=start_xy,
            pace=pace,
            spot=spot,
            guide=guide,
            facing=facing if turn else None,
            turn_pace=(pace if math.isfinite(pace) else preferred_speed(model)) if turn else 0.0,
            far_weight=far,
        )
        par, ipar = self.params.for_walk(stature, terms)
        if in_goal(complex(*start_xy), start_yaw, par, ipar):
            raise PlanningError(
                f"start ({start_xy[0]:.3f}, {start_xy[1]:.3f}) already lies in the goal area "
                f"(within {aim[2]} m of ({aim[0]:.3f}, {aim[1]:.3f})): there is no walk to plan"
            )
        # the starters, for the first expansion (the start node's)
        z0, side0 = model.sample_first_features(o.n_starters, rng)
        frame0 = np.full(len(z0), float(start_yaw))
        split = None
        if turn and request.at_work:  # never nearer the work's front than square (None: facing)
            split = starter_frames(facing, start_yaw, len(z0), rng, request.work_heading)
        if split is not None:  # a large turn: its last part is made along the first steps
            frame0 = split
        elif free_heading and not along:  # anywhere around the downhill heading
            frame0 += rng.uniform(-START_SPREAD, START_SPREAD, len(frame0))
        f0 = o.heuristic_weight * h_start  # as stepcheck.check_steps scores a node
        if h_start > FAR_FROM:
            f0 += far * (h_start - FAR_FROM)
        starters = (z0, frame0, side0, complex(*start_xy), float(start_yaw), f0)
        goal_node, stats, nodes = self._search(model, dec, starters, rng, par, ipar, aim)
        closing = nodes[-1]
        rows = nodes[1]
        path = self._assemble(
            model,
            goal_node,
            nodes[:5],
            nodes[5],
            {
                **stats,
                # whether the walk ends with a closing step (StepModel.sample_stop)
                "closing_step": bool(closing[rows[goal_node]]),
                **({} if spot is None else {"spot": list(aim[:2]), "spot_tolerance": aim[2]}),
            },
        )
        return path, start_distance

    def _start_distance(self, start_xy: np.ndarray) -> float:
        """The field's distance (m) from ``start_xy`` to the goal, after checking the start
        (off the floor, in or too near an obstacle, no route: PlanningError)."""
        check_endpoint(self.workplace, start_xy, self.radius, "start")
        # infinite exactly where GoalDistance.reachable is False (the same nearest cell)
        start_distance = float(self.distance(start_xy))
        if not math.isfinite(start_distance):
            raise PlanningError(
                f"goal ({self.goal[0]:.3f}, {self.goal[1]:.3f}) is unreachable from start "
                f"({start_xy[0]:.3f}, {start_xy[1]:.3f}) in {self.workplace.name}: no "
                f"collision-free route for body radius {self.radius} m"
            )
        return start_distance

    def _aim(
        self, start_xy: np.ndarray, spot, start_distance: float
    ) -> tuple[tuple[float, float, float], float, float]:
        """The walk's goal point and tolerance (x, y, tol: the planner's goal, or ``spot``),
        its distance (m) from ``start_xy`` (the field's ``start_distance``, or for a spot the
        larger of that less the spot's offset and the straight line less its tolerance) and
        the start node's unweighted heuristic (m, as stepcheck.check_steps bounds a node)."""
        o = self.options
        goal_x, goal_y, tolerance = float(self.goal[0]), float(self.goal[1]), o.goal_tolerance
        field_distance = start_distance
        if spot is not None:  # this walk's own goal point (module doc of plan)
            goal_x, goal_y, tolerance = spot
            field_distance -= spot_offset(self.goal, spot)
            start_distance = max(
                field_distance, math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y) - tolerance
            )
        # as stepcheck.check_steps bounds a node: the field's distance, the straight line to
        # the goal point
        h0 = field_distance if o.heuristic == "dijkstra" else 0.0
        euclid = float(math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y))
        return (goal_x, goal_y, tolerance), start_distance, max(h0, euclid)

    def _search(self, model: StepModel, dec: StepDecoder, starters, rng, par, ipar, aim):
        """Run the compiled search (:func:`mjwalk.plan.search.search`) from ``starters`` (z0,
        frame0, side0, start point as complex, start yaw, start node's f) towards ``aim``
        (x, y, tolerance). Returns the goal node, the search's counts (a dict) and the node
        arrays (parent, rows, pos, frames, lefts, feats, closing); a spent budget raises
        PlanningError, an open list run dry :class:`_Exhausted`."""
        o = self.options
        z0, frame0, side0, start, start_yaw, f0 = starters
        gps = (model.gp["left"].kernel, model.gp["right"].kernel)
        sgp = (model.stop_gp["left"], model.stop_gp["right"]) if o.n_stops else None
        stops = (sgp[0].kernel, sgp[1].kernel) if sgp else gps
        none = (np.array([np.inf, np.inf]), np.zeros(len(gps[0][1]), complex))  # never far
        reaches = (dec.closing_reach(sgp[0]), dec.closing_reach(sgp[1])) if sgp else (none, none)
        outcome, goal_node, stats, *nodes = search.search(
            np.ascontiguousarray(z0, dtype=float),
            frame0,
            np.ascontiguousarray(side0 == "left"),
            start,
            start_yaw,
            f0,
            gps,
            stops,
            reaches,
            rng,
            dec.matrix,
            dec.offset,
            self.params.thresholds,
            par,
            ipar,
            self.walk_field.values,
            self.distance.flat_bound(),
        )
        expansions, generated, rejected, stop_draws = stats.tolist()
        goal_x, goal_y, _ = aim
        where = f"({start.real:.3f}, {start.imag:.3f})"
        if outcome == search.BUDGET:
            raise PlanningError(
                f"expansion budget of {o.max_expansions} spent before reaching the "
                f"goal ({goal_x:.3f}, {goal_y:.3f}) from {where}; {generated} steps sampled, "
                f"{rejected} rejected"
            )
        if outcome == search.EXHAUSTED:
            dry = _Exhausted(
                f"search exhausted after {expansions} expansions: no sequence of sampled "
                f"steps reached the goal ({goal_x:.3f}, {goal_y:.3f}) from {where} without "
                f"coming closer than {self.radius} m to an obstacle"
            )
            dry.expansions = expansions
            raise dry
        counts = {
            "expansions": expansions,
            "generated": generated,
            "rejected": rejected,
            "stop_draws": stop_draws,
        }
        return goal_node, counts, nodes

    def _guide(self, pose, request: WalkRequest, rng, model, pace: float):
        """:func:`mjwalk.plan.detour.walk_guide` for a walk of :meth:`plan` (a start yaw is a
        walker already walking unless ``turn_on_spot``) at the walk's ``pace`` (m/s; nan: the
        walker's preferred speed), which sets its berth."""
        (x, y), yaw = pose
        walking = None if yaw is None or request.turn_on_spot else yaw
        goal = self.goal if request.spot is None else request.spot[:2]
        speed = pace if math.isfinite(pace) else preferred_speed(model)
        body = GuideBody(self.radius, walker_stature(model), walker_step_length(model), speed)
        return walk_guide(
            self.workplace, (x, y), goal, walking, request.goal_heading, request.guide, body, rng
        )

    def _assemble(self, model, nid, nodes, feats, stats) -> WalkPath:
        meta = {
            "planner": "hybrid_astar",
            "goal": self.goal.tolist(),
            "goal_tolerance": self.options.goal_tolerance,
            "radius": self.radius,
            "heuristic": self.options.heuristic,
            **stats,
        }
        return assemble_walk(model, nid, nodes, feats, meta).stamp_scene(self.workplace)
