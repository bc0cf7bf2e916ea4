"""Plan walks with the probabilistic hybrid A* (:class:`~mjwalk.plan.hybrid.HybridPlanner`):
one walk, or several independent ones from a seed. Metres, radians (yaw from +x).
"""

from __future__ import annotations

import numpy as np

from mjwalk._args import as_generator, check_seed
from mjwalk.errors import InputError
from mjwalk.gait.default import default_model
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.levelplan import needs_levels, plan_level_walk
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.workplace import Workplace

__all__ = ["plan_walk", "plan_walks"]


def plan_walk(
    workplace: Workplace,
    start,
    goal,
    model=None,
    rng: np.random.Generator | int | None = None,
    options: PlannerOptions | None = None,
) -> WalkPath:
    """Plan one varied, gait-aware, collision-free walk with the probabilistic hybrid A*.

    Args:
        workplace: the scene.
        start: a site name, ``"x,y"``, ``"x,y,yaw_deg"`` or ``(x, y[, yaw])`` (metres, radians).
            Without a yaw the walker starts facing the way the obstacle-aware distance to the
            goal falls fastest (it turns on the spot before walking off).
        goal: a site name, ``"x,y"`` or ``(x, y)``; the walk ends within the options'
            ``goal_tolerance`` (0.25 m by default).
        model: a StepModel (default: :func:`mjwalk.gait.default.default_model`).
        rng: a numpy Generator or a seed.
        options: how to plan (:class:`~mjwalk.plan.options.PlannerOptions`: goal area, body
            radius, search weights, cost, budgets; None: the defaults).

    A start or goal on a raised level of a scene on several levels (a platform, a mezzanine:
    :attr:`Workplace.levels <mjwalk.world.workplace.Workplace.levels>`) makes the walk one over
    levels, by steps, ramps and stairs the walker takes
    (:func:`mjwalk.plan.levelplan.plan_level_walk`); walks on the floor plan as in a flat scene.

    Returns:
        The walk (120 Hz pelvis positions and yaw, its steps; over levels also the surface
        heights, :attr:`~mjwalk.plan.walkpath.WalkPath.z`).

    Raises:
        PlanningError: start/goal off the floor or inside/too near an obstacle (before any
            search), goal unreachable (before any search), or the expansion budget spent.
    """
    if model is None:
        model = default_model()
    rng = as_generator(rng, "plan_walk: rng")
    radius = (options or PlannerOptions()).radius
    if needs_levels(workplace, start, goal, radius):
        return plan_level_walk(workplace, start, goal, model, rng, options)
    return HybridPlanner(workplace, goal, model, options).plan(start, rng)


def plan_walks(
    workplace: Workplace,
    start,
    goal,
    model=None,
    n: int = 15,
    seed: int = 0,
    options: PlannerOptions | None = None,
) -> list[WalkPath]:
    """``n`` independent walks from ``start`` to ``goal``; the same seed gives the same walks.

    Walk ``k`` uses its own random stream (``SeedSequence(seed).spawn``), so a walk does not
    depend on how many others are planned with it. ``options``: as :func:`plan_walk`'s.

    Args:
        workplace: the scene.
        start: a site name, ``"x,y"``, ``"x,y,yaw_deg"`` or (x, y[, yaw]); metres, radians.
        goal: a site name, ``"x,y"`` or (x, y), metres.
        model: the step model; None: the default one (:func:`~mjwalk.gait.default.default_model`).
        n: the number of walks (a whole number >= 0).
        seed: the seed of the walks' streams.
        options: the planner's options; None: the defaults.

    Returns:
        The ``n`` walks, in stream order.
    """
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 0:
        raise InputError(f"plan_walks: n must be a whole number of walks >= 0, got {n!r}")
    seed = check_seed(seed, "plan_walks: seed")
    if model is None:
        model = default_model()
    streams = np.random.SeedSequence(seed).spawn(n)
    radius = (options or PlannerOptions()).radius
    if needs_levels(workplace, start, goal, radius):  # as plan_walk: a walk over levels
        return [
            plan_level_walk(workplace, start, goal, model, np.random.default_rng(s), options)
            for s in streams
        ]
    planner = HybridPlanner(workplace, goal, model, options)
    return [planner.plan(start, np.random.default_rng(s)) for s in streams]
