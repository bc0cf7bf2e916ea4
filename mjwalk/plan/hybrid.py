"""Probabilistic hybrid A* (agethen2018 §3.4, §4.2, Algorithm 1).

Walks are stitched from steps sampled from a learned :class:`~mjwalk.gait.model.StepModel`: the
search starts with ``n_starters`` gait-initiation steps drawn from the model's KDE, and every
expansion draws ``n_successors`` continuations of the expanded step from its Gaussian-process
transition model. Cost is the walked length, step by step, each step counting its straight
start-to-end distance (``cost="chord"``, the paper's) or the swaying pelvis arc
(``cost="path"``: minimizing the arc makes the search pick the long, low-sway steps of fast
walking out of the samples: median speed 1.44 m/s on an 8 m open-floor walk, 1.25 m/s with the
chord; Bandai straight walks: 1.13 m/s). By default (``cost="energy"``) each walking step's
chord is weighted by the metabolic cost of walking at its speed relative to the walker's
preferred one (:func:`~mjwalk.plan.stepcheck.step_energy`: Ralston 1958, least at the
preferred speed, 2.5 % more per metre at 20 % below it; not the starters and closing steps,
which set off from and come to a stand), and each walk has its own preferred speed about the
walker's (:data:`WALK_PACE_SD`). People hold their pace step to step: speed
deviations are corrected at once while step length and duration drift (Dingwell, John &
Cusumano, PLoS Comput Biol 6:e1000856, 2010); the transition GP, first-order in one step's
features, does not: it carries the corpus's speed changes (free walking, turns, the bouts'
starts) into the successors of a steady step. Measured (``benchmarks/bench_variability.py``,
the four Bandai styles' 91 straight walks, 10 planned walks each, seeds 0-2): walk time IQR
117 / 121 / 113 % of the captured (chord, seeds 0-1: 146 / 144 %), median +0.3 / +0.6 / +0.6 %
(chord +1.4 / +1.3 %); planned 9 m walks of one walker (150): step speed SD 0.061 in log
(chord 0.19; captured styles 0.061-0.098), within a walk 0.039 (0.105; captured
0.039-0.048). The heuristic is the
straight-line distance to the goal centre or, by default, the larger of that and an
obstacle-aware bound from a 2-D Dijkstra over a 16-connected occupancy grid divided by the
grid's worst detour factor (both admissible). The search weights the heuristic by 1.01
(weighted A*: a walk is at most 1 % longer than the best continuation of the sampled steps),
which cuts node expansions about eightfold on open floors; ``heuristic_weight=1.0`` is the
paper's plain A*. On walks starting more than 14 m from the goal, nodes farther than 4 m
from it weigh their heuristic by 0.05 more (:data:`FAR_WEIGHT`; long walks through clutter
stay near-linear in expansions). A successor is
rejected when any sample of its pelvis trajectory comes closer to an obstacle (or the floor's
edge) than the body radius, or when it ends in a grid cell (0.08 m, optionally with heading
bins) that is already closed (near the goal: closed for walking on after
:data:`NEAR_GOAL_EXPANSIONS` expansions, never for a closing step).

Because the steps are random, repeated plans between the same points differ — they form the
corridor real walks form — while a fixed ``rng`` seed reproduces a plan exactly.

Speed (``benchmarks/bench_planner.py``). The search loop (:func:`mjwalk.plan.search.search`)
with its GP draws (:mod:`mjwalk.gait.gpdraw`) and step checks (:mod:`mjwalk.plan.stepcheck`)
is compiled with numba: an expansion is ten successors of twenty checked points each, and as
NumPy calls and Python bookkeeping its overhead cost several times its arithmetic. Python keeps
the setup (endpoint checks, the start heading, the KDE starters) and the final chain's 120 Hz
decode. What the compiled loop does per draw:

* **One affine map** (:class:`_Decoder`): features -> pelvis samples, landing foot and yaws in
  the step's frame, as complex numbers so the turn into the world is one product.
* **One clearance lookup** per checked point in :meth:`Workplace.walk_field` (obstacle
  clearance and floor edge in one field, never above either on the floor), stopping at the
  first point that fails.
* **The GP's dense variance** C - k W kᵀ (m inducing inputs) through the upper triangle of W
  (half its memory). It cannot be cut short: every inducing input has k(x, z)/C > 1e-6 at
  the chains' predecessors, and the variance ~ 1e-3 C is a cancellation carried by W's small
  eigenvalues, so even 150 of W's 400 eigen-components leave errors larger than the variance
  (nor stored in float32: errors up to 12x the variance). At m = 400 it was about half of an
  expansion's time; the default model has m = 200
  (:data:`~mjwalk.gait.transition.N_INDUCING` says what that costs the model: nothing
  measurable).

The compiled loop expands the nodes, and draws from ``rng``, in the order the NumPy/Python
implementation before it did (checked on 30 walks in three scenes: the same expansions,
samples and rejections, lengths equal to 1e-8 m).
"""

