"""The feet on ramps: a grounded foot turned about a point of its sole, the trailing foot rising
on its ball to reach, the ground under a swing foot over a ramp's top edge (issue 47,
deliverable 4: the body on ramps).

On a ramp the two feet of a double support stand at different heights: walking up, the
trailing foot a half step's rise below the ground under the pelvis, the leading foot as much
above it (:meth:`~mjwalk.body.legs.edgeswing.StepSurfaces.pelvis_level` keeps the pelvis at
the mean of the two). Where the trailing leg then cannot reach its foot, the foot, already
rising on its ball in pre-swing, rises further (:func:`trailing_reach`) rather than the pelvis
lowering: lowering it folds the leading leg, nearly straight at heel strike, by 30 deg or more
(knee at heel strike on a 5.5 deg ramp, :func:`~mjwalk.plan.synthetic.synthetic_ramp_walk`:
34 deg with the pelvis lowered, 26 deg without; 2 deg on level ground). Uphill walking adds
plantarflexion at push-off (Lay et al., "The effects of sloped surfaces on locomotion: a
kinematic and kinetic analysis", J Biomech 39:1621-1628 (2006); NOT verified here beyond the
title). A swing between a ramp and a level is carried on the ground under its foot
(:func:`crest_ground`), not below a ramp's top edge. World frame, metres, radians; a pitch is
+ toes up.
"""

from __future__ import annotations

import numpy as np

from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.stance import reach_deficit
from mjwalk.body.legs.steps import HEEL_RISE_MAX, FootTracks, StepFrames

#: Passes of :func:`trailing_reach` (raise the heel by the deficit over the ball's lever,
#: measure again); the deficit falls below a millimetre by the third on a 5.5 deg ramp.
REACH_PASSES = 4


def roll_foot(
    feet: FootTracks, s: str, idx: np.ndarray, turn: np.ndarray, fwd: np.ndarray, geom: LegGeometry
) -> None:
    """Turn the ``s`` foot toes down by ``turn`` about a sole point ``fwd`` metres ahead of the
    ankle (the ball: :func:`~mjwalk.body.legs.footpivot.ball_offset`; the heel:
    ``-geom.foot_back``), that point kept where it is; ``feet`` updated in place.

    Args:
        feet: the foot tracks (``ankle``, ``pitch`` and ``fyaw`` per side).
        s: the side ("l"/"r").
        idx: (m,) the samples to turn.
        turn: (m,) the turn, radians (+ toes down).
        fwd: (m,) the pivot's distance ahead of the ankle along the sole, metres.
        geom: the foot's ``ankle_height``.
    """
    ah, p = geom.ankle_height, feet.pitch[s][idx]
    p2 = p - turn
    f = np.stack([np.cos(feet.fyaw[s][idx]), np.sin(feet.fyaw[s][idx])], -1)
    # the pivot's place in the foot's (forward, up) plane, kept while the pitch changes
    dx = fwd * (np.cos(p) - np.cos(p2)) + ah * (np.sin(p) - np.sin(p2))
    dz = fwd * (np.sin(p) - np.sin(p2)) - ah * (np.cos(p) - np.cos(p2))
    feet.ankle[s][idx, :2] += dx[:, None] * f
    feet.ankle[s][idx, 2] += dz
    feet.pitch[s][idx] = p2


def trailing_reach(
    feet: FootTracks,
    root: np.ndarray,
    yaw: np.ndarray,
    grounded: dict[str, np.ndarray],
    slope: dict[str, np.ndarray],
    reach_sq: dict[str, np.ndarray],
    geom: LegGeometry,
) -> bool:
    """Where a grounded foot on a ramp (``slope`` not 0) is already rising on its ball (its
    pitch below its surface's slope) and its leg cannot reach it from the pelvis, its heel
    rises further about the ball (the toes kept on the surface) until it reaches, up to
    :data:`~mjwalk.body.legs.steps.HEEL_RISE_MAX` from the surface; ``feet`` updated in place.
    Feet on level surfaces (steps, stairs, landings) are left alone.

    Args:
        feet: the foot tracks on their surfaces.
        root: (n, 3) the pelvis positions, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        grounded: per side ("l"/"r") whether the foot is on its surface, (n,).
        slope: per side the surface's slope along the foot, (n,) radians (+ uphill).
        reach_sq: per side the leg's squared hip-to-ankle span, (n,) m².
        geom: the leg geometry.

    Returns:
        whether any sample changed.
    """
    ball, moved = ball_offset(geom), False
    for s in "lr":
        ramp = grounded[s] & (np.abs(slope[s]) > 1e-6)
        if not ramp.any():
            continue
        only = {o: ramp if o == s else np.zeros(len(yaw), bool) for o in "lr"}
        for _ in range(REACH_PASSES):
            short = reach_deficit(root, yaw, feet.ankle, only, reach_sq, geom)
            lo = slope[s] - HEEL_RISE_MAX
            up = feet.pitch[s] < slope[s] - 1e-4
            idx = np.flatnonzero(ramp & up & (short > 1e-4) & (feet.pitch[s] > lo + 1e-4))
            if not len(idx):
                break
            p = feet.pitch[s][idx]
            lever = np.maximum(ball * np.cos(p - slope[s][idx]), 0.25 * ball)
            turn = np.minimum(short[idx] / lever, p - lo[idx])
            roll_foot(feet, s, idx, turn, np.full(len(idx), ball), geom)
            feet.toe[s][idx] += turn
            moved = True
    return moved


def crest_ground(
    ankle: np.ndarray, yaw: np.ndarray, fr: StepFrames, sf: StepSurfaces, geom: LegGeometry
) -> np.ndarray:
    """The ground under a swing foot (its heel, ankle and toe tip along its heading) between
    a ramp and a level, as the lower of the lift and landing surfaces' planes, each extended
    from its footprint along its slope: over a ramp's top edge (a convex crest, up onto a
    platform or down off it) that is the edge's height, which a height interpolated between
    the footprints passes under (the toes 2-3 cm into the ramp's top edge on the shipped
    multi-level station's ramp); at a ramp's foot and along a ramp it is at or below it.

    Args:
        ankle: (m, 3) the swing ankle's positions (only x, y used), metres.
        yaw: (m,) the foot's headings, radians from +x CCW.
        fr: the step (its ``lift`` and ``land`` footprints (x, y, yaw)).
        sf: its surfaces (heights and slopes).
        geom: the foot's lengths.

    Returns:
        (m,) the highest of the ground under the foot's three points, metres.
    """
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    out = np.full(len(yaw), -np.inf)
    for d in (-geom.foot_back, 0.0, geom.foot_front):
        p = ankle[:, :2] + d * f
        planes = []
        for pr, h, slope in ((fr.lift, sf.lift, sf.lift_pitch), (fr.land, sf.land, sf.land_pitch)):
            head = np.array([np.cos(pr[2]), np.sin(pr[2])])
            planes.append(h + np.tan(slope) * ((p - np.asarray(pr[:2])) @ head))
        out = np.maximum(out, np.minimum(*planes))
    return out
