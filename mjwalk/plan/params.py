"""The compiled kernels' parameter vectors of one planner and of each of its walks.

:func:`~mjwalk.plan.stepcheck.check_steps` and :func:`~mjwalk.plan.search.search` take a
planner's options as two flat arrays laid out by :mod:`mjwalk.plan.slots`: a float vector
(metres, radians, m/s) and an integer vector. :class:`KernelParams` is the one place that fills
them: from a :class:`~mjwalk.plan.options.PlannerOptions`, the goal and the planner's grids
(:meth:`KernelParams.vectors`, once per walker stature), and from what one walk adds (its pace,
spot, guide, turn on the spot: :class:`WalkTerms`, :meth:`KernelParams.for_walk`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import PlanningError
from mjwalk.gait.transition import POOL_SHARPNESS
from mjwalk.plan import slots
from mjwalk.plan.heuristic import GoalDistance
from mjwalk.plan.occupancy import OccupancyGrid
from mjwalk.plan.options import (
    FAR_FROM,
    FOOT_CLEARANCE,
    FOOT_LENGTH,
    KNEE_CLEARANCE,
    LEG_PROBE_STEP,
    MAX_FOOT_REACH,
    MAX_LIFT_REACH,
    MAX_STRIDE,
    MIN_STEP_ADVANCE,
    NEAR_GOAL_EXPANSIONS,
    ON_SPOT_TURN_SPEED,
    SAFETY_MARGIN,
    STOP_REACH,
    SWING_LIFT_TURN,
    TOE_APPROACH_SHARE,
    TOE_CORNER_CLEARANCE,
    TOE_PROBE_STEP,
    PlannerOptions,
    foot_reach,
    knee_pivot,
    knee_reach,
    lean_params,
    leg_clearance,
    swing_turned,
    toe_corners,
)
from mjwalk.plan.stepcost import guide_lengths
from mjwalk.world.clearance import ClearanceField


def goal_discs(options: PlannerOptions, goal: np.ndarray) -> np.ndarray:
    """The discs a planner's goal area is cut by (``options.goal_within``), checked.

    Args:
        options: the planner's options.
        goal: (2,) the planner's goal point, metres, world frame.

    Returns:
        (k, 3) the discs (x, y, radius; metres), the goal inside every one.

    Raises:
        PlanningError: the goal outside a disc (the goal area would be empty where the walk
            is aimed).
    """
    arr = np.array(options.goal_within, dtype=float).reshape(-1, 3)
    out = np.hypot(arr[:, 0] - goal[0], arr[:, 1] - goal[1]) > arr[:, 2]
    if out.any():
        k = int(np.flatnonzero(out)[0])
        raise PlanningError(
            f"goal_within: the goal ({goal[0]:.3f}, {goal[1]:.3f}) lies outside disc {k} "
            f"({arr[k, 0]:.3f}, {arr[k, 1]:.3f}, radius {arr[k, 2]:.3f} m)"
        )
    return arr


@dataclass(frozen=True, eq=False)
class WalkTerms:
    """What one walk sets in its planner's vectors (world frame, metres, radians).

    Attributes:
        start_xy: the walk's start (x, y); where the goal is out of its sight, the heading term
            counts only along a guide.
        pace: the walk's preferred speed (m/s) of the energy cost; nan: the length cost only.
        spot: (x, y, tolerance) the walk ends within, inside the planner's goal area; None:
            the planner's goal.
        guide: the (GUIDE_POINTS, 2) path the heading follows (clear of obstacles); None: none.
        facing: the heading the walker stands at before a turn on the spot, which then costs
            its time; None: no turn cost.
        turn_pace: the speed (m/s) that time is costed at (metres, as the steps).
        far_weight: the heuristic's extra weight far from the goal
            (:data:`~mjwalk.plan.options.FAR_WEIGHT`; the options' on a long walk, else 0).
    """

    start_xy: np.ndarray
    pace: float = math.nan
    spot: tuple[float, float, float] | None = None
    guide: np.ndarray | None = None
    facing: float | None = None
    turn_pace: float = math.nan
    far_weight: float = 0.0


#: Statures whose vectors one :class:`KernelParams` keeps (the oldest go first): a planner
#: shared by a population's operators (:meth:`KernelParams.for_goal_area`) sees their statures
#: in centimetres, some 25-50 values.
STATURES_KEPT = 64


class KernelParams:
    """The kernels' float and integer vectors of one planner (:mod:`mjwalk.plan.slots`).

    Args:
        options: the planner's options.
        goal: the goal point (x, y), metres.
        discs: (k, 3) goal discs (x, y, radius; metres), checked against the goal.
        grid: the planner's occupancy grid (its cells key the closed set).
        walk_field: the workplace's clearance field of the body's points.
        distance: the goal's obstacle-aware distance field.
    """

    def __init__(
        self,
        options: PlannerOptions,
        goal: np.ndarray,
        discs: np.ndarray,
        grid: OccupancyGrid,
        walk_field: ClearanceField,
        distance: GoalDistance,
    ):
        self.options = options
        self.goal = goal
        self.discs = discs
        self.grid = grid
        self.walk_field = walk_field
        self.distance = distance
        m = options.samples_per_step
        #: Clearance (m) per checked point of a successor: m pelvis samples, the landing ankle
        #: and its toes, the swing knee at half, three quarters and a third of the step.
        self.thresholds = np.array(
            [options.radius + SAFETY_MARGIN] * m
            + [FOOT_CLEARANCE] * 2
            + [KNEE_CLEARANCE] * len(_knee_cols(m))
        )
        self._held: dict[float, tuple[np.ndarray, np.ndarray]] = {}
        #: The float vector's slots that do not depend on the stature, and the integer vector
        #: (which does not at all): made on first use, a walker's stature filled in per stature
        self._shared: tuple[np.ndarray, np.ndarray] | None = None
        #: The vectors of the same planner but for its goal area (:meth:`for_goal_area`), whose
        #: stature vectors these are made from; None: made here
        self._base: KernelParams | None = None

    def for_goal_area(self, options: PlannerOptions, discs: np.ndarray) -> KernelParams:
        """These vectors for another goal area: ``options`` differ from this planner's in
        ``goal_tolerance`` and ``goal_within`` only (a stand zone's planner of the same goal,
        :meth:`~mjwalk.plan.hybrid.HybridPlanner.for_goal_area`). The new vectors are this
        one's per stature with the goal area's slots set over them (the goal tolerance, the
        closing and heading reach, the discs and their count), the values :meth:`vectors`
        would make from ``options`` itself; this one's are made once for all its goal areas.

        Args:
            options: the goal area's planner options.
            discs: (k, 3) its goal discs (x, y, radius; metres), checked against the goal.

        Returns:
            The goal area's :class:`KernelParams` (sharing grids, fields and thresholds).
        """
        out = KernelParams.__new__(KernelParams)
        out.__dict__.update(self.__dict__)
        out.options, out.discs = options, discs
        out._held, out._shared = {}, None
        out._base = self if self._base is None else self._base
        return out

    def vectors(self, stature: float = DEFAULT_STATURE) -> tuple[np.ndarray, np.ndarray]:
        """The float and integer vectors for a walker of ``stature`` metres (the landing leg's
        clearance scales with it): fresh copies of the ones made on first use.

        Args:
            stature: the walker's body height, metres.

        Returns:
            The float vector (:data:`~mjwalk.plan.slots.N_PARAMS`,) and the integer vector
            (:data:`~mjwalk.plan.slots.N_IPARAMS`,).
        """
        held = self._stature_vectors(stature)
        return held[0].copy(), held[1].copy()

    def _stature_vectors(self, stature: float) -> tuple[np.ndarray, np.ndarray]:
        """The vectors of ``stature`` (kept, not copied; the last :data:`STATURES_KEPT`
        statures): made from this planner's options, or from its base's (:meth:`for_goal_area`)
        with the goal area set."""
        held = self._held.get(stature)
        if held is None:
            if self._base is not None:
                held = self._goal_area(*self._base._stature_vectors(stature))
            else:
                if self._shared is None:
                    self._shared = (self._floats(), self._integers())
                held = (_with_stature(self._shared[0], stature), self._shared[1])
            while len(self._held) >= STATURES_KEPT:
                self._held.pop(next(iter(self._held)))
            self._held[stature] = held
        return held

    def _goal_area(self, par: np.ndarray, ipar: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Copies of ``par`` and ``ipar`` with this planner's goal area in their slots (as
        :meth:`_floats` and :meth:`_integers` set them)."""
        par, ipar = par.copy(), ipar.copy()
        _put_tolerance(par, self.options.goal_tolerance)
        _put_discs(par, self.discs)
        ipar[slots.I_N_DISCS] = len(self.discs)
        return par, ipar

    def for_walk(self, stature: float, walk: WalkTerms) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`vectors` with what ``walk`` sets: its pace, its spot (its own goal point and
        tolerance, the goal's field offset by the way between the two, and the planner's goal
        area as one more disc), its guide, the cost of its turn on the spot and its far weight.

        Args:
            stature: the walker's body height, metres.
            walk: the walk's terms (:class:`WalkTerms`).

        Returns:
            The float and integer vectors for the walk (fresh copies).
        """
        par, ipar = self.vectors(stature)
        par[slots.P_PACE] = walk.pace
        if walk.spot is not None:
            goal_x, goal_y, tolerance = walk.spot
            par[slots.P_GOAL_X] = goal_x
            par[slots.P_GOAL_Y] = goal_y
            _put_tolerance(par, tolerance)
            par[slots.P_DIST_OFFSET] = spot_offset(self.goal, walk.spot)
            k = int(ipar[slots.I_N_DISCS])
            j = slots.P_DISC0 + 3 * k
            par[j : j + 3] = (float(self.goal[0]), float(self.goal[1]), self.options.goal_tolerance)
            ipar[slots.I_N_DISCS] = k + 1
        if walk.guide is not None and par[slots.P_HEADING_WEIGHT] > 0.0:
            par[slots.P_GUIDE0 : slots.P_DISC0] = walk.guide.ravel()
            par[slots.P_GUIDE_LEN0 : slots.N_PARAMS] = guide_lengths(
                par[slots.P_GUIDE0 : slots.P_DISC0]
            )
        if math.isnan(par[slots.P_GUIDE0]) and not self.distance.sees(walk.start_xy):
            # the heading term without a guide: only for a goal in sight from the start
            par[slots.P_HEADING_WEIGHT] = 0.0
        if walk.facing is not None:
            par[slots.P_START_YAW] = float(walk.facing)
            par[slots.P_TURN_COST] = walk.turn_pace / ON_SPOT_TURN_SPEED
        par[slots.P_FAR_WEIGHT] = walk.far_weight
        return par, ipar

    def _floats(self) -> np.ndarray:
        """The float vector but for the stature's slots (nan; :func:`_with_stature`)."""
        o, grid, walk = self.options, self.grid, self.walk_field
        m = o.samples_per_step
        knee_cols = _knee_cols(m)
        par = slots.params(
            swing_lift_turn=SWING_LIFT_TURN,
            foot_length=FOOT_LENGTH,
            toe_clearance=TOE_CORNER_CLEARANCE,
            foot_reach=MAX_FOOT_REACH,
            lift_reach=MAX_LIFT_REACH,
            stride=MAX_STRIDE,
            step_advance=MIN_STEP_ADVANCE,
            goal_x=self.goal[0],
            goal_y=self.goal[1],
            tolerance=o.goal_tolerance,
            goal_yaw=math.nan if o.goal_yaw is None else o.goal_yaw,
            yaw_tolerance=o.goal_yaw_tolerance,
            weight=o.heuristic_weight,
            corner_x=grid.x0,
            corner_y=grid.y0,
            cell=o.cell,
            field_x0=walk.x0,
            field_y0=walk.y0,
            field_res=walk.resolution,
            field_lip=walk.lipschitz,
            dist_x0=grid.x0,
            dist_y0=grid.y0,
            dist_cell=grid.cell,
            dist_top_x=grid.free.shape[1] - 1.0,
            dist_top_y=grid.free.shape[0] - 1.0,
            knee_share0=knee_cols[0] / (m - 1),  # the probes' share of the step
            knee_share1=knee_cols[1] / (m - 1),
            knee_turn0=swing_turned(knee_cols[0] / (m - 1)),
            knee_turn1=swing_turned(knee_cols[1] / (m - 1)),
            knee_share2=knee_cols[2] / (m - 1),
            knee_turn2=swing_turned(knee_cols[2] / (m - 1)),
            stop_reach=o.goal_tolerance + STOP_REACH,
            pool_sharpness=POOL_SHARPNESS,
            **lean_params(),
            far_weight=o.far_weight,
            far_from=FAR_FROM,
            leg_step=LEG_PROBE_STEP,
            toe_share=TOE_APPROACH_SHARE,
            toe_step=TOE_PROBE_STEP,
            dist_offset=0.0,
            pace=math.nan,
            heading_weight=o.heading_weight,
            heading_from=o.goal_tolerance + STOP_REACH,
        )
        _put_discs(par, self.discs)
        return par

    def _integers(self) -> np.ndarray:
        o, grid, walk = self.options, self.grid, self.walk_field
        m = o.samples_per_step
        knee_cols = _knee_cols(m)
        return slots.iparams(
            m=m,
            q=max(2, m // 4),  # samples of a step's first quarter (the foot behind lifts off)
            knee_col0=knee_cols[0],
            knee_col1=knee_cols[1],
            knee_col2=knee_cols[2],
            # closed cells as one integer: (i * span + j) * bins + heading bin, with span
            # larger than any cell row index j of a point a step can reach (the grid's rows
            # plus a margin)
            span=4 * max(grid.free.shape) + 1000,
            bins=o.bins,
            field_nx=walk.values.shape[1],
            field_ny=walk.values.shape[0],
            dist_nx=self.distance.grid.free.shape[1],
            dijkstra=o.heuristic == "dijkstra",
            chord=o.cost != "path",
            n_successors=o.n_successors,
            n_stops=o.n_stops,
            max_expansions=o.max_expansions,
            near_goal_expansions=NEAR_GOAL_EXPANSIONS,
            n_discs=len(self.discs),
        )


def _put_tolerance(par: np.ndarray, tolerance: float) -> None:
    """Set the goal tolerance (m) and the closing and heading reach that follow from it
    (``tolerance + STOP_REACH``) in the float vector ``par``, in place."""
    par[slots.P_TOLERANCE] = tolerance
    par[slots.P_STOP_REACH] = tolerance + STOP_REACH
    par[slots.P_HEADING_FROM] = tolerance + STOP_REACH


def _put_discs(par: np.ndarray, discs: np.ndarray) -> None:
    """Set the goal discs ((k, 3): x, y, radius; metres) in the float vector ``par``, in place,
    the slots of discs not given nan (their count is the integer vector's)."""
    par[slots.P_DISC0 : slots.P_GUIDE_LEN0] = np.nan
    for k, (dx, dy, dr) in enumerate(discs):
        par[slots.P_DISC0 + 3 * k : slots.P_DISC0 + 3 * k + 3] = (dx, dy, dr)


def _with_stature(shared: np.ndarray, stature: float) -> np.ndarray:
    """A copy of the float vector ``shared`` with the slots of a walker of ``stature`` metres:
    the swing knee's and the toes' reach, the knee's pivot, the landing leg's clearance and
    the planted feet's reach."""
    par = shared.copy()
    par[slots.P_KNEE_LEAD], par[slots.P_KNEE_SIDE] = knee_reach(stature)
    par[slots.P_KNEE_PIVOT] = knee_pivot(stature)
    par[slots.P_TOE_FRONT], par[slots.P_TOE_SIDE] = toe_corners(stature)
    par[slots.P_LEG_CLEARANCE] = leg_clearance(stature)
    par[slots.P_FOOT_REACH], par[slots.P_FOOT_ROLL] = foot_reach(stature)
    return par


def spot_offset(goal: np.ndarray, spot: tuple[float, float, float]) -> float:
    """Metres between the goal point and a walk's ``spot`` (x, y, tolerance): the goal's
    distance field bounds the way to the spot from below only less this (triangle
    inequality).

    Args:
        goal: (2,) the goal point, metres, world frame.
        spot: (x, y, tolerance) of the walk's spot, metres.

    Returns:
        The distance between the two, metres.
    """
    return math.hypot(spot[0] - goal[0], spot[1] - goal[1])


def _knee_cols(m: int) -> tuple[int, int, int]:
    """The swing-knee probes' pelvis samples of a step of ``m`` samples: at half, three
    quarters and a third of the step (:data:`~mjwalk.plan.options.KNEE_LEAD`)."""
    return m // 2, (3 * m) // 4, m // 3
