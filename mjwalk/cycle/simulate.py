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

Many cycles (:func:`simulate_cycles`) run through joblib, so ``n_jobs`` processes share the
work; inside ``joblib.parallel_config(backend="dask")`` (or ``"ray"``) the same call runs on a
Dask or Ray cluster unchanged (see the README).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mjwalk._args import as_generator, check_seed
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.cycle.context import (
    GOAL_TOLERANCE,
    CycleContext,
    context_of,
    operator_context,
    prepare,
)
from mjwalk.cycle.handling import RETURN_CASE, reach_duration, task_factor
from mjwalk.cycle.poses import (
    carry_abduction,
    carry_pose,
    hand_points,
    standing_pose,
    turn_frames,
    walk_frames,
)
from mjwalk.cycle.reachspot import reach_task
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
from mjwalk.errors import CycleSpecError, InputError, PlanningError
from mjwalk.timeline.collisions import collision_report
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
    spec = ctx.spec
    check_durations(spec.tasks)
    # side streams spawned from the run's generator (its own draws, the walks, are unchanged):
    # the operator, the task-time factors, where the operator stands (at the start, then the
    # spot each walk aims at: plan_task_walk)
    op_rng, hand_rng, stand_rng = rng.spawn(3)
    entropy = _entropy(rng)
    # the run's operator (None without a [population]: the step model's own pace, handling at
    # the reference adult's pace): their humanoid, their steps, their handling pace
    walker = spec.population.draw(op_rng) if spec.population is not None else None
    ctx = operator_context(ctx, walker)
    pace = 1.0 if walker is None else walker.pace
    wp = ctx.workplace
    here = spec.start
    x, y = cycle_start(ctx, stand_rng, walker)  # in the start's stand zone, not on its mark
    home = (x, y)  # where the last walk ended: the reaches there step back or in from it
    yaw = wp.station(here).yaw
    frames = [standing_pose(ctx, x, y, yaw)[None]]
    t = 0.0
    tasks: list[TaskRecord] = []
    walks: list[WalkRecord] = []
    arms: list[ArmRecord] = []
    width: float | None = None  # grip distance (m) of the two-handed part in the hands
    starts: list[int] = []  # first frame of each task
    for i, task in enumerate(spec.tasks):
        t0 = t
        starts.append(sum(len(f) for f in frames))
        kind = TASK_KINDS.get(task.kind)
        if kind is None:  # the spec parser refuses unknown kinds; this guards hand-made specs
            raise CycleSpecError(f"task {i}: unknown kind {task.kind!r}")
        if kind.action == "walk":
            goal = task.site
            assert goal is not None  # the spec loader requires a site for walks
            # from the heading the operator stands at (turning on the spot, then walking) into
            # the heading of the work at the goal
            face = wp.station(goal).yaw
            path = plan_task_walk(ctx, i, (x, y), rng, walker, stand_rng, yaw=yaw, face=face)
            # a two-handed part stays in the hands, in the carrying posture (turns included)
            pose = None if width is None else carry_pose(ctx, frames[0][0], width)
            turn, dt = turn_frames(ctx, x, y, yaw, float(path.yaw[0]), fps, pose=pose)
            frames.append(turn)
            t += dt
            carry = task.hand if kind.carries else None
            if width is not None:
                carry = "both"
            wf = walk_frames(ctx, path, fps, carry, width)
            frames.append(wf)
            t += len(wf) / fps  # the walk, to the video frame
            x, y = (float(v) for v in path.xy[-1])
            home = (x, y)
            yaw = float(path.yaw[-1])
            # the last step lands knee flexed, pelvis low: the turn settles into standing
            turn, dt = turn_frames(ctx, x, y, yaw, face, fps, pose=pose, settle=wf[-1])
            frames.append(turn)
            t += dt
            yaw = face
            # the grid-A* route between the walk's own ends (not the sites' marks: the walk
            # starts and ends where the operator stands), for the report's ``vs A*``
            base = ctx.baseline_route(path.xy[0], path.xy[-1])
            walks.append(
                WalkRecord(
                    task=i,
                    route=task.route or f"{here}->{goal}",
                    start_site=here,
                    goal_site=goal,
                    path=path,
                    baseline_length=float("nan") if base is None else base.length,
                    baseline=base,
                )
            )
            here = goal
        elif kind.action == "reach":
            assert kind.default_hold is not None and kind.reach_case is not None
            hold = task.duration if task.duration is not None else kind.default_hold
            factor = task_factor(hand_rng)  # lognormal, median 1 (mjwalk.cycle.handling)
            hold *= factor / pace  # the hold, like the reach, at the operator's pace
            case = kind.reach_case

            def timing(dist, case=case, factor=factor):
                return (
                    reach_duration(dist, walker, case) * factor,
                    reach_duration(dist, walker, RETURN_CASE) * factor,
                )

            assert task.site is not None  # the spec loader requires a site for reaches
            r = reach_task(
                ctx, task, x, y, yaw, hold, fps, timing, wp.station(here).yaw, width, home
            )
            x, y, yaw = r.x, r.y, r.yaw
            frames.append(r.turn)
            t += r.turn_time
            if task.hand == "both":
                width = r.width if kind.part == "take" else None  # released when put down
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
        elif kind.action == "wait":
            assert kind.default_hold is not None
            hold = task.duration if task.duration is not None else kind.default_hold
            n = max(1, round(hold * fps))
            frames.append(np.repeat(frames[-1][-1:], n, axis=0))
            t += n / fps
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
    if keep_timeline:  # the parts the hands pick, carry and put down, drawn into videos
        ends = [*starts[1:], len(qpos)]
        handlings = [
            Handling(part, task.site, task.hand, starts[i], ends[i])
            for i, task in enumerate(spec.tasks)
            if (part := TASK_KINDS[task.kind].part) is not None and task.site is not None
        ]
        timeline.parts = part_tracks(ctx.model, ctx.jointmap, qpos, handlings, ctx.scratch())
    contacts = collision_report(timeline, data=ctx.scratch()) if collisions else []
    ends = [*starts[1:], len(qpos)]
    ergo = cycle_ergonomics(timeline, spec, starts, ends, t, wp) if ergonomics else None
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
        ergonomics=ergo,
    )


