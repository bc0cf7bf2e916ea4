"""The ground under a swing foot between a ramp and a level (issue 47, deliverable 4: the body
on ramps): over a ramp's top edge, a convex crest, the edge's height, which a height
interpolated between the footprints passes under. World frame, metres, radians; a pitch is
+ toes up.
"""

from __future__ import annotations

import numpy as np

from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footpivot import sole_profile
from mjwalk.body.legs.steps import StepFrames

#: Clearance (m) kept over the ground of a swing between a ramp and a level: the flat swing's
#: toe tip dips up to 0.54 mm below its ground in the sample after toe-off (measured on the
#: multi-level platform cycle's floor steps, run 18), which on a ramp's last footprint put
#: it 0.3 mm into the platform's edge at the ramp's top (run 18).
CREST_CLEARANCE = 0.001


def crest_ground(
    ankle: np.ndarray,
    yaw: np.ndarray,
    fr: StepFrames,
    sf: StepSurfaces,
    geom: LegGeometry,
    pitch: np.ndarray | None = None,
    foot: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """The ground under a swing foot (its heel, ankle and toe tip along its heading) between
    a ramp and a level, as the lower of the lift and landing surfaces' planes, each extended
    from its footprint along its slope: over a ramp's top edge (a convex crest, up onto a
    platform or down off it) that is the edge's height, which a height interpolated between
    the footprints passes under (the toes 2-3 cm into the ramp's top edge on the shipped
    multi-level station's ramp); at a ramp's foot and along a ramp it is at or below it.

    With ``pitch`` (the swing foot's added pitch toward its landing surface's), each sole
    point's ground is taken less the height that pitch moves it by (a point ``d`` ahead of
    the ankle rises ``d tan(pitch)``), and the sole is also checked over the crest itself
    where it lies between heel and toe (the lower of two planes is convex upward at the
    crest: a sole pitched toes down off a platform, heel and toe clear, passed 3 mm into
    the ramp's top edge between them; the multi-level station's stand_platform2 -> stand_ramp,
    rng 4). With ``foot`` as well, the sole is the one the flat swing holds (heel, ball, toe
    tip at its pitch and toe angle) turned by ``pitch`` about the ankle, each point kept as
    high over the ground under it as it is over the floor in the flat swing: a ramp's last
    footfall rolls off its toe tip standing past the ramp's head on the level, and the flat
    foot's points, ahead of where the toes then are and lifted by ``d tan(pitch)``, let the
    tip slide back over the edge 0.8 mm below it (generated hall 526's stress cycle, run 1:
    the toes 0.24 mm into the deck's edge).

    Args:
        ankle: (m, 3) the swing ankle's positions (only x, y used), metres.
        yaw: (m,) the foot's headings, radians from +x CCW.
        fr: the step (its ``lift`` and ``land`` footprints (x, y, yaw)).
        sf: its surfaces (heights and slopes).
        geom: the foot's lengths.
        pitch: (m,) the foot's added pitch, radians, + toes up (None: the foot level).
        foot: (pitch, toe angle) of the flat swing's foot, (m,) each, radians (None: flat).

    Returns:
        (m,) the least height of the ankle's ground offset that keeps the sole's points above
        the ground, metres; :data:`CREST_CLEARANCE` above it between surfaces of different
        slopes (a ramp and a level).
    """
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    tilt = np.zeros(len(yaw)) if pitch is None else np.tan(np.asarray(pitch, dtype=float))
    lines = []  # each surface's height along the foot's line: a + b d
    for pr, h, slope in ((fr.lift, sf.lift, sf.lift_pitch), (fr.land, sf.land, sf.land_pitch)):
        head = np.array([np.cos(pr[2]), np.sin(pr[2])])
        lines.append(
            (
                h + np.tan(slope) * ((ankle[:, :2] - np.asarray(pr[:2])) @ head),
                np.tan(slope) * (f @ head),
            )
        )
    (a0, b0), (a1, b1) = lines
    clear = CREST_CLEARANCE if sf.lift_pitch != sf.land_pitch else 0.0
    points = [np.full(len(yaw), d) for d in (-geom.foot_back, 0.0, geom.foot_front)]
    if pitch is not None:  # where the planes meet (the crest), between heel and toe
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = np.where(np.abs(b1 - b0) > 1e-12, (a0 - a1) / (b1 - b0), 0.0)
        if foot is not None:
            return _held_sole(cross, (a0, b0, a1, b1), pitch, foot, geom) + clear
        points.append(np.clip(cross, -geom.foot_back, geom.foot_front))
    out = np.full(len(yaw), -np.inf)
    for d in points:
        out = np.maximum(out, np.minimum(a0 + b0 * d, a1 + b1 * d) - d * tilt)
    return out + clear


def _held_sole(cross, lines, pitch, foot, geom: LegGeometry) -> np.ndarray:
    """:func:`crest_ground`'s offset for the sole the flat swing holds (``foot``: its pitch and
    toe angle), turned by ``pitch``: per sample the most any of its heel, ankle, ball and toe
    tip, or the sole between two of them over the crest ``cross`` (m ahead of the ankle), needs
    to stay as high over the ground (``lines``: the two planes, a + b d) as it is over the
    floor in the flat swing; metres."""
    a0, b0, a1, b1 = (c[:, None] for c in lines)
    _, z0 = sole_profile(foot[0], foot[1], geom)
    x1, z1 = sole_profile(np.asarray(foot[0], float) + pitch, foot[1], geom)
    rel = z0 - z1  # how much lower each point lies than in the flat swing
    out = np.max(np.minimum(a0 + b0 * x1, a1 + b1 * x1) + rel, axis=1)
    c = cross[:, None]
    top = np.minimum(a0 + b0 * c, a1 + b1 * c)[:, 0]
    for i, k in ((0, 2), (2, 3)):  # heel to ball, ball to toe tip
        with np.errstate(divide="ignore", invalid="ignore"):
            w = (cross - x1[:, i]) / (x1[:, k] - x1[:, i])
        on = np.isfinite(w) & (w >= 0.0) & (w <= 1.0)
        out = np.where(on, np.maximum(out, top + rel[:, i] + w * (rel[:, k] - rel[:, i])), out)
    return out
