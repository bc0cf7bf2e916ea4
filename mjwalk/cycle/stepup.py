"""The step-up limit of a cycle's operator groups (issue 47): the highest riser an operator of a
group steps up or down, from the ``[population]`` table's optional ``step_up`` key::

    [population]
    mix = { adult = 0.8, older_adult = 0.2 }
    step_up = { older_adult = 0.0 }   # a group's limit, metres (or one number for every group)

A group without a limit climbs what a workplace stair may ask: risers up to DIN 18065:2020's
0.19 m (:data:`mjwalk.plan.levelroute.DEFAULT_STEP_UP`, ASR A1.8 §4.5). A lower limit describes
operators who avoid high steps -- 0 m the barrier-free route, no steps at all (DIN 18040-1
§4.3.2, "stufenlos": walking-aid users): the level planner then takes a ramp where the riser
exceeds it (:func:`mjwalk.plan.levelplan.plan_level_walk`), and the report names the route the
group walks. Metres.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from mjwalk.errors import CycleSpecError
from mjwalk.world.norms import MAX_RISER


def parse_step_up(
    value, groups: Sequence[str], fail: Callable[[str, str], CycleSpecError]
) -> tuple[tuple[str, float], ...]:
    """The ``step_up`` value of a ``[population]`` table.

    Args:
        value: a number (every group) or a table of group name = metres.
        groups: the population's group names.
        fail: builds the error to raise from a message and the key.

    Returns:
        (group, limit in metres) pairs, one per group that has a limit.

    Raises:
        CycleSpecError: an unknown group, or a limit that is not a number within 0 m and
            DIN 18065's 0.19 m (a higher limit changes no route: no workplace riser is higher).
    """
    table = {g: value for g in groups} if not isinstance(value, dict) else value
    out = []
    for name, limit in table.items():
        if name not in groups:
            raise fail(
                f"population.step_up.{name}: no such group (groups: {', '.join(groups)})",
                "step_up",
            )
        if (
            isinstance(limit, bool)
            or not isinstance(limit, (int, float))
            or not (math.isfinite(limit) and 0.0 <= limit <= MAX_RISER)
        ):
            raise fail(
                f"population.step_up: {name}'s limit must be metres within 0-{MAX_RISER} "
                f"(DIN 18065), got {limit!r}",
                "step_up",
            )
        out.append((str(name), float(limit)))
    return tuple(out)


def step_up_of(population, walker) -> float | None:
    """The step-up limit of an operator's group.

    Args:
        population: the cycle's :class:`~mjwalk.cycle.population.Population` (None: none).
        walker: the run's :class:`~mjwalk.gait.walker.Walker` (None: the cycle's own operator).

    Returns:
        The group's limit in metres; None when the group has none (the planner's default).
    """
    if population is None or walker is None:
        return None
    return dict(population.step_up).get(getattr(walker, "group", ""))
