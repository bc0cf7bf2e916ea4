"""The hybrid A*'s limits and defaults, and the compiled kernels' parameters made from them.

Clearances and reach limits of the body (metres), the search's weights, budgets and retries,
each with its source; the evidence behind the measured ones is in ``docs/decisions/101``-``106``
and the benchmarks named there. :func:`kernel_params` turns a
:class:`~mjwalk.plan.hybrid.HybridPlanner`'s options into the parameter vectors of
:func:`~mjwalk.plan.stepcheck.check_steps` and :func:`~mjwalk.plan.search.search`
(:mod:`mjwalk.plan.slots`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from mjwalk.anthropometry import ROM_DEG, SHIN_RADIUS, leg_geometry
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.gait.transition import POOL_SHARPNESS
from mjwalk.plan import slots

if TYPE_CHECKING:
    from mjwalk.plan.hybrid import HybridPlanner

#: Extra clearance (metres) demanded of the sampled trajectory points: it covers the bilinear
#: field's error (< 4 mm) and the curve between two of the 16 checked samples of a step, so the
#: full 120 Hz path keeps the body radius by MuJoCo's own geometry.
SAFETY_MARGIN = 0.01
#: Ankle-to-toe length (m) and the clearance (m) both must keep from obstacles and the floor's
#: edge: the landing foot reaches ahead of the pelvis, into a shelf or a car body otherwise.
FOOT_LENGTH = 0.14
FOOT_CLEARANCE = 0.08
#: The landing foot's way in (issue 45: run 32 of the station, seed 0, brushed rack 1's upright
#: with its left toes one frame before landing, the step coming in 28 degrees off the foot's
#: heading). The swing foot has its landing yaw from the phase
#: :data:`~mjwalk.body.legs.steps.SWING_TURNED` on and covers the rest of its chord turned so;
#: over the 66 steps of a station cycle's seven walks synthesized at 1.55, 1.75 and 1.95 m that
#: rest was at most 0.18 of the chord (median 0.10; 0.21 m at most) and the chord up to 55 degrees
#: off the landing yaw. Probes every ``TOE_PROBE_STEP`` metres over the chord's last
#: ``TOE_APPROACH_SHARE`` keep the ankle and the toes FOOT_CLEARANCE
#: (:func:`mjwalk.plan.stepgeom.toe_approach_clear`).
TOE_APPROACH_SHARE = 0.2
TOE_PROBE_STEP = 0.02
#: The swing knee reaches beyond the body radius: over the swings of planned walks played back
#: (1.75 m humanoid) the knee centre lies up to 0.21 m (95th percentile 0.25) ahead along the
#: pelvis yaw and 0.11 m (0.15) to the swing side, and the thigh is 0.035 statures thick
#: (``docs/decisions/103``). Probes at half and three quarters of the step, ``KNEE_LEAD``
#: ahead and ``KNEE_SIDE`` to the swing side, keep ``KNEE_CLEARANCE`` (thigh radius, 1 cm
#: margin and 3 cm for the knee's spread about the probe).
KNEE_LEAD = 0.23
KNEE_SIDE = 0.12
KNEE_CLEARANCE = 0.10
#: The landing leg at heel strike. A foot lands heel first, toes up (the leg synthesis,
#: :mod:`mjwalk.body.legs.synthesis`): its ankle lies some 4 cm behind and 2 cm above the flat
#: footprint's, the heel's upper edge swings 2-3 cm behind the flat heel, and the shin leans
#: back from the ankle towards the hip. A landing foot far ahead of the pelvis (up to
#: MAX_FOOT_REACH) leaves some 0.2 m of shin between the ankle's check and the pelvis's. Probes
#: every ``LEG_PROBE_STEP`` metres along the ankle-to-hip line keep the shin radius
#: (:data:`mjwalk.anthropometry.SHIN_RADIUS` times the walker's stature) plus SAFETY_MARGIN
#: plus half the spacing (:func:`mjwalk.plan.stepgeom.landing_leg_clear`); the first probe
#: also covers the toes-up heel (at 1.75 m its upper back edge reaches 0.09 m behind the
#: ankle, 0.05 m to the side: 0.07 m from the probe, within the 0.077 m kept). Evidence:
#: ``docs/decisions/103`` (``benchmarks/bench_contacts.py``).
LEG_PROBE_STEP = 0.04
#: Largest horizontal distance (m) of a planted foot from the pelvis: the largest seen in the
#: virtual corpus (landing foot vs pelvis at heel strike: median 0.37, 99.9th percentile 0.52).
MAX_FOOT_REACH = 0.55
#: Longest stride (m; same foot, lift-off to landing) and farthest lift-off foot from the pelvis
#: in the first quarter of a step (m): the virtual corpus's maxima (medians 1.33 and 0.48).
MAX_STRIDE = 1.74
MAX_LIFT_REACH = 0.64
#: Without a start yaw, starters set off within +-60 degrees of the obstacle-aware downhill
#: heading (the operator turns on the spot before the first step).
START_SPREAD = math.radians(60.0)
#: Closing steps (gait termination, :meth:`StepModel.sample_stop`) are drawn for nodes within
#: this distance (m) of the goal area, and kept only when they end in it: the walk stops
#: there. The corpus's closing steps move the pelvis 0.2-0.5 m.
STOP_REACH = 0.8
#: Within that reach of the goal a cell closes after this many expansions instead of one, and a
#: node in a closed cell there still draws its closing steps (not its walking ones). A tight goal
#: area (the cycle's 0.1 m) is about a cell (0.08 m) wide: whether a node can stop in it depends
#: on where in its cell it lies and on its step, for which a cell's first node does not stand
#: (``docs/decisions/104``).
NEAR_GOAL_EXPANSIONS = 3
#: The stance leg must follow every step: with the stance sole level sideways (as the leg
#: synthesis keeps it) the ankle takes the sideways lean of the hip-to-ankle line in the stance
#: foot's frame, the hip its lean in the pelvis frame, and a step whose lean leaves the
#: humanoid's ranges even with the leg stretched straight (ROM_DEG, after AAOS: ankle eversion
#: 15 / inversion 35 deg, hip adduction 30 / abduction 45 deg) is rejected
#: (:func:`mjwalk.plan.lean.stance_lean_ok`). The hip offset and leg length are those of the
#: default 1.75 m humanoid (the planner does not know the walker's stature; the lean of a given
#: placement scales about inversely with it). On planned walks the straight-leg lean is within
#: 1-2 deg of the leg synthesis's own (unclipped) ankle inversion where it matters
#: (``docs/decisions/103``, ``benchmarks/bench_stance_lean.py``).
LEAN_GEOMETRY = leg_geometry(1.75)
#: Far from the goal the heuristic weighs more (dynamic weighting, Pohl 1973): beyond
#: ``FAR_FROM`` metres of obstacle-aware distance h, f = g + weight·h + FAR_WEIGHT·(h - FAR_FROM).
#: The bound h falls short of the walked length left by a share that does not shrink with
#: distance (the grid bound is divided by the 16-move detour factor 1.026, and sampled steps
#: weave around obstacles): with the weight alone the open list's f grows along the walk and
#: the search floods back over the nodes it passed. Walked length over h runs to 1.057 (90th
#: percentile) in a cluttered hall; weight plus far weight (1.06) covers it. Only walks
#: starting more than ``LONG_WALK`` metres (h) from their goal get it (``docs/decisions/102``).
FAR_WEIGHT = 0.05
FAR_FROM = 4.0
LONG_WALK = 14.0
#: Expansions one search may spend: the energy cost makes the search back up where sampled
#: successors stray from the walker's pace; 32 m walks in a cluttered hall take up to some
#: 5700 (``docs/decisions/102``).
MAX_EXPANSIONS = 8000
#: A walk longer than this multiple of the obstacle-aware route length from its start to the
#: goal is a loop, not a variation: people do not walk back around a rack to arrive. The
#: planner then searches again with fresh samples (up to ``attempts`` searches in all, keeping
#: the shortest). Walk length over that route length runs continuously up to 1.47 (99th
#: percentile), then jumps to the loops, 1.68-10; 1.5 lies in the gap (``docs/decisions/104``).
#: A walk that still loops after every attempt is returned with ``meta["wandering"]`` set.
WANDER_FACTOR = 1.5
#: Searches a looping walk gets in all (each with fresh samples) before the shortest is kept.
#: A loop costs a short walk's search (milliseconds), so the extra searches are cheap where
#: they happen (``docs/decisions/104``).
WANDER_SEARCHES = 6
#: Searches a walk gets in all when the open list runs dry (every sampled continuation
#: blocked): into a tight stand zone about one search in ten runs dry (``docs/decisions/104``).
#: A plan whose searches ran dry fewer than three times draws the same numbers with three.
ATTEMPTS = 6
#: Weight of the squared heading error in a step's cost while the goal is in sight
#: (:func:`mjwalk.plan.stepcost.heading_factor`: Mombaur, Truong & Laumond 2010, α4 / α0 of
#: their inverse-optimal-control cost of human walking). The walked length (and its energy)
#: grows only with the square of a drift sideways, less than the search's heuristic slack, so
#: without the term the search keeps whatever heading drift the transition GP's samples carry.
#: The term stops within the closing reach of the goal (``stop_reach``), where the walk turns to
#: its goal heading, and counts only where the goal is in sight
#: (:attr:`~mjwalk.plan.heuristic.GoalDistance.in_sight`) on walks that see the goal from their
#: start: where an obstacle hides it, the route around it decides (``docs/decisions/105``).
HEADING_WEIGHT = 5.2
#: Turning speed on the spot (rad/s) of a walker who sets off facing away from the way
#: (``plan(turn_on_spot=True)``): ASSUMPTION, a half turn in about two steps (1.06 s at
#: 113 steps/min), as the cycle turns an operator (``mjwalk.cycle.poses.TURN_SPEED``).
ON_SPOT_TURN_SPEED = math.pi
#: Walk-to-walk spread of a person's pace with the energy cost: each walk's preferred speed is
#: the walker's times exp(N(0, WALK_PACE_SD²)), as the virtual subjects vary theirs from bout
#: to bout (:func:`mjwalk.gait.corpus.sample_subject`, ``speed_sd`` uniform 0.03-0.06).
WALK_PACE_SD = 0.045


def leg_clearance(stature: float = DEFAULT_STATURE) -> float:
    """Clearance (m) the landing leg's probes keep for a walker of ``stature`` metres: the
    shin radius plus SAFETY_MARGIN plus half of LEG_PROBE_STEP."""
    return SHIN_RADIUS * stature + SAFETY_MARGIN + 0.5 * LEG_PROBE_STEP


def lean_params() -> dict[str, float]:
    """The stance-lean check's slots of :func:`mjwalk.plan.slots.params`: hip offset and
    straight-leg length (m) of :data:`LEAN_GEOMETRY`, and the ankle eversion/inversion and hip
    adduction/abduction limits (radians) of ``ROM_DEG``."""
    return {
        "hip_y": LEAN_GEOMETRY.hip_y,
        "leg_span": LEAN_GEOMETRY.thigh + LEAN_GEOMETRY.shank,
        "eversion": -math.radians(ROM_DEG["ankle_inv"][0]),
        "inversion": math.radians(ROM_DEG["ankle_inv"][1]),
        "adduction": -math.radians(ROM_DEG["hip_abd"][0]),
        "abduction": math.radians(ROM_DEG["hip_abd"][1]),
    }


def kernel_params(planner: HybridPlanner, stature: float) -> tuple[np.ndarray, np.ndarray]:
    """The float and integer parameter vectors (:func:`~mjwalk.plan.slots.params`,
    :func:`~mjwalk.plan.slots.iparams`) of ``planner``'s compiled search for a walker of
    ``stature`` metres (the landing leg's clearance scales with it)."""
    m = planner.samples_per_step
    knee_cols = (m // 2, (3 * m) // 4)  # the swing-knee probes' pelvis samples
    walk, gd = planner.walk_field, planner.distance
    par = slots.params(
        knee_lead=KNEE_LEAD,
        knee_side=KNEE_SIDE,
        foot_length=FOOT_LENGTH,
        foot_reach=MAX_FOOT_REACH,
        lift_reach=MAX_LIFT_REACH,
        stride=MAX_STRIDE,
        goal_x=planner.goal[0],
        goal_y=planner.goal[1],
        tolerance=planner.tolerance,
        goal_yaw=math.nan if planner.goal_yaw is None else planner.goal_yaw,
        yaw_tolerance=planner.goal_yaw_tolerance,
        weight=planner.heuristic_weight,
        corner_x=planner.grid.x0,
        corner_y=planner.grid.y0,
        cell=planner.cell,
        field_x0=walk.x0,
        field_y0=walk.y0,
        field_res=walk.resolution,
        dist_x0=planner.grid.x0,
        dist_y0=planner.grid.y0,
        dist_cell=planner.grid.cell,
        dist_top_x=planner.grid.free.shape[1] - 1.0,
        dist_top_y=planner.grid.free.shape[0] - 1.0,
        knee_share0=knee_cols[0] / (m - 1),  # the probes' share of the step
        knee_share1=knee_cols[1] / (m - 1),
        stop_reach=planner.tolerance + STOP_REACH,
        pool_sharpness=POOL_SHARPNESS,
        **lean_params(),
        far_weight=planner.far_weight,
        far_from=FAR_FROM,
        leg_step=LEG_PROBE_STEP,
        leg_clearance=leg_clearance(stature),
        toe_share=TOE_APPROACH_SHARE,
        toe_step=TOE_PROBE_STEP,
        dist_offset=0.0,
        pace=math.nan,
        heading_weight=planner.heading_weight,
        heading_from=planner.tolerance + STOP_REACH,
    )
    for k, (dx, dy, dr) in enumerate(planner.goal_within):
        par[slots.P_DISC0 + 3 * k : slots.P_DISC0 + 3 * k + 3] = (dx, dy, dr)
    ipar = slots.iparams(
        m=m,
        q=max(2, m // 4),  # samples of a step's first quarter (the foot behind lifts off)
        knee_col0=knee_cols[0],
        knee_col1=knee_cols[1],
        # closed cells as one integer: (i * span + j) * bins + heading bin, with span
        # larger than any cell row index j of a point a step can reach (the grid's rows
        # plus a margin)
        span=4 * max(planner.grid.free.shape) + 1000,
        bins=planner.heading_bins,
        field_nx=walk.values.shape[1],
        field_ny=walk.values.shape[0],
        dist_nx=gd.grid.free.shape[1],
        dijkstra=planner.heuristic == "dijkstra",
        chord=planner.cost != "path",
        n_successors=planner.n_successors,
        n_stops=planner.n_stops,
        max_expansions=planner.max_expansions,
        near_goal_expansions=NEAR_GOAL_EXPANSIONS,
        n_discs=len(planner.goal_within),
    )
    return par, ipar