from __future__ import annotations

import math
import time
import weakref

import numpy as np

from mjwalk._args import as_generator, check_seed, finite_points, parse_point
from mjwalk.anthropometry import ROM_DEG, SHIN_RADIUS, leg_geometry
from mjwalk.conventions import DEFAULT_STATURE, SAMPLE_RATE_HZ
from mjwalk.errors import InputError, PlanningError
from mjwalk.gait.features import _I_DUR, StepBatch, spline_basis
from mjwalk.gait.transition import POOL_SHARPNESS
from mjwalk.plan import search, stepcheck
from mjwalk.plan.grid import (
    BODY_RADIUS,
    CELL_SIZE,
    MOVES_16,
    OccupancyGrid,
    check_endpoint,
    shared_grid,
)
from mjwalk.plan.heuristic import GoalDistance, goal_distance
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.world.clearance import ClearanceField
from mjwalk.world.workplace import Workplace

FPS = SAMPLE_RATE_HZ
#: Extra clearance (metres) demanded of the sampled trajectory points: it covers the bilinear
#: field's error (< 4 mm) and the curve between two of the 16 checked samples of a step, so the
#: full 120 Hz path keeps the body radius by MuJoCo's own geometry.
SAFETY_MARGIN = 0.01
#: Ankle-to-toe length (m) and the clearance (m) both must keep from obstacles and the floor's
#: edge: the landing foot reaches ahead of the pelvis, into a shelf or a car body otherwise.
FOOT_LENGTH = 0.14
FOOT_CLEARANCE = 0.08
#: The swing knee reaches beyond the body radius. Measured over the swings of 20 planned walks
#: played back (1.75 m humanoid; pelvis frame at the frame of the knee's farthest reach, which
#: falls at 0.26-0.94 of the step, median 0.69): the knee centre is 0.21 m (95th percentile
#: 0.25, max 0.27) ahead along the pelvis yaw (a turning or side step turns the yaw away from
#: the direction of travel) and 0.11 m (0.15, 0.19) to the swing side; the thigh is 6.1 cm
#: thick (0.035 stature). Probes at half and three quarters of the step, ``KNEE_LEAD`` ahead
#: and ``KNEE_SIDE`` to the swing side, keep ``KNEE_CLEARANCE`` (thigh radius, 1 cm margin and
#: 3 cm for the knee's spread about the probe).
KNEE_LEAD = 0.23
KNEE_SIDE = 0.12
KNEE_CLEARANCE = 0.10
#: The landing leg at heel strike. A foot lands heel first, toes up (the leg synthesis,
#: :mod:`mjwalk.body.legs.synthesis`): its ankle lies some 4 cm behind and 2 cm above the flat
#: footprint's, the heel's upper edge swings 2-3 cm behind the flat heel, and the shin leans
#: back from the ankle towards the hip. A landing foot far ahead of the pelvis (up to
#: MAX_FOOT_REACH) leaves some 0.2 m of shin between the ankle's check and the pelvis's; found
#: by ``benchmarks/bench_contacts.py`` (station run 727 of 1000, seed 0: a 1.64 m operator's
#: last step of route T4 lands 0.51 m ahead of the pelvis, its ankle 8.3 cm beside the corner
#: of rack 2's frame post, and shin and heel touch the post 5-9 mm deep). Probes every
#: ``LEG_PROBE_STEP`` metres along the ankle-to-hip line keep the shin radius
#: (:data:`mjwalk.anthropometry.SHIN_RADIUS` times the walker's stature) plus SAFETY_MARGIN
#: plus half the spacing (:func:`mjwalk.plan.stepcheck.landing_leg_clear`); the first probe
#: also covers the toes-up heel (at 1.75 m its upper back edge reaches 0.09 m behind the
#: ankle, 0.05 m to the side: 0.07 m from the probe, within the 0.077 m kept). Measured with
#: the probes (``bench_contacts.py --walks 200 --cycles 1000 --jobs 2``): corridor 0 of 400
#: walks, station 0 of 1000 runs with contacts (without: 0 and 1); they change the walks of 4
#: of the first 150 station runs (12 of 1050 walks, median route lengths within 1 mm) and 3 of
#: 200 corridor walks.
LEG_PROBE_STEP = 0.04


