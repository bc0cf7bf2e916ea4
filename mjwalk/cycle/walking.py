"""A cycle's walks: the stand zone of each walk (:mod:`mjwalk.cycle.standing`) and the walk
planned into it for the run's operator; the walks of a cycle without animation
(:func:`plan_cycle_walks`). World frame: metres."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mjwalk.cycle.levelsite import START_MARGIN, level_field
from mjwalk.cycle.standing import StandZone, start_zone, work_zone
from mjwalk.cycle.stepup import step_up_of
from mjwalk.cycle.types import TASK_KINDS
from mjwalk.plan.levelplan import needs_levels, plan_level_walk
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.request import WalkRequest

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

__all__ = [
    "START_MARGIN",
    "cycle_start",
    "plan_cycle_walks",
    "plan_task_walk",
    "standing_site",
    "standing_spot",
    "start_zone",
    "work_zone",
]


#: Candidate spots drawn at once by :func:`standing_spot` (uniform over the zone's disc); the
#: stations' zones keep 5-40 % of their disc walkable, so 512 leave a miss below 1e-10.
SPOT_DRAWS = 512
#: Candidates :func:`standing_spot` tests at a time, in their order (the first block nearly
#: always holds the spot; testing all at once found the same one, with more lookups).
SPOT_BLOCK = 64


def standing_spot(
    ctx: CycleContext, zone: StandZone, rng: np.random.Generator
) -> tuple[float, float]:
    """A spot drawn uniformly from the walkable part of ``zone``: in the zone and at least the
    cycle's body radius (plus :data:`START_MARGIN`, to set off from) from every obstacle and
    the floor's edge.

    Args:
        ctx: the cycle context (its scene's walk field, the body radius).
        zone: the stand zone.
        rng: the generator drawn from (:data:`SPOT_DRAWS` candidates at once).

    Returns:
        (x, y) world frame, metres; the zone's own centre (the site) when no draw lands there.
    """
    field = level_field(ctx.workplace, zone.centre, ctx.on_levels)  # the zone's level's
    u = rng.uniform(size=SPOT_DRAWS)  # all draws at once: the generator's state as before
    a = rng.uniform(0.0, 2.0 * np.pi, SPOT_DRAWS)
    cx, cy = (float(v) for v in zone.centre)
    need = ctx.spec.radius + START_MARGIN
    # the first candidate in the zone's discs and keeping ``need``, looked for a block at a
    # time (the first block holds it nearly always): the same elementwise tests of the same
    # points as over all of them at once, each block's points made as they are needed (the
    # same elementwise arithmetic, so the same points)
    for lo in range(0, SPOT_DRAWS, SPOT_BLOCK):
        r, ab = zone.radius * np.sqrt(u[lo : lo + SPOT_BLOCK]), a[lo : lo + SPOT_BLOCK]
        block = np.empty((len(r), 2))
        block[:, 0] = cx + r * np.cos(ab)
        block[:, 1] = cy + r * np.sin(ab)
        ok = np.ones(len(block), dtype=bool)
        for x, y, rad in zone.discs:
            ok &= np.hypot(block[:, 0] - x, block[:, 1] - y) <= rad
        inside = np.flatnonzero(ok)
        hit = inside[field(block[inside]) >= need] if len(inside) else inside
        if len(hit):
            return float(block[hit[0], 0]), float(block[hit[0], 1])
    return zone.centre


def cycle_start(ctx: CycleContext, rng: np.random.Generator, walker=None) -> tuple[float, float]:
    """Where the cycle's operator stands at the start: a :func:`standing_spot` of
    :func:`start_zone` drawn with ``rng`` (``simulate_cycle``'s standing-spot stream).

    Args:
        ctx: the cycle context.
        rng: the generator drawn from.
        walker: the operator; None: the cycle's own humanoid and step model.

    Returns:
        (x, y) world frame, metres.
    """
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else ctx.step_model.pace().step_length
    return standing_spot(ctx, start_zone(ctx.spec, ctx.workplace, stature, step), rng)


#: Where an operator means to stand in a stand zone is a spot drawn uniformly over its walkable
#: part (:func:`standing_spot`): where people stand to work is not one point, it differs between
#: people and from one cycle to the next. The walk ends when the pelvis is within this many of
#: the walker's step lengths of the spot: walking in whole steps, one stops at the footfall
#: nearest the spot, within half a step of it. The routes' spread then matches agethen2018's
#: Table 1 (``benchmarks/bench_variability.py``; docs/decisions/005-standing-spots.md).
SPOT_REACH = 0.5
#: Spots drawn for a walk before it aims at the zone as a whole (a spot within SPOT_REACH step
#: lengths of the start is no walk: the operator already stands there).
SPOT_TRIES = 8
#: The goal area (m) of a walk over levels at most: the default planner's
#: (:class:`~mjwalk.plan.options.PlannerOptions`), which the level planner's legs end in.
GOAL_AREA = PlannerOptions().goal_tolerance


def plan_task_walk(
    ctx: CycleContext,
    i: int,
    start,
    rng: np.random.Generator,
    walker=None,
    spots: np.random.Generator | None = None,
    yaw: float | None = None,
    face: float | None = None,
):
    """The walk of task ``i`` (a walk or carry) from ``start``, as a cycle plans it: steps from
    the cycle's step model (conditioned on ``walker`` when given), ending within
    :data:`SPOT_REACH` step lengths of a spot of the task's stand zone (:func:`work_zone`, for
    the walker's stature and step length) drawn with ``spots`` (:func:`standing_spot`), and
    inside the zone.

    Args:
        ctx: the cycle context.
        i: the task's index in ``ctx.spec.tasks``.
        start: (x, y) where the operator stands, world frame (m).
        rng: the run's generator (the planner's draws).
        walker: the operator; None: the cycle's own step model.
        spots: the standing-spot stream; None: ``rng``.
        yaw: the heading the operator stands at (radians; the task before's): the walk sets off
            from it, turning on the spot first as far as that pays against turning while walking
            (``WalkRequest(turn_on_spot=True)``), a turn of more than a quarter split between
            the spot and the first steps (``at_work``, :mod:`mjwalk.plan.turnsplit`: the first
            steps no nearer the work than square to the front of the site the operator stands
            at, :func:`standing_site`); None: it sets off around the downhill heading.
        face: the heading the operator works at after the walk (radians; the goal site's): the
            walk bends into it as people's do (``WalkRequest(goal_heading=...)``,
            :mod:`mjwalk.plan.guide`); None: it ends as it comes.

    Returns:
        The planned :class:`~mjwalk.plan.walkpath.WalkPath`.
    """
    task = ctx.spec.tasks[i]
    assert task.site is not None  # the spec loader requires a site for walks
    model = ctx.step_model.for_walker(walker)  # the model itself for None
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else ctx.step_model.pace().step_length
    zone = ctx.zone(i, stature, step)
    reach = SPOT_REACH * step
    pose = tuple(start) if yaw is None else (float(start[0]), float(start[1]), float(yaw))
    turn = yaw is not None
    levels = ctx.on_levels and needs_levels(ctx.workplace, pose, task.site, ctx.spec.radius)
    planner = None if levels else ctx.planner(task.site, zone)
    # the front of the work the operator stands at (its stand site's yaw): the turn split's
    # floor (:mod:`mjwalk.plan.turnsplit`), whichever way the last reach turned the body
    work = float(ctx.workplace.station(standing_site(ctx.spec, i)).yaw) if turn else None
    for _ in range(SPOT_TRIES):
        x, y = standing_spot(ctx, zone, rng if spots is None else spots)
        if np.hypot(x - start[0], y - start[1]) > reach:
            if levels:
                return _level_walk(ctx, start, (x, y), model, rng, (reach, walker))
            request = WalkRequest(
                pose, model, (x, y, reach), turn, face, at_work=turn, work_heading=work
            )
            assert planner is not None
            return planner.plan(request, rng)
    if levels:
        return _level_walk(ctx, start, zone.centre, model, rng, (zone.radius, walker))
    assert planner is not None
    request = WalkRequest(
        pose, model, turn_on_spot=turn, goal_heading=face, at_work=turn, work_heading=work
    )
    return planner.plan(request, rng)


def standing_site(spec, i: int) -> str:
    """The site the operator stands at when task ``i`` of ``spec`` begins: the last walk's or
    carry's goal before it, else the cycle's start site.

    Args:
        spec: the cycle (:class:`~mjwalk.cycle.types.CycleSpec`).
        i: a task's index in ``spec.tasks``.

    Returns:
        The site's name.
    """
    here = spec.start
    for task in spec.tasks[:i]:
        if TASK_KINDS[task.kind].motion == "walk":
            here = str(task.site)
    return here


def _level_walk(ctx: CycleContext, start, goal, model, rng, within):
    """A walk over levels (:func:`~mjwalk.plan.levelplan.plan_level_walk`) from ``start`` (x, y:
    it sets off around the heading the search finds, the cycle turns the operator there on the
    spot first) to end within ``within[0]`` metres of the spot ``goal``, for the operator
    ``within[1]`` (their group's step-up limit, :func:`~mjwalk.cycle.stepup.step_up_of`)."""
    reach, walker = within
    pose = (float(start[0]), float(start[1]))
    # the planner's own goal area: it applies to every level leg, so the crossings' stances are
    # reached as the level planner means them (a wider area ends a leg before its crossing)
    options = PlannerOptions(radius=ctx.spec.radius, goal_tolerance=min(reach, GOAL_AREA))
    limit = step_up_of(ctx.spec.population, walker)
    return plan_level_walk(ctx.workplace, pose, goal, model, rng, options, limit)


def plan_cycle_walks(
    ctx: CycleContext,
    rng: np.random.Generator,
    walker=None,
    start=None,
    spots: np.random.Generator | None = None,
) -> list:
    """Only the walks of one cycle, in order, as :func:`simulate_cycle` plans them with the same
    ``rng`` (arms and handling draw from spawned streams). Fast (no animation): for studies of
    the routes alone (``benchmarks/bench_variability.py``). Each walk sets off from the heading
    of the site the operator stands at (the start site's, then the last walk's goal's):
    ``simulate_cycle`` sets off from the heading of the reach done there, which faces the
    reach's target, so a walk after a reach may differ.

    Args:
        ctx: the cycle context.
        rng: the run's generator.
        walker: the operator; None: the cycle's own step model.
        start: (x, y) the run's :func:`cycle_start`, world frame (m); None: the start site.
        spots: the standing-spot stream, after the start's draw; None: ``rng``.

    Returns:
        A list of (task index, start site, goal site, WalkPath).
    """
    spec = ctx.spec
    here = spec.start
    if start is None:
        start = ctx.workplace.station(here).pos[:2]
    x, y = float(start[0]), float(start[1])
    out = []
    for i, task in enumerate(spec.tasks):
        if TASK_KINDS[task.kind].motion == "walk":
            yaw = float(ctx.workplace.station(here).yaw)
            goal = str(task.site)
            face = float(ctx.workplace.station(goal).yaw)
            path = plan_task_walk(ctx, i, (x, y), rng, walker, spots, yaw=yaw, face=face)
            out.append((i, here, goal, path))
            x, y = (float(v) for v in path.xy[-1])
            here = goal
    return out
