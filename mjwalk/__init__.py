"""mjwalk: statistically varied human walking and reaching in MuJoCo assembly workplaces."""

from mjwalk.errors import (
    CaptureError,
    CycleSpecError,
    MjwalkError,
    ModelFileError,
    PlanningError,
    SceneError,
)
from mjwalk.mocap import Take

__version__ = "0.1.0"

__all__ = [
    "CaptureError",
    "CycleSpecError",
    "MjwalkError",
    "ModelFileError",
    "PlanningError",
    "SceneError",
    "Take",
]
