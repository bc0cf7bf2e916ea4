"""The actions a cycle's tasks perform, one class each (:class:`~mjwalk.cycle.actions.base.
Action`): :class:`Walk` (``walk``, ``carry``), :class:`Reach` (``pick``, ``place``,
``fasten``) and :class:`Wait` (``wait``). Importing this package defines them, so the task
kinds (:data:`mjwalk.cycle.types.TASK_KINDS`) find them by name."""

from mjwalk.cycle.actions.base import (
    Action,
    CycleRun,
    CycleState,
    Performed,
    action_class,
)
from mjwalk.cycle.actions.reach_for import Reach
from mjwalk.cycle.actions.wait_for import Wait
from mjwalk.cycle.actions.walk_to import Walk

__all__ = [
    "Action",
    "CycleRun",
    "CycleState",
    "Performed",
    "Reach",
    "Wait",
    "Walk",
    "action_class",
]
