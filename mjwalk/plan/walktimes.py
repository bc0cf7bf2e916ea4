"""Straight walks as the planner walks them: the time a planned walk takes over a distance.

The step model's own straight walks (:func:`mjwalk.gait.straight.model_straight_walks`) steer
its chains greedily; the walks mjwalk plans are searched
(:class:`~mjwalk.plan.hybrid.HybridPlanner`, its energy cost holding the walker's pace).
:func:`planned_straight_walks` plans each distance in an empty straight hall and times it as
captured straight walks are timed, so a capture can be compared with what a cycle simulation
would take (``mjwalk validate``, ``benchmarks/bench_variability.py``).
"""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

from mjwalk.errors import MjwalkError, PlanningError
from mjwalk.gait.straight import time_at
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.world import WorkplaceOptions, workplace_from_model

#: The straight hall's half-width (m) and the floor it leaves behind the start and beyond the
#: goal (m); its length fits the longest walk.
HALL_HALF_WIDTH, HALL_MARGIN = 3.0, 1.0
#: A walk captured in motion starts ``RUN_UP`` metres before the timed stretch (its first step
#: is not a gait initiation); every walk aims ``RUN_ON`` metres beyond its end (m).
RUN_UP, RUN_ON = 2.5, 1.0


def planned_straight_walks(
    model,
    distances: Sequence[float],
    in_motion: Sequence[bool],
    rng: np.random.Generator,
    *,
    failed_as_nan: bool = False,
) -> list[float]:
    """The time (s) the hybrid A* takes to walk each distance (m) straight ahead.

    Each walk is planned in an empty straight hall from rest facing the goal, to a goal
    :data:`RUN_ON` metres beyond the distance; a walk ``in_motion`` is timed from where its
    progress passes :data:`RUN_UP` metres (it started that far before, so it is walking
    there), the others from the start. The time at a distance is read off the steps' ends
    (:func:`mjwalk.gait.straight.time_at`: interpolated within the step that crosses it).
    Distances must be positive and finite (else MjwalkError). A walk the planner cannot plan
    raises its PlanningError, or with ``failed_as_nan`` gives NaN (a model that does not plan
    well still gets its other figures reported).

    Args:
        model: the step model.
        distances: the distances to time, metres (positive, finite).
        in_motion: per distance, whether the walker is already walking at its start.
        rng: the random stream of the plans.
        failed_as_nan: give NaN for a walk that cannot be planned instead of raising.

    Returns:
        The time per distance, seconds (NaN: not planned, with ``failed_as_nan``).
    """
    distances = [float(d) for d in distances]
    if len(distances) != len(in_motion):
        raise MjwalkError(
            f"planned_straight_walks: {len(distances)} distances, {len(in_motion)} in_motion flags"
        )
    bad = [d for d in distances if not 0.0 < d < float("inf")]
    if bad:
        raise MjwalkError(
            f"planned_straight_walks: distances must be positive and finite, got {bad[0]!r}"
        )
    if not distances:
        return []
    lx = 0.5 * (max(distances) + RUN_UP + RUN_ON) + HALL_MARGIN
    ly = HALL_HALF_WIDTH
    xml = (
        '<mujoco model="straight_hall"><worldbody>'
        f'<geom name="floor" type="plane" size="{lx} {ly} 0.05"/>'
        "</worldbody></mujoco>"
    )
    wp = workplace_from_model(
        mujoco.MjModel.from_xml_string(xml), options=WorkplaceOptions(cache=False)
    )
    x0 = -lx + HALL_MARGIN
    out = []
    for d, moving in zip(distances, in_motion, strict=True):
        lead = RUN_UP if moving else 0.0
        planner = HybridPlanner(wp, (x0 + lead + d + RUN_ON, 0.0), model)
        try:
            walk = planner.plan(f"{x0},0,0", rng)
        except PlanningError:
            if not failed_as_nan:
                raise
            out.append(float("nan"))
            continue
        track = [(float(walk.t[s.end]), float(walk.xy[s.end, 0] - x0)) for s in walk.steps]
        track = [(0.0, 0.0), *track]
        t0 = time_at(track, lead) if moving else 0.0
        out.append(time_at(track, lead + d) - t0)
    return out
