"""Simulate assembly cycles: plan every walk, animate walks and arm motions, time every task.

One cycle (:func:`simulate_cycle`) walks the task list of a :class:`CycleSpec`: each ``walk`` /
``carry`` task is planned with the probabilistic hybrid A* (and, for the report, the grid-A*
route between the same sites); the operator turns on the spot towards the walk's first heading
and, at its end, towards the site's facing direction; each ``pick`` / ``place`` / ``fasten``
task is an arm reach from the current standing pose to the site (the :class:`ReachModel`, PCA +
DCS, alzubi-sommer), a hold (the task's duration) and the return. Everything is laid on one
timeline of humanoid poses (``fps`` frames per second), checked for humanoid-vs-scene contacts
with MuJoCo's collision detection.

With a ``[population]`` in the spec each run first draws its operator
(:meth:`~mjwalk.cycle.population.Population.draw`, from the run's first spawned stream): the
humanoid is built at the operator's stature (:func:`operator_context`), the walks are sampled
from the step model conditioned on the operator (:meth:`StepModel.for_walker`), and reach,
hold and return times are divided by the operator's pace (:mod:`mjwalk.cycle.handling`).

Many cycles (:func:`simulate_cycles`) run through joblib, so ``n_jobs`` processes share the
work; inside ``joblib.parallel_config(backend="dask")`` (or ``"ray"``) the same call runs on a
Dask or Ray cluster unchanged (see the README).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from mjwalk.body.humanoid import JointMap, attach_humanoid, pelvis_height
from mjwalk.conventions import SAMPLE_RATE_HZ, Side, side_prefix
from mjwalk.cycle.handling import REACH_CASE, RETURN_CASE, reach_duration, task_factor
from mjwalk.cycle.spec import check_durations
from mjwalk.cycle.standing import StandZone, stand_zone
from mjwalk.cycle.standoff import REACH_TOLERANCE, ArmClearance, step_back_offsets
from mjwalk.cycle.types import (
    ArmRecord,
    CycleResult,
    CycleSpec,
    TaskRecord,
    WalkRecord,
)
from mjwalk.errors import CycleSpecError, InputError
from mjwalk.gait.walker import Walker
from mjwalk.plan.grid import OccupancyGrid, occupancy_grid, plan_grid
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.timeline.collisions import collision_report
from mjwalk.timeline.frames import ease_arms, frames_from_legs, room_and_away, yaw_quat
from mjwalk.timeline.timeline import Timeline
from mjwalk.world.workplace import Workplace, shared_workplace

if TYPE_CHECKING:
    from mjwalk.arms.reach import ReachResult
    from mjwalk.gait.model import StepModel  # loaded on first use (prepare)

#: Turning speed on the spot (rad/s) and shortest turn (s).
TURN_SPEED = math.radians(180.0)
MIN_TURN = 0.25
#: Speed (m/s) of a step back before a reach (:mod:`mjwalk.cycle.standoff`): a slow walk's
#: speed (about half the preferred 1.3 m/s walking speed; Bohannon 1997).
STEP_SPEED = 0.6
#: Lateral offset of the shoulder from the pelvis centre (m, stature 1.75 m; Winter: 0.1·H).
SHOULDER_OFFSET = 0.18
#: The hold of a pick or place without a given duration (s), the median for the reference
#: adult; reach and return times come from the reach distance (MTM-1, mjwalk.cycle.handling).
DEFAULT_HOLD = {"pick": 0.4, "place": 0.4, "fasten": 3.0, "wait": 1.0}
#: Walks of a cycle end this close to their stand site (m): the operator steps up to the
#: workplace (the planner's default goal area of 0.25 m would leave screws out of reach).
GOAL_TOLERANCE = 0.1
#: The hand stops this far above a pick/place site (m) and this far in front of a fasten site.
PICK_CLEARANCE = 0.06
FASTEN_STANDOFF = 0.13
#: The pre-grasp point: this far back towards the operator and (shelf work) up from the target.
APPROACH_BACK = 0.15
APPROACH_UP = 0.10


@dataclass
class CycleContext:
    """Everything a cycle needs that does not change between runs (built once per process)."""

    spec: CycleSpec
    workplace: Workplace
    step_model: StepModel
    reach_model: object
    model: mujoco.MjModel
    jointmap: JointMap
    planners: dict = field(default_factory=dict)
    zones: dict = field(default_factory=dict)
    baselines: dict = field(default_factory=dict)
    grid: OccupancyGrid | None = None  # the grid-A* occupancy grid, built on first use
    clearance: ArmClearance | None = None  # the reach's clearance check, built on first use
    # the scratch MjData and the model it was made for (not copied by dataclasses.replace:
    # an operator's context has its own humanoid model)
    _data: tuple[mujoco.MjModel, mujoco.MjData] | None = field(
        default=None, init=False, repr=False, compare=False
    )

    def scratch(self) -> mujoco.MjData:
        """One MjData of ``model`` for this context's forward kinematics (building one takes
        about a millisecond; every user sets the whole qpos before each use)."""
        if self._data is None or self._data[0] is not self.model:
            self._data = (self.model, mujoco.MjData(self.model))
        return self._data[1]

    def planner(self, goal: str, zone: StandZone | None = None) -> HybridPlanner:
        """The planner of walks to ``goal``, ending in ``zone`` (:mod:`mjwalk.cycle.standing`;
        None: within :data:`GOAL_TOLERANCE` of the site). One per goal and zone."""
        key = (goal, zone)
        if key not in self.planners:
            self.planners[key] = HybridPlanner(
                self.workplace,
                goal,
                self.step_model,
                radius=self.spec.radius,
                goal_tolerance=GOAL_TOLERANCE if zone is None else zone.radius,
                goal_within=() if zone is None else zone.discs,
            )
        return self.planners[key]

    def zone(self, i: int, stature: float, step_length: float) -> StandZone:
        """The stand zone of the walk that is task ``i`` (:func:`work_zone`)."""
        key = (i, round(stature, 3), round(step_length, 3))
        if key not in self.zones:
            self.zones[key] = work_zone(self, i, stature, step_length)
        return self.zones[key]

    def baseline(self, a: str, b: str) -> float:
        if (a, b) not in self.baselines:
            if self.grid is None:
                self.grid = occupancy_grid(self.workplace, radius=self.spec.radius)
            self.baselines[(a, b)] = plan_grid(
                self.workplace, a, b, radius=self.spec.radius, grid=self.grid
            ).length
        return self.baselines[(a, b)]


def _pace_of(model):
    """The step model's pace (:meth:`mjwalk.gait.model.StepModel.pace`), measured once."""
    return model.pace()


