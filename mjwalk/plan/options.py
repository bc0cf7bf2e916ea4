"""The hybrid A*'s limits and defaults: :class:`PlannerOptions` and the constants behind them.

Clearances and reach limits of the body (metres), the search's weights, budgets and retries,
each with its source; the evidence behind the measured ones is in ``docs/decisions/101``-``106``
and the benchmarks named there. A planner's choices are one frozen :class:`PlannerOptions`
(every option with its default and meaning); :class:`~mjwalk.plan.params.KernelParams` encodes
them into the compiled kernels' parameter vectors (:mod:`mjwalk.plan.slots`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mjwalk.anthropometry import ROM_DEG, SHIN_RADIUS, ball_offset, leg_geometry
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE
from mjwalk.errors import InputError
from mjwalk.plan import slots
from mjwalk.plan.occupancy import CELL_SIZE

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
#: off the landing yaw. Probes over the chord's last ``TOE_APPROACH_SHARE`` keep the ankle and
#: the toes FOOT_CLEARANCE, and every point of their way in FOOT_CLEARANCE - TOE_PROBE_STEP / 2:
#: next to an obstacle they lie TOE_PROBE_STEP / L apart (L the walk field's Lipschitz
#: constant, sqrt(2) in the shipped scenes), farther where the way is clearer
#: (:func:`mjwalk.plan.stepgeom.toe_approach_clear`, ``docs/decisions/111``).
TOE_APPROACH_SHARE = 0.2
TOE_PROBE_STEP = 0.02
#: The swing knee reaches beyond the body radius: over the swings of planned walks played back
#: (1.75 m humanoid) the knee centre lies up to 0.21 m (95th percentile 0.25) ahead along the
#: pelvis yaw and 0.11 m (0.15) to the swing side, and the thigh is 0.035 statures thick
#: (``docs/decisions/103``). Probes at half and three quarters of the step, ``KNEE_LEAD``
#: ahead and ``KNEE_SIDE`` to the swing side, keep ``KNEE_CLEARANCE`` (thigh radius, 1 cm
#: margin and 3 cm for the knee's spread about the probe). The knee's farthest reach falls at
#: 0.26-0.94 of the step (docs/decisions/103), and in a turning step its farthest reach
#: sideways comes early, just after toe-off (step phase 0.2), while the foot still points
#: along its lift-off yaw: generated hall 317 (flat-hall stress draws, seed 317, walk 1), the
#: left foot turning 92 deg in one step, the knee 0.24 m beside the pelvis at 0.31 of the
#: step and the thigh 2.2 cm into a thin box the probes at 0.53 and 0.80 kept 0.27 and 0.47 m
#: from. A third probe at a third of the step (after the lifting foot's heading is known, the
#: probes' foot-yaw lead below) closes that gap with the same lead: over 826 planned steps in
#: generated halls (seeds 300-330) the synthesized knee leads the hip along the foot's yaw by
#: a median 0.01-0.07 m at 0.27-0.40 of the step (95th percentile 0.14-0.18, at most 0.28),
#: 0.17-0.21 m at 0.53-0.80 (at most 0.25) (``docs/decisions/103``).
KNEE_LEAD = 0.23
KNEE_SIDE = 0.12
KNEE_CLEARANCE = 0.10
#: The knee bends in the swing foot's plane (the leg IK, :mod:`mjwalk.body.legs.ik`), and the
#: swing foot turns from its lift-off yaw to its landing yaw along a smoothstep between these
#: step phases (the leg synthesis's ``TOE_OFF`` and ``SWING_TURNED``,
#: :mod:`mjwalk.body.legs.steps`, which this stage cannot import; ``tests/plan/test_options.py``
#: checks they agree). In a turning step the knee therefore leads along the swing foot's yaw,
#: not the pelvis's: station run 330 of 2000 (seed 0), a 1.81 m operator's left knee 0.33 m
#: beside the pelvis, its foot 50 degrees behind the pelvis's turn, 3 cm into rack 2's frame.
#: The probes lead along the foot's yaw at their phase (:func:`swing_turned`) from the swing
#: hip's joint centre (:func:`knee_pivot`: ``leg_geometry(stature).hip_y``, 0.087 m at 1.75 m,
#: to the swing side along the pelvis's yaw), not from ``KNEE_SIDE``: that offset, measured
#: along the pelvis's yaw, holds the hip's offset plus the lead turned by the feet's toe-out,
#: which the foot's yaw already turns, so adding both put the probes 4-5 cm outward of the
#: synthesized knee at 0.8 of a toe-out step (20 planned steps, docs/decisions/103). Lead and
#: side scale with stature (the humanoid's segments are stature fractions,
#: :mod:`mjwalk.anthropometry`).
SWING_TURN_PHASES = (0.2, 0.9)
#: A grounded foot whose hip would rotate past its range turns about its ball instead (the
#: leg synthesis's spin turns, :mod:`mjwalk.body.legs.spin`): a swing foot lifts at most the
#: hip's rotation range (``ROM_DEG["hip_rot"]``, 45 deg) off the pelvis's yaw at the step's
#: start, whatever its footprint's yaw. Without this bound a step after a turn on the spot
#: (a footprint 110-135 deg off the pelvis) put the foot 35-50 deg off the synthesized foot
#: at the first knee probe; with it 2-7 deg (docs/decisions/103).
SWING_LIFT_TURN = math.radians(max(abs(a) for a in ROM_DEG["hip_rot"]))
#: The landing leg at heel strike. A foot lands heel first, toes up (the leg synthesis,
#: :mod:`mjwalk.body.legs.synthesis`): its ankle lies some 4 cm behind and 2 cm above the flat
#: footprint's, the heel's upper edge swings 2-3 cm behind the flat heel, and the shin leans
#: back from the ankle towards the hip. A landing foot far ahead of the pelvis (up to
#: MAX_FOOT_REACH) leaves some 0.2 m of shin between the ankle's check and the pelvis's. Probes
#: along the ankle-to-hip line keep the shin radius (:data:`mjwalk.anthropometry.SHIN_RADIUS`
#: times the walker's stature) plus SAFETY_MARGIN plus half of ``LEG_PROBE_STEP``, and every
#: point of the line the shin radius plus SAFETY_MARGIN: next to an obstacle they lie
#: LEG_PROBE_STEP / L apart (L the walk field's Lipschitz constant, sqrt(2) in the shipped
#: scenes), farther where the leg is clearer (:func:`mjwalk.plan.stepgeom.landing_leg_clear`,
#: ``docs/decisions/111``). The line's clearance also covers the toes-up heel (at 1.75 m its
#: upper back edge reaches 0.09 m behind the ankle, 0.05 m to the side, within the 0.057 m the
#: line point beside it keeps). Evidence: ``docs/decisions/103``
#: (``benchmarks/bench_contacts.py``).
LEG_PROBE_STEP = 0.04
#: Largest horizontal distance (m) of a planted foot from the pelvis: the largest seen in the
#: virtual corpus (landing foot vs pelvis at heel strike: median 0.37, 99.9th percentile 0.52).
MAX_FOOT_REACH = 0.55
#: A planted foot rolls in its own vertical plane: behind the body its heel rises about the
#: ball (pre-swing, up to the leg synthesis's ``HEEL_RISE_MAX``, 60 deg,
#: :mod:`mjwalk.body.legs.steps`, which this stage cannot import; ``tests/plan/test_options.py``
#: checks they agree), ahead of it the foot lands heel first, toes up. Either roll brings the
#: ankle towards the hip along the foot's heading only: MAX_FOOT_REACH, measured on corpus
#: walkers (N(1.75, 0.04) m tall, :mod:`mjwalk.gait.subjects`) whose feet point along their
#: walk, holds that gain, a foot turned across the way to the pelvis does not have it (issue 50:
#: station runs 1913, 2306, 3164 and 9146 of 10 000, a foot 40-96 deg across the way to a
#: pelvis 0.48-0.55 m from it, the stance leg reaching it only with the pelvis 5.3-8.3 cm
#: lowered). ASSUMPTION: the gain is the ball's (the larger lever) lift of the ankle's
#: horizontal place at the largest heel rise, ``ball·(1 - cos 60 deg)``, 7.3 cm at 1.75 m, and
#: a foot at θ to the way gains its |cos θ| share (:func:`foot_reach`).
FOOT_ROLL_MAX = math.radians(60.0)
#: Longest stride (m; same foot, lift-off to landing) and farthest lift-off foot from the pelvis
#: in the first quarter of a step (m): the virtual corpus's maxima (medians 1.33 and 0.48).
MAX_STRIDE = 1.74
MAX_LIFT_REACH = 0.64
#: How far (m) a step's end pelvis and its landing ankle lie at least ahead of its start pelvis,
#: along its start heading (the step's frame): a walking step goes forward. In the virtual corpus
#: (the default model's 25 037 steps: straight walks, free walking with its side steps and turns
#: on the spot, pole turns, short walks, their first and closing steps) no step ends with the
#: pelvis behind its start (least 0.022 m ahead, median 0.64) nor lands its foot behind it (least
#: 0.002 m ahead, median 1.01); the transition GP draws such a step only far from its data, and
#: the leg synthesis, a forward gait's, cannot walk it: station runs 5909 and 9828 of 10 000
#: (seed 0; issue 50) stepped a foot 0.43-0.47 m behind the start pelvis, the pelvis going back
#: 0.06-0.20 m, and the stance leg reached its foot only with the pelvis 6.3-7.5 cm lowered
#: (> :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX`). A walking step's landing ankle lies as
#: much at least ahead of its stance ankle, along the same heading: its swing foot passes the
#: stance foot (:func:`~mjwalk.plan.stepgeom.passes_stance`). In the corpus every walking step's
#: does (least 0.043 m, median 0.685, 22 590 steps); a closing step's foot comes beside the stance
#: foot (0.001-0.020 m ahead, median 0.005, 2 447 steps), which that test leaves to the goal.
#: Station run 4395 of 10 000 (seed 0, bebb988): a 1.56 m operator's right foot landed 0.48 m
#: ahead of the pelvis, the next step's left foot 0.24 m behind it (0.24 m ahead of the start
#: pelvis: the test above passed it; the pelvis within 0.48 m of the stance ankle, from its
#: centre or from the stance hip, against a reach of 0.49 m: :func:`foot_reach`), so at heel
#: strike the stance foot lay 0.29 m ahead of its hip (corpus: at most 0.08 m) and the leg
#: synthesis, which lifts that foot's heel as a trailing one's, reached it only with the pelvis
#: 6.8 cm lowered. ASSUMPTION: the limit is the first principle itself (not backward), 0 m, not
#: the corpus's least figures, which are a sample's.
MIN_STEP_ADVANCE = 0.0
#: A walker turning on the spot (or without a start yaw and without a clear guide) sets off
#: within +-60 degrees of the obstacle-aware downhill heading; without a start yaw but with a
#: guide it sets off along the guide (:func:`mjwalk.plan.guide.guide_start_heading`).
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
#: (``WalkRequest(turn_on_spot=True)``): ASSUMPTION, a half turn in about two steps (1.06 s at
#: 113 steps/min), as the cycle turns an operator (``mjwalk.cycle.poses.TURN_SPEED``).
ON_SPOT_TURN_SPEED = math.pi
#: Walk-to-walk spread of a person's pace with the energy cost: each walk's preferred speed is
#: the walker's times exp(N(0, WALK_PACE_SD²)), as the virtual subjects vary theirs from bout
#: to bout (:func:`mjwalk.gait.corpus.sample_subject`, ``speed_sd`` uniform 0.03-0.06).
WALK_PACE_SD = 0.045


def leg_clearance(stature: float = DEFAULT_STATURE) -> float:
    """Clearance (m) the landing leg's probes keep for a walker of ``stature`` metres: the
    shin radius plus SAFETY_MARGIN plus half of LEG_PROBE_STEP (every point of the leg then
    keeps the shin radius plus SAFETY_MARGIN: :func:`mjwalk.plan.stepgeom.landing_leg_clear`).

    Args:
        stature: the walker's body height, metres.

    Returns:
        The clearance, metres.
    """
    return SHIN_RADIUS * stature + SAFETY_MARGIN + 0.5 * LEG_PROBE_STEP


def swing_turned(share: float) -> float:
    """How far the swing foot has turned from its lift-off yaw to its landing yaw at a step
    phase, as the leg synthesis turns it (a smoothstep over :data:`SWING_TURN_PHASES`).

    Args:
        share: the step phase, 0 (lift-off) to 1 (landing).

    Returns:
        The turned share, 0 to 1.
    """
    lo, hi = SWING_TURN_PHASES
    u = min(max((share - lo) / (hi - lo), 0.0), 1.0)
    return u * u * (3 - 2 * u)


def knee_reach(stature: float = DEFAULT_STATURE) -> tuple[float, float]:
    """The swing-knee probes' lead and swing-side offset (m) for a walker of ``stature``
    metres: :data:`KNEE_LEAD` and :data:`KNEE_SIDE`, measured on the 1.75 m humanoid, scaled
    with stature.

    Args:
        stature: the walker's body height, metres.

    Returns:
        (lead, side), metres.
    """
    scale = stature / DEFAULT_STATURE
    return KNEE_LEAD * scale, KNEE_SIDE * scale


def foot_reach(stature: float = DEFAULT_STATURE) -> tuple[float, float]:
    """A planted foot's reach for a walker of ``stature`` metres: the farthest the pelvis may
    lie from its ankle along the foot's heading, :data:`MAX_FOOT_REACH` scaled with stature
    (the leg's lengths are stature fractions, :mod:`mjwalk.anthropometry`), and what the foot's
    roll adds there (:data:`FOOT_ROLL_MAX`): across the foot the reach is the first less the
    second (:func:`mjwalk.plan.stepgeom.out_of_reach`).

    Args:
        stature: the walker's body height, metres.

    Returns:
        (reach, roll), metres.
    """
    geom = leg_geometry(stature)
    ball = ball_offset(geom)  # the toe joint's lead
    return MAX_FOOT_REACH * stature / DEFAULT_STATURE, ball * (1.0 - math.cos(FOOT_ROLL_MAX))


#: The clearance (m) the toes' front corners keep (:func:`toe_corners`): the walk field's error
#: and the path between samples (:data:`SAFETY_MARGIN`) and how much further the toe box reaches
#: at heel strike, the foot pitched toes up about the ankle, than flat: 1.4 cm for station run
#: 1865's 1.87 m operator (toe box centre 0.199 m ahead of the ankle one frame before landing,
#: 0.185 m flat), taken as 1.5 cm.
TOE_CORNER_CLEARANCE = SAFETY_MARGIN + 0.015


def toe_corners(stature: float = DEFAULT_STATURE) -> tuple[float, float]:
    """Where the front corners of the toes of a walker of ``stature`` metres lie from the
    ankle along a flat foot: the humanoid's toe box ends at ``foot_front`` and is the sole's
    width (:func:`mjwalk.anthropometry.leg_geometry`; :func:`mjwalk.body.humanoid.build_humanoid`),
    0.200 m ahead and 0.048 m aside at 1.75 m, 0.223 and 0.053 at 1.95 m.

    The landing toe probe at :data:`FOOT_LENGTH` (0.14 m, not scaled) keeping
    :data:`FOOT_CLEARANCE` does not cover these corners for a tall walker: station run 1865 of
    2000 (seed 0, main c7f4517), a 1.87 m operator's last step of route T4 landed at yaw -61
    deg with the probe 9.4 cm from rack 2's frame post; the toe box's corner, 0.213 m ahead and
    0.051 m aside of the ankle (flat; 1.4 cm further at heel strike), lay 0.089-0.101 m from
    the probe and went 3.6 mm into the post.

    Args:
        stature: the walker's body height, metres.

    Returns:
        (ahead, aside): metres along the foot and to each side of it.
    """
    g = leg_geometry(stature)
    return g.foot_front, 0.5 * g.foot_width


def knee_pivot(stature: float = DEFAULT_STATURE) -> float:
    """The swing-side offset (m) the knee probes lead from along the swing foot's yaw: the hip
    joint centre's lateral offset from the pelvis of a walker of ``stature`` metres
    (:func:`mjwalk.anthropometry.leg_geometry`), about which the knee swings in the foot's plane.

    Args:
        stature: the walker's body height, metres.

    Returns:
        The offset, metres.
    """
    return float(leg_geometry(stature).hip_y)


def lean_params() -> dict[str, float]:
    """The stance-lean check's slots of :func:`mjwalk.plan.slots.params`: hip offset and
    straight-leg length (m) of :data:`LEAN_GEOMETRY`, and the ankle eversion/inversion and hip
    adduction/abduction limits (radians) of ``ROM_DEG``.

    Returns:
        The slot values by slot name (hip_y, leg_span, eversion, inversion, adduction,
        abduction).
    """
    return {
        "hip_y": LEAN_GEOMETRY.hip_y,
        "leg_span": LEAN_GEOMETRY.thigh + LEAN_GEOMETRY.shank,
        "eversion": -math.radians(ROM_DEG["ankle_inv"][0]),
        "inversion": math.radians(ROM_DEG["ankle_inv"][1]),
        "adduction": -math.radians(ROM_DEG["hip_abd"][0]),
        "abduction": math.radians(ROM_DEG["hip_abd"][1]),
    }


@dataclass(frozen=True)
class PlannerOptions:
    """How a :class:`~mjwalk.plan.hybrid.HybridPlanner` plans: every option, with its default.

    Metres, radians (yaw from +x). Checked on construction (:class:`~mjwalk.errors.InputError`,
    before any planning work); ``dataclasses.replace`` makes a variant.
    """

    #: The goal area's radius (m) about the goal point.
    goal_tolerance: float = 0.25
    #: The heading (radians) a walk must end at, None: any.
    goal_yaw: float | None = None
    #: How far (radians) from ``goal_yaw`` the walk's last heading may be.
    goal_yaw_tolerance: float = math.radians(30.0)
    #: The body radius (m) the pelvis path keeps from obstacles and the floor's edge.
    radius: float = BODY_RADIUS
    #: The closed-cell grid's cell (m) and the occupancy grid's.
    cell: float = CELL_SIZE
    #: Heading bins of a closed cell; None: 1, or 8 with a ``goal_yaw`` (:attr:`bins`).
    heading_bins: int | None = None
    #: Gait-initiation steps drawn from the model's KDE for the start node.
    n_starters: int = 30
    #: Continuations drawn from the transition GP per expansion.
    n_successors: int = 10
    #: ``"dijkstra"`` (the obstacle-aware bound) or ``"euclidean"`` (the straight line).
    heuristic: str = "dijkstra"
    #: Expansions one search may spend (:data:`MAX_EXPANSIONS`).
    max_expansions: int = MAX_EXPANSIONS
    #: Pelvis samples of a step the clearance check tests.
    samples_per_step: int = 16
    #: Weight of the heuristic (weighted A*: a walk is at most 1 % longer than the best
    #: continuation of the sampled steps; 1.0 is the paper's plain A*). The bound is
    #: Pohl's (1970, Artif. Intell. 1:193, cost <= w x optimal for an admissible h).
    #: ASSUMPTION: 1 % is a cost-for-speed choice, not a measured figure: it cut the
    #: expansions about eightfold when chosen; 1.00 costs +38 % / +21 % expansions at
    #: 16 / 32 m and does not curve walks more (docs/decisions/112).
    heuristic_weight: float = 1.01
    #: Extra heuristic weight far from the goal on long walks (:data:`FAR_WEIGHT`).
    far_weight: float = FAR_WEIGHT
    #: A step's cost: ``"energy"`` (chord times the metabolic cost of its speed), ``"chord"``
    #: (agethen2018's) or ``"path"`` (the pelvis arc).
    cost: str = "energy"
    #: Searches a walk gets when the open list runs dry (:data:`ATTEMPTS`; at least 1).
    attempts: int = ATTEMPTS
    #: Weight of the squared heading error while the goal is in sight (:data:`HEADING_WEIGHT`).
    heading_weight: float = HEADING_WEIGHT
    #: Closing steps drawn per node near the goal, when the model has them (at least 0).
    n_stops: int = 5
    #: Discs (x, y, radius; metres) the goal area is cut by, at most
    #: :data:`~mjwalk.plan.slots.MAX_GOAL_DISCS` less one (a walk to a spot keeps one).
    goal_within: tuple[tuple[float, float, float], ...] = field(default=())
    #: The goal cells (m) the distance field starts from; None: ``goal_tolerance``. Planners of
    #: one goal with the same ``field_tolerance`` share one field.
    field_tolerance: float | None = None
    #: Whether the distance field routes through passages that keep the body radius plus
    #: SAFETY_MARGIN plus the pelvis's sway (:func:`mjwalk.plan.heuristic.walkable_distance`);
    #: off: through any that keeps the body radius (measured both ways in branch plan-cost2's
    #: commit: off until its mixed cost is settled).
    field_sway: bool = False

    def __post_init__(self):
        if self.heuristic not in ("dijkstra", "euclidean"):
            raise InputError(f"heuristic must be 'dijkstra' or 'euclidean', not {self.heuristic!r}")
        if not self.heuristic_weight >= 1.0:
            raise InputError(f"heuristic_weight must be >= 1, not {self.heuristic_weight}")
        if not self.far_weight >= 0.0:
            raise InputError(f"far_weight must be >= 0, not {self.far_weight}")
        if self.cost not in ("chord", "path", "energy"):
            raise InputError(f"cost must be 'chord', 'path' or 'energy', not {self.cost!r}")
        if not self.heading_weight >= 0.0:
            raise InputError(f"heading_weight must be >= 0, not {self.heading_weight}")
        object.__setattr__(self, "heading_weight", float(self.heading_weight))
        object.__setattr__(self, "attempts", max(1, int(self.attempts)))
        object.__setattr__(self, "n_stops", max(0, int(self.n_stops)))
        object.__setattr__(self, "goal_within", _checked_discs(self.goal_within))

    @property
    def bins(self) -> int:
        """Heading bins of a closed cell: ``heading_bins``, or 1 (8 with a goal yaw, whose
        nodes of other headings must be kept apart)."""
        bins = self.heading_bins
        if bins is None:
            bins = 1 if self.goal_yaw is None else 8
        return max(1, int(bins))

    @property
    def field_cells(self) -> float:
        """The goal cells' radius (m) the distance field starts from."""
        return self.goal_tolerance if self.field_tolerance is None else self.field_tolerance


def _checked_discs(discs) -> tuple[tuple[float, float, float], ...]:
    """``goal_within`` as (x, y, radius) float triples, checked: finite, positive radii, at
    most :data:`~mjwalk.plan.slots.MAX_GOAL_DISCS` less one (whether the goal lies inside
    each is the planner's check, in :mod:`mjwalk.plan.hybrid`)."""
    plain = _plain_discs(discs)
    if plain is not None:
        return plain
    try:
        arr = np.asarray(discs, dtype=float).reshape(-1, 3) if len(discs) else np.zeros((0, 3))
    except (TypeError, ValueError):
        raise InputError(f"goal_within: discs are (x, y, radius) triples, got {discs!r}") from None
    if len(arr) > slots.MAX_GOAL_DISCS - 1:  # one kept for a spot's walk (plan)
        raise InputError(f"goal_within: at most {slots.MAX_GOAL_DISCS - 1} discs, got {len(arr)}")
    if not np.all(np.isfinite(arr)) or np.any(arr[:, 2] <= 0):
        raise InputError("goal_within: discs are (x, y, radius) with finite x, y and radius > 0")
    return tuple((float(x), float(y), float(r)) for x, y, r in arr)


def _plain_discs(discs) -> tuple[tuple[float, float, float], ...] | None:
    """:func:`_checked_discs`' answer without NumPy for the usual input, a short tuple or list
    of valid (x, y, radius) number triples (a planner's options are made for every stand zone:
    NumPy's conversion was half of that); None for anything else, which the checked path then
    converts or refuses."""
    if not isinstance(discs, (tuple, list)) or len(discs) > slots.MAX_GOAL_DISCS - 1:
        return None
    out = []
    for d in discs:
        if not isinstance(d, (tuple, list)) or len(d) != 3:
            return None
        try:
            x, y, r = float(d[0]), float(d[1]), float(d[2])
        except (TypeError, ValueError):
            return None
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(r) and r > 0):
            return None
        out.append((x, y, r))
    return tuple(out)