def cycle_ergonomics(timeline: Timeline, spec: CycleSpec, starts, ends, cycle_time: float, wp):
    """The ergonomics of a cycle's timeline (:func:`mjwalk.ergonomics.assess.assess_cycle`):
    task ``i`` of ``spec`` spans frames ``starts[i]:ends[i]``; a place or fasten handles the
    part its hand picked last (its mass and coupling); ``wp`` the Workplace (the sites)."""
    from mjwalk.ergonomics.angles import angles_from_timeline
    from mjwalk.ergonomics.assess import TaskSpan, assess_cycle

    n = timeline.n_frames
    walking = np.zeros(n, dtype=bool)
    held: dict[str, list[tuple[float, str]]] = {"left": [], "right": [], "both": []}
    spans = []
    for i, task in enumerate(spec.tasks):
        s, e = int(starts[i]), int(ends[i])
        kind = TASK_KINDS[task.kind]
        if kind.action == "walk":
            walking[s:e] = True
        reach, part = kind.action == "reach", kind.part
        mass, coupling = 0.0, task.coupling
        if part == "take":
            mass = task.mass
            held[task.hand].append((task.mass, task.coupling))
        elif part == "put" and held.get(task.hand):
            mass, coupling = held[task.hand].pop()
        pos = None
        if task.site is not None and task.site in wp.stations:
            pos = np.asarray(wp.stations[task.site].pos, dtype=float)
        spans.append(TaskSpan(i, task.kind, s, e, task.hand if task.kind != "walk" else None,
                              task.site, mass, coupling, pos, reach=reach, part=part,
                              lifts=kind.lifts))  # fmt: skip
    ang = angles_from_timeline(timeline, walking)
    return assess_cycle(ang, spans, cycle_time, timeline.fps)


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


def _run_one(
    spec: CycleSpec | str, run: int, seed: int, collisions: bool, on_error: str = "raise"
) -> CycleResult:
    ctx = context_of(spec)
    ss = np.random.SeedSequence([seed, run])
    try:
        return simulate_cycle(ctx, np.random.default_rng(ss), run=run, collisions=collisions)
    except PlanningError as e:
        if on_error == "raise":
            raise
        # the operator this run drew (as simulate_cycle draws it: the first spawned stream)
        op_rng = np.random.default_rng(ss).spawn(3)[0]
        spec = ctx.spec
        walker = spec.population.draw(op_rng) if spec.population is not None else None
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
    alone (``mjwalk simulate ... --only-run K``). Workers load the spec and models once each
    (the default models come from the on-disk cache). A :class:`CycleSpec` is simulated as it
    is in memory (``dataclasses.replace(spec, reach_model=...)`` runs the new model), a path is
    read in each worker. Under
    ``joblib.parallel_config(backend="dask")`` or ``"ray"`` the runs go to that cluster
    unchanged.
    """
    from joblib import Parallel, delayed

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
    jobs = (delayed(_run_one)(job_spec, k, seed, collisions, on_error) for k in indices)
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