def _load_step_model(spec: CycleSpec):
    if spec.step_model == "default":
        from mjwalk.gait.default import default_model

        return default_model()
    from mjwalk.gait.model import StepModel

    return StepModel.load(spec.step_model)


def _load_reach_model(spec: CycleSpec):
    from mjwalk.arms.reach import ReachModel

    if spec.reach_model == "default":
        from mjwalk.arms.reachdefault import default_reach_model

        return default_reach_model()
    return ReachModel.load(spec.reach_model)


@functools.lru_cache(maxsize=4)
def _context_cached(spec_key: str) -> CycleContext:
    from mjwalk.cycle.spec import load_cycle_spec

    return prepare(load_cycle_spec(spec_key))


@functools.lru_cache(maxsize=16)
def _humanoid(scene: str, stature: float) -> tuple[mujoco.MjModel, JointMap]:
    """The scene with a humanoid of ``stature`` metres (kept for the last 16 statures of this
    process: a population's statures come in centimetres, attaching one takes about 15 ms)."""
    return attach_humanoid(Path(scene), stature)


def operator_context(ctx: CycleContext, walker: Walker | None) -> CycleContext:
    """``ctx`` for a run of ``walker``: the humanoid (and ``spec.stature``) of the walker's
    stature; planners, grid-A* baselines and models are shared with ``ctx``. ``ctx`` itself
    without a walker or at the spec's stature."""
    if walker is None or abs(walker.stature - ctx.spec.stature) < 1e-9:
        return ctx
    model, jm = _humanoid(str(ctx.spec.scene), round(walker.stature, 3))
    return replace(
        ctx,
        spec=replace(ctx.spec, stature=walker.stature),
        model=model,
        jointmap=jm,
        clearance=_clearance_of(str(ctx.spec.scene), round(walker.stature, 3)),
    )


@functools.lru_cache(maxsize=16)
def _clearance_of(scene: str, stature: float) -> ArmClearance:
    """The reach's clearance check (:class:`~mjwalk.cycle.standoff.ArmClearance`) of the
    humanoid of ``stature`` metres in ``scene`` (kept like :func:`_humanoid`)."""
    model, jm = _humanoid(scene, stature)
    return ArmClearance(model, jm)


def prepare(spec: CycleSpec) -> CycleContext:
    """Load the scene, the models and the humanoid of ``spec`` (reused by every run)."""
    workplace = shared_workplace(spec.scene)
    model, jm = attach_humanoid(spec.scene, spec.stature)
    return CycleContext(
        spec=spec,
        workplace=workplace,
        step_model=_load_step_model(spec),
        reach_model=_load_reach_model(spec),
        model=model,
        jointmap=jm,
    )


# ---------------------------------------------------------------------------- poses


def _standing(ctx: CycleContext, x: float, y: float, yaw: float) -> np.ndarray:
    q = ctx.jointmap.neutral_qpos(ctx.model, ctx.spec.stature)
    r = ctx.jointmap.root
    q[r : r + 3] = [x, y, pelvis_height(ctx.spec.stature)]
    q[r + 3 : r + 7] = yaw_quat(np.array([yaw]))[0]
    return q


