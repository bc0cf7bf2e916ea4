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
    goal = ctx.spec.tasks[i].site
    assert goal is not None  # the spec loader requires a site for walks
    return _site_zone(ctx, goal, i + 1, stature, step_length)


def start_zone(ctx: CycleContext, stature: float, step_length: float) -> StandZone:
    """Where the operator stands when the cycle starts: the stand zone of the cycle's start
    site for the work done there before the first walk (:func:`work_zone`'s rule). A cycle is
    one of many in a shift: its operator starts where the work at the start site left them,
    not on the site's mark."""
    return _site_zone(ctx, ctx.spec.start, 0, stature, step_length)


def _site_zone(
    ctx: CycleContext, site: str, first: int, stature: float, step_length: float
) -> StandZone:
    """The stand zone of ``site`` for the reaches of tasks ``first, first + 1, ...`` up to
    the next walk or carry."""
    stand = ctx.workplace.station(site).pos
    targets, squarely, hands = [], [], []
    for task in ctx.spec.tasks[first:]:
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
    facing = ctx.workplace.station(site).yaw
    return stand_zone(stand[:2], targets, step_length, stature, facing, squarely, hands)


#: A standing spot keeps this much more than the body radius from obstacles (m): a walk sets
#: off with a first step that sways the pelvis sideways (the default model's first steps: 1.3
#: cm median, 3.6 cm 99th percentile of 4000 drawn, 6.1 cm the largest), so the planner finds
#: no first step from a spot on the radius itself (measured: 9 of 100 station cycles drawn
#: without the margin, all within 1 cm of the radius).
START_MARGIN = 0.04
#: Candidate spots drawn at once by :func:`standing_spot` (uniform over the zone's disc); the
#: stations' zones keep 5-40 % of their disc walkable, so 512 leave a miss below 1e-10.
SPOT_DRAWS = 512


def standing_spot(
    ctx: CycleContext, zone: StandZone, rng: np.random.Generator
) -> tuple[float, float]:
    """A spot (x, y) drawn uniformly from the walkable part of ``zone``: in the zone and at
    least the cycle's body radius (plus :data:`START_MARGIN`, to set off from) from every
    obstacle and the floor's edge. The zone's own centre (the site) when no draw lands
    there."""
    field = ctx.workplace.walk_field()
    r = zone.radius * np.sqrt(rng.uniform(size=SPOT_DRAWS))
    a = rng.uniform(0.0, 2.0 * np.pi, SPOT_DRAWS)
    pts = np.asarray(zone.centre) + np.column_stack([r * np.cos(a), r * np.sin(a)])
    ok = field(pts) >= ctx.spec.radius + START_MARGIN
    for x, y, rad in zone.discs:
        ok &= np.hypot(pts[:, 0] - x, pts[:, 1] - y) <= rad
    hit = np.flatnonzero(ok)
    if len(hit) == 0:
        return zone.centre
    return float(pts[hit[0], 0]), float(pts[hit[0], 1])


def cycle_start(ctx: CycleContext, rng: np.random.Generator, walker=None) -> tuple[float, float]:
    """Where the cycle's operator (``walker``; None: the cycle's own humanoid and step
    model) stands at the start (x, y), metres: a :func:`standing_spot` of :func:`start_zone`
    drawn with ``rng`` (``simulate_cycle``'s standing-spot stream)."""
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else ctx.step_model.pace().step_length
    return standing_spot(ctx, start_zone(ctx, stature, step), rng)


