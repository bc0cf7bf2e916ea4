"""A cycle's walks: the stand zone of each walk (:mod:`mjwalk.cycle.standing`) and the walk
planned into it for the run's operator; the walks of a cycle without animation
(:func:`plan_cycle_walks`). World frame: metres."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mjwalk.cycle.standing import StandZone, stand_zone

if TYPE_CHECKING:
    pass  # loaded on first use (prepare)

from mjwalk.cycle.context import CycleContext
from mjwalk.cycle.reaching import _target


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
    model = ctx.step_model.for_walker(walker)  # the model itself for None
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else ctx.step_model.pace().step_length
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