def _turn_frames(ctx, x, y, yaw0, yaw1, fps, to=None) -> tuple[np.ndarray, float]:
    """Frames of turning on the spot ``(x, y)`` from ``yaw0`` to ``yaw1`` (radians) at
    :data:`TURN_SPEED`; with ``to`` = (x1, y1) the pelvis moves there during the turn (a short
    step back, :mod:`mjwalk.cycle.standoff`; the turn lasts at least as long as that step at
    :data:`STEP_SPEED`). Returns (frames, duration in seconds)."""
    d = (yaw1 - yaw0 + math.pi) % (2 * math.pi) - math.pi
    duration = max(MIN_TURN, abs(d) / TURN_SPEED)
    x1, y1 = (x, y) if to is None else to
    shift = math.hypot(x1 - x, y1 - y)
    if shift > 0.0:
        duration = max(duration, shift / STEP_SPEED)
    n = max(1, round(duration * fps))
    k = np.arange(1, n + 1)
    frames = np.repeat(_standing(ctx, x, y, yaw0)[None], n, axis=0)
    r = ctx.jointmap.root
    frames[:, r] = x + (x1 - x) * k / n
    frames[:, r + 1] = y + (y1 - y) * k / n
    frames[:, r + 3 : r + 7] = yaw_quat(yaw0 + d * k / n)
    return frames, n / fps


def hand_points(ctx, qpos: np.ndarray) -> np.ndarray:
    """(F, 2, 3) world positions (m) of the left and right palm (the hand geoms' centres) in
    the poses ``qpos`` (F, nq)."""
    m, jm = ctx.model, ctx.jointmap
    data = ctx.scratch()
    ids = [m.body(f"{jm.prefix}hand_{p}").id for p in ("l", "r")]
    gids = [int(np.flatnonzero(m.geom_bodyid == b)[0]) for b in ids]
    out = np.empty((len(qpos), 2, 3))
    for f, q in enumerate(np.atleast_2d(qpos)):
        data.qpos[:] = q
        mujoco.mj_kinematics(m, data)
        out[f] = data.geom_xpos[gids]
    return out


def carry_abduction(ctx, width: float) -> float:
    """Shoulder abduction (radians, both arms) of the two-handed carrying posture
    (:data:`~mjwalk.timeline.frames.CARRY_POSE` otherwise) that puts the palms ``width`` metres
    apart: the hands stay on the grips of the part while it is carried. Solved by Brent's
    method within the joint's range (clipped to it when the part is wider or narrower than the
    arms can span)."""
    from scipy.optimize import brentq

    from mjwalk.timeline.frames import CARRY_POSE

    jm = ctx.jointmap
    q = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    for side in "lr":
        q[jm.adr(f"shoulder_{side}_flex")] = CARRY_POSE["shoulder_flex"]
        q[jm.adr(f"elbow_{side}")] = CARRY_POSE["elbow"]

    def gap(abd: float) -> float:
        for side in "lr":
            q[jm.adr(f"shoulder_{side}_abd")] = abd
        h = hand_points(ctx, q[None])[0]
        return float(np.linalg.norm(h[0] - h[1])) - width

    lo, hi = jm.limits("shoulder_l_abd")
    hi = min(hi, 1.2)
    if gap(lo) >= 0.0:
        return float(lo)
    if gap(hi) <= 0.0:
        return float(hi)
    return float(brentq(gap, lo, hi, xtol=1e-4))


def _walk_frames(
    ctx, walk, fps, carry: str | None = None, carry_width: float | None = None
) -> np.ndarray:
    """Frames of a walk after its first sample (legs from the footprints, arm swing from the
    legs). The arms swing fully only in mid-walk: the swing fades in over the first and out
    over the last :data:`ARM_EASE` seconds, so they are at rest when the operator stops at a
    rack or the car. ``carry`` ("left"/"right"): that hand holds the part in front of the body
    (elbow flexed, forearm close to the trunk) instead of swinging; "both": both hands hold a
    part whose grips are ``carry_width`` metres apart (:func:`carry_abduction`)."""
    from mjwalk.body.legs import legs_from_walk

    legs = legs_from_walk(walk, ctx.spec.stature)
    t = np.arange(1, math.floor(walk.duration * fps) + 1) / fps
    if len(t) == 0 or t[-1] < walk.duration - 1e-9:
        t = np.append(t, walk.duration)
    frames = frames_from_legs(ctx.model, ctx.jointmap, legs, t, ctx.spec.stature, "swing", None)
    jm = ctx.jointmap
    room, away = room_and_away(ctx.workplace, frames[:, jm.root : jm.root + 2])
    rest = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    abd = carry_abduction(ctx, carry_width) if carry == "both" and carry_width else None
    ease_arms(frames, t, walk.duration, jm, rest, room, carry, away, ctx.spec.stature, abd)
    return frames