#: Where an operator means to stand in a stand zone is a spot drawn uniformly over its walkable
#: part (:func:`standing_spot`): where people stand to work is not one point, it differs between
#: people and from one cycle to the next. The walk ends when the pelvis is within this many of
#: the walker's step lengths of the spot: walking in whole steps, one stops at the footfall
#: nearest the spot, within half a step of it. Measured (bench_variability, 1000 station
#: cycles, route length IQR/median as % of agethen2018 Table 1's, T1, T2 there/back, T3
#: there/back, T4, T5): agethen2018's participants 75, 37/46, 50/63, 53, 82 against 64,
#: 27/60, 21/62, 33, 50 when walks ended at the first place in the zone their steps reached;
#: the shipped workforce 79, 34/41, 43/49, 55, 60 against 82, 32/50, 20/47, 33, 33; the
#: longest walks (99th percentile over the grid A*'s route) at most 1.21x against 1.34x.
SPOT_REACH = 0.5
#: Spots drawn for a walk before it aims at the zone as a whole (a spot within SPOT_REACH step
#: lengths of the start is no walk: the operator already stands there).
SPOT_TRIES = 8


def plan_task_walk(
    ctx: CycleContext,
    i: int,
    start,
    rng: np.random.Generator,
    walker=None,
    spots: np.random.Generator | None = None,
    yaw: float | None = None,
):
    """The walk of task ``i`` (a walk or carry) from ``start`` (x, y), as a cycle plans it:
    steps from the cycle's step model (conditioned on ``walker`` when given), ending within
    :data:`SPOT_REACH` step lengths of a spot of the task's stand zone (:func:`work_zone`, for
    the walker's stature and step length) drawn with ``spots`` (:func:`standing_spot`; None:
    with ``rng``), and inside the zone. ``yaw`` (radians): the heading the operator stands at
    (the task before's): the walk sets off from it, turning on the spot first as far as that
    pays against turning while walking (``HybridPlanner.plan(turn_on_spot=True)``); None: it
    sets off around the downhill heading."""
    task = ctx.spec.tasks[i]
    assert task.site is not None  # the spec loader requires a site for walks
    model = ctx.step_model.for_walker(walker)  # the model itself for None
    stature = walker.stature if walker is not None else ctx.spec.stature
    step = walker.step_length if walker is not None else ctx.step_model.pace().step_length
    zone = ctx.zone(i, stature, step)
    planner = ctx.planner(task.site, zone)
    reach = SPOT_REACH * step
    pose = tuple(start) if yaw is None else (float(start[0]), float(start[1]), float(yaw))
    turn = yaw is not None
    for _ in range(SPOT_TRIES):
        x, y = standing_spot(ctx, zone, rng if spots is None else spots)
        if np.hypot(x - start[0], y - start[1]) > reach:
            return planner.plan(pose, rng, model=model, spot=(x, y, reach), turn_on_spot=turn)
    return planner.plan(pose, rng, model=model, turn_on_spot=turn)


def plan_cycle_walks(
    ctx: CycleContext,
    rng: np.random.Generator,
    walker=None,
    start=None,
    spots: np.random.Generator | None = None,
) -> list:
    """Only the walks of one cycle, in order, as :func:`simulate_cycle` plans them with the
    same ``rng`` (the run's generator; arms and handling draw from spawned streams) from the
    same ``start`` (x, y: the run's :func:`cycle_start`; None: the start site itself) with the
    same ``spots`` (the standing-spot stream, after the start's draw; None: ``rng``): a list
    of (task index, start site, goal site, WalkPath). Fast (no animation): for studies of the
    routes alone (``benchmarks/bench_variability.py``). Each walk sets off from the heading
    of the site the operator stands at (the start site's, then the last walk's goal's):
    ``simulate_cycle`` sets off from the heading of the reach done there, which faces the
    reach's target, so a walk after a reach may differ."""
    spec = ctx.spec
    here = spec.start
    if start is None:
        start = ctx.workplace.station(here).pos[:2]
    x, y = float(start[0]), float(start[1])
    out = []
    for i, task in enumerate(spec.tasks):
        if task.kind in ("walk", "carry"):
            yaw = float(ctx.workplace.station(here).yaw)
            path = plan_task_walk(ctx, i, (x, y), rng, walker, spots, yaw=yaw)
            goal = str(task.site)
            out.append((i, here, goal, path))
            x, y = (float(v) for v in path.xy[-1])
            here = goal
    return out
