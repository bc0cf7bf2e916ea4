"""Simulate assembly cycles: plan every walk, animate walks and arm motions, time every task.

One cycle (:func:`simulate_cycle`) walks the task list of a :class:`CycleSpec`: each ``walk`` /
``carry`` task is planned with the probabilistic hybrid A* (and, for the report, the grid-A*
route between the walk's own two ends); the operator turns on the spot towards the walk's first
heading and, at its end, towards the site's facing direction; each ``pick`` / ``place`` / ``fasten``
task is an arm reach from the current standing pose to the site (the :class:`ReachModel`, PCA +
DCS, alzubi-sommer), a hold (the task's duration) and the return. Everything is laid on one
timeline of humanoid poses (``fps`` frames per second), checked for humanoid-vs-scene contacts
with MuJoCo's collision detection.

With a ``[population]`` in the spec each run first draws its operator
(:meth:`~mjwalk.cycle.population.Population.draw`, from the run's first spawned stream): the
humanoid is built at the operator's stature (:func:`operator_context`), the walks are sampled
from the step model conditioned on the operator (:meth:`StepModel.for_walker`), and reach,
hold and return times are divided by the operator's pace (:mod:`mjwalk.cycle.handling`).

Many cycles (:func:`simulate_cycles`) run in ``n_jobs`` processes: by default (on Linux) warm
workers forked from this process once it has prepared the cycle and run its first run
(:mod:`mjwalk.cycle.workers`: no import, preparation or kernel loading per worker); inside
``joblib.parallel_config(backend="dask")`` (or ``"ray"``) the same call runs on a Dask or Ray
cluster unchanged (see the README), through joblib.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable, Sequence
from functools import partial
from pathlib import Path

import numpy as np
from joblib import Parallel, delayed

from mjwalk._args import as_generator, check_seed
from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.cycle.actions import Action, CycleRun, CycleState, action_class
from mjwalk.cycle.context import (
    GOAL_TOLERANCE,
    CycleContext,
    context_of,
    operator_context,
    prepare,
)
from mjwalk.cycle.poses import carry_abduction, carry_pose, hand_points, standing_pose
from mjwalk.cycle.seeding import (
    batch_operator,
    draw_operator,
    rng_entropy,
    run_generator,
    run_streams,
)
from mjwalk.cycle.spec import check_durations
from mjwalk.cycle.types import (
    TASK_KINDS,
    ArmRecord,
    CycleResult,
    CycleSpec,
    TaskRecord,
    WalkRecord,
)
from mjwalk.cycle.walking import cycle_start, plan_cycle_walks, plan_task_walk, work_zone
from mjwalk.cycle.workers import forked_workers, map_forked
from mjwalk.ergonomics.angles import angles_from_timeline
from mjwalk.ergonomics.assess import TaskSpan, assess_cycle
from mjwalk.errors import CycleSpecError, InputError, PlanningError
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.timeline.collisions import collision_report
from mjwalk.timeline.geomposes import GeomTable, geom_table, supported
from mjwalk.timeline.parts import Handling, part_tracks
from mjwalk.timeline.timeline import Timeline

__all__ = [
    "GOAL_TOLERANCE",
    "CycleContext",
    "carry_abduction",
    "carry_pose",
    "combined_walk",
    "cycle_start",
    "hand_points",
    "operator_context",
    "plan_cycle_walks",
    "plan_task_walk",
    "prepare",
    "simulate_cycle",
    "simulate_cycles",
    "work_zone",
]


def simulate_cycle(
    spec: CycleSpec | CycleContext,
    rng: np.random.Generator | int | None = None,
    *,
    run: int = 0,
    fps: float = 30.0,
    keep_timeline: bool = False,
    collisions: bool = True,
    ergonomics: bool = True,
) -> CycleResult:
    """Simulate one assembly cycle.

    Args:
        spec: the cycle (or a prepared :class:`CycleContext`, to reuse models across runs).
        rng: random generator or seed (same seed, same cycle).
        run: the run's index (recorded in the result).
        fps: frame rate of the humanoid timeline (the video rate).
        keep_timeline: keep the per-frame poses in ``result.timeline`` (for videos), with the
            tracks of the parts the hands handle (``Timeline.parts``, :mod:`mjwalk.timeline.parts`).
        collisions: run MuJoCo's collision detection over the timeline
            (:func:`~mjwalk.timeline.collisions.check_collisions` checks a result later).
        ergonomics: score the cycle's postures and lifts (RULA, REBA, OWAS, NIOSH, ISO 11226;
            :func:`cycle_ergonomics`) into ``result.ergonomics``.

    Returns:
        A :class:`CycleResult`: walks, arm motions, task times, cycle time, collisions, and the
        run's operator (``result.operator``, drawn from ``spec.population``; None without one).

    Raises:
        PlanningError: a walk cannot be planned (the spec is checked before, so this means an
            unreachable site); MjwalkError for model files.
    """
    rng = as_generator(rng, "simulate_cycle: rng")  # before any work
    ctx = spec if isinstance(spec, CycleContext) else prepare(spec)
    check_durations(ctx.spec.tasks)
    actions = [_action(ctx, i, task) for i, task in enumerate(ctx.spec.tasks)]
    run_, state = _start(ctx, rng, fps)
    frames = [state.pose[None]]
    ground = [np.full(1, run_.ctx.ground((state.x, state.y)))]  # the surface stood on per frame
    n_frames = 1  # the frames so far
    starts: list[int] = []  # first frame of each task
    tasks: list[TaskRecord] = []
    walks: list[WalkRecord] = []
    arms: list[ArmRecord] = []
    for action in actions:
        starts.append(n_frames)
        done = action.perform(run_, state, action.plan(run_, state))
        t, n0 = state.t, n_frames
        for piece, seconds in done.pieces:
            frames.append(piece)
            n_frames += len(piece)
            t += seconds
        here = run_.ctx.ground((state.x, state.y)) if done.ground is None else done.ground
        ground.append(np.broadcast_to(here, n_frames - n0))
        task = action.task
        tasks.append(TaskRecord(action.index, task.kind, task.site, state.t, t, task.route))
        if isinstance(done.record, WalkRecord):
            walks.append(done.record)
        elif isinstance(done.record, ArmRecord):
            arms.append(done.record)
        state = done.state.moved(t=t, pose=frames[-1][-1])
    timeline = _timeline(run_.ctx, np.vstack(frames), fps, walks)
    entropy = rng_entropy(rng)
    result = CycleResult(
        spec=ctx.spec,
        run=run,
        seed=entropy[0] if isinstance(entropy, list) else entropy,
        entropy=entropy,
        tasks=tasks,
        walks=walks,
        arms=arms,
        cycle_time=state.t,
        operator=run_.walker,
    )
    return _finish(
        run_.ctx, timeline, starts, result, keep=keep_timeline, collisions=collisions,
        ergonomics=ergonomics, ground=np.concatenate(ground),
    )  # fmt: skip


def _action(ctx: CycleContext, i: int, task) -> Action:
    """The action of task ``i`` (its kind's :class:`~mjwalk.cycle.actions.base.Action`),
    checked against the scene."""
    kind = TASK_KINDS.get(task.kind)
    if kind is None:  # the spec parser refuses unknown kinds; this guards hand-made specs
        raise CycleSpecError(f"task {i}: unknown kind {task.kind!r}")
    action = action_class(kind)(task, kind, i)
    action.check(ctx)
    return action


def _start(ctx: CycleContext, rng: np.random.Generator, fps: float) -> tuple[CycleRun, CycleState]:
    """The run's operator and streams (:mod:`mjwalk.cycle.seeding`) and where the cycle
    starts: in the start site's stand zone (not on its mark), facing the site's heading."""
    streams = run_streams(rng)
    # the run's operator (None without a [population]: the step model's own pace, handling at
    # the reference adult's pace): their humanoid, their steps, their handling pace
    walker = draw_operator(ctx.spec, streams)
    ctx = operator_context(ctx, walker)
    here = ctx.spec.start
    x, y = cycle_start(ctx, streams.standing, walker)
    yaw = ctx.workplace.station(here).yaw
    pose = standing_pose(ctx, x, y, yaw)
    run = CycleRun(ctx, walker, fps, rng, streams.handling, streams.standing, pose)
    return run, CycleState(x=x, y=y, yaw=yaw, here=here, home=(x, y), pose=pose)


def _timeline(ctx: CycleContext, qpos: np.ndarray, fps: float, walks: list) -> Timeline:
    """The cycle's humanoid timeline, with its walks laid end to end (drawn into videos)."""
    timeline = Timeline(
        model=ctx.model,
        jointmap=ctx.jointmap,
        fps=fps,
        t=np.arange(len(qpos)) / fps,
        qpos=qpos,
        scene=str(ctx.spec.scene),
        stature=ctx.spec.stature,
    )
    timeline.walk = combined_walk([w.path for w in walks])
    return timeline


def _finish(
    ctx: CycleContext,
    timeline: Timeline,
    starts: list[int],
    result: CycleResult,
    *,
    keep: bool,
    collisions: bool,
    ergonomics: bool,
    ground: np.ndarray | None = None,
) -> CycleResult:
    """``result`` with what was asked for: the timeline and the tracks of the parts the hands
    handle (``keep``), the humanoid-vs-scene contacts, the ergonomic scores (heights above
    ``ground``, (F,) world z of the surface stood on in each frame). Task ``i`` spans frames
    ``starts[i]`` up to the next task's first frame."""
    spec = result.spec
    ends = [*starts[1:], len(timeline.qpos)]
    if keep:  # the parts the hands pick, carry and put down, drawn into videos
        handlings = [
            Handling(part, task.site, task.hand, starts[i], ends[i])
            for i, task in enumerate(spec.tasks)
            if (part := TASK_KINDS[task.kind].part) is not None and task.site is not None
        ]
        qpos = timeline.qpos
        timeline.parts = part_tracks(ctx.model, ctx.jointmap, qpos, handlings, ctx.scratch())
        result.timeline = timeline
    # the contact check and the ergonomics read the same kinematics: computed once for both
    table = None
    if collisions and ergonomics and supported(timeline.model):
        human = np.flatnonzero(timeline.model.geom_group == HUMAN_GROUP)
        table = geom_table(timeline.model, timeline.qpos, human)
    if collisions:
        result.collisions = collision_report(timeline, data=ctx.scratch(), table=table)
    if ergonomics:
        wp, t = ctx.workplace, result.cycle_time
        result.ergonomics = cycle_ergonomics(timeline, spec, starts, ends, t, wp, table, ground)
    return result


def cycle_ergonomics(
    timeline: Timeline,
    spec: CycleSpec,
    starts,
    ends,
    cycle_time: float,
    wp,
    table: GeomTable | None = None,
    ground: np.ndarray | None = None,
):
    """The ergonomics of a cycle's timeline (:func:`mjwalk.ergonomics.assess.assess_cycle`): a
    place or fasten handles the part its hand picked last (its mass and coupling). Heights are
    given above the surface the operator stands on (``ground``; the floor in a flat cycle): the
    hands', the ankles' and the sites' (NIOSH's V: the hands' height above the floor the worker
    stands on, Waters et al. 1993; a task on a 0.34 m platform is measured from its top).

    Args:
        timeline: the cycle's humanoid timeline.
        spec: the cycle.
        starts: (n_tasks,) each task's first frame.
        ends: (n_tasks,) each task's end frame (exclusive).
        cycle_time: the cycle's duration, seconds.
        wp: the Workplace (the sites' positions).
        table: the humanoid's geom poses in every frame, if already computed
            (:func:`~mjwalk.ergonomics.angles.angles_from_timeline`).
        ground: (n_frames,) world z (m) of the surface the operator stands on in each frame
            (:attr:`Performed.ground <mjwalk.cycle.actions.base.Performed.ground>`); None: the
            floor's (``wp.floor_z``) throughout.

    Returns:
        The run's ergonomic scores (:class:`~mjwalk.ergonomics.assess.RunErgonomics`).
    """
    n = timeline.n_frames
    g = np.full(n, float(wp.floor_z)) if ground is None else np.asarray(ground, dtype=float)
    if len(g) != n:
        raise InputError(f"cycle_ergonomics: {len(g)} ground heights for {n} frames")
    walking = np.zeros(n, dtype=bool)
    held: dict[str, list[tuple[float, str]]] = {"left": [], "right": [], "both": []}
    spans = []
    for i, task in enumerate(spec.tasks):
        s, e = int(starts[i]), int(ends[i])
        kind = TASK_KINDS[task.kind]
        if kind.motion == "walk":
            walking[s:e] = True
        reach, part = kind.motion == "reach", kind.part
        mass, coupling = 0.0, task.coupling
        if part == "take":
            mass = task.mass
            held[task.hand].append((task.mass, task.coupling))
        elif part == "put" and held.get(task.hand):
            mass, coupling = held[task.hand].pop()
        pos = None
        if task.site is not None and task.site in wp.stations:
            pos = np.asarray(wp.stations[task.site].pos, dtype=float) - [0.0, 0.0, g[min(s, n - 1)]]
        spans.append(TaskSpan(i, task.kind, s, e, task.hand if task.kind != "walk" else None,
                              task.site, mass, coupling, pos, reach=reach, part=part,
                              lifts=kind.lifts))  # fmt: skip
    # heights above the surface stood on (world z where it is the floor at z = 0 throughout)
    ang = angles_from_timeline(timeline, walking, table, g if np.any(g != 0.0) else None)
    return assess_cycle(ang, spans, cycle_time, timeline.fps)


#: One cycle at a time per process. A thread backend (``joblib.parallel_config(backend=
#: "threading")``, a Dask worker with several threads) would run cycles side by side in one
#: process, where their compiled kernels run without the GIL (:mod:`mjwalk._jit`) over state
#: kept per process (the cycle context, its memos, the models' caches); the cycle code is not
#: written for that, and a CI run crashed (segfault) in a threaded batch. Processes (the default
#: forked workers, loky, Dask's worker processes) are not held back by it.
_RUN_LOCK = threading.Lock()


def _run_one(
    spec: CycleSpec | str, run: int, seed: int, collisions: bool, on_error: str = "raise"
) -> CycleResult:
    with _RUN_LOCK:
        return _run_one_locked(spec, run, seed, collisions, on_error)


def _run_one_locked(
    spec: CycleSpec | str, run: int, seed: int, collisions: bool, on_error: str
) -> CycleResult:
    ctx = context_of(spec)
    try:
        return simulate_cycle(ctx, run_generator(seed, run), run=run, collisions=collisions)
    except PlanningError as e:
        if on_error == "raise":
            raise
        spec = ctx.spec
        walker = batch_operator(spec, seed, run)  # the operator this run drew
        return CycleResult(
            spec=spec,
            run=run,
            seed=seed,
            tasks=[],
            walks=[],
            arms=[],
            cycle_time=float("nan"),
            entropy=[seed, run],
            operator=walker,
            error=f"{type(e).__name__}: {e}",
        )


def simulate_cycles(
    spec: CycleSpec | str | Path,
    runs: int,
    seed: int = 0,
    n_jobs: int = 1,
    *,
    collisions: bool = True,
    progress: bool = False,
    only: Sequence[int] | None = None,
    on_error: str = "raise",
) -> list[CycleResult]:
    """Monte Carlo: ``runs`` independent cycles, in parallel through joblib.

    ``on_error="record"`` keeps going when a run's walk cannot be planned
    (:class:`~mjwalk.errors.PlanningError`, e.g. a rare operator whose steps cannot reach a
    tight stand zone): that run comes back with ``result.error`` set, no tasks and a NaN
    cycle time, and the report lists it apart from the statistics. ``"raise"`` (the default)
    re-raises the first such error. Other errors (a bad spec, a model file) always raise.

    Run ``k`` draws from ``SeedSequence([seed, k])`` (``result.entropy``): results do not
    depend on ``n_jobs`` or on the backend, and ``only=[k]`` re-simulates run ``k`` of a batch
    alone (``mjwalk simulate ... --only-run K``). Without a joblib backend of the caller's
    choosing (on Linux) this process prepares the cycle and simulates the first run, then
    forks the workers for the others (:mod:`mjwalk.cycle.workers`): they start with its
    models and compiled kernels. Under a backend the caller chose, joblib's workers load the
    spec and models once each (the default models come from the on-disk cache). A
    :class:`CycleSpec` is simulated as it
    is in memory (``dataclasses.replace(spec, reach_model=...)`` runs the new model), a path is
    read in each worker. Under ``joblib.parallel_config(backend="dask")`` or ``"ray"`` the runs
    go to that cluster unchanged. Runs that share a process through threads (joblib's
    ``"threading"`` backend, a Dask worker with several threads) take turns: one cycle at a
    time per process (:data:`_RUN_LOCK`).

    Args:
        spec: the cycle, or its spec file.
        runs: how many runs the batch has (>= 1).
        seed: the batch's root seed.
        n_jobs: the number of worker processes, as joblib reads it (-1: all cores).
        collisions: check each run's humanoid for contacts with the scene.
        progress: show a progress bar (tqdm).
        only: the indices of the runs to simulate (each in ``0..runs-1``); None: all.
        on_error: "raise" or "record" (see above).

    Returns:
        One :class:`CycleResult` per simulated run, in the order of the indices.

    Raises:
        InputError: bad ``runs``, ``only``, ``seed`` or ``on_error``.
    """
    # a CycleSpec goes to the workers as it is (edits made in memory count), a path as a string
    job_spec: CycleSpec | str = spec if isinstance(spec, CycleSpec) else str(spec)
    if isinstance(runs, bool) or not isinstance(runs, int | np.integer) or runs < 1:
        raise InputError(f"simulate_cycles: runs must be a whole number >= 1, got {runs!r}")
    indices = list(range(runs)) if only is None else [int(k) for k in only]
    bad = [k for k in indices if not 0 <= k < runs]
    if bad or not indices:
        raise InputError(
            f"simulate_cycles: run indices must lie in 0..{runs - 1} (of {runs} runs), "
            f"got {bad or 'none'}"
        )
    seed = check_seed(seed, "simulate_cycles: seed")
    if on_error not in ("raise", "record"):
        raise InputError(f"simulate_cycles: on_error must be 'raise' or 'record', got {on_error!r}")
    one = partial(_run_one, job_spec, seed=seed, collisions=collisions, on_error=on_error)
    workers = forked_workers(n_jobs, len(indices))
    if workers:  # warm workers: forked from this process once it has run the first run
        gen: Iterable[CycleResult] = map_forked(one, indices, workers)
    else:  # joblib's: one job in this process, or the backend the user chose (Dask, Ray)
        as_ = "generator" if progress else "list"
        gen = Parallel(n_jobs=n_jobs, return_as=as_)(delayed(one)(k) for k in indices)
    if progress:
        # deferred: tqdm is optional (not a declared dependency), only needed for progress=True
        from tqdm import tqdm

        gen = tqdm(gen, total=len(indices), desc="cycles", unit="cycle")
    return list(gen)


def combined_walk(paths: list):
    """Walk paths laid end to end as one WalkPath (a cycle's route, drawn into its video): each
    path's times shifted to start one sample after the last one's end.

    Args:
        paths: the walks (:class:`~mjwalk.plan.walkpath.WalkPath`), in order.

    Returns:
        The combined WalkPath, or None without any walk.
    """
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
