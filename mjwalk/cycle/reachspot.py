"""Where the operator stands for a reach: the turn towards the target and the stand-off
search (:mod:`mjwalk.cycle.standoff`) that steps back from the scene or in towards a target out of
reach, leans the trunk for a low target and crouches when standing does not do. World frame:
metres, radians, z up; frames at ``fps`` per second."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from mjwalk.anthropometry import SEG
from mjwalk.conventions import Side
from mjwalk.cycle import reaching
from mjwalk.cycle.holding import two_hand_frames
from mjwalk.cycle.levelsite import level_room, reach_room
from mjwalk.cycle.poses import carry_pose, standing_pose, turn_frames
from mjwalk.cycle.standoff import REACH_TOLERANCE, STEP_BACK, step_back_offsets
from mjwalk.cycle.targets import (
    APPROACH_BACK,
    approach_back_dir,
    approach_offset,
    approach_rise,
    board_run,
    edge_back,
    reach_target,
)
from mjwalk.cycle.tiptoe import rise_steps
from mjwalk.cycle.types import TASK_KINDS

if TYPE_CHECKING:
    from mjwalk.arms.reach import ReachResult
    from mjwalk.cycle.context import CycleContext
    from mjwalk.cycle.types import Task

#: Lateral offset of the shoulder from the pelvis centre (m, stature 1.75 m; Winter: 0.1·H).
SHOULDER_OFFSET = 0.18
#: How deep (share of stature: the pelvis 9, 17 and 26 cm lower at 1.72 m) a one-handed reach
#: that touches the scene from every spot standing or stooping crouches, tried in this order:
#: a semi-squat to a squat with the knees at about 50, 70 and 90 deg (mjwalk.cycle.crouch).
#: People reaching into low storage bend the knees as well as the back (the "semi-squat" and
#: "squat" of lifting studies: Straker 2003, "Evidence to support using squat, semi-squat
#: and stoop techniques to lift low-lying objects", Int. J. Ind. Ergon. 31:149-160).
CROUCH_DROPS = (0.05, 0.10, 0.15)


@dataclass
class WorkingReach:
    """One reach task laid out at its standing spot (world frame, metres, radians, seconds).

    Attributes:
        x, y, yaw: where the operator stands and faces during the reach.
        step_back: metres the operator stepped back from where the walk ended
            (:mod:`mjwalk.cycle.standoff`), 0 when the reach was clear there; negative: they
            stepped in towards a target out of reach from there.
        turn: (F, nq) frames of the turn (and step back) towards the target.
        turn_time: its duration in seconds.
        frames: (G, nq) frames of the reach, hold and return.
        error: distance (m) of the hand's end from its target at the end of the reach, as
            the humanoid holds it.
        result: the reach model's ReachResult (left arm's for two hands, with both warnings).
        width: grip distance (m) of a two-handed part, else None.
        distance: the humanoid's smallest distance (m) to the scene over turn and reach among
            the close pairs (:meth:`~mjwalk.cycle.standoff.ArmClearance.distance`), ``inf``
            when clear.
    """

    x: float
    y: float
    yaw: float
    step_back: float
    turn: np.ndarray
    turn_time: float
    frames: np.ndarray
    error: float
    result: ReachResult
    width: float | None
    distance: float


@dataclass(frozen=True)
class ReachStart:
    """Where the operator stands and what they hold when a reach task starts (world frame,
    metres, radians).

    Attributes:
        x, y: where the operator stands (the walk's end, or a spot a reach before stepped to).
        yaw: the direction they face (radians from +x, counter-clockwise).
        facing: the stand site's facing (radians), along which shelf work comes in
            (:func:`~mjwalk.cycle.targets.approach_offset`); None: none.
        held: grip distance (m) of a two-handed part in the hands, None: none.
        home: where the walk ended (x, y), when the operator stands elsewhere now; None:
            ``(x, y)``.
    """

    x: float
    y: float
    yaw: float
    facing: float | None = None
    held: float | None = None
    home: tuple[float, float] | None = None


def reach_task(
    ctx: CycleContext, task: Task, start: ReachStart, pace: reaching.ReachPace
) -> WorkingReach:
    """Turn towards the target of a pick/place/fasten ``task`` and reach for it from the spot
    ``(start.x, start.y)`` where the walk ended (facing ``start.yaw``); when the arm would come
    closer to the scene than :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` (or the body touch
    it), step back from the target during the turn, :data:`~mjwalk.cycle.standoff.STEP_BACK` at
    a time, until it is clear: the first clear spot whose hand error (m) stays within
    :data:`~mjwalk.cycle.standoff.REACH_TOLERANCE` (or within the error at the walk's end
    spot, when that is larger); the clearest such spot when none within
    :data:`~mjwalk.cycle.standoff.MAX_STEP_BACK` is clear. When the hand falls short of the
    target from there (a spot a step back for the reach before left, a short operator), the
    operator first steps in towards it, by as much as the hand falls short: the first spot from
    which the hand is on its target and clear. When no spot is clear for shelf work, the search
    runs again with the pre-grasp point out of the board under the target (a part deeper on
    its shelf than :data:`~mjwalk.cycle.targets.APPROACH_BACK`: :func:`_over_edge`), kept when
    that reach touches nothing; when it still touches the scene above the shoulder (a short
    operator at a top shelf), the operator rises on the toes, the lowest heel rise that clears
    it (:func:`_tiptoe`). A step never brings the pelvis closer to an
    obstacle or the floor's edge than the planner's body radius (or than it was).

    The steps are measured from ``start.home`` (where the walk ended, when the operator stands
    elsewhere now: a step for the reach before), so each reach at a stand steps back or in as
    far as it needs from the walk's end, and step-backs do not add up. A two-handed place
    (``start.held``) turns and starts its reach in the carrying posture; shelf work comes in
    along ``start.facing`` (:func:`~mjwalk.cycle.targets.approach_offset`). When no spot brings
    the target (both grips of a two-handed part) within the arms' reach (low, below a standing
    reach), the search runs again with the trunk bent forward as far as the target needs
    (:func:`~mjwalk.cycle.reaching.leaning`), and that reach is kept when it brings the hand
    closer; one that still touches the scene or falls short crouches (:func:`_crouching_reach`).

    Args:
        ctx: the run's cycle context.
        task: the pick, place or fasten.
        start: where the operator stands, faces and what they hold (world frame, m, radians).
        pace: the hold time, frame rate and ``timing(distance)`` of the reach (None timing:
            the reference adult's, :func:`~mjwalk.cycle.reaching.default_timing`).

    Returns:
        The :class:`WorkingReach`: where the operator stood, the turn's and the reach's frames,
        the hand's error and the clearance.
    """
    assert task.site is not None  # the spec loader requires a site for reaches
    x, y, home = start.x, start.y, start.home
    site_pos = ctx.workplace.station(task.site).pos
    hx, hy = (float(x), float(y)) if home is None else (float(home[0]), float(home[1]))
    target = reach_target(task.kind, site_pos, hx, hy)  # (from the walk's end)
    back = np.array([hx, hy]) - target[:2]
    back /= max(float(np.linalg.norm(back)), 1e-9)
    # a fastening's approach is level (approach_offset): no headroom to measure
    rise = (
        0.0
        if TASK_KINDS[task.kind].approach == "surface"
        else approach_rise(ctx.model, ctx.scratch(), ctx.spec.stature, target)
    )
    search = _Search(
        ctx=ctx,
        task=task,
        x=float(x),
        y=float(y),
        yaw=float(start.yaw),
        pace=pace,
        facing=start.facing,
        held=start.held,
        home=(hx, hy),
        back=back,
        site_pos=site_pos,
        rise=rise,
        target=target,
    )
    upright = _settle(search, lean=False)
    if upright.distance < np.inf and TASK_KINDS[task.kind].approach == "shelf":
        search, upright = _over_edge(search, upright)
        if upright.distance < 0.0 and task.hand != "both" and _overhead(search):
            search, upright = _tiptoe(search, upright)
    best = upright
    if upright.error > REACH_TOLERANCE:
        # a target no step brings within the arm's reach (low, as a bin by the feet, or deep):
        # the operator bends forward for it, and keeps the lean when it brings the hand closer
        bent = _settle(search, lean=True)
        best = bent if bent.error < upright.error else upright
    # still touching the scene from every spot (a compartment low under a shelf, where the
    # arm from a standing or stooping shoulder slopes down through the shelf's front edge) or
    # short of the target (a part on a pallet): the operator crouches
    return _crouching_reach(search, best)


@dataclass(frozen=True)
class _Search:
    """What the stand-off search of one reach task keeps fixed (:func:`reach_task`'s
    arguments, world frame, metres): ``home`` is where the steps are measured from, ``back``
    the unit direction (x, y) away from the target there, ``rise`` the pre-grasp point's rise
    (:func:`~mjwalk.cycle.targets.approach_rise`), ``target`` the hand's target from ``home``
    (:func:`~mjwalk.cycle.targets.reach_target`; read only) and :attr:`room` the walk
    clearance at ``home``."""

    ctx: CycleContext
    task: Task
    x: float
    y: float
    yaw: float
    pace: reaching.ReachPace
    facing: float | None
    held: float | None
    home: tuple[float, float]
    back: np.ndarray
    site_pos: np.ndarray
    rise: float
    target: np.ndarray
    approach_back: float = APPROACH_BACK
    heel_rise: float = 0.0

    @cached_property
    def room(self) -> float:
        """The walk clearance (m) at ``home`` (:func:`~mjwalk.cycle.levelsite.level_room`),
        found when a step first asks for it (a reach clear from the walk's end never does)."""
        return level_room(self.ctx.workplace, self.home, self.ctx.on_levels)


def _candidate(search: _Search, s: float, lean: bool, drop: float = 0.0) -> WorkingReach | None:
    """The reach from ``s`` metres back (in: < 0) from the walk's end (``lean``: bending the
    trunk forward as far as the target needs; ``drop``: crouched, the pelvis that much lower);
    None when the spot is not clear for the next walk (:func:`~mjwalk.cycle.levelsite.
    reach_room`: the body radius, on levels plus the start margin, or the room there was)."""
    ctx, task, fps = search.ctx, search.task, search.pace.fps
    x, y, yaw = search.x, search.y, search.yaw
    hx, hy = search.home
    xs, ys = float(hx + s * search.back[0]), float(hy + s * search.back[1])
    if s != 0:  # (the room is asked only of a step: most reaches take the walk's end)
        room = level_room(ctx.workplace, (xs, ys), ctx.on_levels, home=(hx, hy))
        if room < reach_room(ctx.spec.radius, ctx.on_levels, search.room):
            return None
    if _same(xs, hx) and _same(ys, hy):  # (the walk's end: its target is known)
        target = search.target
    else:
        target = reach_target(task.kind, search.site_pos, xs, ys)
    # face the target (turning on the spot) before reaching for it
    d = math.hypot(target[0] - xs, target[1] - ys)
    face = math.atan2(target[1] - ys, target[0] - xs)
    if task.hand != "both" and TASK_KINDS[task.kind].approach == "shelf":
        # shelf work: bring the target ahead of the shoulder
        side = 1 if task.hand == "left" else -1
        face -= side * math.asin(min(SHOULDER_OFFSET / d, 0.5))
    grip = search.held if task.hand == "both" else None
    pose = None if grip is None else carry_pose(ctx, standing_pose(ctx, x, y, yaw), grip)
    turn, dt = turn_frames(ctx, (x, y), yaw, face, fps, to=(xs, ys), pose=pose)
    approach = approach_offset(
        task.kind, search.site_pos, xs, ys, search.facing, search.rise, search.approach_back
    )
    q0 = turn[-1]
    width = None
    pace, lowering = search.pace, reaching.Lowering(lean, drop, search.heel_rise)
    if task.hand == "both":
        rf, err, res, width = two_hand_frames(
            ctx, q0, task, approach, pace, held=grip, lowering=lowering
        )
    else:
        arm: Side = "right" if task.hand == "right" else "left"
        rf, err, res = reaching.reach_frames(
            ctx, q0, target, approach, pace, arm, lowering=lowering
        )
    dist = ctx.clearance.distance(np.vstack([turn, rf]))
    return WorkingReach(xs, ys, face, float(s), turn, dt, rf, err, res, width, dist)


def _over_edge(search: _Search, upright: WorkingReach) -> tuple[_Search, WorkingReach]:
    """The search with the pre-grasp point out of the board under the target
    (:func:`~mjwalk.cycle.targets.edge_back`) and its reach, when that reach touches nothing,
    is clearer than ``upright`` and has the hand on its target; else ``search`` and
    ``upright`` (its reach, not clear from any spot).

    A target deeper on a board than :data:`~mjwalk.cycle.targets.APPROACH_BACK` (a part 0.2 m
    back on a shelf) has its pre-grasp point over the board: the reach model, which knows no
    scene, then brings the hand up to it in front of the board's front face, the forearm
    trailing below the hand through the edge (the top shelf of
    ``scenes/shelving_station.xml``, 1.52 m, for operators up to about 1.71 m: forearm and
    palm 3-11 mm into its edge). From a pre-grasp point out of the board the hand comes over
    the edge along the approach, as :func:`~mjwalk.cycle.reaching.reach_frames` means it to.
    """
    edge = _edge_search(search)
    if edge is None:
        return search, upright
    cand = _settle(edge, lean=False)
    # kept when it touches nothing and is clearer, the hand on its target (as a step back)
    if cand.distance > max(upright.distance, 0.0) and cand.error <= max(
        upright.error, REACH_TOLERANCE
    ):
        return edge, cand
    return search, upright


def _edge_search(search: _Search) -> _Search | None:
    """``search`` with the pre-grasp point out of the board under the target
    (:func:`~mjwalk.cycle.targets.edge_back`); None when that is no farther back than its own
    (no board under the target, or a board no arm reaches over)."""
    ctx, task = search.ctx, search.task
    back = approach_back_dir(task.kind, search.site_pos, *search.home, search.facing)
    run = board_run(ctx.model, ctx.scratch(), search.target, back)
    out = edge_back(run, ctx.spec.stature)
    if math.isinf(out) or not out > search.approach_back:
        return None
    return replace(search, approach_back=out)


def _overhead(search: _Search) -> bool:
    """Whether the target is above the operator's shoulder (Winter: 0.818 H over the surface
    they stand on), where rising on the toes brings the shoulder nearer it."""
    ctx = search.ctx
    over = float(search.target[2]) - ctx.ground(search.home)
    return over > SEG["shoulder_height"] * ctx.spec.stature


def _tiptoe(search: _Search, upright: WorkingReach) -> tuple[_Search, WorkingReach]:
    """The search on the toes (:func:`~mjwalk.cycle.tiptoe.tiptoe_pose`), the heels lifting the
    pelvis :data:`~mjwalk.cycle.tiptoe.RISE_STEP` at a time up to
    :func:`~mjwalk.cycle.tiptoe.max_rise`: the lowest rise whose reach touches nothing from
    some spot, the hand on its target; else the clearest rise that touches nothing and is
    clearer than ``upright``; else ``search`` and ``upright``.

    A short operator's shoulder is too low for the arm to come over the front edge of a board
    above the head (the top shelf of ``scenes/shelving_station.xml``, 1.52 m, for operators of
    1.53-1.61 m: the forearm and fingers 16-31 mm into the edge from every spot, with or
    without the approach from out of the board); people rise on their toes for it. The rise
    reaches from out of the board (:func:`_edge_search`) when the target has a board under it.
    """
    best_search, best = search, upright
    tolerance = max(upright.error, REACH_TOLERANCE)
    # the hand comes over the board's edge from out of it (as _over_edge), when it has one
    edge = _edge_search(search) or search
    for rise in rise_steps(search.ctx.spec.stature):
        raised = replace(edge, heel_rise=float(rise))
        cand = _settle(raised, lean=False)
        if cand.error > tolerance:
            continue
        if cand.distance == np.inf:
            return raised, cand
        if cand.distance > max(best.distance, 0.0):
            best_search, best = raised, cand
    return best_search, best


def _same(a: float, b: float) -> bool:
    """Whether two floats are the same number, a zero's sign included."""
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


def _settle(search: _Search, lean: bool, drop: float = 0.0) -> WorkingReach:
    """The stand-off's search (:func:`reach_task`) for reaches with or without the trunk's
    lean, standing or crouched."""
    offsets = step_back_offsets()
    first = _candidate(search, float(offsets[0]), lean, drop)
    assert first is not None  # offsets start at 0: where the operator stands
    if first.error > REACH_TOLERANCE and len(offsets) > 1:
        # out of reach from here (a step back for the reach before, a short operator): step
        # in towards the target first, as far as the hand falls short, onto it and clear
        short = first.error - REACH_TOLERANCE
        n_in = min(len(offsets) - 1, math.ceil(short / STEP_BACK) + 1)
        for j in range(1, n_in + 1):
            cand = _candidate(search, -STEP_BACK * j, lean, drop)
            if cand is not None and cand.distance == np.inf and cand.error <= REACH_TOLERANCE:
                return cand
    tolerance = max(first.error, REACH_TOLERANCE)
    best = first
    for s in offsets:
        cand = first if s == offsets[0] else _candidate(search, float(s), lean, drop)
        if cand is None:
            continue
        # a step back must not cost the hand its target (beyond REACH_TOLERANCE)
        if cand.distance == np.inf and cand.error <= tolerance:
            return cand
        if cand.distance > best.distance and cand.error <= tolerance:
            best = cand
    return best


def _crouching_reach(search: _Search, best: WorkingReach) -> WorkingReach:
    """``best`` (a reach standing or stooping), or when it touches the scene from every spot
    or its hand ends short of the target (beyond :data:`REACH_TOLERANCE`: a part on a pallet),
    the reach crouched (:mod:`mjwalk.cycle.crouch`) the least of :data:`CROUCH_DROPS` deep
    (shares of the operator's stature) that is on its target and clear. Short of the target, a
    crouch is kept when it brings the hand onto it (within :data:`REACH_TOLERANCE`) without
    touching the scene more (a crouch does not bring a far target nearer: a few millimetres
    closer is no reason to squat); touching the scene, when it is clearer with the hand still
    on its target."""
    if best.distance >= 0.0 and best.error <= REACH_TOLERANCE:
        return best
    stature = search.ctx.spec.stature
    for share in CROUCH_DROPS:
        cand = _settle(search, True, float(share * stature))
        if best.error > REACH_TOLERANCE:  # short: on the target, and no more in the scene
            if cand.error <= REACH_TOLERANCE and min(cand.distance, 0.0) >= min(best.distance, 0.0):
                best = cand
        elif cand.error <= REACH_TOLERANCE and cand.distance > best.distance:
            best = cand
        if best.distance == np.inf and best.error <= REACH_TOLERANCE:
            break
    return best