def leg_clearance(stature: float = DEFAULT_STATURE) -> float:
    """Clearance (m) the landing leg's probes keep for a walker of ``stature`` metres: the
    shin radius plus SAFETY_MARGIN plus half of LEG_PROBE_STEP."""
    return SHIN_RADIUS * stature + SAFETY_MARGIN + 0.5 * LEG_PROBE_STEP


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
#: on where in its cell it lies and on its step, for which a cell's first node does not stand.
#: Station route T5 (1.1 m along the rack front, 0.1 m goal, radius 0.30, 200 seeded walks,
#: default model of corpus 2): walks shorter than 1.5 m 51 % with one expansion per cell and no
#: closing-only draws (median 1.31 m, IQR 3.27 m), 79 % with both (1.13 m, 0.12 m).
NEAR_GOAL_EXPANSIONS = 3
#: The stance leg must follow every step: with the stance sole level sideways (as the leg
#: synthesis keeps it) the ankle takes the sideways lean of the hip-to-ankle line in the stance
#: foot's frame, the hip its lean in the pelvis frame, and a step whose lean leaves the
#: humanoid's ranges even with the leg stretched straight (ROM_DEG, after AAOS: ankle eversion
#: 15 / inversion 35 deg, hip adduction 30 / abduction 45 deg) is rejected
#: (:func:`mjwalk.plan.stepcheck.stance_lean_ok`). The hip offset and leg length are those of
#: the default 1.75 m humanoid (the planner does not know the walker's stature; the lean of a
#: given placement scales about inversely with it). On planned walks the straight-leg lean is
#: within 1-2 deg of the leg synthesis's own (unclipped) ankle inversion where it matters.
#: Measured (``benchmarks/bench_stance_lean.py``: the leg tests' four routes, seeds 0-10, 5 walks
#: each, and 3 x 10 walks in three scenes): without the check 1 of 186, 47 of 1803 and 6 of
#: 360 planned steps lean out of range (all but a few in the corridor's corners); with it 5 of
#: 20, 50 of 200 and 10 of 30 walks change (the others because a successor refused during
#: the search changes its course), none fails, median lengths within 0.03 m.
LEAN_GEOMETRY = leg_geometry(1.75)


