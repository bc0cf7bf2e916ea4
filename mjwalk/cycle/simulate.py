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

if TYPE_CHECKING:  # loaded on first use (prepare)
    from mjwalk.gait.model import StepModel

#: Turning speed on the spot (rad/s) and shortest turn (s).
TURN_SPEED = math.radians(180.0)
MIN_TURN = 0.25
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
    baselines: dict = field(default_factory=dict)
    grid: OccupancyGrid | None = None  # the grid-A* occupancy grid, built on first use

    def planner(self, goal: str) -> HybridPlanner:
        if goal not in self.planners:
            self.planners[goal] = HybridPlanner(
                self.workplace,
                goal,
                self.step_model,
                radius=self.spec.radius,
                goal_tolerance=GOAL_TOLERANCE,
            )
        return self.planners[goal]

    def baseline(self, a: str, b: str) -> float:
        if (a, b) not in self.baselines:
            if self.grid is None:
                self.grid = occupancy_grid(self.workplace, radius=self.spec.radius)
            self.baselines[(a, b)] = plan_grid(
                self.workplace, a, b, radius=self.spec.radius, grid=self.grid
            ).length
        return self.baselines[(a, b)]


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
    return replace(ctx, spec=replace(ctx.spec, stature=walker.stature), model=model, jointmap=jm)


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


def _turn_frames(ctx, x, y, yaw0, yaw1, fps) -> tuple[np.ndarray, float]:
    d = (yaw1 - yaw0 + math.pi) % (2 * math.pi) - math.pi
    duration = max(MIN_TURN, abs(d) / TURN_SPEED)
    n = max(1, round(duration * fps))
    frames = np.array([_standing(ctx, x, y, yaw0 + d * (k + 1) / n) for k in range(n)])
    return frames, n / fps


def hand_points(ctx, qpos: np.ndarray) -> np.ndarray:
    """(F, 2, 3) world positions (m) of the left and right palm (the hand geoms' centres) in
    the poses ``qpos`` (F, nq)."""
    m, jm = ctx.model, ctx.jointmap
    data = mujoco.MjData(m)
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
    data = mujoco.MjData(m)
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


def _approach(kind: str, site_pos: np.ndarray, x: float, y: float) -> np.ndarray:
    """Pre-grasp offset (world, m): back towards the operator, and up for shelf work."""
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
    steps = ctx.step_model.for_walker(walker) if walker is not None else None
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
            path = ctx.planner(goal).plan((x, y), rng, model=steps)
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
            assert task.site is not None  # the spec loader requires a site for reaches
            site_pos = wp.station(task.site).pos
            target = _target(ctx, task.kind, site_pos, x, y)
            # face the target (turning on the spot) before reaching for it
            d = math.hypot(target[0] - x, target[1] - y)
            face = math.atan2(target[1] - y, target[0] - x)
            if task.hand != "both" and task.kind != "fasten":
                # shelf work: bring the target ahead of the shoulder
                side = 1 if task.hand == "left" else -1
                face -= side * math.asin(min(SHOULDER_OFFSET / d, 0.5))
            turn, dt = _turn_frames(ctx, x, y, yaw, face, fps)
            frames.append(turn)
            t += dt
            yaw = face
            hold = task.duration if task.duration is not None else DEFAULT_HOLD[task.kind]
            factor = task_factor(hand_rng)  # lognormal, median 1 (mjwalk.cycle.handling)
            hold *= factor / pace  # the hold, like the reach, at the operator's pace
            case = REACH_CASE[task.kind]

            def timing(dist, case=case, factor=factor):
                return (
                    reach_duration(dist, walker, case) * factor,
                    reach_duration(dist, walker, RETURN_CASE) * factor,
                )

            approach = _approach(task.kind, site_pos, x, y)
            q0 = frames[-1][-1]
            if task.hand == "both":
                rf, err, res, width = _two_hand_frames(
                    ctx, q0, task, approach, hold, fps, timing=timing
                )
                if task.kind != "pick":
                    width = None  # released
            else:
                arm: Side = "right" if task.hand == "right" else "left"
                rf, err, res = _reach_frames(
                    ctx, q0, target, approach, hold, fps, arm, timing=timing
                )
            frames.append(rf)
            t += len(rf) / fps
            arms.append(
                ArmRecord(
                    task=i,
                    kind=task.kind,
                    site=task.site,
                    hand=task.hand,
                    duration=len(rf) / fps,
                    hand_error=err,
                    outside=bool(res.outside),
                    warnings=list(res.warnings),
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
    contacts = collision_report(timeline) if collisions else []
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
