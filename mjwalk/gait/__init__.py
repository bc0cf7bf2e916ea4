"""Gait: virtual-subject corpus, step segmentation, step features and the learned StepModel;
the stair and ramp gait of a walker (``stairs``, ``slope``)."""

from mjwalk.gait.slope import SlopeGait, slope_gait
from mjwalk.gait.stairs import StairFlight, StairGait, StairGeometry, stair_gait
from mjwalk.gait.step import Side, Step

__all__ = [
    "Side",
    "SlopeGait",
    "StairFlight",
    "StairGait",
    "StairGeometry",
    "Step",
    "slope_gait",
    "stair_gait",
]