def lean_params() -> dict[str, float]:
    """The stance-lean check's slots of :func:`mjwalk.plan.stepcheck.params`: hip offset and
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


#: Far from the goal the heuristic weighs more (dynamic weighting, Pohl 1973): beyond
#: ``FAR_FROM`` metres of obstacle-aware distance h, f = g + weight·h + FAR_WEIGHT·(h - FAR_FROM).
#: Why: the bound h falls short of the walked length left by a share that does not shrink with
#: distance (the grid bound is divided by the 16-move detour factor 1.026, and sampled steps
#: weave around obstacles), so with weight 1.01 alone the open list's f grows along the walk and
#: the search floods back over the nodes it passed: expansions grew as L^2.5 and 32 m walks in
#: a cluttered hall spent the budget (issue 18). Measured: walked chord length over h at the
#: start, 18 walks of 8-24 m in the generated 36 x 10 m hall with 144 boxes (seed 0): median
#: 1.023, 90th percentile 1.057; weight plus far weight (1.06) covers the 90th percentile.
#: Only walks starting more than ``LONG_WALK`` metres (h) from their goal get it: shorter ones
#: are planned exactly as before (every walk of the shipped scenes: the station, the corridor's
#: 13 m route, whose seeded walks tests pin; the flood stays well within the budget there:
#: measured before, 8 and 16 m walks in the cluttered hall took median 226 and 979 of the
#: 4000 expansions). Measured with the far weight on every walk (FAR_FROM = 4 m): expansions
#: 108, 422, 690 at 8, 16, 32 m, 0 failures in 20 (before: 226, 979, 4090, 11 of 20 failing
#: at 32 m), but two of the corridor's five fixture walks were re-sampled into 6-8 deg knee
#: changes per sample; with FAR_FROM = 14 m instead, 32 m walks still failed 3 of 20.
FAR_WEIGHT = 0.05
FAR_FROM = 4.0
LONG_WALK = 14.0
#: Expansions one search may spend. The energy cost makes the search back up where sampled
#: successors stray from the walker's pace (32 m walks in the cluttered hall, 100 seeded:
#: median 1011 expansions, 90th percentile 2309, against 720 and 1517 with the chord), and
#: 2 of 100 spent 4000 (the chord: 1); with 8000 they took 5652 and 4364.
MAX_EXPANSIONS = 8000


#: A walk longer than this multiple of the obstacle-aware route length from its start to the
#: goal is a loop, not a variation: people do not walk back around a rack to arrive. The
#: planner then searches again with fresh samples (up to ``attempts`` searches in all, keeping
#: the shortest). Measured without re-planning (station cycle, 300 runs, 2100 walks, stand
#: zones): walk length over that route length runs continuously up to 1.47 (99th percentile),
#: then jumps to the loops, 1.68-10; 1.5 lies in the gap. A walk that still loops after every
#: attempt is returned with ``meta["wandering"]`` set.
WANDER_FACTOR = 1.5
#: Searches a looping walk gets in all (each with fresh samples) before the shortest is kept.
#: With three, the shipped workforce's short T5 walks (rack 2 -> rack 3, 1.1 m; slow operators
#: with short steps and small stand zones) still looped on every search in about 1 % of the
#: cycles (99th percentile of length over the grid route 1.38, the loop bound 1.35); with six,
#: 1.24 (``benchmarks/bench_variability.py --cycles 200``). A loop costs a short walk's
#: search (milliseconds), so the extra searches are cheap where they happen.
WANDER_SEARCHES = 6
#: Searches a walk gets in all when the open list runs dry (every sampled continuation
#: blocked). Into a tight stand zone (about 0.02 m^2: a short operator with long steps at a
#: rack) about one search in ten runs dry (measured: 21 of 200 from the same start), so with
#: three in all about one walk in a thousand failed (1 of 300 station cycles, 3-5 of 300 of
#: the two-handed station's; with six, 0 of 900 and 1 of 900 over three populations). A plan
#: whose searches ran dry fewer than three times draws the same numbers either way.
ATTEMPTS = 6


#: :meth:`HybridPlanner.default_heading`'s 72 directions (radians) and its probes 0.3 m out
#: along them (metres), made once.
_HEADING_ANGLES = np.linspace(-math.pi, math.pi, 72, endpoint=False)
_HEADING_PROBES = 0.3 * np.stack([np.cos(_HEADING_ANGLES), np.sin(_HEADING_ANGLES)], axis=1)


#: Weight of the squared heading error in a step's cost while the goal is in sight
#: (:func:`mjwalk.plan.stepcheck.heading_factor`: Mombaur, Truong & Laumond 2010, α4 / α0 of
#: their inverse-optimal-control cost of human walking). Why: the walked length (and its
#: energy) grows only with the square of a drift sideways (0.13 m off the chord over 9 m
#: lengthens the walk by 0.4 %, less than the search's 1 % heuristic slack), so the search
#: kept whatever heading drift the transition GP's samples carried: planned 9 m walks on the
#: open floor deviated from their own chord by 0.13 m median (stride-averaged pelvis, 40
#: walks, seed 3; captured straight walks 0.03-0.04 m). The term stops within the closing
#: reach of the goal (``stop_reach``), where the walk turns to its goal heading. The term
#: counts only where the goal is in sight (:attr:`~mjwalk.plan.heuristic.GoalDistance.in_sight`),
#: and only on walks that see the goal from their start: where an obstacle hides it, the route
#: around it decides (a term that set in only once the goal came into view would charge the
#: side that sees it first: walks passing a pillar 0.1 m off their axis chose the side of the
#: smaller deviation angle 64 % of the time instead of 88 %, the cited logistic model 93 %).
HEADING_WEIGHT = 5.2

#: Turning speed on the spot (rad/s) of a walker who sets off facing away from the way
#: (``plan(turn_on_spot=True)``): ASSUMPTION, a half turn in about two steps (1.06 s at
#: 113 steps/min), as the cycle turns an operator (``mjwalk.cycle.poses.TURN_SPEED``).
ON_SPOT_TURN_SPEED = math.pi

#: Walk-to-walk spread of a person's pace with the energy cost: each walk's preferred speed is
#: the walker's times exp(N(0, WALK_PACE_SD²)), as the virtual subjects vary theirs from bout
#: to bout (:func:`mjwalk.gait.corpus.sample_subject`, ``speed_sd`` uniform 0.03-0.06).
WALK_PACE_SD = 0.045


class _Exhausted(PlanningError):
    """The open list ran dry (all sampled continuations blocked): worth a fresh search."""


def _goal_discs(discs, goal: np.ndarray) -> np.ndarray:
    """(k, 3) goal discs (x, y, radius; metres) checked: finite, positive radii, at most
    :data:`~mjwalk.plan.stepcheck.MAX_GOAL_DISCS` less one, and the goal itself inside every
    one (the goal area must not be empty where the walk is aimed)."""
    arr = np.asarray(discs, dtype=float).reshape(-1, 3) if len(discs) else np.zeros((0, 3))
    if len(arr) > stepcheck.MAX_GOAL_DISCS - 1:  # one kept for a spot's walk (plan)
        raise PlanningError(
            f"goal_within: at most {stepcheck.MAX_GOAL_DISCS - 1} discs, got {len(arr)}"
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


def _to_world(px, py, heading, local: np.ndarray) -> np.ndarray:
    """Local step coordinates (x right, y forward) -> world, for a frame at (px, py) heading
    ``heading`` (radians from +x). ``local`` (..., 2); px, py, heading broadcast against it."""
    s, c = np.sin(heading), np.cos(heading)
    x, y = local[..., 0], local[..., 1]
    return np.stack([px + x * s + y * c, py - x * c + y * s], axis=-1)


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


class _Decoder:
    """What the search needs of a step, as one affine map of its standardized features z (d,).

    ``z @ matrix + offset`` is a complex row (2m + 3,) in the step's local frame (x right,
    y forward; x + iy, metres): the pelvis at m samples evenly spaced in time (sample 0 is the
    start, exactly 0; sample m-1 the end), the landing ankle, (landing foot yaw +
    i · end pelvis yaw) in radians relative to the start heading, and the pelvis yaw at the
    m samples (real parts, radians relative to the start heading; the stance-lean check
    decodes them only for the steps that reach it) and the duration (real part, seconds, not
    clipped; the energy cost's). Decoding features and
    evaluating the landmark spline are both affine (see :mod:`mjwalk.gait.features`), so the
    map is read off the model's own decoder at z = 0 and the unit vectors, then checked on
    random features: a model whose decoding is not affine is refused, not mis-planned.
    """

    def __init__(self, model, m: int):
        d = model.n_dims
        basis = np.vstack([np.zeros(d), np.eye(d)])
        cols = self._columns(model, basis, m)
        self.offset = cols[0]
        self.matrix = np.ascontiguousarray(cols[1:] - cols[0])
        z = np.random.default_rng(0).standard_normal((16, d)) * 3.0
        ref = self._columns(model, z, m)
        if not np.allclose(z @ self.matrix + self.offset, ref, rtol=0.0, atol=1e-9):
            raise PlanningError("the step model's decoding is not affine in its features")

    @staticmethod
    def _columns(model, z: np.ndarray, m: int) -> np.ndarray:
        batch: StepBatch = model.decode(z, "left")
        local, yaw = batch.resample(m)
        return np.column_stack(
            [
                local[..., 0] + 1j * local[..., 1],
                batch.footprint[:, 0] + 1j * batch.footprint[:, 1],
                batch.footprint[:, 2] + 1j * batch.end_yaw,
                yaw + 0j,
                # the duration before decode's clip at MIN_DURATION (the check clips it)
                model.features.decode_raw(z)[:, _I_DUR] + 0j,
            ]
        )


#: Decoders already built, by model and samples per step (:func:`_decoder_of`); the model is
#: held weakly and the oldest entries go beyond :data:`_DECODERS_MAX`.
_DECODERS: dict[tuple[int, int], tuple[weakref.ref, _Decoder]] = {}
_DECODERS_MAX = 16


def _decoder_of(model, m: int) -> _Decoder:
    """The :class:`_Decoder` of ``model`` at ``m`` samples per step, built once per process.

    Building one decodes and checks 23 feature rows (about 0.15 ms, as much as a short walk's
    whole search); planners are made per goal (a cycle's walks, a benchmark's start/goal
    pairs), models per operator (:meth:`StepModel.for_walker`), so it is shared by model."""
    key = (id(model), int(m))
    hit = _DECODERS.get(key)
    if hit is not None and hit[0]() is model:
        return hit[1]
    dec = _Decoder(model, m)
    while len(_DECODERS) >= _DECODERS_MAX:
        _DECODERS.pop(next(iter(_DECODERS)))
    _DECODERS[key] = (weakref.ref(model), dec)
    return dec


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
        self._walk = workplace.walk_field()
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
            held = self._params[stature] = self._make_kernel_params(stature)
        return held[0].copy(), held[1].copy()

    def _make_kernel_params(self, stature: float) -> tuple[np.ndarray, np.ndarray]:
        m = self.samples_per_step
        knee_cols = (m // 2, (3 * m) // 4)  # the swing-knee probes' pelvis samples
        walk, gd = self._walk, self.distance
        par = stepcheck.params(
            knee_lead=KNEE_LEAD,
            knee_side=KNEE_SIDE,
            foot_length=FOOT_LENGTH,
            foot_reach=MAX_FOOT_REACH,
            lift_reach=MAX_LIFT_REACH,
            stride=MAX_STRIDE,
            goal_x=self.goal[0],
            goal_y=self.goal[1],
            tolerance=self.tolerance,
            goal_yaw=math.nan if self.goal_yaw is None else self.goal_yaw,
            yaw_tolerance=self.goal_yaw_tolerance,
            weight=self.heuristic_weight,
            corner_x=self.grid.x0,
            corner_y=self.grid.y0,
            cell=self.cell,
            field_x0=walk.x0,
            field_y0=walk.y0,
            field_res=walk.resolution,
            dist_x0=self.grid.x0,
            dist_y0=self.grid.y0,
            dist_cell=self.grid.cell,
            dist_top_x=self.grid.free.shape[1] - 1.0,
            dist_top_y=self.grid.free.shape[0] - 1.0,
            knee_share0=knee_cols[0] / (m - 1),  # the probes' share of the step
            knee_share1=knee_cols[1] / (m - 1),
            stop_reach=self.tolerance + STOP_REACH,
            pool_sharpness=POOL_SHARPNESS,
            **lean_params(),
            far_weight=self.far_weight,
            far_from=FAR_FROM,
            leg_step=LEG_PROBE_STEP,
            leg_clearance=leg_clearance(stature),
            dist_offset=0.0,
            pace=math.nan,
            heading_weight=self.heading_weight,
            heading_from=self.tolerance + STOP_REACH,
        )
        for k, (dx, dy, dr) in enumerate(self.goal_within):
            par[stepcheck.P_DISC0 + 3 * k : stepcheck.P_DISC0 + 3 * k + 3] = (dx, dy, dr)
        ipar = stepcheck.iparams(
            m=m,
            q=max(2, m // 4),  # samples of a step's first quarter (the foot behind lifts off)
            knee_col0=knee_cols[0],
            knee_col1=knee_cols[1],
            # closed cells as one integer: (i * span + j) * bins + heading bin, with span
            # larger than any cell row index j of a point a step can reach (the grid's rows
            # plus a margin)
            span=4 * max(self.grid.free.shape) + 1000,
            bins=self.heading_bins,
            field_nx=walk.values.shape[1],
            field_ny=walk.values.shape[0],
            dist_nx=gd.grid.free.shape[1],
            dijkstra=self.heuristic == "dijkstra",
            chord=self.cost != "path",
            n_successors=self.n_successors,
            n_stops=self.n_stops,
            max_expansions=self.max_expansions,
            near_goal_expansions=NEAR_GOAL_EXPANSIONS,
            n_discs=len(self.goal_within),
        )
        return par, ipar

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

    def _decoder(self, model=None) -> _Decoder:
        return _decoder_of(self.model if model is None else model, self.samples_per_step)

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
        cost = stepcheck.downhill_costs(
            np.asarray(xy, dtype=float), _HEADING_PROBES, c.values, c.x0, c.y0, c.resolution,
            np.asarray(wp.floor_bounds, dtype=float), float(self.radius),
            self.distance.flat_bound(), g.x0, g.y0, g.cell, g.free.shape[1] - 1.0,
            g.free.shape[0] - 1.0, gx, gy, offset,
        )  # fmt: skip
        return float(_HEADING_ANGLES[int(np.argmin(cost))])

    # -- search ----------------------------------------------------------------------------

    def plan(
        self, start, rng: np.random.Generator, *, model=None, spot=None, turn_on_spot=False
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

        When the open list runs dry (every sampled continuation blocked, which happens now and
        then in tight places), the search starts over with fresh samples, up to ``attempts``
        times in all; a spent expansion budget ends the planning at once. A walk that loops
        (:data:`WANDER_FACTOR`) is searched again too, up to :data:`WANDER_SEARCHES` searches
        in all, and the shortest is kept.
        """
        if spot is not None:  # checked once, before any search
            spot = self._check_spot(spot)
        pose = _parse_pose(self.workplace, start)  # parsed once, before any draw
        t0 = time.perf_counter()
        model = model or self.model
        pace = math.nan
        if self.cost == "energy":  # this walk's own pace (WALK_PACE_SD)
            pace = preferred_speed(model) * math.exp(WALK_PACE_SD * rng.standard_normal())
        best: WalkPath | None = None
        bound = None
        limit = max(self.attempts, WANDER_SEARCHES)
        exhausted = 0
        for attempt in range(limit):
            try:
                path, start_distance = self._plan_once(pose, rng, model, spot, pace, turn_on_spot)
            except _Exhausted as exc:
                exhausted += 1
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
        par[stepcheck.P_PACE] = pace
        if not self.distance.sees(start_xy):  # HEADING_WEIGHT: only for a goal in sight
            par[stepcheck.P_HEADING_WEIGHT] = 0.0
        goal_x, goal_y, tolerance = float(self.goal[0]), float(self.goal[1]), self.tolerance
        field_distance = start_distance
        if spot is not None:  # this walk's own goal point (module doc of plan)
            goal_x, goal_y, tolerance = spot
            par[stepcheck.P_GOAL_X] = goal_x
            par[stepcheck.P_GOAL_Y] = goal_y
            par[stepcheck.P_TOLERANCE] = tolerance
            par[stepcheck.P_STOP_REACH] = tolerance + STOP_REACH
            par[stepcheck.P_HEADING_FROM] = tolerance + STOP_REACH
            # the goal's field bounds the way to the spot from below only less the way between
            # them (triangle inequality; a spot sees its goal in a stand zone)
            offset = math.hypot(goal_x - self.goal[0], goal_y - self.goal[1])
            par[stepcheck.P_DIST_OFFSET] = offset
            field_distance -= offset
            # ... and the walk still ends in the planner's own goal area: one more disc
            k = int(ipar[stepcheck.I_N_DISCS])
            j = stepcheck.P_DISC0 + 3 * k
            par[j : j + 3] = (float(self.goal[0]), float(self.goal[1]), self.tolerance)
            ipar[stepcheck.I_N_DISCS] = k + 1
            start_distance = max(
                field_distance, math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y) - tolerance
            )
        if stepcheck.in_goal(complex(*start_xy), start_yaw, par, ipar):
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
            par[stepcheck.P_START_YAW] = float(facing)
            par[stepcheck.P_TURN_COST] = walk_pace / ON_SPOT_TURN_SPEED
        weight = self.heuristic_weight
        # as stepcheck.check_steps bounds a node: the field's distance, the straight line to
        # the goal point
        h0 = field_distance if self.heuristic == "dijkstra" else 0.0
        euclid = float(math.hypot(start_xy[0] - goal_x, start_xy[1] - goal_y))
        h_start = max(h0, euclid)
        far = self.far_weight if h_start > LONG_WALK else 0.0  # only long walks
        par[stepcheck.P_FAR_WEIGHT] = far
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
            self._walk.values,
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

    def _assemble(self, model, nid, nodes, feats, stats) -> WalkPath:
        parent, rows, pos, frames, lefts = nodes
        chain = []
        while nid > 0:
            chain.append(nid)
            nid = parent[nid]
        chain = np.array(chain[::-1])
        left = lefts[chain]
        batch = model.decode(feats[rows[chain]], np.where(left, "left", "right"))
        ox = pos[parent[chain]].real
        oy = pos[parent[chain]].imag
        fr = frames[chain]
        # the steps at 120 Hz (sample 0 of each is the previous step's last), one frame each
        # (StepBatch.trajectory: K = round(duration·fps) + 1 samples, at least 2, its spline
        # basis looked up once per sample count)
        n = len(chain)
        sizes = np.maximum(np.round(batch.duration * FPS).astype(np.int64) + 1, 2).tolist()
        local_parts, yaw_parts = [], []
        for row, k in enumerate(sizes):
            basis = spline_basis(k)
            local_parts.append((basis @ batch.landmarks[row])[1:])
            yaw_parts.append(basis @ batch.yaw_landmarks[row])
        counts = [k - 1 for k in sizes]
        # every sample's step, then the landing and the stance foot of every step: one turn
        # into the world for all of them
        of = np.concatenate([np.repeat(np.arange(n), counts), np.arange(n), np.arange(n)])
        local = np.concatenate([*local_parts, batch.footprint[:, :2], batch.stance[:, :2]])
        world = _to_world(ox[of], oy[of], fr[of], local)
        k = len(world) - 2 * n
        xy = np.empty((1 + k, 2))
        xy[0] = pos[0].real, pos[0].imag
        xy[1:] = world[:k]
        # sample 0 faces the first step's frame: a starter's turn on the spot (free start
        # heading) is not part of the walk (a cycle turns the operator before it), so the
        # pelvis yaw does not jump between samples 0 and 1
        yaw = np.empty(len(xy))
        yaw[0] = fr[0] + yaw_parts[0][0]
        yaw[1:] = fr[of[:k]] + np.concatenate([y[1:] for y in yaw_parts])
        # world poses (x, y, yaw) of every step's landing foot and of its own estimate of the
        # stance foot
        feet = np.column_stack([world[k : k + n], fr + batch.footprint[:, 2]])
        own_stance = np.column_stack([world[k + n :], fr + batch.stance[:, 2]])
        steps: list[PathStep] = []
        landed: dict[bool, np.ndarray] = {}
        ends = np.cumsum(counts).tolist()
        index = 0
        for row, is_left in enumerate(left.tolist()):
            # A foot stays where it landed: the stance foot of a step is where that foot landed
            # in the step before (each sampled step also carries its own estimate of it, a few
            # centimetres off its predecessor's landing, which would make the foot jump).
            stance_w = landed.get(not is_left, own_stance[row])
            landed[is_left] = feet[row]
            side = "left" if is_left else "right"
            steps.append(
                PathStep(side=side, start=index, end=ends[row], foot=feet[row], stance=stance_w)
            )
            index = ends[row]
        return WalkPath(
            t=np.arange(len(xy)) / FPS,
            xy=xy,
            yaw=yaw,
            steps=steps,
            meta={
                "planner": "hybrid_astar",
                "goal": self.goal.tolist(),
                "goal_tolerance": self.tolerance,
                "radius": self.radius,
                "heuristic": self.heuristic,
                **stats,
            },
        ).stamp_scene(self.workplace)


