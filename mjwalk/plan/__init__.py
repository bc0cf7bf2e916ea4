"""Walk planning: the grid-A* baseline and the probabilistic hybrid A*; the WalkPath."""

from mjwalk.plan.walkpath import PathStep, WalkPath

__all__ = ["PathStep", "WalkPath"]
