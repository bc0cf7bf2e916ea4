"""Body dimensions and joint ranges of the mjwalk humanoid, as fractions of stature.

The figures the humanoid is built from (:mod:`mjwalk.body.humanoid`) and that lower stages need
without building a body: the planner's stance-lean check (:mod:`mjwalk.plan.hybrid`) uses the
leg lengths and the joint ranges. Metres, degrees where named ``_DEG``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.conventions import DEFAULT_STATURE

# Segment lengths as fractions of stature H. Source: D. A. Winter, "Biomechanics and Motor
# Control of Human Movement", 4th ed. (2009), Fig. 4.1 (segment lengths after Drillis & Contini
# 1966). Heights are from the floor in the upright stance.
SEG = {
    "ankle_height": 0.039,  # lateral malleolus height
    "shank": 0.246,  # knee to ankle (0.285 - 0.039)
    "thigh": 0.245,  # greater trochanter/hip centre to knee (0.530 - 0.285)
    "hip_height": 0.530,  # hip joint centre height
    "hip_width": 0.191,  # bi-trochanteric width; hip joint centres ~ half of it apart
    "shoulder_height": 0.818,
    "shoulder_width": 0.259,  # bi-acromial width
    "chin_height": 0.870,
    "head_top": 1.000,
    "upper_arm": 0.186,
    "forearm": 0.146,
    "hand": 0.108,
    "foot_length": 0.152,
    "foot_width": 0.055,
}

# Joint ranges of motion in degrees (lo, hi) in the sign convention above. Sources: American
# Academy of Orthopaedic Surgeons (AAOS), "Joint Motion: Method of Measuring and Recording" (1965)
# normal adult values; spine and hand after I. A. Kapandji, "The Physiology of the Joints".
ROM_DEG: dict[str, tuple[float, float]] = {
    # spine (Kapandji: lumbar flex 60 / ext 35, lat. bend 20, rot 5; thoracic flex 45 / ext 25,
    # bend 20, rot 35; cervical flex 45 / ext 55, bend 45, rot 70)
    "lumbar_flex": (-35, 60),
    "lumbar_bend": (-20, 20),
    "lumbar_rot": (-5, 5),
    "thoracic_flex": (-25, 45),
    "thoracic_bend": (-20, 20),
    "thoracic_rot": (-35, 35),
    "neck_flex": (-55, 45),
    "neck_bend": (-45, 45),
    "neck_rot": (-70, 70),
    # upper limb (AAOS: shoulder flex 180 / ext 60, abd 180 / add 30 (horizontal), rot int 70 /
    # ext 90; elbow 0-150; forearm pron 80 / sup 80; wrist flex 80 / ext 70, ulnar 30 / radial 20)
    "shoulder_flex": (-60, 180),
    "shoulder_abd": (-30, 180),
    "shoulder_rot": (-90, 70),
    "elbow": (0, 150),
    "forearm_pron": (-80, 80),
    "wrist_flex": (-70, 80),
    "wrist_dev": (-20, 30),
    # hand (AAOS: thumb CMC abd 70, MCP 0-50, IP 0-80; finger MCP 0-90, PIP 0-100, DIP 0-90)
    "thumb_cmc": (0, 70),
    "thumb_mcp": (0, 50),
    "thumb_ip": (0, 80),
    "finger_mcp": (0, 90),
    "finger_pip": (0, 100),
    "finger_dip": (0, 90),
    # lower limb (AAOS: hip flex 120 / ext 30, abd 45 / add 30, rot int 45 / ext 45; knee 0-135;
    # ankle dorsi 20 / plantar 50, inversion 35 / eversion 15; first MTP ext 70 / flex 45)
    "hip_flex": (-30, 120),
    "hip_abd": (-30, 45),
    "hip_rot": (-45, 45),
    "knee": (0, 135),
    "ankle_flex": (-50, 20),
    "ankle_inv": (-15, 35),
    "toe": (-45, 70),  # positive = MTP extension (toes up)
}

FINGERS = ("index", "middle", "ring", "little")


def pelvis_height(stature: float = DEFAULT_STATURE) -> float:
    r"""Root (hip-joint-centre) height in the neutral pose, :math:`h = 0.530\,H` (Winter).

    Args:
        stature: body height :math:`H` in metres.

    Returns:
        The height of the hip joint centres above the floor in metres.
    """
    return SEG["hip_height"] * stature


def knee_height(stature: float = DEFAULT_STATURE) -> float:
    r"""Knee joint height standing: ankle height plus shank, :math:`h = 0.285\,H` (Winter).

    Args:
        stature: body height :math:`H` in metres.

    Returns:
        The height of the knee joint centre above the floor in metres.
    """
    return (SEG["ankle_height"] + SEG["shank"]) * stature


@dataclass(frozen=True)
class LegGeometry:
    """Lengths the leg IK needs, metres, in the pelvis frame (x forward, y left, z up).

    Attributes:
        hip_y: lateral offset of each hip joint centre from the root (left +, right -).
        thigh: hip to knee. shank: knee to ankle. ankle_height: ankle above the sole.
        foot_back, foot_front: heel and toe-tip distance from the ankle along the foot, metres.
        foot_width: width of the sole (and toes), metres.
    """

    hip_y: float
    thigh: float
    shank: float
    ankle_height: float
    foot_back: float
    foot_front: float
    foot_width: float = 0.0

    def span(self, knee):
        r"""Hip-to-ankle distance at a knee flexion, by the law of cosines on thigh :math:`L_1` and
        shank :math:`L_2`: :math:`d = \sqrt{L_1^2 + L_2^2 + 2 L_1 L_2 \cos\kappa}`.

        Args:
            knee: knee flexion :math:`\kappa` in radians (0 = straight); a float or an array.

        Returns:
            The hip-to-ankle distance in metres, shaped like ``knee``.
        """
        L1, L2 = self.thigh, self.shank
        return np.sqrt(L1**2 + L2**2 + 2 * L1 * L2 * np.cos(knee))

    def knee_for_span(self, d):
        """Knee flexion that puts the ankle ``d`` metres from the hip (the inverse of
        :meth:`span`, clipped to straight and fully folded).

        Args:
            d: hip-to-ankle distance in metres; a float or an array.

        Returns:
            The knee flexion in radians (0 = straight, up to pi), shaped like ``d``.
        """
        L1, L2 = self.thigh, self.shank
        return np.arccos(np.clip((d**2 - L1**2 - L2**2) / (2 * L1 * L2), -1, 1))


def ball_offset(geom: LegGeometry) -> float:
    """Distance of the ball of the foot (toe joint) ahead of the ankle.

    Args:
        geom: the leg and foot lengths.

    Returns:
        ``foot_front - 0.2 (foot_front + foot_back)``, metres.
    """
    return geom.foot_front - 0.2 * (geom.foot_front + geom.foot_back)


#: Upper-arm capsule radius per metre of stature.
UPPER_ARM_RADIUS = 0.024
#: Shin (shank) capsule radius per metre of stature of the humanoid's legs.
SHIN_RADIUS = 0.027


def leg_geometry(stature: float = DEFAULT_STATURE) -> LegGeometry:
    """The leg lengths of :func:`~mjwalk.body.humanoid.build_humanoid` for a stature.

    Args:
        stature: body height in metres; every length scales with it (Winter's table :data:`SEG`).

    Returns:
        The leg geometry in metres, pelvis frame (x forward, y left, z up).
    """
    H = stature
    fl = SEG["foot_length"] * H
    return LegGeometry(
        hip_y=0.5 * 0.52 * SEG["hip_width"] * H,  # hip centres ~52 % of the bi-trochanteric width
        thigh=SEG["thigh"] * H,
        shank=SEG["shank"] * H,
        ankle_height=SEG["ankle_height"] * H,
        foot_back=0.25 * fl,
        foot_front=0.75 * fl,
        foot_width=SEG["foot_width"] * H,
    )


def shoulder_geometry(stature: float = DEFAULT_STATURE) -> tuple[float, float]:
    """The shoulder geometry of :func:`~mjwalk.body.humanoid.build_humanoid` for a stature.

    Args:
        stature: body height in metres.

    Returns:
        ``(offset, radius)`` in metres: the shoulder joint centre's distance from the trunk axis
        and the upper-arm capsule radius; together the half-width of the body at the shoulders.
    """
    return 0.5 * SEG["shoulder_width"] * stature, UPPER_ARM_RADIUS * stature


#: Abduction of the arms in the walking arm swing, degrees: they hang 6 deg out from the trunk
#: (:func:`mjwalk.timeline.frames.arm_swing`).
ARM_SWING_ABDUCTION_DEG = 6.0


def swing_half_width(stature: float = DEFAULT_STATURE) -> float:
    """Half the width of a walker with its arms swinging, from the body's axis to the outside of
    the hand: the shoulder joint's offset (half the bi-acromial width, :data:`SEG`), the arm
    (upper arm, forearm and hand) hanging :data:`ARM_SWING_ABDUCTION_DEG` out from it, and the
    upper-arm capsule's radius (the arm's thickest part). 0.1995 of the stature: 0.35 m at
    1.75 m, a little wider than half of Fruin's 0.61 m body ellipse (Fruin, "Pedestrian Planning
    and Design", 1971: shoulder breadth with clothing) as the hands swing out.

    Args:
        stature: body height in metres.

    Returns:
        The half-width in metres.
    """
    arm = (SEG["upper_arm"] + SEG["forearm"] + SEG["hand"]) * stature
    out = arm * math.sin(math.radians(ARM_SWING_ABDUCTION_DEG))
    return 0.5 * SEG["shoulder_width"] * stature + out + UPPER_ARM_RADIUS * stature


#: Forward trunk inclination (degrees) a standing reach may use. ISO 11226:2000 (evaluation of
#: static working postures) accepts 0-20 deg of trunk inclination without further conditions;
#: mjwalk's humanoid realises about half of that in its reaches: from a shelf at 1.07-1.10 m it
#: puts the hand on targets up to 0.70 m from the pelvis axis with no error and misses beyond
#: (measured: cycle reach of rack 2's screws and tool from stands moved back 0-0.3 m and
#: sideways +-0.2 m, hand error 0 mm at 0.51-0.70 m, 2.2-2.4 mm at 0.72 m, 27-35 mm at 0.75 m),
#: which is :func:`hand_reach` at 10 deg.
REACH_TRUNK_LEAN_DEG = 10.0


def hand_reach(
    height: float,
    stature: float = DEFAULT_STATURE,
    lean_deg: float = REACH_TRUNK_LEAN_DEG,
    turned: bool = True,
) -> float:
    """Farthest horizontal distance (m) from the body's vertical axis (the pelvis centre) at
    which a standing person puts the grip centre on a point ``height`` metres above the floor.

    The trunk (hip to shoulder, Winter's segment table :data:`SEG`) leans ``lean_deg`` forward,
    the body turns so the reaching shoulder (half the bi-acromial width from the trunk axis)
    lies beside the line to the target, as the cycle turns the operator before a reach, and the
    arm (upper arm, forearm and half the hand) is stretched towards it; ``turned=False``: the
    body faces the target squarely (the cycle's fastening), the shoulder beside the line, so
    the arm reaches across.

    Args:
        height: height of the target point above the floor in metres.
        stature: body height in metres (segment lengths from :data:`SEG`).
        lean_deg: forward trunk inclination in degrees.
        turned: whether the body turns so the reaching shoulder lies beside the line to the
            target (True) or faces the target squarely (False).

    Returns:
        The farthest horizontal distance in metres from the pelvis axis; 0 when the point is out
        of the arm's reach.
    """
    H = stature
    lean = np.radians(lean_deg)
    trunk = (SEG["shoulder_height"] - SEG["hip_height"]) * H
    forward = trunk * np.sin(lean)
    shoulder_z = SEG["hip_height"] * H + trunk * np.cos(lean)
    arm = (SEG["upper_arm"] + SEG["forearm"] + 0.5 * SEG["hand"]) * H
    dz = shoulder_z - height
    if abs(dz) >= arm:
        return 0.0
    ahead = forward + float(np.sqrt(arm**2 - dz**2))
    side = 0.5 * SEG["shoulder_width"] * H
    if turned:
        return float(np.hypot(ahead, side))
    return float(np.sqrt(max(ahead**2 - side**2, 0.0)))