def _default_timing(dist: float) -> tuple[float, float]:
    """The reference adult's reach (MTM-1 case B) and return (case E) times, seconds, for a
    hand movement of ``dist`` metres."""
    return reach_duration(dist, None, "B"), reach_duration(dist, None, RETURN_CASE)


def _arm_scale(reach_model, stature: float) -> float:
    """Reach-model arm length over the arm length of a humanoid of ``stature`` metres (1 at
    the model's stature)."""
    from mjwalk.arms.kinematics import arm_segment_lengths

    lengths = np.asarray(reach_model.lengths, dtype=float)
    return float(lengths[:2].sum() / arm_segment_lengths(stature)[:2].sum())


def _reach_frames(
    ctx,
    q0: np.ndarray,
    target_w: np.ndarray,
    approach_w: np.ndarray,
    hold: float,
    fps: float,
    side: Side = "left",
    timing=None,
):
    """Frames of reaching from pose ``q0`` to ``target_w`` (world, m), holding, returning.

    ``timing(distance)`` gives the (reach, return) durations in seconds of a hand movement of
    ``distance`` metres (rest hand to target); default: the reference adult's MTM-1 case B
    reach and case E return (:mod:`mjwalk.cycle.handling`).

    The reach model (PCA + DCS) brings the hand from rest to the pre-grasp point
    ``target_w + approach_w``; the hand then moves straight onto the target along
    ``-approach_w`` with a minimum-jerk profile (two-link IK, hand direction kept), so it comes
    over a shelf's front edge instead of through it. The return retraces the motion.

    Returns (frames, hand error in metres, ReachResult of the model part)."""
    from mjwalk.arms.kinematics import (
        REST_HAND,
        arm_frames,
        arm_joint_angles,
        min_jerk,
        two_link_ik,
    )
    from mjwalk.arms.reach import reach_for_side

    m, jm, model = ctx.model, ctx.jointmap, ctx.reach_model
    data = ctx.scratch()
    data.qpos[:] = q0
    mujoco.mj_kinematics(m, data)
    ua = m.body(f"{jm.prefix}upper_arm_{side_prefix(side)}").id
    shoulder = data.xpos[ua].copy()
    frame = data.xmat[ua].reshape(3, 3).copy()
    # the reach is solved at the reach model's arm lengths; an operator of another stature has
    # the same arm shape scaled (Winter's shares), so the targets are scaled into the model's
    # size (directions, hence joint angles, do not change with the scale)
    scale = _arm_scale(model, ctx.spec.stature)
    end = frame.T @ (target_w - shoulder) * scale
    pre = frame.T @ (target_w + approach_w - shoulder) * scale
    start = np.asarray(REST_HAND, dtype=float)
    res = reach_for_side(model, pre, side, start)  # a right arm mirrors the left-arm model
    lengths = model.lengths
    u_last = res.directions[-1]
    n_app = max(4, len(res.directions) // 2)
    app = np.repeat(u_last[None], n_app, axis=0)
    for k, tau in enumerate(min_jerk(np.linspace(0.0, 1.0, n_app + 1)[1:])):
        hand = pre + tau * (end - pre)
        wrist = hand - lengths[2] * u_last[2]
        app[k, 0], app[k, 1] = two_link_ik(wrist, lengths[0], lengths[1], u_last[0] * lengths[0])
    directions = np.concatenate([res.directions, app])
    q = arm_joint_angles(directions, side)
    if timing is None:
        timing = _default_timing
    reach_out, reach_back = timing(float(np.linalg.norm(end - start)) / scale)  # operator's metres
    n_out = max(2, round(reach_out * fps))
    out, _ = arm_frames(q0, jm, q, side, np.linspace(0.0, 1.0, n_out + 1)[1:])
    data.qpos[:] = out[-1]
    mujoco.mj_kinematics(m, data)
    wrist = data.xpos[m.body(f"{jm.prefix}hand_{side_prefix(side)}").id]
    tip = wrist + frame @ (directions[-1, 2] * lengths[2] / scale)  # the operator's hand
    error = float(np.linalg.norm(tip - target_w))
    n_hold = max(0, round(hold * fps))
    n_back = max(1, round(reach_back * fps))
    back = out[::-1][np.linspace(0, n_out - 1, n_back).round().astype(int)]
    back = np.vstack([back[1:], q0[None]])
    frames = np.vstack([out, np.repeat(out[-1:], n_hold, axis=0), back])
    return frames, error, res


def _two_hand_frames(ctx, q0, task, approach, hold, fps, timing=None):
    """A two-handed reach (``hand = "both"``): the left arm to the grip site ``<site>_left``, the
    right arm (the mirrored model) to ``<site>_right``, at the same time, holding and returning
    together. Returns (frames, the larger hand error in metres, the left arm's ReachResult with
    both arms' warnings, the grip distance in metres)."""
    from mjwalk.cycle.spec import grip_sites

    wp = ctx.workplace
    parts = {}
    # Both hands of a bimanual reach start and arrive together (Kelso, Southard & Goodman 1979,
    # Science 203: 1029-1031): the second arm takes the first arm's durations.
    first: list[tuple[float, float]] = []

    def shared(dist: float) -> tuple[float, float]:
        if not first:
            first.append(timing(dist) if timing is not None else _default_timing(dist))
        return first[0]

    for side_name, name in grip_sites(task.site, "both"):
        side: Side = "right" if side_name == "right" else "left"
        grip = np.asarray(wp.station(name).pos, dtype=float)
        parts[side] = (
            grip,
            *_reach_frames(ctx, q0, grip, approach, hold, fps, side, timing=shared),
        )
    (gl, fl, el, rl), (gr, fr, er, rr) = parts["left"], parts["right"]
    frames = fl.copy()
    moved = np.any(fr != q0[None], axis=0)  # the right arm's joints
    frames[:, moved] = fr[:, moved]
    rl.warnings = list(rl.warnings) + [w for w in rr.warnings if w not in rl.warnings]
    rl.outside = bool(rl.outside or rr.outside)
    return frames, max(el, er), rl, float(np.linalg.norm(gl - gr))


def _approach(
    kind: str, site_pos: np.ndarray, x: float, y: float, facing: float | None = None
) -> np.ndarray:
    """Pre-grasp offset (world, m): back towards the operator, and up for shelf work. Shelf
    work (pick, place) at a stand site facing ``facing`` (radians from +x) comes in along the
    site's facing, out of the shelf's opening, wherever in the stand zone the operator stands
    (towards the operator, an oblique approach swept the fingers across the rack's frame)."""
    if facing is not None and kind != "fasten":
        d = -np.array([math.cos(facing), math.sin(facing)])
    else:
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
    up = 0.0 if kind == "fasten" else APPROACH_UP
    return np.r_[APPROACH_BACK * d, up]


def _target(ctx, kind: str, site_pos: np.ndarray, x: float, y: float) -> np.ndarray:
    if kind == "fasten":  # stop in front of the surface, towards the operator
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
        return site_pos + np.r_[FASTEN_STANDOFF * d, 0.0]
    return site_pos + np.array([0.0, 0.0, PICK_CLEARANCE])


def work_zone(ctx: CycleContext, i: int, stature: float, step_length: float) -> StandZone:
    """Where the walk that is task ``i`` may end (:func:`mjwalk.cycle.standing.stand_zone`):
    near its stand site, with every reach target of the work done there (the tasks after it
    up to the next walk) within the arm's reach. A two-handed task's targets are its grip
    sites ``<site>_left`` and ``<site>_right``."""
    tasks = ctx.spec.tasks
    goal = tasks[i].site
    assert goal is not None  # the spec loader requires a site for walks
    stand = ctx.workplace.station(goal).pos
    targets, squarely, hands = [], [], []
    for task in tasks[i + 1 :]:
        if task.kind in ("walk", "carry"):
            break
        if task.kind not in ("pick", "place", "fasten") or task.site is None:
            continue
        sites = [f"{task.site}_left", f"{task.site}_right"] if task.hand == "both" else [task.site]
        for name in sites:
            pos = ctx.workplace.station(name).pos
            targets.append(_target(ctx, task.kind, pos, float(stand[0]), float(stand[1])))
            # the cycle faces fastenings and two-handed work squarely (simulate_cycle)
            squarely.append(task.kind == "fasten" or task.hand == "both")
            hands.append(None if squarely[-1] else task.hand)
    facing = ctx.workplace.station(goal).yaw
    return stand_zone(stand[:2], targets, step_length, stature, facing, squarely, hands)


def plan_task_walk(ctx: CycleContext, i: int, start, rng: np.random.Generator, walker=None):
    """The walk of task ``i`` (a walk or carry) from ``start`` (x, y), as a cycle plans it:
    steps from the cycle's step model (conditioned on ``walker`` when given), ending in the
    task's stand zone (:func:`work_zone`) for the walker's stature and step length."""
    task = ctx.spec.tasks[i]
    assert task.site is not None  # the spec loader requires a site for walks
    model = ctx.step_model.for_walker(walker) if walker is not None else ctx.step_model
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else _pace_of(ctx.step_model).step_length
    zone = ctx.zone(i, stature, step)
    return ctx.planner(task.site, zone).plan(start, rng, model=model)


def plan_cycle_walks(ctx: CycleContext, rng: np.random.Generator, walker=None) -> list:
    """Only the walks of one cycle, in order, as :func:`simulate_cycle` plans them with the
    same ``rng`` (the run's generator; arms and handling draw from spawned streams): a list of
    (task index, start site, goal site, WalkPath). Fast (no animation): for studies of the
    routes alone (``benchmarks/bench_variability.py``)."""
    spec = ctx.spec
    here = spec.start
    st = ctx.workplace.station(here)
    x, y = float(st.pos[0]), float(st.pos[1])
    out = []
    for i, task in enumerate(spec.tasks):
        if task.kind in ("walk", "carry"):
            path = plan_task_walk(ctx, i, (x, y), rng, walker)
            goal = str(task.site)
            out.append((i, here, goal, path))
            x, y = (float(v) for v in path.xy[-1])
            here = goal
    return out


@dataclass
class WorkingReach:
    """One reach task laid out at its standing spot (world frame, metres, radians, seconds).

    Attributes:
        x, y, yaw: where the operator stands and faces during the reach.
        step_back: metres the operator stepped back from where the walk ended
            (:mod:`mjwalk.cycle.standoff`), 0 when the reach was clear there.
        turn: (F, nq) frames of the turn (and step back) towards the target.
        turn_time: its duration in seconds.
        frames: (G, nq) frames of the reach, hold and return.
        error: distance (m) of the hand from its target at the end of the reach.
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


def _arm_clearance(ctx: CycleContext) -> ArmClearance:
    if ctx.clearance is None:
        ctx.clearance = ArmClearance(ctx.model, ctx.jointmap)
    return ctx.clearance


def _reach_task(ctx, task, x, y, yaw, hold, fps, timing, facing=None) -> WorkingReach:
    """Turn towards the target of a pick/place/fasten ``task`` and reach for it from the spot
    ``(x, y)`` where the walk ended (facing ``yaw``); when the arm would come closer to the
    scene than :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` (or the body touch it), step back
    from the target during the turn, :data:`~mjwalk.cycle.standoff.STEP_BACK` at a time, until
    it is clear: the first clear spot whose hand error (m) stays within
    :data:`~mjwalk.cycle.standoff.REACH_TOLERANCE` (or within the error at the walk's end
    spot, when that is larger); the clearest such spot when none within
    :data:`~mjwalk.cycle.standoff.MAX_STEP_BACK` is clear. A step back never brings the pelvis
    closer to an obstacle or the floor's edge than the planner's body radius (or than it was).
    ``facing``: the stand site's facing (radians), along which shelf work comes in
    (:func:`_approach`)."""
    assert task.site is not None  # the spec loader requires a site for reaches
    site_pos = ctx.workplace.station(task.site).pos
    back = np.array([x, y]) - _target(ctx, task.kind, site_pos, x, y)[:2]
    back /= max(float(np.linalg.norm(back)), 1e-9)
    check = _arm_clearance(ctx)
    best: WorkingReach | None = None
    first: WorkingReach | None = None
    room0 = float(ctx.workplace.walk_clearance(np.array([x, y]))[()])
    for s in step_back_offsets():
        xs, ys = float(x + s * back[0]), float(y + s * back[1])
        room = float(ctx.workplace.walk_clearance(np.array([xs, ys]))[()])
        if s > 0 and room < min(ctx.spec.radius, room0):
            continue  # the next walk must start clear of obstacles (the planner's body radius)
        target = _target(ctx, task.kind, site_pos, xs, ys)
        # face the target (turning on the spot) before reaching for it
        d = math.hypot(target[0] - xs, target[1] - ys)
        face = math.atan2(target[1] - ys, target[0] - xs)
        if task.hand != "both" and task.kind != "fasten":
            # shelf work: bring the target ahead of the shoulder
            side = 1 if task.hand == "left" else -1
            face -= side * math.asin(min(SHOULDER_OFFSET / d, 0.5))
        turn, dt = _turn_frames(ctx, x, y, yaw, face, fps, to=(xs, ys))
        approach = _approach(task.kind, site_pos, xs, ys, facing)
        q0 = turn[-1]
        width = None
        if task.hand == "both":
            rf, err, res, width = _two_hand_frames(
                ctx, q0, task, approach, hold, fps, timing=timing
            )
        else:
            arm: Side = "right" if task.hand == "right" else "left"
            rf, err, res = _reach_frames(ctx, q0, target, approach, hold, fps, arm, timing=timing)
        dist = check.distance(np.vstack([turn, rf]))
        cand = WorkingReach(xs, ys, face, float(s), turn, dt, rf, err, res, width, dist)
        if first is None:
            first = cand
        # a step back must not cost the hand its target (beyond REACH_TOLERANCE)
        if dist == np.inf and err <= max(first.error, REACH_TOLERANCE):
            return cand
        if best is None or (dist > best.distance and err <= max(first.error, REACH_TOLERANCE)):
            best = cand
    assert best is not None
    return best


# ---------------------------------------------------------------------------- one cycle


def simulate_cycle(
    spec: CycleSpec | CycleContext,
    rng: np.random.Generator | int | None = None,
    *,
    run: int = 0,
    fps: float = 30.0,
    keep_timeline: bool = False,
    collisions: bool = True,
) -> CycleResult:
    """Simulate one assembly cycle.

    Args:
        spec: the cycle (or a prepared :class:`CycleContext`, to reuse models across runs).
        rng: random generator or seed (same seed, same cycle).
        run: the run's index (recorded in the result).
        fps: frame rate of the humanoid timeline (the video rate).
        keep_timeline: keep the per-frame poses in ``result.timeline`` (for videos).
        collisions: run MuJoCo's collision detection over the timeline
            (:func:`~mjwalk.timeline.collisions.check_collisions` checks a result later).

    Returns:
        A :class:`CycleResult`: walks, arm motions, task times, cycle time, collisions, and the
        run's operator (``result.operator``, drawn from ``spec.population``; None without one).

    Raises:
        PlanningError: a walk cannot be planned (the spec is checked before, so this means an
            unreachable site); MjwalkError for model files.
    """
    ctx = spec if isinstance(spec, CycleContext) else prepare(spec)
    spec = ctx.spec
    check_durations(spec.tasks)
    rng = np.random.default_rng(rng)
    # side streams spawned from the run's generator (its own draws, the walks, are unchanged):
    # the operator, the task-time factors, the standing spots (not yet merged)
    op_rng, hand_rng, _stand_rng = rng.spawn(3)
    entropy = _entropy(rng)
    # the run's operator (None without a [population]: the step model's own pace, handling at
    # the reference adult's pace): their humanoid, their steps, their handling pace
    walker = spec.population.draw(op_rng) if spec.population is not None else None
    ctx = operator_context(ctx, walker)
    pace = 1.0 if walker is None else walker.pace
    wp = ctx.workplace
    here = spec.start
    st = wp.station(here)
    x, y, yaw = float(st.pos[0]), float(st.pos[1]), st.yaw
    frames = [_standing(ctx, x, y, yaw)[None]]
    t = 0.0
    tasks: list[TaskRecord] = []
    walks: list[WalkRecord] = []
    arms: list[ArmRecord] = []
    width: float | None = None  # grip distance (m) of the two-handed part in the hands
    for i, task in enumerate(spec.tasks):
        t0 = t
        if task.kind in ("walk", "carry"):
            goal = task.site
            assert goal is not None  # the spec loader requires a site for walks
            path = plan_task_walk(ctx, i, (x, y), rng, walker)
            turn, dt = _turn_frames(ctx, x, y, yaw, float(path.yaw[0]), fps)
            frames.append(turn)
            t += dt
            carry = task.hand if task.kind == "carry" else None
            wf = _walk_frames(ctx, path, fps, carry, width)
            frames.append(wf)
            t += len(wf) / fps  # the walk, to the video frame
            x, y = (float(v) for v in path.xy[-1])
            yaw = float(path.yaw[-1])
            face = wp.station(goal).yaw
            turn, dt = _turn_frames(ctx, x, y, yaw, face, fps)
            frames.append(turn)
            t += dt
            yaw = face
            walks.append(
                WalkRecord(
                    task=i,
                    route=task.route or f"{here}->{goal}",
                    start_site=here,
                    goal_site=goal,
                    path=path,
                    baseline_length=ctx.baseline(here, goal),
                )
            )
            here = goal
        elif task.kind in ("pick", "place", "fasten"):
            hold = task.duration if task.duration is not None else DEFAULT_HOLD[task.kind]
            factor = task_factor(hand_rng)  # lognormal, median 1 (mjwalk.cycle.handling)
            hold *= factor / pace  # the hold, like the reach, at the operator's pace
            case = REACH_CASE[task.kind]

            def timing(dist, case=case, factor=factor):
                return (
                    reach_duration(dist, walker, case) * factor,
                    reach_duration(dist, walker, RETURN_CASE) * factor,
                )

            assert task.site is not None  # the spec loader requires a site for reaches
            r = _reach_task(ctx, task, x, y, yaw, hold, fps, timing, wp.station(here).yaw)
            x, y, yaw = r.x, r.y, r.yaw
            frames.append(r.turn)
            t += r.turn_time
            if task.hand == "both":
                width = r.width if task.kind == "pick" else None  # released on place/fasten
            frames.append(r.frames)
            t += len(r.frames) / fps
            arms.append(
                ArmRecord(
                    task=i,
                    kind=task.kind,
                    site=task.site,
                    hand=task.hand,
                    duration=len(r.frames) / fps,
                    hand_error=r.error,
                    outside=bool(r.result.outside),
                    warnings=list(r.result.warnings),
                    step_back=r.step_back,
                )
            )
        elif task.kind == "wait":
            hold = task.duration if task.duration is not None else DEFAULT_HOLD["wait"]
            n = max(1, round(hold * fps))
            frames.append(np.repeat(frames[-1][-1:], n, axis=0))
            t += n / fps
        else:  # the spec parser refuses unknown kinds; this guards hand-made specs
            raise CycleSpecError(f"task {i}: unknown kind {task.kind!r}")
        tasks.append(TaskRecord(i, task.kind, task.site, t0, t, task.route))
    qpos = np.vstack(frames)
    timeline = Timeline(
        model=ctx.model,
        jointmap=ctx.jointmap,
        fps=fps,
        t=np.arange(len(qpos)) / fps,
        qpos=qpos,
        scene=str(spec.scene),
        stature=ctx.spec.stature,
    )
    timeline.walk = combined_walk([w.path for w in walks])  # drawn into videos
    contacts = collision_report(timeline, data=ctx.scratch()) if collisions else []
    return CycleResult(
        spec=spec,
        run=run,
        seed=entropy[0] if isinstance(entropy, list) else entropy,
        entropy=entropy,
        tasks=tasks,
        walks=walks,
        arms=arms,
        cycle_time=t,
        collisions=contacts,
        timeline=timeline if keep_timeline else None,
        operator=walker,
    )


def _entropy(rng: np.random.Generator) -> int | list[int] | None:
    """The entropy of the SeedSequence behind ``rng``: ``default_rng(SeedSequence(entropy))``
    draws the same numbers (``[seed, run]`` for a run of :func:`simulate_cycles`, the seed for
    ``default_rng(seed)``, the OS's draw for ``default_rng()``). None for a generator built from
    a spawned sequence or without one (it cannot be recreated from an entropy alone)."""
    seq = getattr(rng.bit_generator, "seed_seq", None)
    if not isinstance(seq, np.random.SeedSequence) or seq.spawn_key:
        return None
    ent = seq.entropy
    if isinstance(ent, list | tuple | np.ndarray):
        return [int(v) for v in ent]
    return None if ent is None else int(ent)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------- many cycles


def _run_one(spec_path: str, run: int, seed: int, collisions: bool) -> CycleResult:
    ctx = _context_cached(spec_path)
    ss = np.random.SeedSequence([seed, run])
    return simulate_cycle(ctx, np.random.default_rng(ss), run=run, collisions=collisions)


def simulate_cycles(
    spec: CycleSpec | str | Path,
    runs: int,
    seed: int = 0,
    n_jobs: int = 1,
    *,
    collisions: bool = True,
    progress: bool = False,
    only: Sequence[int] | None = None,
) -> list[CycleResult]:
    """Monte Carlo: ``runs`` independent cycles, in parallel through joblib.

    Run ``k`` draws from ``SeedSequence([seed, k])`` (``result.entropy``): results do not
    depend on ``n_jobs`` or on the backend, and ``only=[k]`` re-simulates run ``k`` of a batch
    alone (``mjwalk simulate ... --only-run K``). Workers load the spec and models once each
    (the default models come from the on-disk cache). Under
    ``joblib.parallel_config(backend="dask")`` or ``"ray"`` the runs go to that cluster
    unchanged.
    """
    from joblib import Parallel, delayed

    if isinstance(spec, CycleSpec):
        spec_path = str(spec.path)
    else:
        spec_path = str(spec)
    if isinstance(runs, bool) or not isinstance(runs, int | np.integer) or runs < 1:
        raise InputError(f"simulate_cycles: runs must be a whole number >= 1, got {runs!r}")
    indices = list(range(runs)) if only is None else [int(k) for k in only]
    bad = [k for k in indices if not 0 <= k < runs]
    if bad or not indices:
        raise InputError(
            f"simulate_cycles: run indices must lie in 0..{runs - 1} (of {runs} runs), "
            f"got {bad or 'none'}"
        )
    jobs = (delayed(_run_one)(spec_path, k, seed, collisions) for k in indices)
    if progress:
        from tqdm import tqdm

        out = []
        gen = Parallel(n_jobs=n_jobs, return_as="generator")(jobs)
        for r in tqdm(gen, total=len(indices), desc="cycles", unit="cycle"):
            out.append(r)
        return out
    return list(Parallel(n_jobs=n_jobs)(jobs))


def combined_walk(paths: list):
    """Walk paths laid end to end as one WalkPath (a cycle's route, drawn into its video);
    None without any walk."""
    from mjwalk.plan.walkpath import PathStep, WalkPath

    if not paths:
        return None
    xy, yaw, t, steps = [], [], [], []
    offset, t0 = 0, 0.0
    for p in paths:
        xy.append(p.xy)
        yaw.append(p.yaw)
        t.append(p.t + t0)
        steps += [
            PathStep(s.side, s.start + offset, s.end + offset, s.foot, s.stance) for s in p.steps
        ]
        offset += len(p.xy)
        t0 = t[-1][-1] + 1.0 / SAMPLE_RATE_HZ
    return WalkPath(np.concatenate(t), np.vstack(xy), np.concatenate(yaw), steps)
