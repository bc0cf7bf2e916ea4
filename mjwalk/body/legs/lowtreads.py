"""Low tops (mats, cable bridges, floor plates: :mod:`mjwalk.plan.lowtops`) as the legs' steps
take them: a plane in level walking, a tread where a step crosses a riser from or onto one
(:func:`low_treads`). Used by :func:`mjwalk.body.legs.rampreach.level_feet_on_ramps`. Metres
above the floor, radians.
"""

from __future__ import annotations

from dataclasses import replace

from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.world.norms import LEVEL_TOLERANCE


def low_treads(walk, surfs: list[StepSurfaces], level: list[bool], low) -> list[StepSurfaces]:
    """The footprints standing on a low top (a mat, a cable bridge, a floor plate:
    :mod:`mjwalk.plan.lowtops`) as a step crossing a riser takes them: a tread, whose height
    the riser is measured from (a foot on a 15 mm mat before a 0.17 m step rises 0.155 m onto
    it, the step swung over the riser's edge with the pelvis on the mat, :attr:`~mjwalk.body.
    legs.edgeswing.StepSurfaces.edged`), not a ramp's plane that changes height without an
    edge; a level step keeps them as planes (swung over the top's edge, not as off a stair).
    Before, the mat's footprints of the first riser step of a crossing were planes, so that
    step (0.015 -> 0.17 m) was no edged step: its pelvis rose to the mean of its feet before
    the next step dropped it back to the mat, and the legs reached the trailing foot only with
    the pelvis 0.069 m lowered (a 15 mm mat 5 cm short of a 0.34 m platform's step).

    Args:
        walk: the walk (its steps' footprints).
        surfs: its steps' surfaces (:func:`~mjwalk.body.legs.rampreach.level_feet_on_ramps`).
        level: per step whether it is level walking
            (:func:`~mjwalk.body.legs.rampreach.level_planes`).
        low: a footprint (x, y, yaw) -> (height above the floor, pitch) of the low tops under
            it, or None.

    Returns:
        the surfaces, a flat footprint at its low top's height (within the levels' own
        :data:`~mjwalk.world.norms.LEVEL_TOLERANCE`, 4 mm: a heel strike near a mat's edge
        stands 0.4 mm above it, :func:`~mjwalk.body.legs.rampreach.heel_face_need`) marked on
        a plane exactly in the level steps.
    """
    out = []
    for k, (s, sf) in enumerate(zip(walk.steps, surfs, strict=True)):
        prints = (walk.steps[k - 1].stance if k else s.stance, s.stance, s.foot)
        flags = [sf.lift_ramp, sf.stance_ramp, sf.land_ramp]
        for i, (name, print_) in enumerate(zip(("lift", "stance", "land"), prints, strict=True)):
            on = low(print_)
            if on is not None and not getattr(sf, f"{name}_pitch") and abs(
                on[0] - getattr(sf, name)) <= LEVEL_TOLERANCE:  # fmt: skip
                flags[i] = level[k]
        out.append(replace(sf, lift_ramp=flags[0], stance_ramp=flags[1], land_ramp=flags[2]))
    return out
