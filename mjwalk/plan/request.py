"""One walk asked of a :class:`~mjwalk.plan.hybrid.HybridPlanner`: :class:`WalkRequest`.

A planner holds what all its walks share (the scene, the goal, the step model,
:class:`~mjwalk.plan.options.PlannerOptions`); a request holds what one walk adds: where it
starts, the step model of its walker, the spot it ends at, whether the walker turns on the spot
first, the heading it arrives at and a path for its heading to follow. World frame, metres,
radians (yaw from +x).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.errors import InputError
from mjwalk.gait.model import StepModel
from mjwalk.plan.guide import resample_guide


@dataclass(frozen=True, eq=False)
class WalkRequest:
    """One walk for :meth:`~mjwalk.plan.hybrid.HybridPlanner.plan`, checked on construction
    (:class:`~mjwalk.errors.InputError`, before any planning work).

    Attributes:
        start: a site name, ``"x,y"``, ``"x,y,yaw_deg"`` or ``(x, y[, yaw])`` (metres,
            radians); parsed against the planner's workplace.
        model: the step model to sample from instead of the planner's (e.g. the planner's
            conditioned on the walker, :meth:`~mjwalk.gait.model.StepModel.for_walker`: same
            feature dimensions and GPs); None: the planner's.
        spot: (x, y, tolerance), metres: the walk ends within ``tolerance`` of (x, y), which
            must lie in the planner's goal area (checked by the planner); None: anywhere in it.
        turn_on_spot: with a start yaw, the walker stands facing it and turns on the spot
            before the first step, the turn costed by its time; without, a start yaw is the
            heading of a walker already walking.
        at_work: with ``turn_on_spot``, the walker stands at the work it faced (a cycle's
            stand site): a turn of more than a quarter is split, all but a one-step direction
            change on the spot and the rest along the first steps
            (:mod:`mjwalk.plan.turnsplit`); without, the search weighs the whole turn as
            before.
        work_heading: with ``at_work``, the heading square to the front of the work (radians; a
            stand site's yaw): the split's first steps go no nearer the work than square to
            it; None: the start yaw (the walker faces its work squarely).
        goal_heading: the heading (radians) the walker means to arrive at; it shapes the path
            the walk's heading follows (:mod:`mjwalk.plan.guide`), no condition of the goal.
        guide: a (k, 2) path (metres) from near the start to near the goal for the heading to
            follow instead, resampled to :data:`~mjwalk.plan.guide.GUIDE_POINTS` points.
    """

    start: object
    model: StepModel | None = None
    spot: tuple[float, float, float] | None = None
    turn_on_spot: bool = False
    goal_heading: float | None = None
    guide: np.ndarray | None = None
    at_work: bool = False
    work_heading: float | None = None

    def __post_init__(self):
        if self.spot is not None:
            object.__setattr__(self, "spot", _checked_spot(self.spot))
        if self.goal_heading is not None:
            object.__setattr__(self, "goal_heading", _checked_heading(self.goal_heading))
        if self.work_heading is not None:
            heading = _checked_heading(self.work_heading, "work_heading")
            object.__setattr__(self, "work_heading", heading)
        if self.guide is not None:
            try:
                guide = resample_guide(self.guide)
            except (TypeError, ValueError) as exc:
                raise InputError(f"guide: {exc}") from None
            object.__setattr__(self, "guide", guide)


def _checked_spot(spot) -> tuple[float, float, float]:
    """``spot`` as three floats: finite, with a tolerance > 0."""
    try:
        x, y, tol = (float(v) for v in spot)
    except (TypeError, ValueError):
        raise InputError(f"spot must be (x, y, tolerance) in metres, got {spot!r}") from None
    if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(tol) and tol > 0):
        raise InputError(f"spot must be finite with a tolerance > 0, got {spot!r}")
    return x, y, tol


def _checked_heading(heading, name: str = "goal_heading") -> float:
    """``heading`` as finite radians (``name``: the field, for the message)."""
    try:
        value = float(heading)
    except (TypeError, ValueError):
        value = math.nan
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite radians, got {heading!r}")
    return value
