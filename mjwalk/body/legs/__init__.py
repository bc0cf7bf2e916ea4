"""Leg motion of a planned walk: reference gait, gait analysis of capture, leg kinematics and the
synthesis of joint angles from a WalkPath's footprints (:func:`legs_from_walk`)."""

from mjwalk.body.legs.synthesis import (
    BANDAI_LANDMARKS,
    DEFAULT_REFERENCE,
    LEG_JOINTS,
    WINTER_GAIT,
    LegMotion,
    ReferenceGait,
    bandai_reference,
    foot_lowest,
    gait_cycles,
    heel_strikes,
    leg_fk,
    leg_ik,
    legs_from_walk,
    reference_angle,
    reference_from_takes,
    sagittal_angles,
    warp_reference,
    winter_reference,
)

__all__ = [
    "BANDAI_LANDMARKS",
    "DEFAULT_REFERENCE",
    "LEG_JOINTS",
    "WINTER_GAIT",
    "LegMotion",
    "ReferenceGait",
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
    "warp_reference",
    "winter_reference",
]
