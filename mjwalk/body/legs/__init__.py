"""Leg motion of a planned walk: reference gait tables (:mod:`~mjwalk.body.legs.reference`),
gait analysis of capture (:mod:`~mjwalk.body.legs.analysis`), leg kinematics
(:mod:`~mjwalk.body.legs.ik`), the steps' frames and curves
(:mod:`~mjwalk.body.legs.steps`, :mod:`~mjwalk.body.legs.spin`) and the synthesis of joint
angles from a WalkPath's footprints (:func:`~mjwalk.body.legs.synthesis.legs_from_walk`)."""

from mjwalk.body.legs.analysis import (
    gait_cycles,
    heel_strikes,
    reference_from_takes,
    sagittal_angles,
)
from mjwalk.body.legs.ik import LEG_JOINTS, foot_lowest, leg_fk, leg_ik
from mjwalk.body.legs.reference import (
    BANDAI_LANDMARKS,
    DEFAULT_REFERENCE,
    WINTER_GAIT,
    ReferenceGait,
    bandai_reference,
    reference_angle,
    warp_reference,
    winter_reference,
)
from mjwalk.body.legs.steps import StepFrames, step_frames
from mjwalk.body.legs.synthesis import LegMotion, legs_from_walk

__all__ = [
    "BANDAI_LANDMARKS",
    "DEFAULT_REFERENCE",
    "LEG_JOINTS",
    "WINTER_GAIT",
    "LegMotion",
    "ReferenceGait",
    "StepFrames",
    "bandai_reference",
    "foot_lowest",
    "gait_cycles",
    "heel_strikes",
    "leg_fk",
    "leg_ik",
    "legs_from_walk",
    "reference_angle",
    "reference_from_takes",
    "sagittal_angles",
    "step_frames",
    "warp_reference",
    "winter_reference",
]