def plan_walk(
    workplace: Workplace,
    start,
    goal,
    model=None,
    rng: np.random.Generator | int | None = None,
    **options,
) -> WalkPath:
    """Plan one varied, gait-aware, collision-free walk with the probabilistic hybrid A*.

    Args:
        workplace: the scene.
        start: a site name, ``"x,y"``, ``"x,y,yaw_deg"`` or ``(x, y[, yaw])`` (metres, radians).
            Without a yaw the walker starts facing the way the obstacle-aware distance to the
            goal falls fastest (it turns on the spot before walking off).
        goal: a site name, ``"x,y"`` or ``(x, y)``; the walk ends within ``goal_tolerance``.
        model: a StepModel (default: :func:`mjwalk.gait.default.default_model`).
        rng: a numpy Generator or a seed.
        **options: see :class:`HybridPlanner` (goal_tolerance=0.25, goal_yaw=None,
            radius=0.25, cell=0.08, heading_bins=None (1, or 8 with a goal yaw), n_starters=30,
            n_successors=10, heuristic="dijkstra" | "euclidean", heuristic_weight=1.01,
            far_weight=0.05 (walks from beyond LONG_WALK = 14 m, nodes beyond FAR_FROM = 4 m),
            cost="energy" | "chord" | "path",
            max_expansions=8000 (per search), attempts=6,
            samples_per_step=16).

    Raises:
        PlanningError: start/goal off the floor or inside/too near an obstacle (before any
            search), goal unreachable (before any search), or the expansion budget spent.
    """
    if model is None:
        from mjwalk.gait.default import default_model

        model = default_model()
    rng = as_generator(rng, "plan_walk: rng")
    return HybridPlanner(workplace, goal, model, **options).plan(start, rng)


def plan_walks(
    workplace: Workplace,
    start,
    goal,
    model=None,
    n: int = 15,
    seed: int = 0,
    **options,
) -> list[WalkPath]:
    """``n`` independent walks from ``start`` to ``goal``; the same seed gives the same walks.

    Walk ``k`` uses its own random stream (``SeedSequence(seed).spawn``), so a walk does not
    depend on how many others are planned with it.
    """
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 0:
        raise InputError(f"plan_walks: n must be a whole number of walks >= 0, got {n!r}")
    seed = check_seed(seed, "plan_walks: seed")
    if model is None:
        from mjwalk.gait.default import default_model

        model = default_model()
    planner = HybridPlanner(workplace, goal, model, **options)
    streams = np.random.SeedSequence(seed).spawn(n)
    return [planner.plan(start, np.random.default_rng(s)) for s in streams]
